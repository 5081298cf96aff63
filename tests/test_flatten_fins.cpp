// Edges shared by three or more faces, which no piece of fabric holds: a fin
// (a triangle or a small flap glued on an edge) is left out of the pattern
// and named; anything larger is refused, naming the edge. A fin flattened
// with the rest came out as a second closed outline inside the piece: a cut
// line in the SVG and DXF that no one asked for.
#include <string>
#include <vector>

#include "anisoform/flatten.h"
#include "anisoform/pattern_export.h"
#include "test_support.h"

using namespace aniso;

namespace {

// The mesh with one more triangle on the edge (a, b): its third corner a new
// vertex off the surface, an edge's length above the edge's middle.
Mesh with_fin(Mesh mesh, int a, int b) {
  const Eigen::Vector3d pa = mesh.V.row(a), pb = mesh.V.row(b);
  const int tip = mesh.num_vertices();
  mesh.V.conservativeResize(tip + 1, 3);
  mesh.V.row(tip) = (0.5 * (pa + pb) + Eigen::Vector3d(0.0, 0.0, (pb - pa).norm())).transpose();
  const int face = mesh.num_triangles();
  mesh.F.conservativeResize(face + 1, 3);
  mesh.F.row(face) << a, b, tip;
  return mesh;
}

}  // namespace

TEST_CASE("flatten: a fin triangle on the torso panel is left out and named, the pattern one outline as without it",
          "[flatten][fins]") {
  const Mesh torso = test::load("open/human_woman_torso_front_patch.obj");
  // Face 100's first edge is inside the panel: the fin makes it a three-face edge.
  const Mesh mesh = with_fin(torso, torso.F(100, 0), torso.F(100, 1));
  const int fin = torso.num_triangles();
  FlattenOptions options;
  options.su = 0.8;
  const FlattenOutput reference = flatten(torso, {}, options);
  const FlattenOutput out = flatten(mesh, {}, options);
  CHECK(out.result.metrics.dropped_faces == std::vector<int>{fin});
  CHECK(out.patch.mesh.num_triangles() == torso.num_triangles());
  // The fin made a second boundary loop, written as a second closed outline.
  CHECK(out.result.metrics.boundary_loops == 1);
  const Pattern pattern = make_pattern(out.patch, out.result);
  CHECK(pattern.outline_count() == 1);
  PatternExportOptions export_options;
  export_options.mm_per_unit = 1000.0;
  CHECK(test::count_of(write_pattern_svg(pattern, export_options), "class=\"outline\"") == 1);
  CHECK(test::count_of(write_pattern_dxf(pattern, export_options), "POLYLINE") == 1);
  // The pattern of the panel as it is without the fin.
  REQUIRE(out.result.uv.rows() == reference.result.uv.rows());
  CHECK((out.result.uv - reference.result.uv).cwiseAbs().maxCoeff() < 1e-9);
  CHECK(out.result.metrics.compression_error_mean == Approx(reference.result.metrics.compression_error_mean));
  CHECK(flatten_problem(out.result.metrics).empty());
  CHECK(test::any_contains(flatten_warnings(out.result.metrics),
                 "1 face(s) hanging off edges shared by three or more faces (a fin: face " + std::to_string(fin) +
                     ") were left out of the pattern"));
}

TEST_CASE("flatten: a closed mesh whose only boundary is a fin is refused as closed, naming the fin",
          "[flatten][fins]") {
  // Spot with one fin triangle (its last face, 1654, on the edge (44, 66)):
  // it used to flatten around the fin, folded over.
  const Mesh mesh = test::load("malformed/bad_nonmanifold_edge.obj");
  const std::string message =
      test::error_message_of([&] { flatten(mesh, {}, FlattenOptions{}); }, ErrorCode::BadMesh);
  CHECK(message ==
        "the patch is closed: flattening needs a boundary; select a part of the mesh (1 face(s) hanging off "
        "edges shared by three or more faces were left out: face " +
            std::to_string(mesh.num_triangles() - 1) + ")");
}

TEST_CASE("flatten: three equal pages on one edge are no fin: refused, naming the edge and its faces",
          "[flatten][fins]") {
  // Three unit squares (two triangles each) hinged on the edge (0, 1).
  Mesh book;
  book.V.resize(8, 3);
  book.V << 0, 0, 0, 0, 1, 0,  //
      1, 0, 0, 1, 1, 0,        //
      -1, 0, 0, -1, 1, 0,      //
      0, 0, 1, 0, 1, 1;
  book.F.resize(6, 3);
  book.F << 0, 2, 1, 1, 2, 3,  //
      1, 4, 0, 1, 5, 4,        //
      0, 6, 1, 1, 6, 7;
  const std::string message =
      test::error_message_of([&] { flatten(book, {}, FlattenOptions{}); }, ErrorCode::BadMesh);
  CHECK(message ==
        "the patch cannot be laid flat as one piece: edge (0, 1) is shared by 3 faces (0, 2, 4), and no flat piece "
        "can hold an edge shared by three or more faces; the faces off it are more than a fin: select the faces on "
        "one side of it and flatten them apart");
}
