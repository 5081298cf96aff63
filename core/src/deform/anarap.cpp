#include "deform/anarap.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "anisoform/transforms.h"
#include "base/simd_pair.h"
#include "deform/anderson.h"

namespace aniso {

namespace {
// Differences kept by Anderson acceleration: Peng et al. use 5-6; more costs
// memory (2 position arrays each) for little gain.
constexpr int kAndersonWindow = 5;

// A Newton step shorter than this (radians) ends the fit: the rotation is
// then within about its square of the maximum (Newton's convergence is
// quadratic), and the next iteration's fit, warm-started from it, goes on
// from there. An exact fit at every iteration does not change where the
// iterations converge (at their fixed point every fit starts at its
// maximum) nor how many they take (the armadillo's AnARAP stretch: 491
// plain, 62 L-BFGS iterations to 1e-6 either way), and its second and
// third steps were a sixth of an iteration (cyl50k).
constexpr double kFitStep = 0.1;

// The rotation fits' Newton step (fit_rotation below), written once for T =
// double (one cell) and T = Pair (two cells, one per lane: first_steps).
template <typename T>
struct Quat {
  T w, x, y, z;
};

template <typename T>
using Mat3 = T[3][3];

inline double root(double v) { return std::sqrt(v); }
inline Pair root(Pair v) { return Pair{std::sqrt(v[0]), std::sqrt(v[1])}; }

// q as a rotation matrix (Eigen's toRotationMatrix).
template <typename T>
void to_matrix(const Quat<T>& q, Mat3<T>& R) {
  const T tx = q.x + q.x, ty = q.y + q.y, tz = q.z + q.z;
  const T twx = tx * q.w, twy = ty * q.w, twz = tz * q.w, txx = tx * q.x, txy = ty * q.x, txz = tz * q.x,
          tyy = ty * q.y, tyz = tz * q.y, tzz = tz * q.z;
  R[0][0] = 1.0 - (tyy + tzz), R[0][1] = txy - twz, R[0][2] = txz + twy;
  R[1][0] = txy + twz, R[1][1] = 1.0 - (txx + tzz), R[1][2] = tyz - twx;
  R[2][0] = txz - twy, R[2][1] = tyz + twx, R[2][2] = 1.0 - (txx + tyy);
}

// sum of A .* B, f(A) when B = S.
template <typename T>
T inner(const Mat3<T>& A, const Mat3<T>& B) {
  T sum = A[0][0] * B[0][0];
  for (int k = 1; k < 9; ++k) sum += A[k / 3][k % 3] * B[k / 3][k % 3];
  return sum;
}

// The Newton system at R: M = R^T S, its gradient g, tr M, and
// H = tr(M) I - sym(M) by its adjugate (H^-1 g = adj_g / det), with the
// leading minors h00, minor2, det for Sylvester's criterion.
template <typename T>
struct NewtonSystem {
  T g[3], trace, h00, minor2, det, adj_g[3];
};

template <typename T>
NewtonSystem<T> newton_system(const Mat3<T>& R, const Mat3<T>& S) {
  Mat3<T> M;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) M[i][j] = R[0][i] * S[0][j] + R[1][i] * S[1][j] + R[2][i] * S[2][j];
  }
  NewtonSystem<T> sys;
  sys.g[0] = M[2][1] - M[1][2], sys.g[1] = M[0][2] - M[2][0], sys.g[2] = M[1][0] - M[0][1];
  sys.trace = M[0][0] + M[1][1] + M[2][2];
  const T h00 = sys.trace - M[0][0], h11 = sys.trace - M[1][1], h22 = sys.trace - M[2][2];
  const T h01 = -0.5 * (M[0][1] + M[1][0]), h02 = -0.5 * (M[0][2] + M[2][0]), h12 = -0.5 * (M[1][2] + M[2][1]);
  const T c00 = h11 * h22 - h12 * h12, c01 = h02 * h12 - h01 * h22, c02 = h01 * h12 - h02 * h11;
  const T c11 = h00 * h22 - h02 * h02, c12 = h01 * h02 - h00 * h12;
  sys.h00 = h00;
  sys.minor2 = h00 * h11 - h01 * h01;
  sys.det = h00 * c00 + h01 * c01 + h02 * c02;
  const T* g = sys.g;
  sys.adj_g[0] = c00 * g[0] + c01 * g[1] + c02 * g[2];
  sys.adj_g[1] = c01 * g[0] + c11 * g[1] + c12 * g[2];
  sys.adj_g[2] = c02 * g[0] + c12 * g[1] + sys.minor2 * g[2];
  return sys;
}

// q exp([d]x) to first order, normalized: q (1, d/2) / |q (1, d/2)|. The
// angle comes out as 2 atan(|d| / 2) = |d| - |d|^3 / 12 + ..., exact enough
// for a Newton step (which shrinks quadratically) and free of trigonometry,
// which would cost more than the rest of the step.
template <typename T>
Quat<T> turned(const Quat<T>& q, const T d[3]) {
  const T bx = 0.5 * d[0], by = 0.5 * d[1], bz = 0.5 * d[2];
  Quat<T> r{q.w - q.x * bx - q.y * by - q.z * bz, q.w * bx + q.x + q.y * bz - q.z * by,
            q.w * by + q.y + q.z * bx - q.x * bz, q.w * bz + q.z + q.x * by - q.y * bx};
  const T inverse_norm = 1.0 / root(r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z);
  r.w *= inverse_norm, r.x *= inverse_norm, r.y *= inverse_norm, r.z *= inverse_norm;
  return r;
}

Eigen::Matrix3d as_matrix(const Mat3<double>& A) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m(i, j) = A[i][j];
  }
  return m;
}

// Rotation maximizing f(R) = tr(R^T S), warm-started from q; returns R (q as
// a matrix). Each step perturbs on the right, R = R0 exp([d]x), with M = R0^T S:
//   f = tr M + g.d - 1/2 d^T H d + O(|d|^3),
//   g = (M32 - M23, M13 - M31, M21 - M12),  H = tr(M) I - sym(M),
// and takes Newton's step d = H^-1 g while H is positive definite (near the
// maximum it is, and the iteration converges quadratically). Where H is not
// (far from the maximum, or S nearly singular) it takes Müller et al.'s
// (2016) scaled-gradient step d = g / |tr M|, which always ascends. The fit
// stops after a step shorter than kFitStep that raised f, so that f never
// falls: the local step never raises the energy. The rotation stays exactly
// orthonormal (a unit quaternion) whatever S is: no SVD, no reflection.
Eigen::Matrix3d fit_rotation(const Eigen::Matrix3d& S_in, Eigen::Quaterniond& q) {
  Mat3<double> S, R;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) S[i][j] = S_in(i, j);
  }
  Quat<double> current{q.w(), q.x(), q.y(), q.z()};
  to_matrix(current, R);
  const double scale = S_in.cwiseAbs().sum();
  if (!(scale > 0.0)) return as_matrix(R);
  const double tiny = 1e-12 * scale;
  for (int it = 0; it < 24; ++it) {
    const NewtonSystem<double> sys = newton_system(R, S);
    double d[3];
    for (int k = 0; k < 3; ++k) {
      d[k] = sys.h00 > tiny && sys.minor2 > tiny * tiny && sys.det > tiny * tiny * tiny
                 ? sys.adj_g[k] / sys.det
                 : sys.g[k] / (std::abs(sys.trace) + tiny);
    }
    const double step = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (!std::isfinite(step)) break;
    const Quat<double> next_q = turned(current, d);
    Mat3<double> next;
    to_matrix(next_q, next);
    // The check that keeps f rising.
    const double raised = inner(next, S);
    if (step < kFitStep * kFitStep) {
      if (raised >= sys.trace) {
        q = Eigen::Quaterniond(next_q.w, next_q.x, next_q.y, next_q.z);
        return as_matrix(next);
      }
      // Converged, and f fell by round-off only: keep the rotation it had.
      if (step < 1e-12) break;
    }
    current = next_q;
    std::memcpy(R, next, sizeof R);
  }
  q = Eigen::Quaterniond(current.w, current.x, current.y, current.z);
  return as_matrix(R);
}

// fit_rotation's first Newton step for two cells at once, one per lane:
// during the iterations nearly every fit ends there (1.002 steps a fit on
// the koala's stretch), and its chain of dependent operations, run for two
// cells side by side, takes about the time of one. A lane is done (true)
// when the step is the whole fit: H positive definite, a step shorter than
// kFitStep, f raised. Otherwise its q is left as it was, for fit_rotation.
void first_steps(const Eigen::Matrix3d* const S[2], Eigen::Quaterniond* const q[2], Eigen::Matrix3d* const out[2],
                 bool done[2]) {
  const Quat<Pair> current{{q[0]->w(), q[1]->w()}, {q[0]->x(), q[1]->x()}, {q[0]->y(), q[1]->y()},
                           {q[0]->z(), q[1]->z()}};
  Mat3<Pair> Sp, R, next;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) Sp[i][j] = Pair{(*S[0])(i, j), (*S[1])(i, j)};
  }
  to_matrix(current, R);
  const NewtonSystem<Pair> sys = newton_system(R, Sp);
  const Pair d[3] = {sys.adj_g[0] / sys.det, sys.adj_g[1] / sys.det, sys.adj_g[2] / sys.det};
  const Pair step = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const Quat<Pair> next_q = turned(current, d);
  to_matrix(next_q, next);
  const Pair raised = inner(next, Sp);
  for (int lane = 0; lane < 2; ++lane) {
    const double tiny = 1e-12 * S[lane]->cwiseAbs().sum();
    done[lane] = tiny > 0.0 && sys.h00[lane] > tiny && sys.minor2[lane] > tiny * tiny &&
                 sys.det[lane] > tiny * tiny * tiny && step[lane] < kFitStep * kFitStep &&
                 raised[lane] >= sys.trace[lane];
    if (!done[lane]) continue;
    *q[lane] = Eigen::Quaterniond(next_q.w[lane], next_q.x[lane], next_q.y[lane], next_q.z[lane]);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) (*out[lane])(i, j) = next[i][j][lane];
    }
  }
}

// Energy of one cell: sum w|e'|^2 - 2 tr(R^T S) + sum w|t|^2, S = sum w e' t^T
// (t the target edges), the last term precomputed (target_energy_).
inline double cell_energy(double edge_energy, const Eigen::Matrix3d& S, const Eigen::Matrix3d& R,
                          double target_energy) {
  return edge_energy - 2.0 * (R.array() * S.array()).sum() + target_energy;
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
  const int m = rest.num_triangles();
  spoke_edge_.resize(static_cast<Eigen::Index>(neighbors_.size()), 3);
  std::vector<double> fan_size(n_, 0.0);  // |tr C_i|, C_i = sum w e e^T over the cell
  for (int i = 0; i < n_; ++i) {
    for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
      const Eigen::RowVector3d e = rest.V.row(neighbors_[q]) - rest.V.row(i);
      spoke_edge_.row(q) = e;
      if (elements_ == ArapElements::Spokes) fan_size[i] += spoke_weight_[q] * e.squaredNorm();
    }
  }
  if (elements_ == ArapElements::Spokes) {
    // The triangle sides each spoke lies on (side 3t + k opposite corner k):
    // a spoke's target map is the mean of theirs. Kept as sides -> spokes
    // (CSR over sides), so that set_targets reads the maps in order: gathering
    // them per spoke was a random read of 72 bytes per side and spoke, a third
    // of a live preview's time at 26k vertices. Side a-b's spokes are a -> b
    // and b -> a, in increasing spoke order, found in the short sorted
    // neighbour lists of a and b: linear, where sorting the sides and the
    // (side, spoke) pairs took a seventh of the precompute (200k koala:
    // 1.53 -> 1.33 s natively).
    const auto spoke_of = [&](int from, int to) {
      const auto first = neighbors_.begin() + offsets_[from], last = neighbors_.begin() + offsets_[from + 1];
      const auto it = std::lower_bound(first, last, to);
      return it != last && *it == to ? static_cast<int>(it - neighbors_.begin()) : -1;
    };
    std::vector<int> sides_per_spoke(neighbors_.size(), 0);
    side_spoke_offsets_.assign(3 * static_cast<std::size_t>(m) + 1, 0);
    side_spokes_.clear();
    side_spokes_.reserve(6 * static_cast<std::size_t>(m));
    for (int t = 0; t < m; ++t) {
      for (int k = 0; k < 3; ++k) {
        const int a = rest.F(t, (k + 1) % 3), b = rest.F(t, (k + 2) % 3);
        if (a != b) {
          const int low = spoke_of(std::min(a, b), std::max(a, b)), high = spoke_of(std::max(a, b), std::min(a, b));
          for (const int q : {low, high}) {
            if (q < 0) continue;
            side_spokes_.push_back(q);
            ++sides_per_spoke[q];
          }
        }
        side_spoke_offsets_[3 * static_cast<std::size_t>(t) + k + 1] = static_cast<int>(side_spokes_.size());
      }
    }
    spoke_share_.assign(neighbors_.size(), 0.0);
    for (std::size_t q = 0; q < neighbors_.size(); ++q) {
      if (sides_per_spoke[q] > 0) spoke_share_[q] = 1.0 / sides_per_spoke[q];
    }
    // The identity's targets; the polar ones are made by set_targets,
    // the first to need them.
    spoke_target_ = spoke_edge_;
  } else {
    side_edge_.resize(3 * static_cast<Eigen::Index>(m), 3);
    for (int t = 0; t < m; ++t) {
      for (int k = 0; k < 3; ++k) {
        const Eigen::RowVector3d e = rest.V.row(rest.F(t, (k + 2) % 3)) - rest.V.row(rest.F(t, (k + 1) % 3));
        side_edge_.row(3 * t + k) = e;
        const double energy = weights.weight(t, k) * e.squaredNorm();
        for (int c = 0; c < 3; ++c) fan_size[rest.F(t, c)] += energy;
      }
    }
    side_target_ = side_edge_;
  }
  energy_scale_ = 0.0;
  for (int i = 0; i < n_; ++i) energy_scale_ += std::abs(fan_size[i]);
  target_energy_.resize(n_);
  update_target_energy();
  rotation_.assign(n_, Eigen::Quaterniond::Identity());
  rotation_matrices_.assign(n_, Eigen::Matrix3d::Identity());
  spoke_coupling_.resize(neighbors_.size());
  auto coupling_size = [&](int i) {
    const int degree = offsets_[i + 1] - offsets_[i];
    return degree > 0 ? std::abs(fan_size[i]) / degree : 0.0;
  };
  for (int i = 0; i < n_; ++i) {
    for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
      spoke_coupling_[q] = 0.5 * (coupling_size(i) + coupling_size(neighbors_[q]));
    }
  }
  // The local step's scratch, sized here: the solver is built in the
  // background (Deformer::prepare_step), and the first local step, a live
  // preview's first value, then writes into memory already touched.
  target_covariance_.resize(n_);
  polar_covariance_.resize(n_);
  edge_energy_.setZero(n_);
  laplacian_v_.setZero(n_, 3);
}

void AnArapSolver::set_targets(const SideTargets& T, bool polar_targets) {
  // The polar parts, once per side; P of a mean is taken as the mean of the
  // P's (equal where the sides' maps are, which is everywhere but at creases).
  // Consecutive sides often carry the very same map (the identity all over
  // the unselected part, one map per triangle where the weights are equal):
  // the last decomposition is reused for them, bit for bit the same P (1.2
  // million decompositions at 200k vertices were half of the set-up that is
  // not the factorization).
  polar_differs_ = false;
  Eigen::Matrix3d last_T, last_P;
  bool have_last = false;
  const auto polar_of = [&](const Eigen::Matrix3d& Ts) -> const Eigen::Matrix3d& {
    if (!polar_targets) return Ts;  // polar_differs_ stays false: never read
    if (have_last && std::memcmp(Ts.data(), last_T.data(), sizeof(double) * 9) == 0) return last_P;
    last_P = polar_positive_part(Ts);
    last_T = Ts;
    have_last = true;
    if ((last_P - Ts).cwiseAbs().maxCoeff() > 1e-12 * (1.0 + Ts.cwiseAbs().maxCoeff())) polar_differs_ = true;
    return last_P;
  };
  Eigen::Matrix3d maps[3];
  const int m = rest_.num_triangles();
  if (elements_ == ArapElements::Spokes) {
    // A spoke's map is the mean of its sides' maps: each side adds its share
    // of T e (a spoke on no side keeps the identity). In side order: the
    // spoke rows are written nearly in order (gathering the maps per spoke
    // read them at random, a third of a live preview's time at 26k vertices).
    // The polar targets are summed from the first side whose P differs from
    // its map on, the sides before it taken as their maps (their P's equal
    // them to 1e-12): a stretch has no such side and writes none (at 200k
    // vertices 29 MB, first touched by the commit, 3 % of it in WASM).
    spoke_target_.setZero(spoke_edge_.rows(), 3);
    bool summing_polar = false;
    for (int t = 0; t < m; ++t) {
      T(t, maps);
      for (int k = 0; k < 3; ++k) {
        const std::size_t s = 3 * static_cast<std::size_t>(t) + k;
        const Eigen::Matrix3d P = polar_of(maps[k]);
        if (polar_differs_ && !summing_polar) {
          spoke_polar_ = spoke_target_;
          summing_polar = true;
        }
        for (int j = side_spoke_offsets_[s]; j < side_spoke_offsets_[s + 1]; ++j) {
          const int q = side_spokes_[j];
          const Eigen::Vector3d e = spoke_share_[q] * spoke_edge_.row(q).transpose();
          spoke_target_.row(q) += (maps[k] * e).transpose();
          if (summing_polar) spoke_polar_.row(q) += (P * e).transpose();
        }
      }
    }
    for (std::size_t q = 0; q < spoke_share_.size(); ++q) {
      if (spoke_share_[q] != 0.0) continue;
      spoke_target_.row(q) = spoke_edge_.row(q);
      if (summing_polar) spoke_polar_.row(q) = spoke_edge_.row(q);
    }
  } else {
    side_polar_.resize(side_edge_.rows(), 3);
    for (int t = 0; t < m; ++t) {
      T(t, maps);
      for (int k = 0; k < 3; ++k) {
        const int s = 3 * t + k;
        const Eigen::Vector3d e = side_edge_.row(s).transpose();
        side_target_.row(s) = (maps[k] * e).transpose();
        side_polar_.row(s) = (polar_of(maps[k]) * e).transpose();
      }
    }
  }
  update_target_energy();
}

void AnArapSolver::set_identity_targets() {
  if (elements_ == ArapElements::Spokes) {
    spoke_target_ = spoke_edge_;
  } else {
    side_target_ = side_edge_;
  }
  // The polar targets are not read while polar_differs_ is false.
  polar_differs_ = false;
  update_target_energy();
}

namespace {

// A side's steps (AnArapSolver::set_scale_steps, set_shear_steps) for its
// share e of a target row's rest edge, its weight w and its triangle's
// frame u, v: w (u.e) u and w (v.e) v for the scales, w (v.e) u for a shear.
struct SideShare {
  int side;  // 3t + k
  double w;
  const Eigen::Vector3d& e;
  Eigen::Vector3d u, v;
  bool across_only = false;  // its triangle is square to the direction (Frames::along_normal)
  Eigen::Vector3d along() const {
    return across_only ? Eigen::Vector3d::Zero() : Eigen::Vector3d((w * u.dot(e)) * u);
  }
  // Across only: the edge's whole in-plane part (v's and u's), scaled by sv.
  Eigen::Vector3d across() const {
    return across_only ? Eigen::Vector3d(w * (v.dot(e) * v + u.dot(e) * u)) : Eigen::Vector3d((w * v.dot(e)) * v);
  }
  // v turned to `orientation`, the side's share of the shear taken
  // (oriented_frame, element_targets.cpp; shear_share, element_targets.h):
  // none across only.
  Eigen::Vector3d sheared(const Eigen::Vector3d& orientation) const {
    if (across_only) return Eigen::Vector3d::Zero();
    const Eigen::Vector3d oriented = v.dot(orientation) < 0.0 ? Eigen::Vector3d(-v) : v;
    return (w * shear_share(v, orientation) * oriented.dot(e)) * u;
  }
};

}  // namespace

template <typename Visit>
void AnArapSolver::visit_side_shares(const Positions& u, const Positions& v, const Eigen::VectorXd& side_weight,
                                     Visit&& visit, const std::vector<char>* along_normal) const {
  // Directly, not through a 3x3 map per side as set_targets takes them: no
  // map or polar part per side (a slider's first value cost 5x a later one
  // through set_targets with unit steps).
  for (int s = 0; s < 3 * rest_.num_triangles(); ++s) {
    if (side_weight[s] == 0.0) continue;
    const Eigen::Vector3d a = u.row(s / 3).transpose(), b = v.row(s / 3).transpose();
    const bool across_only = along_normal && (*along_normal)[static_cast<std::size_t>(s / 3)];
    if (elements_ == ArapElements::SpokesAndRims) {
      const Eigen::Vector3d e = side_edge_.row(s).transpose();
      visit(s, SideShare{s, side_weight[s], e, a, b, across_only});
      continue;
    }
    // A spoke's map is the mean of its sides' (set_targets): each side adds
    // its share.
    for (int k = side_spoke_offsets_[s]; k < side_spoke_offsets_[s + 1]; ++k) {
      const int q = side_spokes_[k];
      const Eigen::Vector3d e = spoke_share_[q] * spoke_edge_.row(q).transpose();
      visit(q, SideShare{s, side_weight[s], e, a, b, across_only});
    }
  }
}

Positions& AnArapSolver::zeroed_step(Positions& step) const {
  const Eigen::Index rows = elements_ == ArapElements::Spokes ? spoke_edge_.rows() : side_edge_.rows();
  step.setZero(rows, 3);
  return step;
}

Positions& AnArapSolver::rest_targets() {
  const bool spokes = elements_ == ArapElements::Spokes;
  Positions& target = spokes ? spoke_target_ : side_target_;
  target = spokes ? spoke_edge_ : side_edge_;
  return target;
}

void AnArapSolver::set_scale_steps(const Frames& frames, const Eigen::VectorXd& side_weight) {
  Positions& along = zeroed_step(scale_step_[0]);
  Positions& across = zeroed_step(scale_step_[1]);
  visit_side_shares(
      frames.u, frames.v, side_weight,
      [&](int row, const SideShare& side) {
        along.row(row) += side.along().transpose();
        across.row(row) += side.across().transpose();
      },
      &frames.along_normal);
}

void AnArapSolver::set_scale_targets(double su, double sv) {
  const bool spokes = elements_ == ArapElements::Spokes;
  Positions& target = spokes ? spoke_target_ : side_target_;
  const Positions& edge = spokes ? spoke_edge_ : side_edge_;
  target = edge + (su - 1.0) * scale_step_[0] + (sv - 1.0) * scale_step_[1];
  scale_targets_set();
}

void AnArapSolver::set_scale_targets(const Frames& frames, const Eigen::VectorXd& side_weight, double su,
                                     double sv) {
  Positions& target = rest_targets();
  visit_side_shares(
      frames.u, frames.v, side_weight,
      [&target, su, sv](int row, const SideShare& side) {
        target.row(row) += ((su - 1.0) * side.along() + (sv - 1.0) * side.across()).transpose();
      },
      &frames.along_normal);
  scale_targets_set();
}

void AnArapSolver::set_shear_steps(const Frames& frames, const Eigen::VectorXd& side_weight,
                                   const Eigen::Vector3d& orientation) {
  Positions& sheared = zeroed_step(shear_step_);
  visit_side_shares(
      frames.u, frames.v, side_weight,
      [&](int row, const SideShare& side) { sheared.row(row) += side.sheared(orientation).transpose(); },
      &frames.along_normal);
}

void AnArapSolver::set_shear_targets(double h) {
  const bool spokes = elements_ == ArapElements::Spokes;
  Positions& target = spokes ? spoke_target_ : side_target_;
  target = (spokes ? spoke_edge_ : side_edge_) + h * shear_step_;
  scale_targets_set();
}

void AnArapSolver::set_shear_targets(const Frames& frames, const Eigen::VectorXd& side_weight,
                                     const Eigen::Vector3d& orientation, double h) {
  Positions& target = rest_targets();
  visit_side_shares(
      frames.u, frames.v, side_weight,
      [&](int row, const SideShare& side) { target.row(row) += (h * side.sheared(orientation)).transpose(); },
      &frames.along_normal);
  scale_targets_set();
}

void AnArapSolver::set_rotation_targets(const Positions& axis, const Eigen::VectorXd& side_weight, double radians) {
  Positions& target = rest_targets();
  double last_w = 0.0, sine = 0.0, versine = 0.0;  // of the last side's angle
  visit_side_shares(axis, axis, side_weight, [&](int row, const SideShare& side) {
    if (side.w != last_w) {
      last_w = side.w;
      sine = std::sin(side.w * radians);
      versine = 1.0 - std::cos(side.w * radians);
    }
    const Eigen::Vector3d& a = side.u;  // the axis (given as both u and v)
    target.row(row) += (sine * a.cross(side.e) + versine * (a.dot(side.e) * a - side.e)).transpose();
  });
  scale_targets_set();
}

void AnArapSolver::set_twist_targets(const Positions& frames_u, const Eigen::VectorXd& side_weight,
                                     const TransformSpec& spec) {
  Positions& target = rest_targets();
  int last_side = -1;
  Eigen::Matrix3d jacobian;  // of the last side
  visit_side_shares(frames_u, frames_u, side_weight, [&](int row, const SideShare& side) {
    if (side.side != last_side) {  // a side's spokes come one after the other
      last_side = side.side;
      const int t = side.side / 3, k = side.side % 3;
      const Eigen::Vector3d midpoint =
          0.5 * (rest_.V.row(rest_.F(t, (k + 1) % 3)) + rest_.V.row(rest_.F(t, (k + 2) % 3))).transpose();
      jacobian = twist_jacobian(spec, side.w, midpoint);
    }
    target.row(row) += (jacobian * side.e - side.e).transpose();
  });
  scale_targets_set();
}

void AnArapSolver::scale_targets_set() {
  // Symmetric positive definite maps are their own polar parts, and a
  // shear's or a rotation's are read only by the paper's scheme, which takes
  // set_targets: the polar targets are not used (with_polar is false) until
  // set_targets sets them.
  polar_differs_ = false;
  update_target_energy();
}

void AnArapSolver::update_target_energy() {
  target_energy_.setZero();
  if (elements_ == ArapElements::Spokes) {
    target_sum_.setZero(n_, 3);
    for (int i = 0; i < n_; ++i) {
      for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
        target_energy_[i] += spoke_weight_[q] * spoke_target_.row(q).squaredNorm();
        target_sum_.row(i) += spoke_weight_[q] * spoke_target_.row(q);
      }
    }
    return;
  }
  for (int t = 0; t < rest_.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const double energy = weights_.weight(t, k) * side_target_.row(3 * t + k).squaredNorm();
      for (int c = 0; c < 3; ++c) target_energy_[rest_.F(t, c)] += energy;
    }
  }
}

void AnArapSolver::reset_rotations() {
  rotation_.assign(n_, Eigen::Quaterniond::Identity());
}

void AnArapSolver::warm_up(const LaplacianSolver& solver, const Frames& frames) {
  const Eigen::VectorXd every_side = Eigen::VectorXd::Ones(3 * rest_.num_triangles());
  set_scale_targets(frames, every_side, 1.0, 1.0);  // adds 0 * (the steps) to the rest edges
  // The steps are zeroed first: at 200k vertices 58 MB, whose page faults
  // were a third of a first preview.
  set_scale_steps(frames, every_side);
  local_step(rest_.V);
  Positions b, V = rest_.V;
  global_rhs(b);
  solver.solve(b, V);
  reset_rotations();
  rotation_matrices_.assign(n_, Eigen::Matrix3d::Identity());
}

void AnArapSolver::covariance_spokes(const Positions& V, bool with_polar, Eigen::VectorXd& edge_energy) {
  for (int i = 0; i < n_; ++i) {
    Eigen::Matrix3d full = Eigen::Matrix3d::Zero(), polar = Eigen::Matrix3d::Zero();
    Eigen::Vector3d pull = Eigen::Vector3d::Zero();  // sum w (v_j - v_i) = -(L V)_i
    double energy = 0.0;
    const Eigen::RowVector3d vi = V.row(i);
    for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
      const Eigen::Vector3d deformed = (V.row(neighbors_[q]) - vi).transpose();
      const Eigen::Vector3d weighted = spoke_weight_[q] * deformed;
      full.noalias() += weighted * spoke_target_.row(q);
      if (with_polar) polar.noalias() += weighted * spoke_polar_.row(q);
      energy += weighted.dot(deformed);
      pull += weighted;
    }
    target_covariance_[i] = full;
    if (with_polar) polar_covariance_[i] = polar;
    edge_energy[i] = energy;
    laplacian_v_.row(i) = -pull.transpose();
  }
}

void AnArapSolver::covariance_spokes_rims(const Positions& V, bool with_polar, Eigen::VectorXd& edge_energy) {
  std::fill(target_covariance_.begin(), target_covariance_.end(), Eigen::Matrix3d::Zero());
  laplacian_v_.setZero();
  if (with_polar) std::fill(polar_covariance_.begin(), polar_covariance_.end(), Eigen::Matrix3d::Zero());
  edge_energy.setZero();
  for (int t = 0; t < rest_.num_triangles(); ++t) {
    Eigen::Matrix3d full = Eigen::Matrix3d::Zero(), polar = Eigen::Matrix3d::Zero();
    double energy = 0.0;
    for (int k = 0; k < 3; ++k) {
      const int a = rest_.F(t, (k + 1) % 3), b = rest_.F(t, (k + 2) % 3);
      const Eigen::Vector3d deformed = (V.row(b) - V.row(a)).transpose();
      const double w = weights_.weight(t, k);
      full.noalias() += (w * deformed) * side_target_.row(3 * t + k);
      if (with_polar) polar.noalias() += (w * deformed) * side_polar_.row(3 * t + k);
      energy += w * deformed.squaredNorm();
      laplacian_v_.row(a) -= w * deformed.transpose();
      laplacian_v_.row(b) += w * deformed.transpose();
    }
    for (int k = 0; k < 3; ++k) {
      target_covariance_[rest_.F(t, k)] += full;
      if (with_polar) polar_covariance_[rest_.F(t, k)] += polar;
      edge_energy[rest_.F(t, k)] += energy;
    }
  }
}

double AnArapSolver::local_step(const Positions& V) { return local_step(V, rotation_); }

double AnArapSolver::local_step(const Positions& V, const std::vector<Eigen::Quaterniond>& start) {
  // Each fit starts from start[i], copied into rotation_ as the fit reaches it.
  const bool elsewhere = &start != &rotation_;
  Eigen::VectorXd& edge_energy = edge_energy_;
  target_covariance_.resize(n_);
  polar_covariance_.resize(n_);
  edge_energy.resize(n_);
  laplacian_v_.resize(n_, 3);
  // The paper's scheme fits the rotations to the polar targets; where those
  // are the targets (no rotational part), or with coupled rotations (fitted
  // to the whole targets), the polar covariance is not needed.
  const bool with_polar = coupling_ == 0.0 && polar_differs_;
  if (elements_ == ArapElements::Spokes) {
    covariance_spokes(V, with_polar, edge_energy);
  } else {
    covariance_spokes_rims(V, with_polar, edge_energy);
  }
  // Each cell's energy is added in index order, right after its rotation's
  // fit (its S and R still in cache: a pass of its own read them again,
  // 29 MB a local step at 200k vertices); the coupled sweep adds its own.
  // Negative cotangent weights (obtuse triangles) can make this sum slightly
  // negative near the optimum: it is reported as it is.
  double energy = 0.0;
  const auto add_cell = [&](int i) {
    energy += cell_energy(edge_energy[i], target_covariance_[i], rotation_matrices_[i], target_energy_[i]);
  };
  if (coupling_ > 0.0) {
    if (elsewhere) rotation_ = start;
    energy = coupled_rotations();
  } else {
    const std::vector<Eigen::Matrix3d>& fitted = with_polar ? polar_covariance_ : target_covariance_;
    int i = 0;
    for (; i + 1 < n_; i += 2) {
      if (elsewhere) {
        rotation_[i] = start[i];
        rotation_[i + 1] = start[i + 1];
      }
      const Eigen::Matrix3d* const S[2] = {&fitted[i], &fitted[i + 1]};
      Eigen::Quaterniond* const q[2] = {&rotation_[i], &rotation_[i + 1]};
      Eigen::Matrix3d* const out[2] = {&rotation_matrices_[i], &rotation_matrices_[i + 1]};
      bool done[2];
      first_steps(S, q, out, done);
      for (int lane = 0; lane < 2; ++lane) {
        if (!done[lane]) *out[lane] = fit_rotation(*S[lane], *q[lane]);
      }
      add_cell(i);
      add_cell(i + 1);
    }
    for (; i < n_; ++i) {
      if (elsewhere) rotation_[i] = start[i];
      rotation_matrices_[i] = fit_rotation(fitted[i], rotation_[i]);
      add_cell(i);
    }
  }
  return energy;
}

double AnArapSolver::coupled_rotations() {
  // In index order, each R_i against its neighbours' latest rotations (as
  // matrices, each converted once per sweep and again when it changes).
  std::vector<Eigen::Matrix3d>& R = rotation_matrices_;
  for (int i = 0; i < n_; ++i) R[i] = rotation_[i].toRotationMatrix();
  // The energy is added as the sweep goes, while the cell's values are in
  // cache: the cell's own right after its fit, a spoke's coupling at the
  // later of its ends (both fitted by then), twice, for its two directions
  // (k_ij = k_ji). Passes of their own after the sweep read every cell and
  // every spoke again.
  double energy = 0.0;
  for (int i = 0; i < n_; ++i) {
    Eigen::Matrix3d S = target_covariance_[i];
    for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
      S.noalias() += (2.0 * coupling_ * spoke_coupling_[q]) * R[neighbors_[q]];
    }
    R[i] = fit_rotation(S, rotation_[i]);
    energy += cell_energy(edge_energy_[i], target_covariance_[i], R[i], target_energy_[i]);
    for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
      const int j = neighbors_[q];
      if (j >= i) continue;
      // |R_i - R_j|^2 = 6 - 2 tr(R_i^T R_j); tr of a rotation = 4 w^2 - 1 of
      // the quaternion q_i^-1 q_j.
      const double w = rotation_[i].dot(rotation_[j]);
      energy += 2.0 * coupling_ * spoke_coupling_[q] * (6.0 - 2.0 * (4.0 * w * w - 1.0));
    }
  }
  return energy;
}

void AnArapSolver::global_rhs(Positions& b) const {
  const std::vector<Eigen::Matrix3d>& R = rotation_matrices_;
  if (elements_ == ArapElements::Spokes) {
    b.resize(n_, 3);  // every row is written below
    // b_i = -1/2 sum_j w_ij (R_i + R_j) t_ij: a spoke's target t_ij = T_ij e_ij
    // is the same map seen from both ends (t_ji = -t_ij). The R_i part is R_i
    // times the cell's weighted target sum, which changes with the targets only.
    for (int i = 0; i < n_; ++i) {
      Eigen::Vector3d acc = R[i] * target_sum_.row(i).transpose();
      for (int q = offsets_[i]; q < offsets_[i + 1]; ++q) {
        acc.noalias() += R[neighbors_[q]] * (spoke_weight_[q] * spoke_target_.row(q).transpose());
      }
      b.row(i) = -0.5 * acc.transpose();
    }
    return;
  }
  b.setZero(n_, 3);
  for (int t = 0; t < rest_.num_triangles(); ++t) {
    const Eigen::Matrix3d M = (R[rest_.F(t, 0)] + R[rest_.F(t, 1)] + R[rest_.F(t, 2)]) / 3.0;
    for (int k = 0; k < 3; ++k) {
      const int a = rest_.F(t, (k + 1) % 3), c = rest_.F(t, (k + 2) % 3);
      // The side's rest edge runs a -> c; v_a - v_c is its negative.
      const Eigen::Vector3d d = -weights_.weight(t, k) * (M * side_target_.row(3 * t + k).transpose());
      b.row(a) += d.transpose();
      b.row(c) -= d.transpose();
    }
  }
}

bool AnArapSolver::converged(double previous, double energy, double tolerance, bool accelerated,
                             int& small_steps) {
  // Accelerated iterations stop after this many energy changes below the
  // tolerance in a row (plain ones after one): an accelerated step that
  // happened to gain little is no sign of convergence by itself.
  constexpr int kAcceleratedSmallSteps = 3;
  // Relative change, measured against the energy's own size but never
  // against less than a 1e-12 part of the fans' rest size, so that an exact
  // solution (energy ~ 0) stops too.
  const double reference = std::max(std::abs(previous), 1e-12 * energy_scale_);
  // At an exact solution (energy at the floor: nothing to do, an identity
  // edit) accelerated steps only stir rounding noise, so that counts as
  // small too.
  const bool at_floor = accelerated && std::abs(energy) <= 1e-12 * energy_scale_;
  const bool small = std::abs(previous - energy) <= tolerance * reference || at_floor;
  small_steps = small ? small_steps + 1 : 0;
  settled_ = tolerance >= 0.0 && small_steps >= (accelerated ? kAcceleratedSmallSteps : 1);
  return settled_;
}

int AnArapSolver::run(const LaplacianSolver& solver, Positions& V, int max_iterations,
                        double tolerance, std::vector<double>& history, bool final_energy,
                        Acceleration acceleration, const std::function<void(int)>& on_iteration) {
  settled_ = false;
  // L-BFGS's gradient L V - b(R) is E's only where R is fitted exactly to V.
  // Coupled rotations are fitted by one Gauss-Seidel sweep from the last
  // ones, so there its model is off and its steps erratic (a twist's native
  // and WASM replays differed by 5.6e-4 of the diagonal; with Anderson by
  // 5e-13): those iterations are Anderson accelerated, on the rotations
  // (run_coupled).
  if (acceleration == Acceleration::Lbfgs && coupling_ > 0.0) acceleration = Acceleration::Anderson;
  if (acceleration == Acceleration::Anderson && coupling_ > 0.0) {
    return run_coupled(solver, V, max_iterations, tolerance, history, final_energy, on_iteration);
  }
  if (acceleration == Acceleration::Lbfgs) {
    return run_lbfgs(solver, V, max_iterations, tolerance, history, final_energy, on_iteration);
  }
  const bool accelerate = acceleration == Acceleration::Anderson;
  Positions b, g, proposal;
  AndersonMixer mixer(kAndersonWindow);
  std::vector<Eigen::Quaterniond> kept_rotations;
  double previous = local_step(V);
  int iterations = 0, small_steps = 0;
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
    if (on_iteration) on_iteration(iterations);
    if (converged(previous, energy, tolerance, accelerate, small_steps)) break;
    previous = energy;
  }
  return iterations;
}

int AnArapSolver::run_coupled(const LaplacianSolver& solver, Positions& V, int max_iterations, double tolerance,
                              std::vector<double>& history, bool final_energy,
                              const std::function<void(int)>& on_iteration) {
  // The rotations as one n by 4 block (Eigen's coefficient order x, y, z, w),
  // the mixer's state.
  using Quaternions = RotationMixer::StateType;
  static_assert(sizeof(Eigen::Quaterniond) == 4 * sizeof(double), "rotation_ is read as n by 4 doubles");
  if (n_ == 0) return 0;
  const auto rotations = [this] { return Eigen::Map<const Quaternions>(rotation_.front().coeffs().data(), n_, 4); };
  RotationMixer mixer(kAndersonWindow);
  Positions b, g;
  // x: the rotations the next sweep starts from (the mixer's x_k). The sweep
  // output G(x_k) it is mixed with stays in rotation_ until a proposal takes
  // its place; it is then swapped aside into accepted_rotations, for the
  // safeguard, rather than copied.
  Quaternions x, proposal;
  std::vector<Eigen::Quaterniond> accepted_rotations(n_);
  double accepted = local_step(V);
  x = rotations();
  bool proposed = false;  // rotation_ holds a mixed proposal, not yet known to lower E
  int iterations = 0, small_steps = 0;
  for (int it = 0; it < max_iterations; ++it) {
    global_rhs(b);
    g = V;
    solver.solve(b, g);
    if (!final_energy && it + 1 == max_iterations) {
      V = g;
      history.push_back(accepted);
      return ++iterations;
    }
    double energy = local_step(g);  // G(x): the sweep from x at L^-1 b(x)
    if (proposed && !(energy < accepted)) {
      // The safeguard: the plain iteration from the accepted rotations, as
      // they were (not normalized again).
      rotation_.swap(accepted_rotations);
      for (int i = 0; i < n_; ++i) rotation_matrices_[i] = rotation_[i].toRotationMatrix();
      mixer.reset();
      global_rhs(b);
      g = V;
      solver.solve(b, g);
      x = rotations();
      energy = local_step(g);
    }
    V.swap(g);
    history.push_back(energy);
    ++iterations;
    if (on_iteration) on_iteration(iterations);
    if (converged(accepted, energy, tolerance, true, small_steps)) break;
    accepted = energy;
    // A proposal only where the next iteration checks it: not after the last
    // one (the rotations stay those V was fitted with, which a warm start
    // goes on from), nor before a preview's last, which skips the check.
    const bool checked = it + 1 < max_iterations && (final_energy || it + 2 < max_iterations);
    proposed = mixer.propose(x, rotations(), proposal) && checked;
    if (!proposed) {
      x = rotations();
      continue;
    }
    // The proposal, normalized row by row, becomes the rotations and the
    // next x in one pass; a quaternion that mixed to nothing keeps its
    // accepted rotation.
    accepted_rotations.swap(rotation_);
    for (int i = 0; i < n_; ++i) {
      const Eigen::Vector4d q = proposal.row(i).transpose();
      const double norm = q.norm();
      if (norm > 1e-8 && std::isfinite(norm)) {
        rotation_[i].coeffs() = q / norm;
      } else {
        rotation_[i] = accepted_rotations[i];
      }
      x.row(i) = rotation_[i].coeffs().transpose();
      rotation_matrices_[i] = rotation_[i].toRotationMatrix();
    }
  }
  return iterations;
}

}  // namespace aniso
