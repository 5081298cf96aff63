// The local/global iterations of the anisotropic ARAP parameterization
// (Liu et al. 2008 with the target T_t of METHOD §8), with the fold guard.
//
// Edge k of triangle t runs from corner k+1 to corner k+2 (mod 3), opposite
// corner k, so its weight is CotanWeights::weight(t, k): the energy uses
// exactly the weights the prefactored Laplacian was assembled from, and the
// global step is its exact minimizer for fixed rotations.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "anisoform/error.h"
#include "flatten/flatten_pipeline.h"
#include "anisoform/laplacian.h"
#include "geometry/laplacian_solver.h"

namespace aniso {

namespace {

// Below this fraction of the energy scale (sum of w |T x|^2) the map is exact
// to round-off; a relative change is meaningless there.
constexpr double kExactEnergyFraction = 1e-24;
// The guard stops (stalled) when the fold-free part of a step is below this.
constexpr double kMinStepFraction = 1e-12;
// Shortened steps in a row without relative progress above the tolerance
// after which the guard stops (stalled).
constexpr int kMaxStagnantSteps = 10;
// One vertex per component: the global step is free up to a translation
// per component (the rotations come from the local step).
std::vector<int> one_pin_per_component(const FlattenPatch& patch) {
  std::vector<int> pins(patch.num_components, -1);
  for (int i = 0; i < patch.mesh.num_vertices(); ++i) {
    if (pins[patch.component[i]] < 0) pins[patch.component[i]] = i;
  }
  return pins;
}

}  // namespace

struct ArapFlattening::Impl {
  Triangles F;
  TriangleCharts charts;
  Eigen::MatrixX3d weight;  // #T by 3 half-cotangent weights
  std::unique_ptr<LaplacianSolver> solver;

  // The target edges T_t x_k, #T by 6 (edge k at columns 2k, 2k+1).
  Eigen::MatrixXd target_edges(const FlattenTargets& targets) const {
    const int m = static_cast<int>(F.rows());
    const Eigen::MatrixXd& corners = charts.corners;
    Eigen::MatrixXd q(m, 6);
    for (int t = 0; t < m; ++t) {
      const Eigen::Vector2d cu = targets.direction.row(t);
      const Eigen::Vector2d cv(-cu.y(), cu.x());
      const Eigen::Matrix2d T =
          targets.su[t] * cu * cu.transpose() + targets.sv[t] * cv * cv.transpose();
      for (int k = 0; k < 3; ++k) {
        const int p = (k + 1) % 3, r = (k + 2) % 3;
        const Eigen::Vector2d x(corners(t, 2 * r) - corners(t, 2 * p),
                                corners(t, 2 * r + 1) - corners(t, 2 * p + 1));
        q.block<1, 2>(t, 2 * k) = (T * x).transpose();
      }
    }
    return q;
  }

  // Local step: the best rotation per triangle (cos, sin in #T by 2), and the
  // energy of uv with them.
  double fit_rotations(const Eigen::MatrixXd& q, const Eigen::MatrixX2d& uv,
                       Eigen::MatrixX2d& rotation) const {
    double energy = 0.0;
    for (int t = 0; t < F.rows(); ++t) {
      Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
      Eigen::Vector2d edge[3];
      for (int k = 0; k < 3; ++k) {
        edge[k] = (uv.row(F(t, (k + 2) % 3)) - uv.row(F(t, (k + 1) % 3))).transpose();
        S += weight(t, k) * edge[k] * q.block<1, 2>(t, 2 * k);
      }
      // argmax over SO(2) of tr(R^T S) = c (S00 + S11) + s (S10 - S01): the
      // angle atan2(S10 - S01, S00 + S11), taken as a normalized vector (no
      // trigonometry); always a proper rotation.
      const double along = S(0, 0) + S(1, 1), across = S(1, 0) - S(0, 1);
      const double length = std::hypot(along, across);
      const double c = length > 0.0 ? along / length : 1.0;
      const double s = length > 0.0 ? across / length : 0.0;
      rotation.row(t) = Eigen::RowVector2d(c, s);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d target(c * q(t, 2 * k) - s * q(t, 2 * k + 1),
                                     s * q(t, 2 * k) + c * q(t, 2 * k + 1));
        energy += weight(t, k) * (edge[k] - target).squaredNorm();
      }
    }
    return energy;
  }

  // Global step: L u = b, b_i = sum over edges (i -> j) of -w R q, b_j += w R q.
  void solve_positions(const Eigen::MatrixXd& q, const Eigen::MatrixX2d& rotation,
                       Eigen::MatrixXd& uv) const {
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(uv.rows(), 2);
    for (int t = 0; t < F.rows(); ++t) {
      const double c = rotation(t, 0), s = rotation(t, 1);
      for (int k = 0; k < 3; ++k) {
        const Eigen::RowVector2d rotated(c * q(t, 2 * k) - s * q(t, 2 * k + 1),
                                         s * q(t, 2 * k) + c * q(t, 2 * k + 1));
        const Eigen::RowVector2d pull = weight(t, k) * rotated;
        rhs.row(F(t, (k + 1) % 3)) -= pull;
        rhs.row(F(t, (k + 2) % 3)) += pull;
      }
    }
    solver->solve(rhs, uv);
  }
};

ArapFlattening::ArapFlattening(const FlattenPatch& patch, const TriangleCharts& charts)
    : impl_(std::make_unique<Impl>()) {
  impl_->F = patch.mesh.F;
  const CotanWeights weights = cotangent_weights(patch.mesh);
  impl_->weight = weights.weight;
  impl_->solver = std::make_unique<LaplacianSolver>(cotangent_laplacian(patch.mesh, weights),
                                                    one_pin_per_component(patch));
  impl_->charts = charts;
  factorizations_ = 1;
}

ArapFlattening::~ArapFlattening() = default;

const LaplacianSolver& ArapFlattening::laplacian() const { return *impl_->solver; }

ArapFlattenReport ArapFlattening::solve(const FlattenTargets& targets,
                                        const ArapFlattenSettings& settings,
                                        Eigen::MatrixX2d& uv) const {
  const Impl& im = *impl_;
  if (targets.direction.rows() != im.F.rows() || uv.rows() != im.solver->num_vertices()) {
    fail(ErrorCode::BadParameter, "the targets or the start map do not match the patch");
  }
  const Eigen::MatrixXd q = im.target_edges(targets);
  double energy_scale = 0.0;
  for (int t = 0; t < im.F.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      energy_scale += std::abs(im.weight(t, k)) * q.block<1, 2>(t, 2 * k).squaredNorm();
    }
  }
  const double exact_energy = kExactEnergyFraction * energy_scale;

  ArapFlattenReport report;
  Eigen::MatrixX2d rotation(im.F.rows(), 2);
  double energy = im.fit_rotations(q, uv, rotation);
  report.energy_history.push_back(energy);
  int folded = count_folded(im.F, im.charts, uv);
  Eigen::MatrixXd candidate(uv.rows(), 2);
  int stagnant_steps = 0;
  while (report.iterations < settings.max_iterations) {
    if (folded > 0 && report.iterations >= settings.unfold_iterations) break;
    if (energy <= exact_energy) {
      report.converged = true;
      break;
    }
    candidate = uv;  // the pinned rows keep their place
    im.solve_positions(q, rotation, candidate);
    if (!candidate.allFinite()) {
      fail(ErrorCode::Numerical, "the flattening's global step produced a non-finite position");
    }
    // The guard: from a fold-free map, take only fold-free steps. For fixed
    // rotations the energy is a convex quadratic minimized at the candidate,
    // so every shortened step still lowers it (the iteration stays monotone).
    const bool guarded = settings.guard_folds && folded == 0;
    bool shortened = false;
    if (guarded) {
      const double fraction = fold_free_step_fraction(im.F, im.charts, uv, candidate);
      if (fraction < 1.0) {
        if (!(fraction > kMinStepFraction)) {
          report.stalled = true;
          break;
        }
        const Eigen::MatrixX2d step = candidate - uv;
        candidate = uv + fraction * step;
        // Round-off near a root: halve until the count agrees.
        for (double f = 0.5 * fraction; count_folded(im.F, im.charts, candidate) > 0; f *= 0.5) {
          if (!(f > kMinStepFraction)) {
            candidate = uv;
            break;
          }
          candidate = uv + f * step;
        }
        shortened = true;
        ++report.shortened_steps;
      }
    }
    uv = candidate;
    if (!guarded) folded = count_folded(im.F, im.charts, uv);
    const double previous = energy;
    energy = im.fit_rotations(q, uv, rotation);
    ++report.iterations;
    report.energy_history.push_back(energy);
    if (settings.progress && !settings.progress(report.iterations, energy)) break;
    const bool small_change = previous - energy <= settings.tolerance * previous;
    if ((!shortened && small_change) || energy <= exact_energy) {
      report.converged = true;
      break;
    }
    // A shortened step's small change says nothing about convergence (the
    // step was small), but many in a row mean a triangle near zero area
    // blocks every step: the guard has reached what it can.
    stagnant_steps = shortened && small_change ? stagnant_steps + 1 : 0;
    if (stagnant_steps >= kMaxStagnantSteps) {
      report.stalled = true;
      break;
    }
  }
  report.energy = energy;
  report.folded = count_folded(im.F, im.charts, uv);
  return report;
}

}  // namespace aniso
