#include "deform/anarap.h"

#include <cmath>

#include "anisoform/transforms.h"
#include "deform/anderson.h"

namespace aniso {

namespace {
// Differences kept by Anderson acceleration: Peng et al. use 5-6; more costs
// memory (2 position arrays each) for little gain.
constexpr int kAndersonWindow = 5;

// Rotation maximizing f(R) = tr(R^T S), warm-started from q. Each step
// perturbs on the right, R = R0 exp([d]x), with M = R0^T S:
//   f = tr M + g.d - 1/2 d^T H d + O(|d|^3),
//   g = (M32 - M23, M13 - M31, M21 - M12),  H = tr(M) I - sym(M),
// and takes Newton's step d = H^-1 g while H is positive definite (near the
// maximum it is, and the iteration converges quadratically: one or two
// steps from a warm start). Where H is not (far from the maximum, or S
// nearly singular) it takes Müller et al.'s (2016) scaled-gradient step
// d = g / |tr M|, which always ascends. The rotation stays exactly
// orthonormal (a unit quaternion) whatever S is: no SVD, no reflection.
void fit_rotation(const Eigen::Matrix3d& S, Eigen::Quaterniond& q) {
  const double scale = S.cwiseAbs().sum();
  if (!(scale > 0.0)) return;
  for (int it = 0; it < 24; ++it) {
    const Eigen::Matrix3d M = q.toRotationMatrix().transpose() * S;
    const Eigen::Vector3d g(M(2, 1) - M(1, 2), M(0, 2) - M(2, 0), M(1, 0) - M(0, 1));
    const double trace = M.trace();
    // H = tr(M) I - sym(M), symmetric: solved by its adjugate, with
    // Sylvester's criterion (leading minors positive) for definiteness.
    const double h00 = trace - M(0, 0), h11 = trace - M(1, 1), h22 = trace - M(2, 2);
    const double h01 = -0.5 * (M(0, 1) + M(1, 0)), h02 = -0.5 * (M(0, 2) + M(2, 0)),
                 h12 = -0.5 * (M(1, 2) + M(2, 1));
    const double c00 = h11 * h22 - h12 * h12, c01 = h02 * h12 - h01 * h22, c02 = h01 * h12 - h02 * h11;
    const double det = h00 * c00 + h01 * c01 + h02 * c02;
    const double minor2 = h00 * h11 - h01 * h01;
    const double tiny = 1e-12 * scale;
    Eigen::Vector3d d;
    if (h00 > tiny && minor2 > tiny * tiny && det > tiny * tiny * tiny) {
      const double c11 = h00 * h22 - h02 * h02, c12 = h01 * h02 - h00 * h12;
      d = Eigen::Vector3d(c00 * g.x() + c01 * g.y() + c02 * g.z(),  //
                          c01 * g.x() + c11 * g.y() + c12 * g.z(),  //
                          c02 * g.x() + c12 * g.y() + minor2 * g.z()) /
          det;
    } else {
      d = g / (std::abs(trace) + tiny);
    }
    const double step = d.squaredNorm();
    if (!std::isfinite(step)) return;
    // First-order exponential, normalized: the angle comes out as
    // 2 atan(|d| / 2) = |d| - |d|^3 / 12 + ..., exact enough for a Newton step
    // (which shrinks quadratically) and free of trigonometry, which would cost
    // more than the rest of the step.
    const Eigen::Quaterniond delta(1.0, 0.5 * d.x(), 0.5 * d.y(), 0.5 * d.z());
    q = (q * delta).normalized();
    // Newton's error after this step is O(|d|^2): below 1e-12 rad.
    if (step < 1e-12) break;
  }
}

// Energy of one cell: sum w|e'|^2 - 2 tr(B^T A) + tr(B^T B C), the last
// term precomputed (target_energy_).
inline double cell_energy(double edge_energy, const Eigen::Matrix3d& A, const Eigen::Matrix3d& B,
                          double target_energy) {
  return edge_energy - 2.0 * (B.array() * A.array()).sum() + target_energy;
}

double target_term(const Eigen::Matrix3d& T, const Eigen::Matrix3d& C) {
  return ((T.transpose() * T).array() * C.array()).sum();
}

}  // namespace

AnArapSolver::AnArapSolver(const Mesh& rest, const CotanWeights& weights,
                               const Eigen::SparseMatrix<double>& laplacian, ArapElements elements)
    : rest_(rest), weights_(weights), elements_(elements), n_(rest.num_vertices()) {
  offsets_.assign(n_ + 1, 0);
  neighbors_.reserve(static_cast<std::size_t>(laplacian.nonZeros()));
  spoke_weight_.reserve(static_cast<std::size_t>(laplacian.nonZeros()));
  // L is symmetric: column i lists the neighbours of i with -w_ij.
  for (int i = 0; i < n_; ++i) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(laplacian, i); it; ++it) {
      if (it.row() == i) continue;
      neighbors_.push_back(static_cast<int>(it.row()));
      spoke_weight_.push_back(-it.value());
    }
    offsets_[i + 1] = static_cast<int>(neighbors_.size());
  }
  spoke_edge_.resize(static_cast<Eigen::Index>(neighbors_.size()), 3);
  weighted_edge_sum_ = Positions::Zero(n_, 3);
  rest_covariance_.assign(n_, Eigen::Matrix3d::Zero());
  for (int i = 0; i < n_; ++i) {
    for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
      const Eigen::RowVector3d e = rest.V.row(neighbors_[q]) - rest.V.row(i);
      spoke_edge_.row(q) = e;
      weighted_edge_sum_.row(i) += spoke_weight_[q] * e;
      if (elements_ == ArapElements::Spokes) {
        rest_covariance_[i] += spoke_weight_[q] * e.transpose() * e;
      }
    }
  }
  if (elements_ == ArapElements::SpokesAndRims) {
    for (int t = 0; t < rest.num_triangles(); ++t) {
      Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d e = (rest.V.row(rest.F(t, (k + 2) % 3)) - rest.V.row(rest.F(t, (k + 1) % 3))).transpose();
        C += weights.weight(t, k) * e * e.transpose();
      }
      for (int k = 0; k < 3; ++k) rest_covariance_[rest.F(t, k)] += C;
    }
  }
  energy_scale_ = 0.0;
  for (int i = 0; i < n_; ++i) energy_scale_ += std::abs(rest_covariance_[i].trace());
  T_.assign(n_, Eigen::Matrix3d::Identity());
  P_ = T_;
  B_ = T_;
  target_energy_.resize(n_);
  for (int i = 0; i < n_; ++i) target_energy_[i] = rest_covariance_[i].trace();
  rotation_.assign(n_, Eigen::Quaterniond::Identity());
  spoke_coupling_.resize(neighbors_.size());
  auto fan_size = [&](int i) {
    const int degree = offsets_[i + 1] - offsets_[i];
    return degree > 0 ? std::abs(rest_covariance_[i].trace()) / degree : 0.0;
  };
  for (int i = 0; i < n_; ++i) {
    for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
      spoke_coupling_[q] = 0.5 * (fan_size(i) + fan_size(neighbors_[q]));
    }
  }
}

void AnArapSolver::set_targets(const std::vector<Eigen::Matrix3d>& T) {
  T_ = T;
  symmetric_targets_ = true;
  for (int i = 0; i < n_; ++i) {
    P_[i] = polar_positive_part(T_[i]);
    target_energy_[i] = target_term(T_[i], rest_covariance_[i]);
    if ((P_[i] - T_[i]).cwiseAbs().maxCoeff() > 1e-12 * (1.0 + T_[i].cwiseAbs().maxCoeff())) {
      symmetric_targets_ = false;
    }
  }
}

void AnArapSolver::reset_rotations() {
  rotation_.assign(n_, Eigen::Quaterniond::Identity());
}

void AnArapSolver::covariance_spokes(const Positions& V, std::vector<Eigen::Matrix3d>& A,
                                       Eigen::VectorXd& edge_energy) const {
  for (int i = 0; i < n_; ++i) {
    Eigen::Matrix3d acc = Eigen::Matrix3d::Zero();
    double energy = 0.0;
    const Eigen::RowVector3d vi = V.row(i);
    for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
      const Eigen::Vector3d deformed = (V.row(neighbors_[q]) - vi).transpose();
      const double w = spoke_weight_[q];
      acc.noalias() += (w * deformed) * spoke_edge_.row(q);
      energy += w * deformed.squaredNorm();
    }
    A[i] = acc;
    edge_energy[i] = energy;
  }
}

void AnArapSolver::covariance_spokes_rims(const Positions& V, std::vector<Eigen::Matrix3d>& A,
                                            Eigen::VectorXd& edge_energy) const {
  std::fill(A.begin(), A.end(), Eigen::Matrix3d::Zero());
  edge_energy.setZero();
  for (int t = 0; t < rest_.num_triangles(); ++t) {
    Eigen::Matrix3d acc = Eigen::Matrix3d::Zero();
    double energy = 0.0;
    for (int k = 0; k < 3; ++k) {
      const int a = rest_.F(t, (k + 1) % 3), b = rest_.F(t, (k + 2) % 3);
      const Eigen::Vector3d deformed = (V.row(b) - V.row(a)).transpose();
      const Eigen::RowVector3d e = rest_.V.row(b) - rest_.V.row(a);
      const double w = weights_.weight(t, k);
      acc.noalias() += (w * deformed) * e;
      energy += w * deformed.squaredNorm();
    }
    for (int k = 0; k < 3; ++k) {
      A[rest_.F(t, k)] += acc;
      edge_energy[rest_.F(t, k)] += energy;
    }
  }
}

double AnArapSolver::local_step(const Positions& V) {
  std::vector<Eigen::Matrix3d>& A = covariance_;
  Eigen::VectorXd& edge_energy = edge_energy_;
  A.resize(n_);
  edge_energy.resize(n_);
  if (elements_ == ArapElements::Spokes) {
    covariance_spokes(V, A, edge_energy);
  } else {
    covariance_spokes_rims(V, A, edge_energy);
  }
  double energy = 0.0;
  if (coupling_ > 0.0) {
    energy += coupled_rotations(A);
    for (int i = 0; i < n_; ++i) energy += cell_energy(edge_energy[i], A[i], B_[i], target_energy_[i]);
    return energy;
  }
  for (int i = 0; i < n_; ++i) {
    // S = sum w e' (P e)^T = A P^T; P is symmetric.
    fit_rotation(A[i] * P_[i], rotation_[i]);
    B_[i].noalias() = rotation_[i].toRotationMatrix() * T_[i];
    energy += cell_energy(edge_energy[i], A[i], B_[i], target_energy_[i]);
  }
  // Negative cotangent weights (obtuse triangles) can make this sum slightly
  // negative near the optimum: it is reported as it is.
  return energy;
}

double AnArapSolver::coupled_rotations(const std::vector<Eigen::Matrix3d>& A) {
  // In index order, each R_i against its neighbours' latest rotations (as
  // matrices, each converted once per sweep and again when it changes).
  std::vector<Eigen::Matrix3d>& R = rotation_matrices_;
  R.resize(n_);
  for (int i = 0; i < n_; ++i) R[i] = rotation_[i].toRotationMatrix();
  for (int i = 0; i < n_; ++i) {
    Eigen::Matrix3d S = A[i] * T_[i].transpose();
    for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
      S.noalias() += (2.0 * coupling_ * spoke_coupling_[q]) * R[neighbors_[q]];
    }
    fit_rotation(S, rotation_[i]);
    R[i] = rotation_[i].toRotationMatrix();
    B_[i].noalias() = R[i] * T_[i];
  }
  double energy = 0.0;
  for (int i = 0; i < n_; ++i) {
    for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
      // |R_i - R_j|^2 = 6 - 2 tr(R_i^T R_j); tr of a rotation = 4 w^2 - 1 of
      // the quaternion q_i^-1 q_j.
      const double w = rotation_[i].dot(rotation_[neighbors_[q]]);
      energy += coupling_ * spoke_coupling_[q] * (6.0 - 2.0 * (4.0 * w * w - 1.0));
    }
  }
  return energy;
}

void AnArapSolver::global_rhs(Positions& b) const {
  b.setZero(n_, 3);
  if (elements_ == ArapElements::Spokes) {
    // b_i = -1/2 (B_i g_i + sum_j w_ij B_j e_ij), with g_i = sum_j w_ij e_ij.
    for (int i = 0; i < n_; ++i) {
      Eigen::Vector3d acc = B_[i] * weighted_edge_sum_.row(i).transpose();
      for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
        acc.noalias() += B_[neighbors_[q]] * (spoke_weight_[q] * spoke_edge_.row(q).transpose());
      }
      b.row(i) = -0.5 * acc.transpose();
    }
    return;
  }
  for (int t = 0; t < rest_.num_triangles(); ++t) {
    const Eigen::Matrix3d M = (B_[rest_.F(t, 0)] + B_[rest_.F(t, 1)] + B_[rest_.F(t, 2)]) / 3.0;
    for (int k = 0; k < 3; ++k) {
      const int a = rest_.F(t, (k + 1) % 3), c = rest_.F(t, (k + 2) % 3);
      const Eigen::Vector3d d = weights_.weight(t, k) * (M * (rest_.V.row(a) - rest_.V.row(c)).transpose());
      b.row(a) += d.transpose();
      b.row(c) -= d.transpose();
    }
  }
}

int AnArapSolver::run(const LaplacianSolver& solver, Positions& V, int max_iterations,
                        double tolerance, std::vector<double>& history, bool final_energy,
                        bool accelerate) {
  Positions b, g, proposal;
  AndersonMixer mixer(kAndersonWindow);
  std::vector<Eigen::Quaterniond> kept_rotations;
  double previous = local_step(V);
  int iterations = 0;
  for (int it = 0; it < max_iterations; ++it) {
    global_rhs(b);
    g = V;
    solver.solve(b, g);  // G(V): the plain iteration's next positions
    if (!final_energy && it + 1 == max_iterations) {
      V = g;
      history.push_back(previous);
      return ++iterations;
    }
    double energy = 0.0;
    if (accelerate && mixer.propose(V, g, proposal)) {
      // The safeguard: the proposal's energy (with rotations fitted to it)
      // must be below the last accepted one, else the plain step is taken
      // from the rotations as they were.
      kept_rotations = rotation_;
      energy = local_step(proposal);
      if (energy < previous) {
        V.swap(proposal);
      } else {
        rotation_ = kept_rotations;
        mixer.reset();
        V.swap(g);
        energy = local_step(V);
      }
    } else {
      V.swap(g);
      energy = local_step(V);
    }
    history.push_back(energy);
    ++iterations;
    // Relative change, measured against the energy's own size but never
    // against less than a 1e-12 part of the fans' rest size, so that an exact
    // solution (energy ~ 0) stops too.
    const double reference = std::max(std::abs(previous), 1e-12 * energy_scale_);
    if (tolerance >= 0.0 && std::abs(previous - energy) <= tolerance * reference) break;
    previous = energy;
  }
  return iterations;
}

}  // namespace aniso
