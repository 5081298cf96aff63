// The local/global iterations of the anisotropic ARAP parameterization
// (Liu et al. 2008 with the target T_t of METHOD §8), with the fold guard.
//
// Edge k of triangle t runs from corner k+1 to corner k+2 (mod 3), opposite
// corner k, so its weight is CotanWeights::weight(t, k): the energy uses
// exactly the weights the prefactored Laplacian was assembled from, and the
// global step is its exact minimizer for fixed rotations.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "anisoform/error.h"
#include "base/lbfgs_memory.h"
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
// L-BFGS (run_lbfgs): pairs kept and the halvings of a step that raised the
// energy, as AnARAP's (deform/anarap_lbfgs.cpp measured them), the largest
// scale of H0 = scale L^-1 (AnARAP's 3 measured no better here: cyl50k 9 ->
// 10 iterations to 1e-6, the open bunny 22 -> 33, hemisphere 12 either way)
// and the small changes in a row that end the iterations.
constexpr int kFlattenMemory = 5;
constexpr double kFlattenMaxScale = 2.0;
constexpr int kFlattenHalvings = 2;
constexpr int kFlattenQuietSteps = 3;
// The per-triangle arrays the iterations stream through, one row per
// triangle, and the map the local step, the right-hand side and the
// gradient gather corners from, one row per vertex (a row-major copy): a
// triangle's values then share a cache line, where column-major Eigen
// matrices spread them over one line per column (the local step touched 12
// lines per triangle; 38 % of the flatten benchmark's profile, 23 % now).
// The same values in the same order: bit for bit the iterations they were.
using TargetEdges = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;  // T_t x_k, edge k at 2k, 2k+1
using Rotations = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;    // cos, sin per triangle
using EdgeWeights = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

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
  EdgeWeights weight;  // #T by 3 half-cotangent weights
  std::unique_ptr<LaplacianSolver> solver;

  // The target edges T_t x_k, #T by 6 (edge k at columns 2k, 2k+1).
  TargetEdges target_edges(const FlattenTargets& targets) const {
    const int m = static_cast<int>(F.rows());
    const Eigen::MatrixXd& corners = charts.corners;
    TargetEdges q(m, 6);
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
  template <typename Map>
  double fit_rotations(const TargetEdges& q, const Map& map, Rotations& rotation) const {
    const UvRows uv = map;
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
      // The square root of the squares, and std::hypot only where they over-
      // or underflow: glibc's exactly rounded hypot took a tenth of the
      // flattening's time.
      const double squares = along * along + across * across;
      const double length = squares > std::numeric_limits<double>::min() &&
                                    squares < std::numeric_limits<double>::infinity()
                                ? std::sqrt(squares)
                                : std::hypot(along, across);
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

  // The global step's right-hand side: L u = b, b_i = sum over edges
  // (i -> j) of -w R q, b_j += w R q.
  Eigen::MatrixXd global_rhs(const TargetEdges& q, const Rotations& rotation, int num_vertices) const {
    UvRows rhs = UvRows::Zero(num_vertices, 2);
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
    return Eigen::MatrixXd(rhs);
  }

  // E's gradient for the rotations fitted to uv (up to a factor 2): L uv - b,
  // zero on the pinned rows. L is assembled from the very weights of the
  // energy, edge by edge.
  template <typename Map>
  Eigen::MatrixXd energy_gradient(const Map& map, const Eigen::MatrixXd& rhs) const {
    const UvRows uv = map;
    UvRows g = -rhs;
    for (int t = 0; t < F.rows(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const int a = F(t, (k + 1) % 3), b = F(t, (k + 2) % 3);
        const Eigen::RowVector2d pull = weight(t, k) * (uv.row(a) - uv.row(b));
        g.row(a) += pull;
        g.row(b) -= pull;
      }
    }
    for (const int p : solver->pinned()) g.row(p).setZero();
    return Eigen::MatrixXd(g);
  }

  // The fold guard: moves `candidate` back towards the fold-free `uv` until
  // no triangle folds on the way. Returns false if only a vanishing part of
  // the step is fold-free (the guard has stalled); `shortened` says whether
  // the step was cut.
  bool guard_step(const Eigen::MatrixX2d& uv, Eigen::MatrixXd& candidate, bool& shortened) const {
    shortened = false;
    const double fraction = fold_free_step_fraction(F, charts, uv, candidate);
    if (!(fraction < 1.0)) return true;
    if (!(fraction > kMinStepFraction)) return false;
    const Eigen::MatrixX2d step = candidate - uv;
    candidate = uv + fraction * step;
    // Round-off near a root: halve until the count agrees.
    for (double f = 0.5 * fraction; count_folded(F, charts, candidate) > 0; f *= 0.5) {
      if (!(f > kMinStepFraction)) {
        candidate = uv;
        break;
      }
      candidate = uv + f * step;
    }
    shortened = true;
    return true;
  }

  // Plain local/global iterations (the paper's). Returns the last energy.
  double run_plain(const TargetEdges& q, const ArapFlattenSettings& settings, double exact_energy,
                   int folded, Eigen::MatrixX2d& uv, Rotations& rotation, double energy,
                   ArapFlattenReport& report) const {
    Eigen::MatrixXd candidate(uv.rows(), 2);
    int stagnant_steps = 0;
    while (report.iterations < settings.max_iterations) {
      if (folded > 0 && report.iterations >= settings.unfold_iterations) break;
      if (energy <= exact_energy) {
        report.converged = true;
        break;
      }
      candidate = uv;  // the pinned rows keep their place
      solver->solve(global_rhs(q, rotation, static_cast<int>(uv.rows())), candidate);
      if (!candidate.allFinite()) {
        fail(ErrorCode::Numerical, "the flattening's global step produced a non-finite position");
      }
      // The guard: from a fold-free map, take only fold-free steps. For fixed
      // rotations the energy is a convex quadratic minimized at the candidate,
      // so every shortened step still lowers it (the iteration stays monotone).
      const bool guarded = settings.guard_folds && folded == 0;
      bool shortened = false;
      if (guarded && !guard_step(uv, candidate, shortened)) {
        report.stalled = true;
        break;
      }
      if (shortened) ++report.shortened_steps;
      uv = candidate;
      if (!guarded) folded = count_folded(F, charts, uv);
      const double previous = energy;
      energy = fit_rotations(q, uv, rotation);
      ++report.iterations;
      report.energy_history.push_back(energy);
      if (settings.progress && !settings.progress(report.iterations, energy)) break;
      const bool small_change = small_decrease(previous, energy, settings.tolerance);
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
    return energy;
  }

  // L-BFGS on the ARAP energy from a fold-free map, as AnARAP's
  // (deform/anarap_lbfgs.cpp says why and how): H0 = scale L^-1 with the
  // prefactored Laplacian, so a step without pairs is exactly the plain one.
  // Every step goes through the fold guard and is kept only if the energy
  // falls (halved up to kFlattenHalvings times, else the plain step from the last
  // rotations, which never raises it). Returns the last energy.
  double run_lbfgs(const TargetEdges& q, const ArapFlattenSettings& settings, double exact_energy,
                   Eigen::MatrixX2d& uv, Rotations& rotation, double energy,
                   ArapFlattenReport& report) const {
    const int n = static_cast<int>(uv.rows());
    Eigen::MatrixXd rhs = global_rhs(q, rotation, n);
    Eigen::MatrixXd gradient = energy_gradient(uv, rhs);
    LbfgsMemory<Eigen::MatrixXd> memory(kFlattenMemory);
    double scale = 1.0;
    const auto apply_h0 = [&](const Eigen::MatrixXd& v, Eigen::MatrixXd& r) {  // L^-1 v
      r = Eigen::MatrixXd::Zero(n, 2);
      solver->solve(v, r);
    };
    int quiet_steps = 0, stagnant_steps = 0;
    Eigen::MatrixXd direction, trial(n, 2);
    while (report.iterations < settings.max_iterations) {
      if (energy <= exact_energy) {
        report.converged = true;
        break;
      }
      // direction = -H gradient (zero on the pins).
      memory.direction(gradient, direction, trial, apply_h0, scale);
      const Rotations kept_rotation = rotation;
      bool shortened = false;
      trial = uv + direction;
      if (!trial.allFinite()) {
        fail(ErrorCode::Numerical, "the flattening's global step produced a non-finite position");
      }
      bool moved = guard_step(uv, trial, shortened);
      double trial_energy = fit_rotations(q, trial, rotation);
      for (int h = 0; h < kFlattenHalvings && moved && !(trial_energy < energy) && !memory.empty(); ++h) {
        trial = uv + (trial - uv) * 0.5;  // on the fold-free segment already checked
        trial_energy = fit_rotations(q, trial, rotation);
      }
      if (!(moved && trial_energy < energy) && !memory.empty()) {
        // The plain step from the last rotations (rhs is theirs).
        rotation = kept_rotation;
        memory.clear();
        scale = 1.0;
        trial = uv;
        solver->solve(rhs, trial);
        moved = guard_step(uv, trial, shortened);
        trial_energy = fit_rotations(q, trial, rotation);
      }
      if (!moved) {
        rotation = kept_rotation;
        report.stalled = true;
        break;
      }
      if (shortened) ++report.shortened_steps;
      Eigen::MatrixXd next_rhs = global_rhs(q, rotation, n);
      Eigen::MatrixXd next_gradient = energy_gradient(trial, next_rhs);
      if (shortened) {
        // A step the guard cut short keeps no pair, and the next step is the
        // plain one: near a fold the quasi-Newton model aims past the
        // triangle about to fold, the guard cuts every step short, and the
        // iterations stall where that triangle blocks them. Plain steps
        // stalled lower (the whole open mesh, su 0.8 along its longest
        // axis, to 1e-6): with pairs kept the hand ended 3.3 % above
        // plain's energy (the guard cut every step), spothead 0.046 % and
        // demosthenes 0.11 %; now the hand ends at plain's energy,
        // spothead and demosthenes 0.043 % and 0.059 % above it (their
        // first steps, not cut, differ). Patches the guard never cuts
        // iterate as before.
        memory.clear();
        scale = 1.0;
      } else {
        const double curvature_ratio = memory.push_step(uv, trial, gradient, next_gradient, rhs, next_rhs);
        if (curvature_ratio > 0.0) scale = std::clamp(curvature_ratio, 1.0, kFlattenMaxScale);
      }
      uv = trial;
      rhs.swap(next_rhs);
      gradient.swap(next_gradient);
      const double previous = energy;
      energy = trial_energy;
      ++report.iterations;
      report.energy_history.push_back(energy);
      if (settings.progress && !settings.progress(report.iterations, energy)) break;
      // As the plain loop's rule, with kFlattenQuietSteps small changes in a row:
      // one quasi-Newton step that happened to gain little is no sign of
      // convergence by itself.
      const bool small_change = small_decrease(previous, energy, settings.tolerance);
      quiet_steps = small_change && !shortened ? quiet_steps + 1 : 0;
      stagnant_steps = small_change && shortened ? stagnant_steps + 1 : 0;
      if (quiet_steps >= kFlattenQuietSteps || energy <= exact_energy) {
        report.converged = true;
        break;
      }
      if (stagnant_steps >= kMaxStagnantSteps) {
        report.stalled = true;
        break;
      }
    }
    return energy;
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

const std::vector<int>& ArapFlattening::pinned() const { return impl_->solver->pinned(); }

ArapFlattenReport ArapFlattening::solve(const FlattenTargets& targets,
                                        const ArapFlattenSettings& settings,
                                        Eigen::MatrixX2d& uv) const {
  const Impl& im = *impl_;
  if (targets.direction.rows() != im.F.rows() || uv.rows() != im.solver->num_vertices()) {
    fail(ErrorCode::BadParameter, "the targets or the start map do not match the patch");
  }
  const TargetEdges q = im.target_edges(targets);
  double energy_scale = 0.0;
  for (int t = 0; t < im.F.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      energy_scale += std::abs(im.weight(t, k)) * q.block<1, 2>(t, 2 * k).squaredNorm();
    }
  }
  const double exact_energy = kExactEnergyFraction * energy_scale;

  ArapFlattenReport report;
  Rotations rotation(im.F.rows(), 2);
  double energy = im.fit_rotations(q, uv, rotation);
  report.energy_history.push_back(energy);
  const int folded = count_folded(im.F, im.charts, uv);
  // L-BFGS needs the guard's monotone steps: a folded start (which only the
  // plain steps may unfold) iterates plainly.
  if (settings.accelerate && settings.guard_folds && folded == 0) {
    energy = im.run_lbfgs(q, settings, exact_energy, uv, rotation, energy, report);
  } else {
    energy = im.run_plain(q, settings, exact_energy, folded, uv, rotation, energy, report);
  }
  report.energy = energy;
  report.folded = count_folded(im.F, im.charts, uv);
  return report;
}

}  // namespace aniso
