// What stays put (METHOD §7).
#include <catch2/catch.hpp>

#include "anisoform/deformer.h"
#include "solver_test_support.h"
#include "test_support.h"

using namespace aniso;

namespace {

// Weight 1 on the vertices with x above `x`, 0 elsewhere.
Eigen::VectorXd beyond_x(const Mesh& mesh, double x) {
  return (mesh.V.col(0).array() > x).cast<double>().matrix();
}

}  // namespace

TEST_CASE("gauge: unselected parts stay where they were", "[gauge]") {
  const Mesh mesh = test::load("closed/cat-low-resolution.obj");
  const double xmax = mesh.V.col(0).maxCoeff(), xmin = mesh.V.col(0).minCoeff();
  const Eigen::VectorXd w = beyond_x(mesh, xmin + 0.75 * (xmax - xmin));
  Deformer deformer(mesh);
  for (Method method : {Method::AnArap, Method::AnDefGrad}) {
    DeformRequest request = test::stretch_request(method, Eigen::Vector3d::UnitX(), 1.4);
    request.selection = w;
    const DeformResult r = deformer.deform(request);
    double far_motion = 0.0;
    int far = 0;
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      if (mesh.V(i, 0) < xmin + 0.4 * (xmax - xmin)) {
        far_motion = std::max(far_motion, (r.V.row(i) - mesh.V.row(i)).norm());
        ++far;
      }
    }
    INFO(method_name(method));
    CHECK(far > 100);
    CHECK(far_motion < 0.01 * test::diagonal(mesh.V));
  }
}

TEST_CASE("gauge: each component of a multi-part mesh is solved and kept in place", "[gauge]") {
  const Mesh mesh = test::load("malformed/multi_component.obj");
  Deformer deformer(mesh);
  // Select the second part only (Blub, shifted +2 in x).
  const Eigen::VectorXd w = beyond_x(mesh, 1.2);
  DeformRequest request = test::stretch_request(Method::AnArap, Eigen::Vector3d::UnitY(), 1.3);
  request.selection = w;
  const DeformResult r = deformer.deform(request);
  double untouched = 0.0, moved = 0.0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const double d = (r.V.row(i) - mesh.V.row(i)).norm();
    (w[i] > 0 ? moved : untouched) = std::max(w[i] > 0 ? moved : untouched, d);
  }
  CHECK(untouched < 1e-9);
  CHECK(moved > 0.05);
}

TEST_CASE("gauge: a whole multi-part mesh scaled uniformly is one similarity, its parts' gap scaled too",
          "[gauge][method9]") {
  // METHOD §9: v' = s R v up to one translation, and §7: the centroid kept.
  // Each part used to be scaled about its own centroid: the gap stayed.
  const Mesh mesh = test::load("malformed/multi_component.obj");
  const Eigen::RowVector3d centroid = mesh.V.colwise().mean();
  Deformer deformer(mesh);
  for (Method method : {Method::AnArap, Method::AnDefGrad}) {
    DeformRequest request = test::stretch_request(method, Eigen::Vector3d::UnitX(), 1.5, 1.5);
    request.tolerance = 1e-12;
    const DeformResult r = deformer.deform(request);
    const Positions expected = (1.5 * (mesh.V.rowwise() - centroid)).rowwise() + centroid;
    INFO(method_name(method));
    CHECK((r.V - expected).rowwise().norm().maxCoeff() < 1e-6 * test::diagonal(mesh.V));
  }
}

TEST_CASE("gauge: a part wholly selected with part of its neighbour moves with it; alone it stays", "[gauge]") {
  // Blub (x > 1.2) and Spot's side towards it (x > 0.1) stretched along x:
  // Blub, held by nothing of its own, follows Spot's selected side out.
  const Mesh mesh = test::load("malformed/multi_component.obj");
  Deformer deformer(mesh);
  DeformRequest request = test::stretch_request(Method::AnDefGrad, Eigen::Vector3d::UnitX(), 1.5);
  request.selection = beyond_x(mesh, 0.1);
  const DeformResult r = deformer.deform(request);
  double spot_side = -1e9, blub_from = 1e9, blub_moved = 0.0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.V(i, 0) > 1.2) {
      blub_from = std::min(blub_from, r.V(i, 0));
      blub_moved += (r.V(i, 0) - mesh.V(i, 0)) / 1.0;
    } else {
      spot_side = std::max(spot_side, r.V(i, 0));
    }
  }
  // Spot's selected side reached further out, and Blub moved out with it: the
  // gap between them grew by the stretch instead of closing.
  double rest_side = -1e9, rest_blub = 1e9;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.V(i, 0) > 1.2) rest_blub = std::min(rest_blub, mesh.V(i, 0));
    else rest_side = std::max(rest_side, mesh.V(i, 0));
  }
  CHECK(spot_side > rest_side + 0.05);
  CHECK(blub_from - spot_side > 0.9 * (rest_blub - rest_side));
  CHECK(blub_moved > 0.0);
}

TEST_CASE("gauge: user pins hold exactly and handles move exactly (ARAP)", "[gauge]") {
  const Mesh mesh = test::load("closed/spool.off");
  Deformer deformer(mesh);
  DeformRequest request;
  request.method = Method::Arap;
  request.pins = {0, 1, 2};
  request.handles = {100, 101};
  request.handle_offset = Eigen::Vector3d(0.1, 0.2, -0.1);
  const DeformResult r = deformer.deform(request);
  for (int p : request.pins) CHECK(r.V.row(p) == mesh.V.row(p));
  for (int h : request.handles) CHECK((r.V.row(h) - mesh.V.row(h) - request.handle_offset.transpose()).norm() < 1e-12);
  CHECK(r.iterations >= 1);
}

TEST_CASE("deformer: bad requests are refused with the problem named, and the session survives", "[gauge]") {
  const Mesh mesh = test::load("closed/spool.off");
  Deformer deformer(mesh);
  DeformRequest request = test::stretch_request(Method::AnArap, Eigen::Vector3d::UnitX(), 1.2);
  request.selection = Eigen::VectorXd::Constant(5, 1.0);
  CHECK_THROWS_WITH(deformer.deform(request), Catch::Contains("5 weights") && Catch::Contains("649"));
  request.selection = Eigen::VectorXd::Constant(mesh.num_vertices(), 1.0);
  request.selection[17] = 1.5;
  CHECK_THROWS_WITH(deformer.deform(request), Catch::Contains("vertex 17"));
  request.selection[17] = 1.0;
  request.pins = {100000};
  CHECK_THROWS_WITH(deformer.deform(request), Catch::Contains("100000"));
  request.pins.clear();
  request.direction.vector = Eigen::Vector3d::Zero();
  CHECK_THROWS_WITH(deformer.deform(request), Catch::Contains("direction"));
  request.direction.vector = Eigen::Vector3d::UnitX();
  request.handles = {3};
  CHECK_THROWS_WITH(deformer.deform(request), Catch::Contains("arap"));
  request.handles.clear();
  // Direction sources are checked before any work (validate_direction_source).
  request.direction.kind = DirectionSource::Kind::CurvatureMax;
  request.direction.curvature_smoothing = 1000000000;
  CHECK_THROWS_WITH(deformer.deform(request), Catch::Contains("from 0 to 1000, got 1000000000"));
  request.direction.kind = DirectionSource::Kind::Constraints;
  DirectionConstraint arrow;
  arrow.vertex = 7;
  arrow.has_amounts = true;
  for (const double su : {0.0, -1.0}) {
    arrow.su = su;
    request.direction.constraints = {arrow};
    CHECK_THROWS_WITH(deformer.deform(request), Catch::Contains("direction constraint 1 (vertex 7): su must be positive"));
  }
  arrow.su = 1.0;
  arrow.vertex = 649;
  request.direction.constraints = {arrow};
  CHECK_THROWS_WITH(deformer.deform(request), Catch::Contains("(vertex 649): vertex index out of range"));
  request.direction.kind = DirectionSource::Kind::Global;
  CHECK_NOTHROW(deformer.deform(request));
  // A mesh that cannot be solved is refused at construction.
  Mesh bad = mesh;
  bad.V(5, 0) = std::nan("");
  CHECK_THROWS_WITH(Deformer(bad), Catch::Contains("vertex 5"));
}
