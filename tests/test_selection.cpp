// Selections: the CLI region forms, region weights, edge-path distances and
// the smooth falloff border.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "anisoform/error.h"
#include "anisoform/selection.h"
#include "cli_runner.h"
#include "test_support.h"

using aniso::Region;

namespace {

using aniso::test::bad_parameter_message;
using aniso::test::write_temp_text;

// A strip of unit squares along x, two triangles each: vertices (k, 0, 0) and
// (k, 1, 0) for k = 0..cells. Edge paths along the bottom row are straight.
aniso::Mesh strip(int cells) {
  aniso::Mesh mesh;
  mesh.V.resize(2 * (cells + 1), 3);
  for (int k = 0; k <= cells; ++k) {
    mesh.V.row(2 * k) << k, 0, 0;
    mesh.V.row(2 * k + 1) << k, 1, 0;
  }
  mesh.F.resize(2 * cells, 3);
  for (int k = 0; k < cells; ++k) {
    mesh.F.row(2 * k) << 2 * k, 2 * k + 2, 2 * k + 3;
    mesh.F.row(2 * k + 1) << 2 * k, 2 * k + 3, 2 * k + 1;
  }
  return mesh;
}

double smoothstep(double x) {
  const double t = std::min(1.0, std::max(0.0, x));
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

TEST_CASE("selection: parse_region reads every CLI form", "[selection]") {
  CHECK(aniso::parse_region("all").kind == Region::Kind::All);

  const Region box = aniso::parse_region("box:-1,-2,-3,1,2.5,3e0");
  CHECK(box.kind == Region::Kind::Box);
  CHECK(box.min == Eigen::Vector3d(-1, -2, -3));
  CHECK(box.max == Eigen::Vector3d(1, 2.5, 3));

  const Region sphere = aniso::parse_region("sphere:0.5, 0, -1, 2");
  CHECK(sphere.kind == Region::Kind::Sphere);
  CHECK(sphere.center == Eigen::Vector3d(0.5, 0, -1));
  CHECK(sphere.radius == 2.0);

  const std::string plain = write_temp_text("selection_plain.txt", "# picked\n3\n\n7\r\n  11  \n");
  const Region listed = aniso::parse_region("file:" + plain);
  CHECK(listed.kind == Region::Kind::Vertices);
  CHECK(listed.vertices == std::vector<int>{3, 7, 11});
  CHECK(listed.weights.empty());

  const std::string weighted = write_temp_text("selection_weighted.txt", "3 0.25\n7\n11 1 # full\n");
  const Region soft = aniso::parse_region("file:" + weighted);
  CHECK(soft.vertices == std::vector<int>{3, 7, 11});
  CHECK(soft.weights == std::vector<double>{0.25, 1.0, 1.0});
}

TEST_CASE("selection: parse_region errors name the problem", "[selection]") {
  CHECK_THAT(bad_parameter_message([] { aniso::parse_region("box:1,2,3,4"); }),
             Catch::Contains("box needs 6 numbers, got 4"));
  CHECK_THAT(bad_parameter_message([] { aniso::parse_region("sphere:1,2,x,4"); }),
             Catch::Contains("sphere number 3: 'x' is not a number"));
  CHECK_THAT(bad_parameter_message([] { aniso::parse_region("sphere:1,2,3,nan"); }),
             Catch::Contains("sphere number 4"));
  CHECK_THAT(bad_parameter_message([] { aniso::parse_region("box:0,0,0,1,1,1,"); }),
             Catch::Contains("box needs 6 numbers, got 7"));
  CHECK_THAT(bad_parameter_message([] { aniso::parse_region("cube:1"); }),
             Catch::Contains("unknown region 'cube:1'"));
  CHECK_THAT(aniso::test::error_message_of([] { aniso::parse_region("file:/nonexistent/sel.txt"); },
                                           aniso::ErrorCode::BadFile),
             Catch::Contains("cannot open /nonexistent/sel.txt: no such file"));

  const std::string bad_index = write_temp_text("selection_bad_index.txt", "1\n2\n-3\n");
  CHECK_THAT(bad_parameter_message([&] { aniso::parse_region("file:" + bad_index); }),
             Catch::Contains(bad_index + " line 3: vertex index must be a non-negative integer, got '-3'"));
  const std::string bad_weight = write_temp_text("selection_bad_weight.txt", "1 0.5\n2 1.5\n");
  CHECK_THAT(bad_parameter_message([&] { aniso::parse_region("file:" + bad_weight); }),
             Catch::Contains("line 2: weight 1.5 is outside [0, 1]"));
  const std::string extra = write_temp_text("selection_extra.txt", "1 0.5 7\n");
  CHECK_THAT(bad_parameter_message([&] { aniso::parse_region("file:" + extra); }),
             Catch::Contains("line 1: expected a vertex index and an optional weight, got 3 values"));
  const std::string hex_weight = write_temp_text("selection_hex_weight.txt", "1 0.5\n2 0x1p-1\n");
  CHECK_THAT(bad_parameter_message([&] { aniso::parse_region("file:" + hex_weight); }),
             Catch::Contains("line 2: weight: '0x1p-1' is a hexadecimal number"));
  CHECK_THAT(bad_parameter_message([] { aniso::parse_region("sphere:0,0,0,0x1p0"); }),
             Catch::Contains("sphere number 4: '0x1p0' is a hexadecimal number"));
  CHECK_THAT(aniso::test::error_message_of(
                 [] { aniso::parse_region(std::string("file:") + aniso::test::kScratchDir); },
                 aniso::ErrorCode::BadFile),
             Catch::Contains(std::string(aniso::test::kScratchDir) + " is a directory, not a regular file"));
  const std::string empty = write_temp_text("selection_empty.txt", "# nothing\n\n");
  CHECK_THAT(bad_parameter_message([&] { aniso::parse_region("file:" + empty); }),
             Catch::Contains("lists no vertices"));
}

TEST_CASE("selection: region weights of boxes, spheres and vertex lists", "[selection]") {
  const aniso::Mesh mesh = strip(4);  // x = 0..4, y = 0..1

  CHECK(aniso::region_weights(mesh, aniso::parse_region("all")) == Eigen::VectorXd::Ones(10));

  const Eigen::VectorXd box = aniso::region_weights(mesh, aniso::parse_region("box:0.5,-1,-1,2,0.5,1"));
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const bool inside = mesh.V(i, 0) >= 0.5 && mesh.V(i, 0) <= 2 && mesh.V(i, 1) <= 0.5;
    CHECK(box[i] == (inside ? 1.0 : 0.0));
  }

  const Eigen::VectorXd ball = aniso::region_weights(mesh, aniso::parse_region("sphere:0,0,0,1"));
  CHECK(ball.sum() == 3.0);  // (0,0), (0,1) and (1,0): the radius is inclusive

  Region listed;
  listed.kind = Region::Kind::Vertices;
  listed.vertices = {2, 5, 2};
  listed.weights = {0.25, 0.5, 0.75};
  const Eigen::VectorXd soft = aniso::region_weights(mesh, listed);
  CHECK(soft[2] == 0.75);  // listed twice: the larger weight
  CHECK(soft[5] == 0.5);
  CHECK(soft.sum() == 1.25);
}

TEST_CASE("selection: region_weights refuses bad regions", "[selection]") {
  const aniso::Mesh mesh = strip(2);
  Region listed;
  listed.kind = Region::Kind::Vertices;
  listed.vertices = {0, 6};
  CHECK_THAT(bad_parameter_message([&] { aniso::region_weights(mesh, listed); }),
             Catch::Contains("selected vertex 6 is out of range (the mesh has 6 vertices)"));
  listed.vertices = {0, 1};
  listed.weights = {0.5, -0.1};
  CHECK_THAT(bad_parameter_message([&] { aniso::region_weights(mesh, listed); }),
             Catch::Contains("selected vertex 1 has weight"));
  listed.weights = {0.5};
  CHECK_THAT(bad_parameter_message([&] { aniso::region_weights(mesh, listed); }),
             Catch::Contains("2 vertices but 1 weights"));
  CHECK_THAT(bad_parameter_message([&] { aniso::region_weights(mesh, aniso::parse_region("sphere:0,0,0,-1")); }),
             Catch::Contains("sphere radius is negative"));
  CHECK_THAT(bad_parameter_message([&] { aniso::region_weights(mesh, aniso::parse_region("box:0,2,0,1,1,1")); }),
             Catch::Contains("box minimum exceeds its maximum along y"));
}

TEST_CASE("selection: edge-path distances are exact along straight edge paths", "[selection]") {
  const aniso::Mesh mesh = strip(6);
  Eigen::VectorXd seed = Eigen::VectorXd::Zero(mesh.num_vertices());
  seed[0] = 1.0;
  const Eigen::VectorXd d = aniso::distance_from(mesh, seed);
  for (int k = 0; k <= 6; ++k) {
    CHECK(d[2 * k] == Approx(k).margin(1e-12));                       // along the bottom row
    CHECK(d[2 * k + 1] == Approx(k == 0 ? 1.0 : (k - 1) + std::sqrt(2.0)).margin(1e-12));  // one diagonal
  }
}

TEST_CASE("selection: distances from several seeds are the nearest seed's, infinite across components",
          "[selection]") {
  const aniso::Mesh mesh = aniso::test::load("malformed/multi_component.obj");  // spot + blub, disjoint
  const int n = mesh.num_vertices();
  Eigen::VectorXd first = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd second = Eigen::VectorXd::Zero(n);
  first[10] = 1.0;
  second[400] = 0.3;
  const Eigen::VectorXd both = aniso::distance_from(mesh, first + second);
  const Eigen::VectorXd d1 = aniso::distance_from(mesh, first);
  const Eigen::VectorXd d2 = aniso::distance_from(mesh, second);
  int unreachable = 0;
  for (int i = 0; i < n; ++i) {
    if (std::isfinite(both[i])) CHECK(both[i] == Approx(std::min(d1[i], d2[i])).margin(1e-12));
    CHECK(std::isinf(both[i]) == std::isinf(std::min(d1[i], d2[i])));
    // An edge path is never shorter than the straight line.
    if (std::isfinite(d1[i])) CHECK(d1[i] >= (mesh.V.row(i) - mesh.V.row(10)).norm() - 1e-12);
    if (std::isinf(both[i])) ++unreachable;
  }
  CHECK(unreachable > 0);  // the second body (both seeds lie on the first)
  CHECK(unreachable < n);
}

TEST_CASE("selection: falloff is smoothstep(1 - d/falloff) outside the region, weights kept inside",
          "[selection]") {
  const aniso::Mesh mesh = aniso::test::load("closed/spot_triangulated.obj");
  const aniso::BoundingBox box = aniso::bounding_box(mesh.V);
  Region sphere;
  sphere.kind = Region::Kind::Sphere;
  sphere.center = mesh.V.row(0).transpose();
  sphere.radius = 0.1 * box.diagonal();
  const Eigen::VectorXd region = aniso::region_weights(mesh, sphere);
  REQUIRE(region.sum() > 0);
  const double falloff = 0.2 * box.diagonal();
  const Eigen::VectorXd w = aniso::apply_falloff(mesh, region, falloff);
  const Eigen::VectorXd d = aniso::distance_from(mesh, region);
  int border = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    CHECK(w[i] == Approx(std::max(region[i], smoothstep(1.0 - d[i] / falloff))).margin(1e-15));
    if (w[i] > 0.0 && w[i] < 1.0) ++border;
  }
  CHECK(border > 10);
  CHECK(aniso::selection_weights(mesh, sphere, falloff) == w);
  CHECK(aniso::apply_falloff(mesh, region, 0.0) == region);
}

TEST_CASE("selection: falloff keeps soft vertex weights and fades from them", "[selection]") {
  const aniso::Mesh mesh = strip(8);
  Eigen::VectorXd region = Eigen::VectorXd::Zero(mesh.num_vertices());
  region[0] = 0.5;
  region[1] = 0.5;
  const Eigen::VectorXd w = aniso::apply_falloff(mesh, region, 4.0);
  CHECK(w[0] == 0.5);
  CHECK(w[2] == Approx(0.5 * smoothstep(1.0 - 1.0 / 4.0)));  // one unit from the nearest seed
  CHECK(w[8] == 0.0);                                          // four units away: the border ends
  for (int k = 1; k < 8; ++k) CHECK(w[2 * k + 2] <= w[2 * k]);
}

TEST_CASE("selection: apply_falloff refuses a negative or non-finite width", "[selection]") {
  const aniso::Mesh mesh = strip(2);
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(mesh.num_vertices());
  CHECK_THAT(bad_parameter_message([&] { aniso::apply_falloff(mesh, w, -1.0); }),
             Catch::Contains("falloff must be a finite distance >= 0"));
  CHECK_THAT(bad_parameter_message(
                 [&] { aniso::apply_falloff(mesh, w, std::numeric_limits<double>::quiet_NaN()); }),
             Catch::Contains("falloff"));
  CHECK_THAT(bad_parameter_message([&] { aniso::distance_from(mesh, Eigen::VectorXd::Ones(3)); }),
             Catch::Contains("seed weights have 3 entries, the mesh has 6 vertices"));
}

TEST_CASE("selection: a bounded falloff gives exactly the weights of a walk over the whole mesh",
          "[selection]") {
  // The reference: the unbounded edge-path distance of every vertex, put into
  // the documented rule max(w, smoothstep(1 - d/falloff)).
  const aniso::Mesh mesh = aniso::test::load("closed/armadillo.off");
  const aniso::BoundingBox box = aniso::bounding_box(mesh.V);
  Region sphere;
  sphere.kind = Region::Kind::Sphere;
  sphere.center = mesh.V.row(100).transpose();
  sphere.radius = 0.03 * box.diagonal();
  const Eigen::VectorXd region = aniso::region_weights(mesh, sphere);
  const Eigen::VectorXd d = aniso::distance_from(mesh, region);
  REQUIRE(std::isfinite(d.maxCoeff()));  // the unbounded walk reaches every vertex
  for (double share : {0.01, 0.05, 0.3}) {
    const double falloff = share * box.diagonal();
    const Eigen::VectorXd w = aniso::apply_falloff(mesh, region, falloff);
    int border = 0, differ = 0;
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      differ += w[i] != std::max(region[i], smoothstep(1.0 - d[i] / falloff));
      border += w[i] > 0.0 && w[i] < 1.0;
    }
    CHECK(differ == 0);
    CHECK(border > 0);
  }
}
