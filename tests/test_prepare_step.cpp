// The background preparation of a rest pose (Deformer::prepare_step,
// Session::prepare_step): one part per call, so that the browser's one
// solver thread answers a select between the parts instead of after the
// whole set-up (3.2 s at 200k vertices). Checked: the parts and their
// shares, that the next edit factorizes nothing and gives the same
// positions bit for bit, that an edit between the parts finishes what they
// began, and that the session's edit state is untouched.
#include <vector>

#include <catch2/catch.hpp>

#include "anisoform/deformer.h"
#include "anisoform/session.h"
#include "test_support.h"

using namespace aniso;

namespace {

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

TEST_CASE("prepare_step: five parts with rising shares to 1, then the edit factorizes nothing and is unchanged",
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
  REQUIRE(shares.size() == 5);
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
  // The copy and Laplacian, the workspace, the ordering and analysis.
  for (int part = 0; part < 3; ++part) CHECK(deformer.prepare_step() < 1.0);
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
  CHECK(parts == 4);
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
