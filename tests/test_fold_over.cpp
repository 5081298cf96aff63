// The 3D fold-over guard (count_inverted, DeformResult::inverted, the CLI's
// "inverted"): moderate edits fold nothing, extreme ones fold triangles over,
// and turning a part far without folding it does not count.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include "anisoform/deformer.h"
#include "anisoform/distortion.h"
#include "anisoform/error.h"
#include "geometry/frames.h"
#include "mesh/topology.h"
#include "anisoform/transforms.h"
#include "cli_runner.h"
#include "solver_test_support.h"
#include "test_support.h"

using namespace aniso;

TEST_CASE("fold-over: a moderate stretch folds nothing, an extreme shear or twist does", "[fold]") {
  // The low-resolution Spot (829 vertices, 3.5x fewer than spot_triangulated):
  // the same shape at nearly the same size (diagonal 2.66, not 2.59), so the
  // same twist is still near the largest valid one (13,500 deg/unit here).
  const Mesh mesh = test::load("formats/spot_lowres.obj");
  Deformer deformer(mesh);
  for (const Method method : {Method::AnDefGrad, Method::AnArap}) {
    INFO(method_name(method));
    const DeformResult stretched =
        deformer.deform(test::stretch_request(method, Eigen::Vector3d::UnitY(), 1.5));
    CHECK(stretched.inverted == 0);
    CHECK(stretched.inverted == count_inverted(mesh, stretched.V));

    DeformRequest shear = test::stretch_request(method, Eigen::Vector3d::UnitY(), 1.0);
    shear.transform.shear = 10.0;
    const DeformResult sheared = deformer.deform(shear);
    WARN("spot shear 10 " << method_name(method) << ": inverted " << sheared.inverted << " of "
                          << mesh.num_triangles());
    CHECK(sheared.inverted > 0);

    DeformRequest twist;
    twist.method = method;
    twist.transform.twist = true;
    twist.transform.twist_axis = Eigen::Vector3d::UnitY();
    // Near the largest valid twist (limits.h: 36,000 degrees over the
    // bounding-box diagonal, 2.59 on Spot).
    twist.transform.twist_degrees_per_unit = 13000.0;
    twist.transform.twist_origin =
        default_twist_origin(mesh.V, Eigen::VectorXd::Ones(mesh.num_vertices()), Eigen::Vector3d::UnitY());
    const DeformResult twisted = deformer.deform(twist);
    WARN("spot twist 13000 deg/unit " << method_name(method) << ": inverted " << twisted.inverted);
    CHECK(twisted.inverted > 0);
  }
}

TEST_CASE("fold-over: turning a part far is not folding it", "[fold]") {
  const Mesh mesh = test::load("closed/spot_triangulated.obj");
  // The whole mesh turned 180 deg: every normal points the other way in world
  // space, yet nothing is folded.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Positions turned = (mesh.V * R.transpose()).eval();
  CHECK(count_inverted(mesh, turned) == 0);
  // The spool twisted ~180 deg end to end about its axis (x) turns the far
  // rim's normals past 90 deg but folds no triangle.
  const Mesh spool = test::load("closed/spool.off");
  Deformer deformer(spool);
  DeformRequest twist;
  twist.method = Method::AnDefGrad;
  twist.transform.twist = true;
  twist.transform.twist_axis = Eigen::Vector3d::UnitX();
  twist.transform.twist_degrees_per_unit = 340.0;
  twist.transform.twist_origin =
      default_twist_origin(spool.V, Eigen::VectorXd::Ones(spool.num_vertices()), Eigen::Vector3d::UnitX());
  const DeformResult twisted = deformer.deform(twist);
  const Positions rest_normals = triangle_normals(spool);
  const Positions normals = triangle_normals(Mesh{twisted.V, spool.F});
  int turned_past_90 = 0;
  for (int t = 0; t < spool.num_triangles(); ++t) turned_past_90 += rest_normals.row(t).dot(normals.row(t)) < 0.0;
  WARN("spool twist 340 deg/unit: normals turned past 90 deg " << turned_past_90 << ", inverted "
                                                              << twisted.inverted);
  CHECK(turned_past_90 > 0);
  CHECK(twisted.inverted == 0);
}

TEST_CASE("fold-over: a vertex dragged past its neighbour folds triangles over", "[fold]") {
  const Mesh mesh = test::load("closed/spot_triangulated.obj");
  Positions V = mesh.V;
  // Move vertex 0 along the surface, past its neighbour j: the triangles of
  // the edge (0, j) turn over while everything around stays put.
  const VertexAdjacency adjacency = vertex_adjacency(mesh.F, mesh.num_vertices());
  const int j = adjacency.neighbors[adjacency.offsets[0]];
  V.row(0) = mesh.V.row(0) + 2.5 * (mesh.V.row(j) - mesh.V.row(0));
  const int folded = count_inverted(mesh, V);
  WARN("vertex 0 dragged past vertex " << j << ": inverted " << folded);
  CHECK(folded > 0);
  CHECK(count_inverted(mesh, mesh.V) == 0);
  CHECK_THROWS_AS(count_inverted(mesh, Positions(V.topRows(3))), Error);
}

TEST_CASE("fold-over: the CLI reports inverted triangles", "[fold][cli]") {
  const std::string in = test::mesh_path("formats/spot_lowres.obj");
  const nlohmann::json moderate = test::stdout_json(test::run_expecting(
      {"deform", in, test::temp_path("moderate.obj"), "--method", "andefgrad", "--scale", "1.3"}, 0));
  REQUIRE(moderate.contains("inverted"));
  CHECK(moderate["inverted"] == 0);
  const nlohmann::json extreme = test::stdout_json(test::run_expecting(
      {"deform", in, test::temp_path("extreme.obj"), "--method", "andefgrad", "--shear", "10"}, 0));
  REQUIRE(extreme["inverted"].is_number_integer());
  CHECK(extreme["inverted"].get<int>() > 0);
}
