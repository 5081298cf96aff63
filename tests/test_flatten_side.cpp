// Which side of the fabric a pattern shows (kPatternSide, pattern_export.h):
// the piece seen from the side its faces' normals point to. A pattern maker
// cuts the mirror image of a piece as a wrong piece, so the rule must hold
// whatever the mesh's winding, and the files must say it.
#include <cmath>
#include <string>
#include <vector>

#include "anisoform/flatten.h"
#include "anisoform/pattern_export.h"
#include "test_support.h"

using namespace aniso;

namespace {

const char* const kTorsoPanel = "open/human_woman_torso_front_patch.obj";

// The pattern per input vertex (the patch numbers vertices as its faces meet
// them, which a change of winding changes).
Eigen::MatrixX2d uv_by_input_vertex(const FlattenOutput& out, int input_vertices) {
  Eigen::MatrixX2d uv = Eigen::MatrixX2d::Zero(input_vertices, 2);
  for (std::size_t i = 0; i < out.patch.input_vertex.size(); ++i) {
    uv.row(out.patch.input_vertex[i]) = out.result.uv.row(static_cast<int>(i));
  }
  return uv;
}

// The largest distance between b and a turned and moved onto it as well as
// a rotation and a translation can (2D Procrustes without reflection).
double rigid_misfit(const Eigen::MatrixX2d& a, const Eigen::MatrixX2d& b) {
  const Eigen::MatrixX2d a0 = a.rowwise() - a.colwise().mean();
  const Eigen::MatrixX2d b0 = b.rowwise() - b.colwise().mean();
  double dot = 0.0, cross = 0.0;
  for (int i = 0; i < a0.rows(); ++i) {
    dot += a0(i, 0) * b0(i, 0) + a0(i, 1) * b0(i, 1);
    cross += a0(i, 0) * b0(i, 1) - a0(i, 1) * b0(i, 0);
  }
  const double angle = std::atan2(cross, dot);
  Eigen::Matrix2d turn;
  turn << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return ((a0 * turn.transpose()) - b0).rowwise().norm().maxCoeff();
}

Eigen::MatrixX2d mirrored_pattern(Eigen::MatrixX2d uv) {
  uv.col(0) = -uv.col(0);
  return uv;
}

double pattern_extent(const Eigen::MatrixX2d& uv) { return (uv.colwise().maxCoeff() - uv.colwise().minCoeff()).maxCoeff(); }

// Every face counter-clockwise in the pattern, with the patch's winding.
int clockwise_faces(const FlattenOutput& out) {
  int clockwise = 0;
  for (int t = 0; t < out.patch.mesh.num_triangles(); ++t) {
    const Eigen::RowVector2d a = out.result.uv.row(out.patch.mesh.F(t, 0));
    const Eigen::RowVector2d ab = out.result.uv.row(out.patch.mesh.F(t, 1)) - a;
    const Eigen::RowVector2d ac = out.result.uv.row(out.patch.mesh.F(t, 2)) - a;
    if (!(ab.x() * ac.y() - ab.y() * ac.x() > 0.0)) ++clockwise;
  }
  return clockwise;
}

Mesh with_faces_turned(Mesh mesh, const std::vector<int>& faces) {
  for (const int f : faces) std::swap(mesh.F(f, 1), mesh.F(f, 2));
  return mesh;
}

}  // namespace

TEST_CASE("flatten: the torso panel wound the other way is its pattern's mirror image, and the files say "
          "which side they show", "[flatten][side]") {
  const Mesh mesh = test::load(kTorsoPanel);
  std::vector<int> all(mesh.num_triangles());
  for (int f = 0; f < mesh.num_triangles(); ++f) all[f] = f;
  const Mesh reversed = with_faces_turned(mesh, all);
  FlattenOptions options;
  options.su = 0.8;
  const FlattenOutput front = flatten(mesh, {}, options);
  const FlattenOutput back = flatten(reversed, {}, options);
  const Eigen::MatrixX2d a = uv_by_input_vertex(front, mesh.num_vertices());
  const Eigen::MatrixX2d b = uv_by_input_vertex(back, mesh.num_vertices());
  const double size = pattern_extent(a);
  INFO("pattern " << size << " across");
  // Each seen from its normals' side: the mirror image of the other, not the same piece.
  CHECK(rigid_misfit(mirrored_pattern(a), b) < 1e-6 * size);
  CHECK(rigid_misfit(a, b) > 0.5 * size);
  CHECK(clockwise_faces(front) == 0);
  CHECK(clockwise_faces(back) == 0);
  CHECK(front.result.metrics.reoriented_faces.empty());
  CHECK(back.result.metrics.reoriented_faces.empty());

  // A cutter reads which side is up on the sheet itself, and a program in the file.
  const Pattern pattern = make_pattern(front.patch, front.result);
  PatternExportOptions export_options;
  export_options.mm_per_unit = 1000.0;
  const std::string svg = write_pattern_svg(pattern, export_options);
  const std::string dxf = write_pattern_dxf(pattern, export_options);
  const std::string side = "Face up: the side the mesh's face normals point to (the outside, for outward normals)";
  CHECK(std::string(kPatternSide) == side);
  CHECK(svg.find("<desc>" + side + "</desc>") != std::string::npos);
  CHECK(svg.find("\">" + side + "</tspan>") != std::string::npos);
  CHECK(dxf.find("999\n" + side + "\n") != std::string::npos);
  CHECK(dxf.find("0\nTEXT\n8\nNOTE\n") != std::string::npos);
  CHECK(dxf.find("1\n" + side + "\n") != std::string::npos);
}

TEST_CASE("flatten: faces wound against the rest of their piece are turned over and named, the pattern as if "
          "they were not", "[flatten][side]") {
  const Mesh mesh = test::load(kTorsoPanel);
  FlattenOptions options;
  options.su = 0.8;
  const FlattenOutput reference = flatten(mesh, {}, options);
  const Eigen::MatrixX2d wanted = uv_by_input_vertex(reference, mesh.num_vertices());
  const double size = pattern_extent(wanted);

  SECTION("one face (it folded over and the solver stopped unconverged)") {
    const FlattenOutput out = flatten(with_faces_turned(mesh, {100}), {}, options);
    CHECK(out.result.metrics.reoriented_faces == std::vector<int>{100});
    CHECK(out.result.metrics.flipped == 0);
    CHECK(rigid_misfit(wanted, uv_by_input_vertex(out, mesh.num_vertices())) < 1e-6 * size);
    const std::vector<std::string> warnings = flatten_warnings(out.result.metrics);
    CHECK(test::any_contains(warnings, "1 face(s) were wound against their neighbours (face 100): turned over to the "
                             "winding most of the piece has"));
    CHECK(flatten_problem(out.result.metrics).empty());
  }
  SECTION("the faces right of the middle, under half (the outline crossed itself 22 times, in 7 loops)") {
    std::vector<int> right;
    for (int f = 0; f < mesh.num_triangles(); ++f) {
      double x = 0.0;
      for (int k = 0; k < 3; ++k) x += mesh.V(mesh.F(f, k), 0);
      if (x > 0.0) right.push_back(f);
    }
    REQUIRE(2 * right.size() < static_cast<std::size_t>(mesh.num_triangles()));
    const FlattenOutput out = flatten(with_faces_turned(mesh, right), {}, options);
    CHECK(out.result.metrics.reoriented_faces == right);
    CHECK(out.result.metrics.boundary_loops == 1);
    CHECK(out.result.metrics.outline_crossings == 0);
    CHECK(rigid_misfit(wanted, uv_by_input_vertex(out, mesh.num_vertices())) < 1e-6 * size);
    CHECK(test::any_contains(flatten_warnings(out.result.metrics),
                   std::to_string(right.size()) + " face(s) were wound against their neighbours (faces " +
                       std::to_string(right[0]) + ", "));
  }
}

TEST_CASE("flatten: a Moebius strip, which no winding makes one-sided, is refused by name", "[flatten][side]") {
  // A strip of 24 quads around a circle, turned half a turn on the way.
  const int segments = 24;
  Mesh strip;
  strip.V.resize(2 * segments, 3);
  strip.F.resize(2 * segments, 3);
  for (int s = 0; s < segments; ++s) {
    const double angle = 2.0 * test::kPi * s / segments;
    const double twist = 0.5 * angle;
    const Eigen::Vector3d centre(std::cos(angle), std::sin(angle), 0.0);
    const Eigen::Vector3d across =
        0.2 * (std::cos(twist) * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0) +
               std::sin(twist) * Eigen::Vector3d::UnitZ());
    strip.V.row(2 * s) = (centre - across).transpose();
    strip.V.row(2 * s + 1) = (centre + across).transpose();
  }
  for (int s = 0; s < segments; ++s) {
    const int a = 2 * s, b = 2 * s + 1;
    // The last quad joins the first pair the other way round: the half turn.
    const bool last = s == segments - 1;
    const int c = last ? 1 : 2 * s + 2, d = last ? 0 : 2 * s + 3;
    strip.F.row(2 * s) << a, c, b;
    strip.F.row(2 * s + 1) << b, c, d;
  }
  const std::string message =
      test::error_message_of([&] { flatten(strip, {}, FlattenOptions{}); }, ErrorCode::BadMesh);
  CHECK(message.find("the patch cannot be wound one way: it is non-orientable (like a Moebius strip: at face ") !=
        std::string::npos);
  CHECK(message.find("a piece of fabric has a right and a wrong side: cut the patch there") != std::string::npos);
}

TEST_CASE("cli: flatten's JSON says which side the pattern shows, and its SVG too", "[flatten][side][cli]") {
  const std::string svg_path = test::temp_path("torso_side.svg");
  const CliRun run = test::run_cli_expecting(
      {"flatten", test::mesh_path(kTorsoPanel), svg_path, "--mm-per-unit", "1000"}, 0);
  CHECK(test::stdout_json(run)["side"] ==
        "Face up: the side the mesh's face normals point to (the outside, for outward normals)");
  CHECK(test::slurp(svg_path).find("<desc>Face up: the side the mesh's face normals point to") != std::string::npos);
}
