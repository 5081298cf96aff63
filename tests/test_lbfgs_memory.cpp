// LbfgsMemory (base/lbfgs_memory.h), the L-BFGS memory of AnARAP/ARAP and
// the flattening: its direction, from the products of the pairs it keeps,
// is the textbook two-loop recursion's (Nocedal & Wright, Algorithm 7.4) as
// pairs come and the oldest go, it obeys the secant equation H y = s for the newest pair,
// and a pair without positive curvature is not kept. The pairs come from spot's
// cotangent Laplacian L with H0 = scale L^-1, as in the solvers.
#include <cmath>
#include <deque>
#include <memory>
#include <vector>

#include <catch2/catch.hpp>

#include "anisoform/laplacian.h"
#include "base/lbfgs_memory.h"
#include "geometry/laplacian_solver.h"
#include "test_support.h"

using namespace aniso;

namespace {

constexpr int kCapacity = 5;
constexpr double kScale = 1.5;

struct SpotSystem {
  Mesh mesh;
  std::vector<int> pins{0, 100};
  Eigen::SparseMatrix<double> L;
  std::unique_ptr<LaplacianSolver> solver;

  SpotSystem() : mesh(test::load("closed/spot_triangulated.obj")) {
    L = cotangent_laplacian(mesh, cotangent_weights(mesh));
    solver = std::make_unique<LaplacianSolver>(L, pins);
  }

  int n() const { return mesh.num_vertices(); }

  void zero_pins(Positions& x) const {
    for (const int p : pins) x.row(p).setZero();
  }

  // Step k: a smooth field over the mesh, zero on the pins.
  Positions step(int k) const {
    Positions s(n(), 3);
    for (int i = 0; i < n(); ++i) {
      for (int c = 0; c < 3; ++c) s(i, c) = std::sin((k + 1) * 3.0 * mesh.V(i, c) + c);
    }
    zero_pins(s);
    return s;
  }

  // Its gradient change under the SPD model Hessian L + D (D a positive
  // diagonal, so that L^-1 alone is not the inverse Hessian).
  Positions change(const Positions& s) const {
    Positions y = L * s;
    for (int i = 0; i < n(); ++i) y.row(i) += (1.0 + mesh.V.row(i).squaredNorm()) * s.row(i);
    zero_pins(y);
    return y;
  }

  void apply_inverse(const Positions& q, Positions& r) const {
    r = Positions::Zero(n(), 3);
    solver->solve(q, r);
  }

  // M of H0 = kScale M, as direction() takes it: L^-1.
  auto inverse() const {
    return [this](const Positions& q, Positions& r) { apply_inverse(q, r); };
  }
};

double dot(const Positions& a, const Positions& b) { return a.cwiseProduct(b).sum(); }

// Nocedal & Wright's Algorithm 7.4, as written: -H g.
Positions textbook_direction(const SpotSystem& problem, const std::deque<Positions>& s, const std::deque<Positions>& y,
                             const Positions& g) {
  const int m = static_cast<int>(s.size());
  std::vector<double> alpha(m), rho(m);
  Positions q = g;
  for (int k = m - 1; k >= 0; --k) {
    rho[k] = 1.0 / dot(s[k], y[k]);
    alpha[k] = rho[k] * dot(s[k], q);
    q -= alpha[k] * y[k];
  }
  Positions r;
  problem.apply_inverse(q, r);
  r *= kScale;
  for (int k = 0; k < m; ++k) {
    const double beta = rho[k] * dot(y[k], r);
    r += (alpha[k] - beta) * s[k];
  }
  return -r;
}

double relative_difference(const Positions& a, const Positions& b) { return (a - b).norm() / b.norm(); }

}  // namespace

TEST_CASE("L-BFGS memory: the direction is the two-loop recursion's, pairs kept and dropped",
          "[lbfgs]") {
  const SpotSystem problem;
  const Positions zero = Positions::Zero(problem.n(), 3);
  Positions gradient = problem.change(problem.mesh.V);
  LbfgsMemory<Positions> memory(kCapacity);
  std::deque<Positions> s, y;
  Positions direction, scratch;
  memory.direction(gradient, direction, scratch, problem.inverse(), kScale);
  CHECK(relative_difference(direction, textbook_direction(problem, s, y, gradient)) < 1e-14);
  // Two more pairs than kept: the oldest go.
  for (int k = 0; k < kCapacity + 2; ++k) {
    const Positions step = problem.step(k);
    const Positions change = problem.change(step);
    const double ratio = memory.push_step(zero, step, zero, change, zero, zero);
    // b0 = b1 here, so s.L s / s.y = (s.y + s.(b1 - b0)) / s.y is 1.
    CHECK(ratio == Approx(1.0));
    s.push_back(step);
    y.push_back(change);
    if (static_cast<int>(s.size()) > kCapacity) {
      s.pop_front();
      y.pop_front();
    }
    INFO(s.size() << " pairs after " << k + 1 << " pushed");
    memory.direction(gradient, direction, scratch, problem.inverse(), kScale);
    CHECK(relative_difference(direction, textbook_direction(problem, s, y, gradient)) < 1e-10);
    // The secant equation of the newest pair: H y = s.
    memory.direction(change, direction, scratch, problem.inverse(), kScale);
    CHECK(relative_difference(direction, -step) < 1e-10);
    gradient = change + 0.5 * gradient;
  }
}

TEST_CASE("L-BFGS memory: a pair without positive curvature is not kept", "[lbfgs]") {
  const SpotSystem problem;
  const Positions zero = Positions::Zero(problem.n(), 3);
  LbfgsMemory<Positions> memory(kCapacity);
  const Positions step = problem.step(0);
  CHECK(memory.push_step(zero, step, zero, Positions(-problem.change(step)), zero, zero) == 0.0);
  CHECK(memory.empty());
  CHECK(memory.push_step(zero, step, zero, problem.change(step), zero, zero) > 0.0);
  CHECK_FALSE(memory.empty());
  memory.clear();
  CHECK(memory.empty());
  // After clear(), the direction is the scaled preconditioned gradient again.
  const Positions gradient = problem.change(problem.mesh.V);
  Positions direction, scratch, expected;
  memory.direction(gradient, direction, scratch, problem.inverse(), kScale);
  problem.apply_inverse(gradient, expected);
  CHECK(relative_difference(direction, Positions(-kScale * expected)) < 1e-14);
}

TEST_CASE("L-BFGS memory: pairs pushed with no direction between them give the textbook direction", "[lbfgs]") {
  // The products of each pair with the earlier ones are taken with the next
  // direction; a second pair before it must take them at once.
  const SpotSystem problem;
  const Positions zero = Positions::Zero(problem.n(), 3);
  const Positions gradient = problem.change(problem.mesh.V);
  LbfgsMemory<Positions> memory(kCapacity);
  std::deque<Positions> s, y;
  for (int k = 0; k < kCapacity + 2; ++k) {
    const Positions step = problem.step(k);
    const Positions change = problem.change(step);
    memory.push_step(zero, step, zero, change, zero, zero);
    s.push_back(step);
    y.push_back(change);
    if (static_cast<int>(s.size()) > kCapacity) {
      s.pop_front();
      y.pop_front();
    }
  }
  Positions direction, scratch;
  memory.direction(gradient, direction, scratch, problem.inverse(), kScale);
  CHECK(relative_difference(direction, textbook_direction(problem, s, y, gradient)) < 1e-10);
}

TEST_CASE("L-BFGS memory: a step pushed as the caller's matrix, its change written by the caller, is the same pair",
          "[lbfgs]") {
  // AnARAP's pairs: s is the direction taken, y and the products come from
  // its own pass (fill); they must give the textbook direction too.
  const SpotSystem problem;
  const Positions zero = Positions::Zero(problem.n(), 3);
  const Positions gradient = problem.change(problem.mesh.V);
  LbfgsMemory<Positions> memory(kCapacity);
  std::deque<Positions> s, y;
  Positions direction, scratch;
  for (int k = 0; k < kCapacity + 1; ++k) {
    Positions step = problem.step(k);
    const Positions change = problem.change(step);
    s.push_back(step);
    y.push_back(change);
    if (static_cast<int>(s.size()) > kCapacity) {
      s.pop_front();
      y.pop_front();
    }
    const double ratio = memory.push_step(step, [&](Positions& written) {
      written = change;
      StepProducts p;
      p.sy = dot(s.back(), change);
      p.ss = dot(s.back(), s.back());
      p.yy = dot(change, change);
      return p;
    });
    CHECK(ratio == Approx(1.0));
    memory.direction(gradient, direction, scratch, problem.inverse(), kScale);
    CHECK(relative_difference(direction, textbook_direction(problem, s, y, gradient)) < 1e-10);
  }
}
