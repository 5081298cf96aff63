// AnARAP / ARAP by L-BFGS on the energy (Liu, Bouaziz & Kavan 2017,
// "Quasi-Newton methods for real-time simulation of hyperelastic
// materials"), with the prefactored Laplacian as the initial inverse Hessian.
//
// With the rotations fitted to V (the local step), E's gradient over the free
// vertices is proportional to g = L V - b(R) (the global step solves g = 0),
// and the plain local/global step is V - L^-1 g: preconditioned gradient
// descent with step 1. L-BFGS keeps the last few (s, y) pairs of position and
// gradient changes and turns that step into a quasi-Newton one at the same
// cost: one Laplacian solve and one local step per iteration (plus a matrix-
// vector product with L, far cheaper than the solve). Without pairs (the
// first iteration) the step is exactly the plain one.
//
// Safeguard: a step is kept only if its energy, with rotations fitted to it,
// is below the last one; else it is halved (kHalvings times), and if that
// fails too the plain step is taken from the last rotations and the pairs are
// forgotten. The plain step never raises the energy, so neither does any
// iteration.
//
// Why over Anderson acceleration (anderson.h, still available): on the
// anisotropic stretch the local/global fixed point is approached along a
// few slow, smooth modes that the Laplacian-preconditioned quasi-Newton
// model captures (cyl50k, tolerance 1e-6: 2,649 plain iterations, 652
// Anderson, 183 L-BFGS; README "Accelerated iterations" has the times).
#include <algorithm>
#include <cmath>
#include "base/lbfgs_memory.h"
#include "deform/anarap.h"

namespace aniso {

namespace {

// (s, y) pairs kept: 5 measured as well as 12 or 25 on the cylinders.
constexpr int kMemory = 5;
// Largest scale of H0 = scale L^-1 (see run_lbfgs). Iterations to 1e-6 with
// the cap at 2 / 3 / 4 / 6: cyl50k ARAP 41 / 39 / 40 / 41, AnARAP 164 / 141 /
// 151 / 153; armadillo ARAP 72 / 63 / 63 / 74, AnARAP 62 / 58 / 58 / 63;
// cyl200k ARAP 609 / 510, AnARAP 406 / 418. Above 3 the longer steps need
// more halvings than they save.
constexpr double kMaxScale = 3.0;
// Halvings of a quasi-Newton step that raised the energy before the plain
// step is taken instead (without them a plain step followed most
// quasi-Newton steps of the cyl50k stretch; with two, 5 in 250 iterations).
constexpr int kHalvings = 2;

}  // namespace

void AnArapSolver::energy_gradient(const std::vector<char>& pinned, Positions& b, Positions& g) const {
  global_rhs(b);
  g.resize(n_, 3);
  for (int i = 0; i < n_; ++i) {
    if (pinned[i]) {
      g.row(i).setZero();
    } else {
      g.row(i) = laplacian_v_.row(i) - b.row(i);
    }
  }
}

int AnArapSolver::run_lbfgs(const LaplacianSolver& solver, Positions& V, int max_iterations, double tolerance,
                            std::vector<double>& history, bool final_energy,
                            const std::function<void(int)>& on_iteration) {
  std::vector<char> pinned(n_, 0);
  for (const int p : solver.pinned()) pinned[p] = 1;
  Positions b, next_b, g, next_g, direction, trial;
  // H0 = scale L^-1. The fitted rotations only lower E's curvature below
  // L's (y = L s - (b' - b)), so the Newton step is longer than the plain
  // one by about s.L s / s.y; the last pair's ratio, between 1 and
  // kMaxScale, scales it (Nocedal & Wright's H0 scaling, measured against
  // L instead of the identity).
  double scale = 1.0;
  LbfgsMemory<Positions> memory(kMemory);
  // r is the caller's scratch: the solve writes every free row and reads the
  // pinned ones, which must be zero (r = 0 there), so only those are zeroed.
  const auto apply_h0 = [&](const Positions& q, Positions& r) {
    r.resize(n_, 3);
    for (const int p : solver.pinned()) r.row(p).setZero();
    solver.solve(q, r);
    r *= scale;
  };
  std::vector<Eigen::Quaterniond> kept_rotations;
  double previous = local_step(V);
  energy_gradient(pinned, b, g);
  int iterations = 0, small_steps = 0;
  for (int it = 0; it < max_iterations; ++it) {
    if (!final_energy && it + 1 == max_iterations) {
      // No energy after the last step to check a quasi-Newton step against:
      // the plain one, which never raises it.
      solver.solve(b, V);
      history.push_back(previous);
      return ++iterations;
    }
    // direction = -H g with H0 = scale L^-1 (zero on the pins).
    memory.direction(g, direction, trial, apply_h0);
    kept_rotations = rotation_;
    trial = V + direction;
    double energy = local_step(trial);
    for (int h = 0; h < kHalvings && !(energy < previous) && !memory.empty(); ++h) {
      direction *= 0.5;
      trial = V + direction;
      energy = local_step(trial);
    }
    if (!(energy < previous) && !memory.empty()) {
      // The plain step from the last rotations (b is theirs).
      rotation_ = kept_rotations;
      memory.clear();
      scale = 1.0;
      trial = V;
      solver.solve(b, trial);
      energy = local_step(trial);
    }
    energy_gradient(pinned, next_b, next_g);
    const double curvature_ratio = memory.push_step(V, trial, g, next_g, b, next_b);
    if (curvature_ratio > 0.0) scale = std::clamp(curvature_ratio, 1.0, kMaxScale);
    V.swap(trial);
    g.swap(next_g);
    b.swap(next_b);
    history.push_back(energy);
    ++iterations;
    if (on_iteration) on_iteration(iterations);
    if (converged(previous, energy, tolerance, true, small_steps)) break;
    previous = energy;
  }
  return iterations;
}

}  // namespace aniso
