// How a pose gets its factorization ahead of, or cheaper than, its first
// edit.
// - The background preparation (Deformer::prepare_step,
//   Session::prepare_step): one part per call, so that the browser's one
//   solver thread answers a select between the parts instead of after the
//   whole set-up (3.2 s at 200k vertices). Checked: the parts and their
//   shares, that the next edit factorizes nothing and gives the same
//   positions bit for bit, that an edit between the parts finishes what
//   they began, and that the session's edit state is untouched.
// - Reuse across poses (SupernodalPlan, LaplacianPatterns): every pose of a
//   mesh has a Laplacian of the same pattern, so a pose's factorization
//   reuses the ordering and analysis of an earlier one. Checked: the factor
//   solves bit for bit as one planned afresh, a matrix of another pattern is
//   planned afresh, and a Deformer of a new pose given its mesh's patterns
//   reuses them and deforms exactly as one without them.
#include <memory>
#include <vector>

#include <catch2/catch.hpp>

#include "anisoform/deformer.h"
#include "anisoform/laplacian.h"
#include "anisoform/session.h"
#include "geometry/laplacian_solver.h"
#include "geometry/supernodal_ldlt.h"
#include "test_support.h"

using namespace aniso;

namespace {

Eigen::SparseMatrix<double> laplacian_of(const Mesh& mesh) {
  return cotangent_laplacian(mesh, cotangent_weights(mesh));
}

// The cat's legs and lower body (paper Fig. 1: legs elongated), stretched
// along the vertical axis.
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

TEST_CASE("prepare_step: nine parts with rising shares to 1, then the edit factorizes nothing and is unchanged",
          "[prepare]") {
  const Mesh cat = test::load("closed/cat-low-resolution.obj");
  const DeformRequest request = leg_stretch(cat);
  Deformer cold(cat);
  const DeformResult expected = cold.deform(request);
  REQUIRE(cold.factorizations() == 1);

  Deformer prepared(cat);
  std::vector<double> reported;
  prepared.set_progress([&reported](ProgressStage stage, double share) {
    CHECK(stage == ProgressStage::Factorize);
    reported.push_back(share);
  });
  std::vector<double> shares;
  while (shares.size() < 10 && (shares.empty() || shares.back() < 1.0)) shares.push_back(prepared.prepare_step());
  // The copy and Laplacian, the workspace, the ordering, four parts of the
  // numeric factorization, the AnARAP structures, the warm-up (a preview's
  // work, thrown away).
  REQUIRE(shares.size() == 9);
  for (std::size_t k = 1; k < shares.size(); ++k) CHECK(shares[k] > shares[k - 1]);
  CHECK(shares.back() == 1.0);
  CHECK(prepared.factorizations() == 1);
  // The factorization's own progress within its parts, never falling.
  REQUIRE(reported.size() > shares.size());
  for (std::size_t k = 1; k < reported.size(); ++k) CHECK(reported[k] >= reported[k - 1]);
  // Nothing left: a call is free and reports nothing.
  const std::size_t heard = reported.size();
  CHECK(prepared.prepare_step() == 1.0);
  CHECK(reported.size() == heard);

  prepared.set_progress({});
  const DeformResult result = prepared.deform(request);
  CHECK(prepared.factorizations() == 1);
  CHECK(result.iterations == expected.iterations);
  CHECK(result.V == expected.V);
}

TEST_CASE("prepare_step: an edit between the parts finishes the ordered factorization, and the rest is free",
          "[prepare]") {
  const Mesh cat = test::load("closed/cat-low-resolution.obj");
  const DeformRequest request = leg_stretch(cat);
  const Positions expected = Deformer(cat).deform(request).V;

  Deformer deformer(cat);
  // The copy and Laplacian, the workspace, the ordering and analysis, a
  // quarter of the numeric factorization.
  for (int part = 0; part < 4; ++part) CHECK(deformer.prepare_step() < 1.0);
  CHECK(deformer.factorizations() == 0);
  CHECK(deformer.deform(request).V == expected);
  CHECK(deformer.factorizations() == 1);
  CHECK(deformer.prepare_step() == 1.0);  // the edit built the rest
  CHECK(deformer.factorizations() == 1);

  // Pins other than the gauge's (its lowest vertex, 0) still get their own:
  // ARAP's handles.
  DeformRequest arap;
  arap.method = Method::Arap;
  arap.handles = {cat.num_vertices() - 1};
  arap.handle_offset = Eigen::Vector3d(0.0, 0.01, 0.0);
  arap.max_iterations = 2;
  deformer.deform(arap);
  CHECK(deformer.factorizations() == 2);
}

TEST_CASE("Session::prepare_step changes no edit state; the edit after it factorizes nothing", "[prepare][session]") {
  Session session;
  const Mesh cat = test::load("closed/cat-low-resolution.obj");
  session.adopt_mesh(cat, {});
  Region box;
  box.kind = Region::Kind::Box;
  box.min = Eigen::Vector3d(-1e9, -1e9, -1e9);
  box.max = Eigen::Vector3d(1e9, cat.V.col(1).minCoeff() + 0.3 * (cat.V.col(1).maxCoeff() - cat.V.col(1).minCoeff()), 1e9);
  const int selected = session.select(box, 0.0, SelectionMode::Replace);
  REQUIRE(selected > 100);
  const Eigen::VectorXd selection = session.selection();
  const Positions positions = session.positions();

  int parts = 0;
  while (session.prepare_step() < 1.0) ++parts;
  CHECK(parts == 8);
  CHECK(session.selection() == selection);
  CHECK(session.positions() == positions);
  CHECK(session.factorizations() == 1);

  DeformOp op;
  op.request = leg_stretch(cat);
  op.request.selection.resize(0);  // the session's selection is used
  session.deform(op);
  CHECK(session.factorizations() == 1);
  CHECK(session.positions() != positions);
}

TEST_CASE("factor reuse: a second pose's Laplacian solves bit for bit as planned afresh", "[factor-reuse]") {
  const Mesh cat = test::load("closed/cat-low-resolution.obj");
  const Mesh stretched{Deformer(cat).deform(leg_stretch(cat)).V, cat.F};
  const Eigen::SparseMatrix<double> L1 = laplacian_of(cat);
  const Eigen::SparseMatrix<double> L2 = laplacian_of(stretched);
  REQUIRE(!L1.isApprox(L2));  // other values, the same pattern
  const std::vector<int> pins = {0, 17};

  LaplacianSolver first(L1, pins, LaplacianSolver::Deferred{});
  const std::shared_ptr<SupernodalPlan> kept = first.plan();  // as a LaplacianPatterns keeps it
  first.factorize();
  CHECK(first.plan() == nullptr);
  LaplacianSolver fresh(L2, pins, LaplacianSolver::Deferred{});
  LaplacianSolver reusing(L2, pins, LaplacianSolver::Deferred{}, kept.get());
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

TEST_CASE("factorization in parts: any number of parts gives the same factor bit for bit", "[prepare]") {
  const Mesh cat = test::load("closed/cat-low-resolution.obj");
  const Eigen::SparseMatrix<double> L = laplacian_of(cat);
  const std::vector<int> pins = {0};
  LaplacianSolver whole(L, pins);
  LaplacianSolver in_parts(L, pins, LaplacianSolver::Deferred{});
  int parts = 1;
  while (!in_parts.factorize_until(parts / 10.0)) ++parts;
  CHECK(parts >= 5);  // a tenth of the work at a time, at least a supernode a part
  CHECK(in_parts.factorize_until(0.0));  // done: nothing more

  const Positions b = cat.V;
  Positions x_whole = cat.V, x_parts = cat.V;
  whole.solve(b, x_whole);
  in_parts.solve(b, x_parts);
  CHECK(x_parts == x_whole);
}

TEST_CASE("factorization in parts: supernodes that add no work are still factored", "[prepare]") {
  // Columns with nothing below the diagonal add nothing to the work measure
  // (sum of c^2): the free vertices of components left with one each, the
  // root of a tree with several children. Here all of them: a diagonal
  // matrix, whose work is 0 from the start. Reaching all the work is not
  // reaching the end: factoring up to the whole once stopped after the
  // first column.
  constexpr int n = 5;
  Eigen::SparseMatrix<double> diagonal(n, n);
  for (int i = 0; i < n; ++i) diagonal.insert(i, i) = 1.0 + i;
  diagonal.makeCompressed();
  for (const double first_part : {0.5, 1.0}) {
    SupernodalPlan plan(diagonal);
    if (first_part < 1.0) plan.factor_until(0.0, first_part);
    REQUIRE(plan.factor_until(0.0, 1.0));
    const SupernodalLdlt got = plan.take_factor();
    CHECK(got.bad_pivot == -1);
    REQUIRE(got.perm.size() == static_cast<std::size_t>(n));
    REQUIRE(got.d.size() == n);
    for (int i = 0; i < n; ++i) CHECK(got.d[got.perm[i]] == 1.0 + i);  // the pivots are the diagonal
  }
}

TEST_CASE("factor reuse: a matrix of another pattern is planned afresh", "[factor-reuse]") {
  const Mesh cat = test::load("closed/cat-low-resolution.obj");
  const Mesh spot = test::load("closed/spot_triangulated.obj");
  const SupernodalPlan cat_plan(laplacian_of(cat));
  const Eigen::SparseMatrix<double> L = laplacian_of(spot);
  Eigen::SparseMatrix<double> lower = L.triangularView<Eigen::Lower>();
  lower.coeffRef(0, 0) += 1.0;  // definite: nothing pinned
  SupernodalPlan other(cat_plan, lower);
  CHECK_FALSE(other.reused());
  const SupernodalLdlt expected = supernodal_ldlt(lower, 0.0);
  REQUIRE(other.factor_until(0.0, 1.0));
  const SupernodalLdlt got = other.take_factor();
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
