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
#include "base/simd_pair.h"
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

// E's new gradient and the pair of the step s in one pass over the rows
// (of 3): g1 = lv - b1 (zero on the pinned rows), y = g1 - g0, and the
// products s.y, s.(b1 - b0), s.s and y.y, each summed over the rows' x and
// y in a pair of lanes and their z apart. As a gradient pass and a pair pass
// (base/vector_kernels.h's step_pair), these read the vectors 11 times.
StepProducts gradient_pair(const double* s, const double* lv, const double* b1, const double* b0, const double* g0,
                           const std::vector<char>& pinned, double* g1, double* y) {
  Pair sy{}, s_db{}, ss{}, yy{};
  double sy_z = 0.0, s_db_z = 0.0, ss_z = 0.0, yy_z = 0.0;
  for (std::size_t i = 0; i < pinned.size(); ++i) {
    const std::size_t j = 3 * i;
    Pair g_xy = {0.0, 0.0};
    double g_z = 0.0;
    if (!pinned[i]) {
      g_xy = load_pair(lv + j) - load_pair(b1 + j);
      g_z = lv[j + 2] - b1[j + 2];
    }
    store_pair(g1 + j, g_xy);
    g1[j + 2] = g_z;
    const Pair y_xy = g_xy - load_pair(g0 + j), s_xy = load_pair(s + j);
    const double y_z = g_z - g0[j + 2], s_z = s[j + 2];
    store_pair(y + j, y_xy);
    y[j + 2] = y_z;
    sy += s_xy * y_xy;
    sy_z += s_z * y_z;
    s_db += s_xy * (load_pair(b1 + j) - load_pair(b0 + j));
    s_db_z += s_z * (b1[j + 2] - b0[j + 2]);
    ss += s_xy * s_xy;
    ss_z += s_z * s_z;
    yy += y_xy * y_xy;
    yy_z += y_z * y_z;
  }
  return {sy[0] + sy[1] + sy_z, s_db[0] + s_db[1] + s_db_z, ss[0] + ss[1] + ss_z, yy[0] + yy[1] + yy_z};
}

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
  // r = L^-1 q (the memory applies the scale). r is the caller's scratch:
  // the solve writes every free row and reads the pinned ones, which must be
  // zero (r = 0 there), so only those are zeroed.
  const auto apply_h0 = [&](const Positions& q, Positions& r) {
    r.resize(n_, 3);
    for (const int p : solver.pinned()) r.row(p).setZero();
    solver.solve(q, r);
  };
  double previous = local_step(V);
  energy_gradient(pinned, b, g);
  std::vector<Eigen::Quaterniond> kept_rotations = rotation_;
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
    memory.direction(g, direction, trial, apply_h0, scale);
    // The last rotations are kept aside (swapped, not copied): the trial's
    // fits start from them, and the plain step falls back on them.
    kept_rotations.swap(rotation_);
    trial = V + direction;
    double energy = local_step(trial, kept_rotations);
    for (int h = 0; h < kHalvings && !(energy < previous) && !memory.empty(); ++h) {
      direction *= 0.5;
      trial = V + direction;
      energy = local_step(trial, kept_rotations);
    }
    if (!(energy < previous) && !memory.empty()) {
      // The plain step from the last rotations (b is theirs).
      rotation_.swap(kept_rotations);
      memory.clear();
      scale = 1.0;
      trial = V;
      solver.solve(b, trial);
      energy = local_step(trial);
      direction = trial - V;
    }
    // direction is now the step taken, the pair's s.
    global_rhs(next_b);
    next_g.resize(n_, 3);
    const double curvature_ratio = memory.push_step(direction, [&](Positions& y) {
      return gradient_pair(direction.data(), laplacian_v_.data(), next_b.data(), b.data(), g.data(), pinned,
                           next_g.data(), y.data());
    });
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
