// check_mesh on the malformed meshes (each with one documented defect) and on
// small hand-made meshes; welding, soup detection and polygon triangulation.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "anisoform/deformer.h"
#include "anisoform/error.h"
#include "anisoform/mesh_check.h"
#include "anisoform/mesh_io.h"
#include "anisoform/op.h"
#include "anisoform/session.h"
#include "test_support.h"

using aniso::Mesh;
using aniso::MeshReport;
using aniso::ProblemKind;
using aniso::test::load;

namespace {

std::vector<int> elements_of(const MeshReport& report, ProblemKind kind) {
  std::vector<int> elements;
  for (const aniso::Problem& problem : report.problems) {
    if (problem.kind == kind) elements.push_back(problem.element);
  }
  return elements;
}

std::string message_of(const MeshReport& report, ProblemKind kind) {
  for (const aniso::Problem& problem : report.problems) {
    if (problem.kind == kind) return problem.message;
  }
  return "";
}

Mesh make_mesh(std::vector<Eigen::RowVector3d> positions, std::vector<Eigen::RowVector3i> faces) {
  Mesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(positions.size()), 3);
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < positions.size(); ++i) mesh.V.row(i) = positions[i];
  for (std::size_t i = 0; i < faces.size(); ++i) mesh.F.row(i) = faces[i];
  return mesh;
}

// Positions of a polygon's corners in the z = 0 plane; indices 0..n-1.
aniso::Positions planar(const std::vector<std::pair<double, double>>& corners) {
  aniso::Positions V(static_cast<Eigen::Index>(corners.size()), 3);
  for (std::size_t i = 0; i < corners.size(); ++i) V.row(i) << corners[i].first, corners[i].second, 0;
  return V;
}

std::vector<int> iota(int n) {
  std::vector<int> indices(n);
  for (int i = 0; i < n; ++i) indices[i] = i;
  return indices;
}

// Signed area of a triangle of planar corners (> 0: counter-clockwise seen from +z).
double signed_area(const aniso::Positions& V, const std::array<int, 3>& t) {
  const Eigen::Vector3d a = V.row(t[0]).transpose();
  return 0.5 * (V.row(t[1]).transpose() - a).cross(V.row(t[2]).transpose() - a).z();
}

double polygon_area(const aniso::Positions& V) {
  double area = 0;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Index j = (i + 1) % V.rows();
    area += 0.5 * (V(i, 0) * V(j, 1) - V(j, 0) * V(i, 1));
  }
  return area;
}

}  // namespace

TEST_CASE("check_mesh: a clean closed mesh has no problems and its MANIFEST counts", "[check]") {
  const MeshReport report = aniso::check_mesh(load("closed/spot_triangulated.obj"));
  CHECK(report.problems.empty());
  CHECK(report.solvable());
  CHECK(report.blocking_summary().empty());
  CHECK(report.components == 1);
  CHECK(report.boundary_loops == 0);
  CHECK(report.edge_manifold);
  CHECK(report.vertex_manifold);
  CHECK(report.consistently_oriented);
  CHECK(report.bbox.diagonal() > 0);
}

TEST_CASE("check_mesh: the NaN vertex is named and blocks solving", "[check]") {
  const Mesh mesh = load("malformed/bad_nan_coordinate.obj");
  const MeshReport report = aniso::check_mesh(mesh);
  CHECK(report.non_finite_vertices == 1);
  CHECK(elements_of(report, ProblemKind::NonFiniteCoordinate) == std::vector<int>{5});
  CHECK_THAT(message_of(report, ProblemKind::NonFiniteCoordinate), Catch::Contains("vertex 5"));
  CHECK_FALSE(report.solvable());
  CHECK(std::isfinite(report.bbox.diagonal()));  // the box leaves the NaN out
  try {
    aniso::require_solvable(mesh);
    FAIL("require_solvable accepted a NaN vertex");
  } catch (const aniso::Error& error) {
    CHECK(error.code() == aniso::ErrorCode::BadMesh);
    CHECK_THAT(error.what(), Catch::Contains("vertex 5 has a non-finite coordinate"));
  }
}

TEST_CASE("check_mesh: zero-area triangles are counted, the mesh stays solvable", "[check]") {
  const MeshReport report = aniso::check_mesh(load("malformed/bad_degenerate_faces.obj"));
  CHECK(report.degenerate_triangles == 6);
  // The four slivers appended at the end (1-based 1656, 1658, 1660, 1662) and
  // the two split faces whose new corner coincides with an old one.
  CHECK(elements_of(report, ProblemKind::ZeroAreaTriangle) == std::vector<int>{800, 1200, 1655, 1657, 1659, 1661});
  CHECK(report.boundary_loops == 0);
  CHECK(report.edge_manifold);
  CHECK(report.solvable());
  CHECK(aniso::check_mesh(load("malformed/degtri_sliding.off")).degenerate_triangles == 4);
}

TEST_CASE("check_mesh: flipped faces are the ones reported, their 15 edges counted", "[check]") {
  const MeshReport report = aniso::check_mesh(load("malformed/bad_flipped_faces.obj"));
  CHECK_FALSE(report.consistently_oriented);
  CHECK(report.inconsistent_edges == 15);
  // 1-based 4, 51, 52, 701, 1501 in the MANIFEST.
  CHECK(elements_of(report, ProblemKind::InconsistentOrientation) == std::vector<int>{3, 50, 51, 700, 1500});
  CHECK(report.solvable());
}

TEST_CASE("check_mesh: the fin triangle makes edge (44, 66) non-manifold", "[check]") {
  const MeshReport report = aniso::check_mesh(load("malformed/bad_nonmanifold_edge.obj"));
  CHECK_FALSE(report.edge_manifold);
  CHECK(report.non_manifold_edges == 1);
  CHECK(elements_of(report, ProblemKind::NonManifoldEdge) == std::vector<int>{1654});  // the fin
  CHECK_THAT(message_of(report, ProblemKind::NonManifoldEdge),
             Catch::Contains("edge (44, 66) is shared by 3 faces"));
  CHECK(report.boundary_loops == 1);
  CHECK(report.solvable());
}

TEST_CASE("check_mesh: the real Spider STL shows its MANIFEST defects", "[check]") {
  const aniso::ReadResult read = aniso::read_mesh(aniso::test::mesh_path("malformed/Spider_binary.stl"));
  const MeshReport report = aniso::check_mesh(read.mesh);
  CHECK(report.vertices == 722);
  CHECK(report.triangles == 1368);
  CHECK(report.components == 18);
  CHECK(report.non_manifold_edges == 16);
  // All 56 zero-area triangles have corners welded together: repeated corners.
  CHECK(report.degenerate_triangles == 56);
  CHECK(elements_of(report, ProblemKind::RepeatedCorner).size() == 56);
  CHECK_FALSE(report.consistently_oriented);
  // 6 connected boundary pieces; at non-manifold boundary vertices the walk
  // may split one piece into several loops.
  CHECK(report.boundary_loops >= 6);
  CHECK(report.solvable());
}

TEST_CASE("check_mesh: the soup is detected and exact welding gives back the closed spot", "[check]") {
  const Mesh soup = load("malformed/bad_triangle_soup.obj");
  CHECK(aniso::is_triangle_soup(soup));
  CHECK(aniso::check_mesh(soup).components == 1654);
  std::vector<int> old_to_new;
  const Mesh welded = aniso::weld_vertices(soup, 0.0, &old_to_new);
  CHECK(old_to_new.size() == 4962);
  CHECK(welded.num_vertices() == 829);
  CHECK(welded.num_triangles() == 1654);
  CHECK_FALSE(aniso::is_triangle_soup(welded));
  const MeshReport report = aniso::check_mesh(welded);
  CHECK(report.components == 1);
  CHECK(report.boundary_loops == 0);
  CHECK(report.edge_manifold);
  CHECK(report.consistently_oriented);

  const Mesh spot = load("formats/spot_lowres.obj");
  CHECK_FALSE(aniso::is_triangle_soup(spot));
  SECTION("welding a mesh without duplicates changes nothing") {
    const Mesh same = aniso::weld_vertices(spot, 0.0, &old_to_new);
    CHECK(same.V == spot.V);
    CHECK(same.F == spot.F);
  }
}

TEST_CASE("weld_vertices: a tolerance merges positions within it in every coordinate, not farther", "[check]") {
  const Mesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1e-7, -1e-7, 0}, {1, 1e-7, 3e-7}, {0, 1.1, 0},
                               {std::nan(""), 0, 0}},
                              {{0, 1, 2}, {3, 4, 5}, {3, 6, 2}});
  std::vector<int> old_to_new;
  const Mesh welded = aniso::weld_vertices(mesh, 1e-6, &old_to_new);
  CHECK(old_to_new == std::vector<int>{0, 1, 2, 0, 1, 3, 4});  // NaN equals nothing
  CHECK(welded.num_vertices() == 5);
  CHECK(welded.V.row(1) == Eigen::RowVector3d(1, 0, 0));  // the earliest vertex of a group stays
  CHECK(welded.num_triangles() == 3);
  CHECK(aniso::weld_vertices(mesh, 0.0).num_vertices() == 7);
  // A face welding collapses is dropped.
  const Mesh sliver = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1e-9, 0}}, {{0, 1, 2}});
  CHECK(aniso::weld_vertices(sliver, 1e-6).num_triangles() == 0);
  CHECK_THROWS_AS(aniso::weld_vertices(mesh, -1.0), aniso::Error);
}

TEST_CASE("check_mesh: hand-made defects are each named with their element", "[check]") {
  // Two triangles touching only at vertex 0 (a bowtie), a duplicate of the
  // first, a face with a repeated corner, and an unused vertex 5.
  const Mesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}, {9, 9, 9}},
                              {{0, 1, 2}, {0, 3, 4}, {2, 0, 1}, {1, 1, 2}});
  const MeshReport report = aniso::check_mesh(mesh);
  CHECK(elements_of(report, ProblemKind::DuplicateFace) == std::vector<int>{2});
  CHECK_THAT(message_of(report, ProblemKind::DuplicateFace), Catch::Contains("same vertices as face 0"));
  CHECK(elements_of(report, ProblemKind::RepeatedCorner) == std::vector<int>{3});
  CHECK(elements_of(report, ProblemKind::UnreferencedVertex) == std::vector<int>{5});
  CHECK(elements_of(report, ProblemKind::NonManifoldVertex) == std::vector<int>{0});
  CHECK(report.unreferenced_vertices == 1);
  CHECK(report.duplicate_faces == 1);
  CHECK(report.degenerate_triangles == 1);
  CHECK_FALSE(report.vertex_manifold);
  CHECK(report.solvable());  // none of these blocks a solve

  SECTION("problem kinds come in enum order, elements ascending within a kind") {
    for (std::size_t i = 1; i < report.problems.size(); ++i) {
      const auto& a = report.problems[i - 1];
      const auto& b = report.problems[i];
      CHECK((a.kind < b.kind || (a.kind == b.kind && a.element <= b.element)));
    }
  }
  SECTION("an index out of range blocks, and the summary lists blocking problems only") {
    Mesh bad = mesh;
    bad.F(1, 2) = 17;
    bad.V(4, 1) = std::numeric_limits<double>::infinity();
    const MeshReport bad_report = aniso::check_mesh(bad);
    CHECK(elements_of(bad_report, ProblemKind::IndexOutOfRange) == std::vector<int>{1});
    CHECK_FALSE(bad_report.solvable());
    const std::string summary = bad_report.blocking_summary();
    CHECK_THAT(summary, Catch::Contains("vertex 4") && Catch::Contains("face 1 (0, 3, 17)"));
    CHECK_THAT(summary, !Catch::Contains("duplicate") && !Catch::Contains("same vertices"));
    CHECK(bad_report.blocking_summary(1) == message_of(bad_report, ProblemKind::NonFiniteCoordinate) + "; ... and 1 more");
    CHECK_THROWS_AS(aniso::require_solvable(bad), aniso::Error);
  }
  SECTION("an empty mesh is named and blocks") {
    const MeshReport empty = aniso::check_mesh(Mesh{});
    CHECK(elements_of(empty, ProblemKind::EmptyMesh).size() == 2);
    CHECK(empty.blocking_summary() == "the mesh has no vertices; the mesh has no triangles");
  }
  CHECK(std::string(aniso::problem_kind_name(ProblemKind::NonManifoldEdge)) == "non-manifold-edge");
}

TEST_CASE("triangulate_polygon: convex, concave and collinear polygons give n-2 triangles covering their area", "[check]") {
  const std::vector<std::vector<std::pair<double, double>>> polygons = {
      {{0, 0}, {1, 0}, {1, 1}, {0, 1}},                                  // square
      {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},                  // L shape
      {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {1.5, 1}, {0, 1}},        // collinear corners
      {{0, 0}, {4, 0}, {4, 4}, {3, 1}, {2, 4}, {1, 1}, {0, 4}},          // comb with deep notches
      {{0, 0}, {10, 0}, {10, 1}, {1, 1}, {1, 9}, {10, 9}, {10, 10}, {0, 10}},  // C shape
  };
  for (const auto& corners : polygons) {
    const aniso::Positions V = planar(corners);
    const std::vector<int> polygon = iota(static_cast<int>(corners.size()));
    const auto triangles = aniso::triangulate_polygon(V, polygon);
    INFO("polygon with " << corners.size() << " corners");
    CHECK(triangles.size() == corners.size() - 2);
    double area = 0;
    for (const auto& t : triangles) {
      CHECK(signed_area(V, t) > 0);  // no flipped triangle: the winding is kept
      area += signed_area(V, t);
    }
    CHECK(area == Approx(polygon_area(V)).epsilon(1e-12));
    // Reversed, the polygon winds the other way and so do its triangles.
    std::vector<int> reversed(polygon.rbegin(), polygon.rend());
    for (const auto& t : aniso::triangulate_polygon(V, reversed)) CHECK(signed_area(V, t) < 0);
  }
}

TEST_CASE("triangulate_polygon: a hole joined by a doubled bridge edge is left uncovered", "[check]") {
  // Outer square 0..3 (counter-clockwise), inner square 4..7 (clockwise),
  // bridge 0-4 walked there and back: 0 1 2 3 0 4 7 6 5 4 over 8 vertices.
  const aniso::Positions V = planar({{0, 0}, {4, 0}, {4, 4}, {0, 4}, {1, 1}, {3, 1}, {3, 3}, {1, 3}});
  const std::vector<int> polygon = {0, 1, 2, 3, 0, 4, 7, 6, 5, 4};
  const auto triangles = aniso::triangulate_polygon(V, polygon);
  CHECK(triangles.size() == 8);
  double area = 0;
  for (const auto& t : triangles) {
    CHECK(signed_area(V, t) > 0);
    area += signed_area(V, t);
  }
  CHECK(area == Approx(16 - 4));
}

TEST_CASE("triangulate_polygon: degenerate and self-intersecting polygons still give n-2 triangles", "[check]") {
  // All corners on a line: no plane, a fan.
  CHECK(aniso::triangulate_polygon(planar({{0, 0}, {1, 0}, {2, 0}, {3, 0}}), iota(4)).size() == 2);
  // A bowtie crosses itself: no proper ears, still 2 triangles.
  CHECK(aniso::triangulate_polygon(planar({{0, 0}, {1, 1}, {1, 0}, {0, 1}}), iota(4)).size() == 2);
  // A non-finite corner.
  aniso::Positions nan_corner = planar({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  nan_corner(2, 0) = std::nan("");
  CHECK(aniso::triangulate_polygon(nan_corner, iota(4)).size() == 2);
  // A non-planar quad is triangulated in its best-fit plane.
  aniso::Positions bent = planar({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  bent(2, 2) = 0.3;
  CHECK(aniso::triangulate_polygon(bent, iota(4)).size() == 2);
  // A 20000-corner star (every other corner reflex). Its speed is the
  // benchmarks' business; a quadratic ear search would hit ctest's timeout.
  std::vector<std::pair<double, double>> star;
  for (int i = 0; i < 20000; ++i) {
    const double angle = 2 * std::acos(-1.0) * i / 20000;
    const double radius = i % 2 ? 1.0 : 0.9;
    star.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  CHECK(aniso::triangulate_polygon(planar(star), iota(20000)).size() == 19998);

  CHECK_THROWS_AS(aniso::triangulate_polygon(planar({{0, 0}, {1, 0}}), iota(2)), aniso::Error);
  CHECK_THROWS_AS(aniso::triangulate_polygon(planar({{0, 0}, {1, 0}, {0, 1}}), {0, 1, 3}), aniso::Error);
}

TEST_CASE("check_mesh: an unused vertex counts toward neither the box, the unit guess nor the mesh's size",
          "[check]") {
  // spothead (0.93 units wide: metres) plus one `v 10 10 10` that no face
  // uses: the box reached 10, the unit guess said centimetres (a pattern 100
  // times too small), and the move and twist limits grew with it.
  std::string text = aniso::test::slurp(aniso::test::mesh_path("open/spothead.obj"));
  REQUIRE(!text.empty());
  const std::string plain = text;
  text += "\nv 10 10 10\n";
  aniso::Session session;
  const aniso::SessionMeshInfo& info = session.load_mesh(reinterpret_cast<const std::uint8_t*>(text.data()),
                                                         text.size(), "spothead_unused.obj");
  REQUIRE(info.report.unreferenced_vertices == 1);
  const Mesh head = load("open/spothead.obj");
  const aniso::BoundingBox expected = aniso::bounding_box(head.V);
  CHECK(info.report.bbox.min == expected.min);
  CHECK(info.report.bbox.max == expected.max);
  const aniso::Json json = aniso::to_json(info);
  CHECK(json["unitGuess"]["name"] == "m");
  CHECK(json["bbox"]["max"][0].get<double>() == expected.max.x());
  // The deformer measures the same size: a move of 100 diagonals of spothead is the limit.
  Mesh with_unused = head;
  with_unused.V.conservativeResize(head.num_vertices() + 1, 3);
  with_unused.V.row(head.num_vertices()) = Eigen::RowVector3d(10, 10, 10);
  aniso::DeformRequest move;
  move.method = aniso::Method::Arap;
  move.handles = {0};
  move.handle_offset = Eigen::Vector3d(101.0 * expected.diagonal(), 0, 0);
  const std::string message = aniso::test::bad_parameter_message([&] { aniso::Deformer(with_unused).deform(move); });
  CHECK_THAT(message, Catch::Contains("bounding-box diagonal of 1.5"));
}
