// A pose's factorization reuses the ordering and analysis of the same mesh's
// earlier poses (SupernodalPlan, LaplacianPatterns): their Laplacians share
// one pattern. Checked: the factor solves bit for bit as one planned afresh,
// a matrix of another pattern is planned afresh, and a Deformer of a new
// pose given its mesh's patterns reuses them and deforms exactly as one
// without them.
#include <memory>

#include <catch2/catch.hpp>

#include "anisoform/deformer.h"
#include "anisoform/laplacian.h"
#include "geometry/laplacian_solver.h"
#include "geometry/supernodal_ldlt.h"
#include "test_support.h"

using namespace aniso;

namespace {

Eigen::SparseMatrix<double> laplacian_of(const Mesh& mesh) {
  return cotangent_laplacian(mesh, cotangent_weights(mesh));
}

// The cat with its legs stretched: a second pose of the same mesh.
DeformRequest leg_stretch(const Mesh& mesh) {
  const double low = mesh.V.col(1).minCoeff();
  const double high = mesh.V.col(1).maxCoeff();
  DeformRequest request;
  request.selection = (mesh.V.col(1).array() < low + 0.3 * (high - low)).cast<double>().matrix();
  request.direction.vector = Eigen::Vector3d::UnitY();
  request.transform.su = 1.4;
  request.max_iterations = 6;
  return request;
}

}  // namespace

TEST_CASE("factor reuse: a second pose's Laplacian solves bit for bit as planned afresh", "[factor-reuse]") {
  const Mesh cat = test::load("closed/cat-low-resolution.obj");
  const Mesh stretched{Deformer(cat).deform(leg_stretch(cat)).V, cat.F};
  const Eigen::SparseMatrix<double> L1 = laplacian_of(cat);
  const Eigen::SparseMatrix<double> L2 = laplacian_of(stretched);
  REQUIRE(!L1.isApprox(L2));  // other values, the same pattern
  const std::vector<int> pins = {0, 17};

  LaplacianSolver first(L1, pins, LaplacianSolver::Deferred{});
  first.factorize();
  LaplacianSolver fresh(L2, pins, LaplacianSolver::Deferred{});
  LaplacianSolver reusing(L2, pins, LaplacianSolver::Deferred{}, first.plan().get());
  CHECK_FALSE(fresh.plan()->reused());
  CHECK(reusing.plan()->reused());
  fresh.factorize();
  reusing.factorize();

  Positions b = stretched.V;  // any right-hand side; the pinned rows are held
  Positions x_fresh = stretched.V, x_reusing = stretched.V;
  fresh.solve(b, x_fresh);
  reusing.solve(b, x_reusing);
  CHECK(x_reusing == x_fresh);
  CHECK((x_fresh - stretched.V).norm() > 0.0);  // the solve did something
}

TEST_CASE("factor reuse: a matrix of another pattern is planned afresh", "[factor-reuse]") {
  const Mesh cat = test::load("closed/cat-low-resolution.obj");
  const Mesh spot = test::load("closed/spot_triangulated.obj");
  const SupernodalPlan cat_plan(laplacian_of(cat));
  const Eigen::SparseMatrix<double> L = laplacian_of(spot);
  Eigen::SparseMatrix<double> lower = L.triangularView<Eigen::Lower>();
  lower.coeffRef(0, 0) += 1.0;  // definite: nothing pinned
  const SupernodalPlan other(cat_plan, lower);
  CHECK_FALSE(other.reused());
  const SupernodalLdlt expected = supernodal_ldlt(lower, 0.0);
  const SupernodalLdlt got = other.factor(0.0);
  CHECK(got.bad_pivot == -1);
  CHECK(got.perm == expected.perm);
  CHECK(got.d == expected.d);
}

TEST_CASE("factor reuse: a new pose's Deformer reuses its mesh's patterns and deforms bit for bit the same",
          "[factor-reuse]") {
  const Mesh cat = test::load("closed/cat-low-resolution.obj");
  const auto patterns = std::make_shared<LaplacianPatterns>();
  Deformer first(cat, patterns);
  const DeformRequest stretch = leg_stretch(cat);
  const Mesh pose{first.deform(stretch).V, cat.F};
  REQUIRE(patterns->by_pins.size() == 1);
  CHECK_FALSE(patterns->by_pins.begin()->second->reused());

  DeformRequest widen = stretch;  // a second edit, from the new pose
  widen.direction.vector = Eigen::Vector3d::UnitX();
  widen.transform.su = 1.2;
  Deformer reusing(pose, patterns);
  const Positions got = reusing.deform(widen).V;
  REQUIRE(patterns->by_pins.size() == 1);
  CHECK(patterns->by_pins.begin()->second->reused());
  CHECK(got == Deformer(pose).deform(widen).V);
}
