// Mesh readers and writers on the real files of ../shared/meshes: the same
// mesh from every format, polygon triangulation, clean errors for malformed
// files, exact round trips, and robustness against truncated and corrupted
// bytes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "anisoform/error.h"
#include "anisoform/mesh_check.h"
#include "anisoform/mesh_io.h"
#include "geometry/frames.h"
#include "test_support.h"

using aniso::Mesh;
using aniso::MeshFormat;
using aniso::ReadResult;
using aniso::test::load;
using aniso::test::mesh_path;

namespace {

std::string file_bytes(const std::string& relative) {
  std::ifstream in(mesh_path(relative), std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

ReadResult read_text(const std::string& text, MeshFormat format) {
  return aniso::read_mesh_from_memory(text.data(), text.size(), format);
}

// The message of the aniso::Error with `code` that `call` throws.
template <class Call>
std::string error_message(Call call, aniso::ErrorCode code = aniso::ErrorCode::BadFile) {
  return aniso::test::error_message_of(call, code);
}

std::string read_error(const std::string& relative) {
  return error_message([&] { aniso::read_mesh(mesh_path(relative)); });
}

using Position = std::array<double, 3>;

Position position_of(const Mesh& mesh, int v, bool as_float32) {
  Position p;
  for (int k = 0; k < 3; ++k) p[k] = as_float32 ? static_cast<float>(mesh.V(v, k)) : mesh.V(v, k);
  return p;
}

// `mesh`'s triangles in `reference`'s vertex numbering, matched by position
// (rounded to float32 when the file stored float32), each rotated to start at
// its smallest index so that winding is kept; sorted.
std::vector<std::array<int, 3>> triangles_in_numbering_of(const Mesh& reference, const Mesh& mesh,
                                                         bool as_float32) {
  std::map<Position, int> reference_index;
  for (int v = 0; v < reference.num_vertices(); ++v) reference_index[position_of(reference, v, as_float32)] = v;
  std::vector<std::array<int, 3>> triangles;
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    std::array<int, 3> t;
    for (int k = 0; k < 3; ++k) {
      const auto found = reference_index.find(position_of(mesh, mesh.F(f, k), as_float32));
      REQUIRE(found != reference_index.end());
      t[k] = found->second;
    }
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    triangles.push_back(t);
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

double triangle_area(const Mesh& mesh, int f) {
  const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose();
  const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1)).transpose();
  const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2)).transpose();
  return 0.5 * (b - a).cross(c - a).norm();
}

}  // namespace

TEST_CASE("mesh_io: every spot_lowres file in formats/ reads to the same mesh as spot_lowres.obj", "[io]") {
  const Mesh reference = load("formats/spot_lowres.obj");
  REQUIRE(reference.num_vertices() == 829);
  REQUIRE(reference.num_triangles() == 1654);

  SECTION("OBJ, OFF and ASCII PLY: identical positions and faces") {
    for (const char* file : {"formats/spot_lowres.off", "formats/spot_lowres_ascii.ply"}) {
      INFO(file);
      const Mesh mesh = load(file);
      CHECK(mesh.V == reference.V);
      CHECK(mesh.F == reference.F);
    }
  }
  SECTION("binary PLY: float32 positions within 1e-6 relative, identical faces") {
    const Mesh mesh = load("formats/spot_lowres_binary.ply");
    REQUIRE(mesh.num_vertices() == 829);
    CHECK(mesh.F == reference.F);
    const double scale = reference.V.cwiseAbs().maxCoeff();
    CHECK((mesh.V - reference.V).cwiseAbs().maxCoeff() <= 1e-6 * scale);
  }
  SECTION("STL: after welding, the same triangles up to vertex numbering") {
    const auto expected = triangles_in_numbering_of(reference, reference, false);
    for (const auto& [file, float32] : {std::pair{"formats/spot_lowres_ascii.stl", false},
                                        std::pair{"formats/spot_lowres_binary.stl", true}}) {
      INFO(file);
      const ReadResult read = aniso::read_mesh(mesh_path(file));
      CHECK(read.mesh.num_vertices() == 829);
      CHECK(read.mesh.num_triangles() == 1654);
      CHECK(read.report.vertices_welded == 3 * 1654 - 829);
      CHECK(triangles_in_numbering_of(reference, read.mesh, float32) == expected);
    }
  }
}

TEST_CASE("mesh_io: polygons triangulate into n-2 triangles of positive area, wound like their neighbours", "[io]") {
  struct Case {
    const char* file;
    int triangles;  // sum of (corners - 2) over the file's polygons
    int polygons;   // faces with more than 3 corners
    int boundary_loops;
  };
  const Case cases[] = {
      {"formats/spot_quadrangulated.obj", 2 * 2928, 2928, 0},
      {"formats/spot_control_mesh.obj", 4 + 2 * 160 + 3 * 16, 160 + 16, 0},
      {"formats/concave_polygon.obj", 66 - 2, 1, 2},  // outer rim and hole, joined by a bridge
      {"malformed/box_without_lineending.obj", 12, 6, 0},
  };
  for (const Case& c : cases) {
    INFO(c.file);
    const ReadResult read = aniso::read_mesh(mesh_path(c.file));
    CHECK(read.mesh.num_triangles() == c.triangles);
    CHECK(read.report.polygons_triangulated == c.polygons);
    const aniso::MeshReport report = aniso::check_mesh(read.mesh);
    CHECK(report.degenerate_triangles == 0);
    CHECK(report.consistently_oriented);
    CHECK(report.edge_manifold);
    CHECK(report.vertex_manifold);
    CHECK(report.boundary_loops == c.boundary_loops);
    for (int f = 0; f < read.mesh.num_triangles(); ++f) CHECK(triangle_area(read.mesh, f) > 0);
  }
}

TEST_CASE("mesh_io: the concave 66-gon's triangles cover exactly its area and face along its normal", "[io]") {
  const Mesh mesh = load("formats/concave_polygon.obj");
  // The file's corners, in order: the polygon's signed area (rim minus hole)
  // is half its Newell normal.
  const std::vector<int> corners = {27, 23, 19, 15, 11, 5,  2,  1,  3,  6,  12, 16, 20, 24, 28, 34, 38,
                                    42, 46, 50, 54, 60, 63, 64, 62, 59, 53, 49, 45, 41, 37, 31, 32, 35,
                                    39, 43, 47, 51, 55, 57, 61, 58, 56, 52, 48, 44, 40, 36, 33, 30, 26,
                                    22, 18, 14, 10, 8,  4,  7,  9,  13, 17, 21, 25, 29, 32, 31};
  Eigen::Vector3d newell = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector3d p = mesh.V.row(corners[i] - 1).transpose();
    const Eigen::Vector3d q = mesh.V.row(corners[(i + 1) % corners.size()] - 1).transpose();
    newell += p.cross(q);
  }
  double covered = 0;
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose();
    const Eigen::Vector3d normal = (mesh.V.row(mesh.F(f, 1)).transpose() - a).cross(mesh.V.row(mesh.F(f, 2)).transpose() - a);
    CHECK(normal.dot(newell) > 0);  // the polygon's winding is kept
    covered += 0.5 * normal.norm();
  }
  CHECK(covered == Approx(0.5 * newell.norm()).epsilon(1e-9));
}

TEST_CASE("mesh_io: malformed files fail with a message naming the problem", "[io]") {
  const std::pair<const char*, const char*> empties[] = {{"malformed/empty.obj", "not an OBJ mesh"},
                                                         {"malformed/empty.off", "not an OFF mesh"},
                                                         {"malformed/empty.ply", "not a PLY mesh"},
                                                         {"malformed/empty.stl", "not an STL mesh"}};
  for (const auto& [file, what] : empties) {
    INFO(file);
    CHECK_THAT(read_error(file), Catch::Contains("file is empty (0 bytes): " + std::string(what)));
  }
  const std::string obj_index = read_error("malformed/bad_index_out_of_range.obj");
  CHECK_THAT(obj_index, Catch::Contains("face 21 references vertex 840, but the file has 829 vertices (line 852)"));
  const std::string off_index = read_error("malformed/bad_index_out_of_range.off");
  // From 0, as the file numbers its vertices (MANIFEST: the 31st face).
  CHECK_THAT(off_index, Catch::Contains("face 30 references vertex 829, but the file has 829 vertices "
                                        "(OFF numbers vertices and faces from 0) (line 862)"));
  CHECK_THAT(off_index, Catch::Contains("line 862"));
  const std::string stl = read_error("malformed/truncated_binary.stl");
  CHECK_THAT(stl, Catch::Contains("truncated") && Catch::Contains("1654 triangles") &&
                      Catch::Contains("82784 bytes") && Catch::Contains("50107 bytes") &&
                      Catch::Contains("1000 complete triangles"));
  CHECK_THAT(read_error("malformed/truncated_binary.ply"),
             Catch::Contains("truncated") && Catch::Contains("ends after 900 of 1654 faces"));
  CHECK_THAT(read_error("malformed/number_formats.obj"),
             Catch::Contains("'3.1+e2' is not a number (line 11)"));
  // The path is named, so a user knows which file of several is at fault.
  CHECK_THAT(read_error("malformed/empty.obj"), Catch::Contains("malformed/empty.obj"));
}

TEST_CASE("mesh_io: odd but valid files read as their MANIFEST entries say", "[io]") {
  SECTION("a UTF-16 file is decoded, with a note") {
    const ReadResult read = aniso::read_mesh(mesh_path("malformed/box_UTF16BE.obj"));
    CHECK(read.mesh.num_vertices() == 8);
    CHECK(read.mesh.num_triangles() == 12);
    CHECK(read.report.polygons_triangulated == 6);
    REQUIRE_FALSE(read.report.notes.empty());
    CHECK_THAT(read.report.notes.front(), Catch::Contains("UTF-16"));
    CHECK(aniso::check_mesh(read.mesh).boundary_loops == 0);
  }
  SECTION("lines and points are skipped and counted") {
    const ReadResult read = aniso::read_mesh(mesh_path("malformed/testmixed.obj"));
    CHECK(read.mesh.num_vertices() == 8);
    CHECK(read.mesh.num_triangles() == 12);
    CHECK(read.report.elements_skipped == 12);
  }
  SECTION("header-only files are empty meshes that check_mesh reports") {
    for (const char* file : {"malformed/empty_mesh_header_only.off", "malformed/empty_mesh_header_only.ply",
                             "malformed/empty_mesh_zero_triangles.stl"}) {
      INFO(file);
      const Mesh mesh = load(file);
      CHECK(mesh.num_vertices() == 0);
      CHECK(mesh.num_triangles() == 0);
      const aniso::MeshReport report = aniso::check_mesh(mesh);
      CHECK_FALSE(report.solvable());
      REQUIRE_FALSE(report.problems.empty());
      CHECK(report.problems.front().kind == aniso::ProblemKind::EmptyMesh);
    }
  }
}

TEST_CASE("mesh_io: MANIFEST counts hold for the closed, open and format meshes", "[io]") {
  struct Entry {
    const char* file;
    int vertices, faces, components, boundary_loops;
  };
  const Entry entries[] = {
      {"closed/spot_triangulated.obj", 2930, 5856, 1, 0},
      {"closed/bunny_npm.obj", 1839, 3674, 1, 0},
      {"closed/fandisk.off", 6475, 12946, 1, 0},
      {"closed/torus.obj", 2304, 4608, 1, 0},
      {"closed/cat-low-resolution.obj", 7949, 15894, 1, 0},
      {"closed/spool.off", 649, 1294, 1, 0},
      {"closed/knot1.off", 3200, 6400, 1, 0},
      {"closed/human_woman.obj", 6890, 13776, 1, 0},
      {"closed/armadillo.off", 26002, 52000, 1, 0},
      {"closed/nefertiti-lowres.obj", 35002, 70000, 1, 0},
      {"open/demosthenes-low-res.obj", 8394, 16719, 1, 1},
      {"open/hemisphere.obj", 2051, 4000, 1, 1},
      {"open/spothead.obj", 4537, 9024, 1, 1},
      {"open/hand_lowres.obj", 810, 1602, 1, 1},
      {"open/nefertiti_face.off", 299, 562, 1, 1},
      {"open/plane.off", 841, 1600, 1, 1},
      {"open/cube_no_bottom.obj", 25, 40, 1, 1},
      {"open/stanford-bunny.obj", 35947, 69451, 1, 5},
      {"open/human_woman_torso_front_patch.obj", 531, 972, 1, 1},
      {"formats/fandisk_binary.stl", 6475, 12946, 1, 0},
      {"formats/armadillo_binary.ply", 26002, 52000, 1, 0},
      {"malformed/multi_component.obj", 1774, 3540, 2, 0},
      {"malformed/boxNotManifold.obj", 9, 12, 1, 1},
      {"malformed/openscad-nonmanifold-crash.obj", 717, 1442, 2, 0},
      {"malformed/degtri_sliding.off", 8, 8, 1, 1},
  };
  for (const Entry& entry : entries) {
    INFO(entry.file);
    const aniso::MeshReport report = aniso::check_mesh(load(entry.file));
    CHECK(report.vertices == entry.vertices);
    CHECK(report.triangles == entry.faces);
    CHECK(report.components == entry.components);
    CHECK(report.boundary_loops == entry.boundary_loops);
    CHECK(report.edge_manifold);
    CHECK(report.solvable());
  }
  SECTION("the 200k-vertex PLY") {
    const Mesh koala = load("large/koala_loop1_200k.ply");
    CHECK(koala.num_vertices() == 199990);
    CHECK(koala.num_triangles() == 399976);
  }
}

TEST_CASE("mesh_io: writers round-trip every format", "[io]") {
  const Mesh mesh = load("formats/spot_lowres.obj");
  struct Case {
    MeshFormat format;
    bool binary;
  };
  for (const Case c : {Case{MeshFormat::Obj, false}, Case{MeshFormat::Off, false}, Case{MeshFormat::Ply, true},
                       Case{MeshFormat::Ply, false}, Case{MeshFormat::Stl, true}, Case{MeshFormat::Stl, false}}) {
    INFO(aniso::format_name(c.format) << (c.binary ? " binary" : " ascii"));
    aniso::WriteOptions options;
    options.binary = c.binary;
    const std::string bytes = aniso::write_mesh_to_memory(mesh, c.format, options);
    const Mesh back = aniso::read_mesh_from_memory(bytes.data(), bytes.size(), c.format).mesh;
    if (c.format == MeshFormat::Stl) {
      // STL welds: the same triangles, numbered by first use; binary is float32.
      CHECK(triangles_in_numbering_of(mesh, back, c.binary) == triangles_in_numbering_of(mesh, mesh, false));
    } else {
      CHECK(back.V == mesh.V);  // shortest round-trip text, or doubles: exact
      CHECK(back.F == mesh.F);
    }
  }
  SECTION("through a file, format from the extension") {
    const std::string path = std::string(aniso::test::kScratchDir) + "/round_trip_spot.ply";
    aniso::write_mesh(path, mesh);
    const Mesh back = aniso::read_mesh(path).mesh;
    CHECK(back.V == mesh.V);
    CHECK(back.F == mesh.F);
  }
  SECTION("a mesh with an index out of range is refused, not written") {
    Mesh bad = mesh;
    bad.F(7, 1) = 829;
    CHECK_THAT(error_message([&] { aniso::write_mesh_to_memory(bad, MeshFormat::Stl); }, aniso::ErrorCode::BadMesh),
               Catch::Contains("face 7"));
  }
}

TEST_CASE("mesh_io: write_obj_with_uv writes one vt per vertex and faces a/a b/b c/c", "[io]") {
  const Mesh mesh = load("open/nefertiti_face.off");
  Eigen::MatrixX2d uv(mesh.num_vertices(), 2);
  uv.col(0) = mesh.V.col(0);
  uv.col(1) = mesh.V.col(1);
  const std::string text = aniso::write_obj_with_uv(mesh, uv);
  std::istringstream lines(text);
  int vt = 0;
  for (std::string line; std::getline(lines, line);) vt += line.rfind("vt ", 0) == 0;
  CHECK(vt == mesh.num_vertices());
  CHECK_THAT(text, Catch::Contains("f 1/1 "));
  const Mesh back = read_text(text, MeshFormat::Obj).mesh;
  CHECK(back.V == mesh.V);
  CHECK(back.F == mesh.F);
  CHECK_THAT(error_message([&] { aniso::write_obj_with_uv(mesh, Eigen::MatrixX2d(3, 2)); },
                           aniso::ErrorCode::BadParameter),
             Catch::Contains("uv"));
}

// Each (vertex, texture coordinate) pair of the file's face corners, as
// written ("739/1" -> {738, 0}), for every face.
std::set<std::pair<int, int>> obj_corner_pairs(const std::string& text) {
  std::set<std::pair<int, int>> pairs;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("f ", 0) != 0) continue;
    std::istringstream corners(line.substr(2));
    for (std::string corner; corners >> corner;) {
      const std::size_t slash = corner.find('/');
      pairs.emplace(std::stoi(corner.substr(0, slash)) - 1, std::stoi(corner.substr(slash + 1)) - 1);
    }
  }
  return pairs;
}

TEST_CASE("mesh_io: an OBJ's texture coordinates are read per corner and written back", "[io]") {
  for (const char* file : {"closed/spot_triangulated.obj", "formats/spot_quadrangulated.obj"}) {
    INFO(file);
    const std::string text = file_bytes(file);
    const ReadResult read = read_text(text, MeshFormat::Obj);
    // Spot's UV seams: 3225 coordinates for 2930 vertices.
    REQUIRE(read.attributes.texture.uv.rows() == 3225);
    REQUIRE(read.attributes.texture.faces.rows() == read.mesh.F.rows());
    // Every triangle corner pairs its vertex with a coordinate the file pairs
    // it with (the quads' triangles too), and all of the file's pairs are used.
    std::set<std::pair<int, int>> pairs;
    for (Eigen::Index f = 0; f < read.mesh.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) pairs.emplace(read.mesh.F(f, k), read.attributes.texture.faces(f, k));
    CHECK(pairs == obj_corner_pairs(text));

    // Written with them and read again: the same mesh and texture, bitwise.
    aniso::WriteOptions options;
    options.attributes = &read.attributes;
    const std::string written = aniso::write_mesh_to_memory(read.mesh, MeshFormat::Obj, options);
    const ReadResult back = read_text(written, MeshFormat::Obj);
    CHECK(back.mesh.V == read.mesh.V);
    CHECK(back.mesh.F == read.mesh.F);
    CHECK(back.attributes.texture.uv == read.attributes.texture.uv);
    CHECK(back.attributes.texture.faces == read.attributes.texture.faces);
    // Without them: positions and faces only, as before.
    CHECK(read_text(aniso::write_mesh_to_memory(read.mesh, MeshFormat::Obj), MeshFormat::Obj).attributes.texture.empty());
  }
}

TEST_CASE("mesh_io: an OBJ's vertex colours (v x y z r g b) are kept when every vertex has them", "[io]") {
  // Spot with a colour per vertex, from its position.
  const Mesh spot = load("formats/spot_lowres.obj");
  std::string text;
  for (Eigen::Index i = 0; i < spot.V.rows(); ++i) {
    text += "v " + std::to_string(spot.V(i, 0)) + " " + std::to_string(spot.V(i, 1)) + " " + std::to_string(spot.V(i, 2));
    for (int k = 0; k < 3; ++k) text += " " + std::to_string(0.5 + 0.25 * std::tanh(spot.V(i, k)));
    text += "\n";
  }
  for (Eigen::Index f = 0; f < spot.F.rows(); ++f) {
    text += "f " + std::to_string(spot.F(f, 0) + 1) + " " + std::to_string(spot.F(f, 1) + 1) + " " +
            std::to_string(spot.F(f, 2) + 1) + "\n";
  }
  const ReadResult read = read_text(text, MeshFormat::Obj);
  REQUIRE(read.attributes.vertex_colors.rows() == spot.V.rows());
  CHECK(read.attributes.vertex_colors(3, 1) == Approx(0.5 + 0.25 * std::tanh(spot.V(3, 1))).margin(1e-6));
  aniso::WriteOptions options;
  options.attributes = &read.attributes;
  const ReadResult back = read_text(aniso::write_mesh_to_memory(read.mesh, MeshFormat::Obj, options), MeshFormat::Obj);
  CHECK(back.attributes.vertex_colors == read.attributes.vertex_colors);
  CHECK(back.mesh.V == read.mesh.V);
  // Not every vertex coloured, or a w instead: none kept, the mesh read as before.
  CHECK(read_text("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n", MeshFormat::Obj).attributes.vertex_colors.rows() == 0);
  CHECK(read_text("v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 1 2 3\n", MeshFormat::Obj).attributes.vertex_colors.rows() == 0);
}

TEST_CASE("mesh_io: an OBJ's mtllib and usemtl statements are read and written again", "[io]") {
  // A LightWave export: one library, one material for its one (66-gon) face.
  const ReadResult concave = aniso::read_mesh(mesh_path("formats/concave_polygon.obj"));
  CHECK(concave.attributes.materials.libraries == std::vector<std::string>{"concave_polygon.mtl"});
  REQUIRE(concave.attributes.materials.runs.size() == 1);
  CHECK(concave.attributes.materials.runs[0] == std::make_pair(0, std::string("test")));
  // Two usemtl before the same face: the second holds.
  CHECK(aniso::read_mesh(mesh_path("malformed/testmixed.obj")).attributes.materials.runs ==
        std::vector<std::pair<int, std::string>>{{0, "Default"}});

  // Runs start at their polygon's first triangle; a quad is two.
  const std::string text =
      "mtllib shop.mtl  # the library\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
      "usemtl wood\nf 1 2 3 4\nusemtl steel\nf 2 5 6 3\nf 1 2 3\n";
  const ReadResult read = read_text(text, MeshFormat::Obj);
  CHECK(read.attributes.materials.libraries == std::vector<std::string>{"shop.mtl"});
  CHECK(read.attributes.materials.runs == std::vector<std::pair<int, std::string>>{{0, "wood"}, {2, "steel"}});
  aniso::WriteOptions options;
  options.attributes = &read.attributes;
  const std::string written = aniso::write_mesh_to_memory(read.mesh, MeshFormat::Obj, options);
  CHECK_THAT(written, Catch::StartsWith("# written by anisoform\nmtllib shop.mtl\nv "));
  // (each before its first triangle: wood before the first, steel before the third)
  CHECK(written.find("usemtl wood\nf ") < written.find("\nf "));
  CHECK(written.find("usemtl steel\nf ") > written.find("\nf ", written.find("\nf ") + 1));
  const ReadResult back = read_text(written, MeshFormat::Obj);
  CHECK(back.attributes.materials.libraries == read.attributes.materials.libraries);
  CHECK(back.attributes.materials.runs == read.attributes.materials.runs);
  CHECK(back.mesh.F == read.mesh.F);
}

TEST_CASE("mesh_io: texture coordinates that are malformed or missing somewhere are dropped, the mesh kept", "[io]") {
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  const auto read = [&](const std::string& rest) { return read_text(square + rest, MeshFormat::Obj); };
  const ReadResult whole = read("vt 0 0\nvt 1 0 0.5\nvt 1 1\nvt 0.5\nf 1/1 2/2 3/3\nf 1/-4 3/-2 4/-1\n");
  REQUIRE(whole.attributes.texture.faces.rows() == 2);
  CHECK(whole.attributes.texture.faces.row(1) == Eigen::RowVector3i(0, 2, 3));
  CHECK(whole.attributes.texture.uv.row(3) == Eigen::RowVector2d(0.5, 0.0));  // v defaults to 0
  CHECK(whole.report.notes.empty());
  const struct {
    std::string rest;
    std::string why;
  } cases[] = {
      {"vt 0 0\nvt 1 zero\nvt 1 1\nf 1/1 2/2 3/3\n", "the texture coordinate (line 6) is malformed"},
      {"vt 0 0\nvt 1 nan\nvt 1 1\nf 1/1 2/2 3/3\n", "the texture coordinate (line 6) is malformed"},
      {"vt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\nf 1 3 4\n", "some face corners have none"},
      {"vt 0 0\nvt 1 0\nf 1/1 2/2 3/3\n", "a face corner names texture coordinate 3, but the file has 2"},
      {"vt 0 0\nf 1/1 2/-2 3/1\n", "a face corner names texture coordinate 0, but the file has 1"},
  };
  for (const auto& c : cases) {
    INFO(c.rest);
    const ReadResult dropped = read(c.rest);
    CHECK(dropped.attributes.texture.empty());
    CHECK(dropped.mesh.num_triangles() >= 1);
    REQUIRE(dropped.report.notes.size() == 1);
    CHECK(dropped.report.notes[0] == "texture coordinates ignored (" + c.why + ")");
  }
}

// Spot (a real scan-like PLY) with the properties a coloured scan has: a
// colour per vertex (uchar, from its position), a quality (float) and
// normals (here deliberately wrong: a writer computes them for the shape).
aniso::VertexProperties scan_properties(const Mesh& mesh) {
  aniso::VertexProperties properties = {{"red", "uchar", {}}, {"green", "uint8", {}}, {"blue", "uchar", {}},
                                        {"quality", "float", {}}, {"nx", "float", {}}, {"ny", "float", {}},
                                        {"nz", "float", {}}, {"label", "int", {}}};
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    for (int k = 0; k < 3; ++k) properties[k].values.push_back(std::floor(127.5 * (1.0 + std::tanh(mesh.V(i, k)))));
    properties[3].values.push_back(static_cast<float>(0.25 * static_cast<double>(i % 7)));
    for (int k = 4; k < 7; ++k) properties[k].values.push_back(1.0);
    properties[7].values.push_back(-static_cast<double>(i));
  }
  return properties;
}

// `mesh` written as PLY (binary or text) with these vertex properties.
std::string ply_with_properties(const Mesh& mesh, const aniso::VertexProperties& properties, bool binary) {
  aniso::SurfaceAttributes attributes;
  attributes.vertex_properties = properties;
  aniso::WriteOptions options;
  options.binary = binary;
  options.attributes = &attributes;
  return aniso::write_mesh_to_memory(mesh, MeshFormat::Ply, options);
}

TEST_CASE("mesh_io: a PLY's other vertex properties are read and written again in their types", "[io]") {
  const Mesh spot = aniso::read_mesh(mesh_path("formats/spot_lowres_binary.ply")).mesh;
  const aniso::VertexProperties given = scan_properties(spot);
  for (const bool binary : {true, false}) {
    INFO("binary " << binary);
    const std::string written = ply_with_properties(spot, given, binary);
    CHECK_THAT(written, Catch::Contains("property uchar red\nproperty uint8 green") &&
                            Catch::Contains("property int label\nelement face"));
    const ReadResult back = read_text(written, MeshFormat::Ply);
    CHECK(back.mesh.V == spot.V);
    CHECK(back.mesh.F == spot.F);
    REQUIRE(back.attributes.vertex_properties.size() == given.size());
    const aniso::Positions normals = aniso::vertex_normals(spot);
    for (std::size_t p = 0; p < given.size(); ++p) {
      INFO(given[p].name);
      CHECK(back.attributes.vertex_properties[p].name == given[p].name);
      CHECK(back.attributes.vertex_properties[p].type == given[p].type);
      if (p >= 4 && p < 7) {
        // The shape's normals, not the ones given.
        for (Eigen::Index i = 0; i < spot.V.rows(); ++i) {
          CHECK(back.attributes.vertex_properties[p].values[i] == Approx(normals(i, p - 4)).margin(1e-6));
        }
      } else {
        CHECK(back.attributes.vertex_properties[p].values == given[p].values);
      }
    }
  }
  // A plain PLY has none.
  CHECK(aniso::read_mesh(mesh_path("formats/spot_lowres_ascii.ply")).attributes.vertex_properties.empty());
}

TEST_CASE("mesh_io: a vertex colour or property that is not finite is dropped with a note naming it", "[io]") {
  // NaN and inf in them were read and written out again ('v 0 0 0 nan inf -1',
  // a PLY's quality column of nan): no NaN or inf reaches an output file. The
  // positions are kept, and the attribute goes, as a malformed texture
  // coordinate does.
  const Mesh spot = load("formats/spot_lowres.obj");
  for (const char* bad : {"nan", "inf", "-inf", "1e999"}) {
    INFO(bad);
    std::string text;
    for (Eigen::Index i = 0; i < spot.V.rows(); ++i) {
      text += "v " + std::to_string(spot.V(i, 0)) + " " + std::to_string(spot.V(i, 1)) + " " +
              std::to_string(spot.V(i, 2)) + (i == 5 ? std::string(" 0.5 ") + bad + " 0.5\n" : " 0.5 0.5 0.5\n");
    }
    for (Eigen::Index f = 0; f < spot.F.rows(); ++f) {
      text += "f " + std::to_string(spot.F(f, 0) + 1) + " " + std::to_string(spot.F(f, 1) + 1) + " " +
              std::to_string(spot.F(f, 2) + 1) + "\n";
    }
    const ReadResult read = read_text(text, MeshFormat::Obj);
    CHECK(read.mesh.num_vertices() == spot.num_vertices());
    CHECK(read.attributes.vertex_colors.rows() == 0);
    REQUIRE(read.report.notes.size() == 1);
    CHECK(read.report.notes[0] == "vertex colours ignored (vertex 5 has a colour value that is not a finite number "
                                  "(line 6))");
    aniso::WriteOptions options;
    options.attributes = &read.attributes;
    CHECK_THAT(aniso::write_mesh_to_memory(read.mesh, MeshFormat::Obj, options),
               !Catch::Contains("nan") && !Catch::Contains("inf"));
  }
  // A PLY's quality of inf at vertex 7, NaN at 9: that property goes, the others stay.
  aniso::VertexProperties properties = scan_properties(spot);
  properties[3].values[7] = std::numeric_limits<double>::infinity();
  properties[3].values[9] = std::numeric_limits<double>::quiet_NaN();
  for (const bool binary : {true, false}) {
    INFO("binary " << binary);
    const ReadResult read = read_text(ply_with_properties(spot, properties, binary), MeshFormat::Ply);
    REQUIRE(read.attributes.vertex_properties.size() == properties.size() - 1);
    for (const aniso::VertexProperty& property : read.attributes.vertex_properties) CHECK(property.name != "quality");
    REQUIRE(read.report.notes.size() == 1);
    // Vertex 7 is on line 26, after the header's 18 (binary files have no lines).
    CHECK(read.report.notes[0] == std::string("vertex property 'quality' ignored (vertex 7 has inf") +
                                      (binary ? "" : " (line 26)") + ", not a finite number)");
    aniso::WriteOptions again;
    again.binary = false;
    again.attributes = &read.attributes;
    CHECK_THAT(aniso::write_mesh_to_memory(read.mesh, MeshFormat::Ply, again),
               !Catch::Contains("nan") && !Catch::Contains("inf"));
  }
}

TEST_CASE("mesh_io: vertex colours go from a PLY to an OBJ and from an OBJ to a PLY", "[io]") {
  const Mesh spot = aniso::read_mesh(mesh_path("formats/spot_lowres_binary.ply")).mesh;
  const int n = static_cast<int>(spot.V.rows());
  aniso::SurfaceAttributes scan;
  scan.vertex_properties = scan_properties(spot);  // red, green (uint8), blue, quality, normals, label
  aniso::WriteOptions options;
  options.attributes = &scan;
  // The scan's colours, as an OBJ's v x y z r g b in [0, 1].
  const ReadResult obj = read_text(aniso::write_mesh_to_memory(spot, MeshFormat::Obj, options), MeshFormat::Obj);
  REQUIRE(obj.attributes.vertex_colors.rows() == n);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) CHECK(obj.attributes.vertex_colors(i, k) == Approx(scan.vertex_properties[k].values[i] / 255.0).margin(1e-6));
  }
  CHECK(aniso::vertex_colors(scan, n) == aniso::vertex_colors(obj.attributes, n));
  // ...and back into a PLY as red, green, blue uchar: the scan's bytes again.
  options.attributes = &obj.attributes;
  const std::string ply = aniso::write_mesh_to_memory(spot, MeshFormat::Ply, options);
  CHECK_THAT(ply, Catch::Contains("property uchar red\nproperty uchar green\nproperty uchar blue\nelement face"));
  const ReadResult back = read_text(ply, MeshFormat::Ply);
  REQUIRE(back.attributes.vertex_properties.size() == 3);
  for (int k = 0; k < 3; ++k) CHECK(back.attributes.vertex_properties[k].values == scan.vertex_properties[k].values);
  // A PLY's own properties win over the conversion; 16-bit and float channels scale to [0, 1].
  aniso::SurfaceAttributes wide;
  wide.vertex_properties = {{"red", "ushort", std::vector<double>(n, 65535.0)}, {"green", "float", std::vector<double>(n, 0.25)},
                            {"blue", "uchar", std::vector<double>(n, 0.0)}};
  const Eigen::MatrixX3d colors = aniso::vertex_colors(wide, n);
  REQUIRE(colors.rows() == n);
  CHECK(colors(0, 0) == 1.0);
  CHECK(colors(0, 1) == 0.25);
  CHECK(colors(0, 2) == 0.0);
  // A channel missing: no colours.
  wide.vertex_properties.pop_back();
  CHECK(aniso::vertex_colors(wide, n).rows() == 0);
  CHECK(aniso::vertex_colors(aniso::SurfaceAttributes{}, n).rows() == 0);
}

TEST_CASE("mesh_io: a PLY with more than 16 other vertex properties keeps the first 16 and says so", "[io]") {
  std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  for (int p = 0; p < 18; ++p) text += "property uchar p" + std::to_string(p) + "\n";
  text += "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (int v = 0; v < 3; ++v) {
    text += std::to_string(v % 2) + " " + std::to_string(v / 2) + " 0";
    for (int p = 0; p < 18; ++p) text += " " + std::to_string(p + v);
    text += "\n";
  }
  text += "3 0 1 2\n";
  const ReadResult read = read_text(text, MeshFormat::Ply);
  REQUIRE(read.attributes.vertex_properties.size() == 16);
  CHECK(read.attributes.vertex_properties[15].name == "p15");
  CHECK(read.attributes.vertex_properties[15].values == std::vector<double>{15, 16, 17});
  REQUIRE(read.report.notes.size() == 1);
  CHECK(read.report.notes[0] == "kept the first 16 vertex properties besides x, y, z; dropped 2 more");
}

TEST_CASE("mesh_io: format_from_path maps extensions and leaves GLB to the browser app", "[io]") {
  CHECK(aniso::format_from_path("a/b.OBJ") == MeshFormat::Obj);
  CHECK(aniso::format_from_path("x.off") == MeshFormat::Off);
  CHECK(aniso::format_from_path("x.Ply") == MeshFormat::Ply);
  CHECK(aniso::format_from_path("dir.v2/x.stl") == MeshFormat::Stl);
  CHECK_THAT(error_message([] { aniso::format_from_path("x.glb"); }, aniso::ErrorCode::BadParameter),
             Catch::Contains("GLB") && Catch::Contains("browser app only"));
  CHECK_THAT(error_message([] { aniso::read_mesh(mesh_path("formats/box.glb")); }, aniso::ErrorCode::BadParameter),
             Catch::Contains("browser app only"));
  CHECK_THAT(error_message([] { aniso::format_from_path("x.3ds"); }, aniso::ErrorCode::BadParameter),
             Catch::Contains("'.3ds'"));
  CHECK_THAT(error_message([] { aniso::format_from_path("dir.v2/mesh"); }, aniso::ErrorCode::BadParameter),
             Catch::Contains("no file extension"));
  CHECK_THAT(error_message([] { aniso::read_mesh("/nonexistent/x.obj"); }), Catch::Contains("cannot open"));
}

TEST_CASE("mesh_io: OBJ accepts every corner form, relative indices, CRLF and no final newline", "[io]") {
  const std::string text =
      "# a quad and a triangle\r\n"
      "o square\r\n"
      "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0 1.0\r\nv 0 1 0 0.5 0.5 0.5\r\n"
      "vt 0 0\r\nvn 0 0 1\r\n"
      "f 1/1/1 2/1/1 3//1 -1/1\r\n"
      "g tail\r\n"
      "v 2 0 0\r\n"
      "f -4 -1 -3";
  const ReadResult read = read_text(text, MeshFormat::Obj);
  REQUIRE(read.mesh.num_vertices() == 5);
  REQUIRE(read.mesh.num_triangles() == 3);
  CHECK(read.report.polygons_triangulated == 1);
  CHECK(read.mesh.F.row(2) == Eigen::RowVector3i(1, 4, 2));
  CHECK(read.mesh.V(3, 1) == 1.0);

  CHECK_THAT(error_message([] { read_text("v 0 0 0\nv 1 0 0\nf 1 2 -3\n", MeshFormat::Obj); }),
             Catch::Contains("relative index -3") && Catch::Contains("line 3"));
  CHECK_THAT(error_message([] { read_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", MeshFormat::Obj); }),
             Catch::Contains("face 1 has 2 corners"));
  CHECK_THAT(error_message([] { read_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/ 3\n", MeshFormat::Obj); }),
             Catch::Contains("malformed corner '2/'"));
  CHECK_THAT(error_message([] { read_text("v 0 0\n", MeshFormat::Obj); }), Catch::Contains("fewer than 3"));
  CHECK_THAT(error_message([] { read_text(std::string("v 0 0 0\n\0\1\2", 11), MeshFormat::Obj); }),
             Catch::Contains("binary data"));
}

TEST_CASE("mesh_io: lines ending in a lone CR (old Mac OS) read as lines in every text format", "[io]") {
  // An OBJ of such lines was one line: "'v' is not a number (line 1)".
  const struct {
    const char* file;
    MeshFormat format;
  } files[] = {{"formats/spot_lowres.obj", MeshFormat::Obj},
               {"formats/spot_lowres.off", MeshFormat::Off},
               {"formats/spot_lowres_ascii.ply", MeshFormat::Ply},
               {"formats/spot_lowres_ascii.stl", MeshFormat::Stl}};
  for (const auto& f : files) {
    INFO(f.file);
    const std::string unix_text = file_bytes(f.file);
    std::string mac_text;
    for (std::size_t i = 0; i < unix_text.size(); ++i) {
      if (unix_text[i] == '\r' && i + 1 < unix_text.size() && unix_text[i + 1] == '\n') continue;
      mac_text += unix_text[i] == '\n' ? '\r' : unix_text[i];
    }
    REQUIRE(mac_text.find('\n') == std::string::npos);
    const ReadResult expected = read_text(unix_text, f.format);
    const ReadResult read = read_text(mac_text, f.format);
    CHECK(read.mesh.V == expected.mesh.V);
    CHECK(read.mesh.F == expected.mesh.F);
  }
  // Line numbers count them: the OFF's bad index on its line 862, the PLY's
  // on line 13 (from 0, as the file numbers vertices), CR, LF and CRLF mixed.
  std::string off = file_bytes("malformed/bad_index_out_of_range.off");
  for (char& c : off) c = c == '\n' ? '\r' : c;
  CHECK_THAT(error_message([&] { read_text(off, MeshFormat::Off); }),
             Catch::Contains("face 30 references vertex 829") && Catch::Contains("(line 862)"));
  const std::string ply = "ply\rformat ascii 1.0\r\nelement vertex 3\nproperty float x\rproperty float y\r"
                          "property float z\relement face 3\rproperty list uchar int vertex_indices\rend_header\r"
                          "0 0 0\r1 0 0\r\n0 1 0\n3 0 1 2\r3 0 2 1\r3 0 1 7\r";
  CHECK(error_message([&] { read_text(ply, MeshFormat::Ply); }) ==
        "face 2 references vertex 7, but the file has 3 vertices (PLY numbers vertices and faces from 0) (line 15)");
}

TEST_CASE("mesh_io: numbers are parsed strictly, with the unusual valid spellings accepted", "[io]") {
  const ReadResult read =
      read_text("v +1 2. -3.0\nv 1e2 +2.e+1 .5E-1\nv nan inf -inf\nf 1 2 3\n", MeshFormat::Obj);
  CHECK(read.mesh.V.row(0) == Eigen::RowVector3d(1, 2, -3));
  CHECK(read.mesh.V.row(1) == Eigen::RowVector3d(100, 20, 0.05));
  CHECK(std::isnan(read.mesh.V(2, 0)));
  CHECK(std::isinf(read.mesh.V(2, 2)));
  for (const char* bad : {"3.1+e2", "3.1-e2", "1,5", "0x10", "--1", "+-1", "1e", "e5", "."}) {
    INFO(bad);
    const std::string reason = std::string(bad) == "0x10" ? "is a hexadecimal number" : "is not a number";
    CHECK_THAT(error_message([&] { read_text(std::string("v 0 0 ") + bad + "\n", MeshFormat::Obj); }),
               Catch::Contains("'" + std::string(bad) + "' " + reason) && Catch::Contains("(line 1)"));
  }
}

TEST_CASE("mesh_io: PLY reads either byte order and any types, skipping other properties and elements", "[io]") {
  // A big-endian file: double coordinates between a uchar and a float
  // property, uint list counts with ushort indices, an int property after
  // the list, and an 'edge' element between vertices and faces.
  std::string big_endian =
      "ply\r\nformat binary_big_endian 1.0\r\ncomment made by hand\r\n"
      "element vertex 4\r\nproperty uchar flag\r\nproperty double x\r\nproperty double y\r\n"
      "property double z\r\nproperty float confidence\r\n"
      "element edge 1\r\nproperty list uchar int vertex_pair\r\n"
      "element face 1\r\nproperty list uint ushort vertex_indices\r\nproperty int material\r\n"
      "end_header\r\n";
  auto append_big = [&](auto value) {
    char bytes[sizeof value];
    std::memcpy(bytes, &value, sizeof value);
    std::reverse(bytes, bytes + sizeof value);  // the test machines are little endian
    big_endian.append(bytes, sizeof value);
  };
  const double square[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}};
  for (const auto& p : square) {
    append_big(std::uint8_t{7});
    for (double coordinate : p) append_big(coordinate);
    append_big(0.25f);
  }
  append_big(std::uint8_t{2});
  append_big(std::int32_t{0});
  append_big(std::int32_t{1});
  append_big(std::uint32_t{4});
  for (std::uint16_t i : {0, 1, 2, 3}) append_big(i);
  append_big(std::int32_t{-1});
  const ReadResult read = read_text(big_endian, MeshFormat::Ply);
  REQUIRE(read.mesh.num_vertices() == 4);
  REQUIRE(read.mesh.num_triangles() == 2);
  CHECK(read.mesh.V.row(2) == Eigen::RowVector3d(1, 1, 0.5));
  CHECK(read.report.elements_skipped == 1);
  CHECK(read.report.polygons_triangulated == 1);

  SECTION("ASCII with int coordinates and a 'vertex_index' list") {
    const std::string ascii =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty int x\nproperty short y\nproperty uchar z\n"
        "element face 1\nproperty list uchar uint vertex_index\nend_header\n0 0 0\n2 0 0\n0 -3 1\n3 0 1 2\n";
    const Mesh mesh = read_text(ascii, MeshFormat::Ply).mesh;
    CHECK(mesh.V.row(2) == Eigen::RowVector3d(0, -3, 1));
    CHECK(mesh.F.row(0) == Eigen::RowVector3i(0, 1, 2));
  }
  SECTION("errors name the element") {
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
    CHECK_THAT(error_message([&] { read_text(header + "3 0 1 3\n", MeshFormat::Ply); }),
               Catch::Contains("face 0 references vertex 3, but the file has 3 vertices (PLY numbers vertices and "
                               "faces from 0) (line 13)"));
    CHECK_THAT(error_message([&] { read_text(header + "3 0 1\n", MeshFormat::Ply); }),
               Catch::Contains("ends after 0 of 1 faces"));
    CHECK_THAT(error_message([&] { read_text("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                             "property float y\nend_header\n0 0\n", MeshFormat::Ply); }),
               Catch::Contains("x, y or z"));
    CHECK_THAT(error_message([] { read_text("solid x\n", MeshFormat::Ply); }), Catch::Contains("'ply'"));
  }
}

TEST_CASE("mesh_io: STL is binary when its size says so, even when the header starts with 'solid'", "[io]") {
  const Mesh mesh = load("formats/spot_lowres.obj");
  std::string binary = aniso::write_mesh_to_memory(mesh, MeshFormat::Stl);
  binary.replace(0, 10, "solid spot");
  const Mesh back = read_text(binary, MeshFormat::Stl).mesh;
  CHECK(back.num_vertices() == 829);
  CHECK(back.num_triangles() == 1654);

  const std::string ascii =
      "solid two\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
      "  endloop\n endfacet\n facet normal 0 0 1\n  outer loop\n   vertex 1 0 0\n   vertex 1 1 0\n"
      "   vertex 0 1 0\n  endloop\n endfacet\nendsolid two\n";
  const ReadResult read = read_text(ascii, MeshFormat::Stl);
  CHECK(read.mesh.num_vertices() == 4);
  CHECK(read.mesh.num_triangles() == 2);
  CHECK(read.report.vertices_welded == 2);
  CHECK_THAT(error_message([&] { read_text(ascii.substr(0, 70), MeshFormat::Stl); }),
             Catch::Contains("truncated"));
  CHECK_THAT(error_message([] { read_text("solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n"
                                          " vertex 0 1 0\n vertex 1 1 1\n", MeshFormat::Stl); }),
             Catch::Contains("more than 3 vertices"));
  CHECK_THAT(error_message([] { read_text("not an stl", MeshFormat::Stl); }), Catch::Contains("too short"));
}

namespace {

// `bytes` with the first `from` replaced by `to` (which must be there).
std::string with_replaced(std::string bytes, const std::string& from, const std::string& to) {
  const std::size_t at = bytes.find(from);
  REQUIRE(at != std::string::npos);
  return bytes.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("mesh_io: a header promising more elements than the bytes hold is refused up front", "[io]") {
  // Real files whose header now promises a billion elements: the message names
  // the count and the size, and nothing of that size is allocated (a vector
  // of 1e9 vertices would need 24 GB: bad_alloc, not this Error, without the check).
  SECTION("binary PLY") {
    const std::string bytes = with_replaced(file_bytes("formats/spot_lowres_binary.ply"),
                                            "element vertex 829", "element vertex 1000000000");
    CHECK_THAT(error_message([&] { read_text(bytes, MeshFormat::Ply); }),
               Catch::Contains("declares element counts vertex 1000000000, face 1654") &&
                   Catch::Contains("need at least 12000001654 bytes") && Catch::Contains("truncated"));
  }
  SECTION("ASCII PLY") {
    const std::string bytes = with_replaced(file_bytes("formats/spot_lowres_ascii.ply"),
                                            "element face 1654", "element face 1000000000");
    CHECK_THAT(error_message([&] { read_text(bytes, MeshFormat::Ply); }),
               Catch::Contains("face 1000000000") && Catch::Contains("bytes follow it"));
  }
  SECTION("OFF") {
    const std::string bytes =
        with_replaced(file_bytes("formats/spot_lowres.off"), "829 1654", "1000000000 1654");
    CHECK_THAT(error_message([&] { read_text(bytes, MeshFormat::Off); }),
               Catch::Contains("declares 1000000000 vertices and 1654 faces") && Catch::Contains("bytes follow it"));
  }
  SECTION("binary STL") {
    std::string bytes = file_bytes("formats/spot_lowres_binary.stl");
    const unsigned char billion[4] = {0x00, 0xCA, 0x9A, 0x3B};  // 1e9, little endian
    bytes.replace(80, 4, reinterpret_cast<const char*>(billion), 4);
    CHECK_THAT(error_message([&] { read_text(bytes, MeshFormat::Stl); }),
               Catch::Contains("declares 1000000000 triangles") &&
                   Catch::Contains("but the file has " + std::to_string(bytes.size()) + " bytes"));
  }
  SECTION("a count beyond any size does not overflow the check") {
    const std::string bytes = with_replaced(file_bytes("formats/spot_lowres_binary.ply"),
                                            "element vertex 829", "element vertex 9223372036854775807");
    CHECK_THAT(error_message([&] { read_text(bytes, MeshFormat::Ply); }), Catch::Contains("9223372036854775807"));
  }
  SECTION("a plainly truncated file is still reported where it ends") {
    CHECK_THAT(read_error("malformed/truncated_binary.ply"), Catch::Contains("ends after 900 of 1654 faces"));
  }
}

TEST_CASE("mesh_io: readers never crash or hang on truncated or corrupted bytes", "[io]") {
  std::mt19937 random(20261122);
  const std::pair<const char*, MeshFormat> files[] = {
      {"formats/spot_lowres.obj", MeshFormat::Obj},        {"formats/spot_lowres.off", MeshFormat::Off},
      {"formats/spot_lowres_ascii.ply", MeshFormat::Ply},  {"formats/spot_lowres_binary.ply", MeshFormat::Ply},
      {"formats/spot_lowres_ascii.stl", MeshFormat::Stl},  {"formats/spot_lowres_binary.stl", MeshFormat::Stl},
      {"formats/concave_polygon.obj", MeshFormat::Obj},
  };
  int reads = 0, errors = 0;
  auto try_read = [&](const std::string& bytes, MeshFormat format) {
    ++reads;
    try {
      const Mesh mesh = aniso::read_mesh_from_memory(bytes.data(), bytes.size(), format).mesh;
      aniso::check_mesh(mesh);  // whatever was read is a mesh check_mesh can take
    } catch (const aniso::Error&) {
      ++errors;
    }
  };
  for (const auto& [file, format] : files) {
    INFO(file);
    const std::string original = file_bytes(file);
    REQUIRE(!original.empty());
    for (int cut = 0; cut < 40; ++cut) try_read(original.substr(0, random() % original.size()), format);
    for (int mutation = 0; mutation < 60; ++mutation) {
      std::string corrupted = original;
      // Mostly within the first kilobyte, where headers and counts are.
      const std::size_t span = mutation % 2 ? std::min<std::size_t>(1024, corrupted.size()) : corrupted.size();
      for (int flips = 1 + mutation % 4; flips > 0; --flips) {
        corrupted[random() % span] = static_cast<char>(random() % 256);
      }
      try_read(corrupted, format);
    }
  }
  for (MeshFormat format : {MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply, MeshFormat::Stl}) {
    for (int garbage = 0; garbage < 20; ++garbage) {
      std::string bytes(random() % 300, '\0');
      for (char& c : bytes) c = static_cast<char>(random() % 256);
      try_read(bytes, format);
    }
  }
  CHECK(reads == 7 * 100 + 80);
  CHECK(errors > 0);
}

TEST_CASE("mesh_io: a COFF's vertex colours are read, and written to OFF (as COFF), PLY and OBJ", "[io]") {
  // plane.off is a COFF whose vertices are all 192 192 192 255.
  const aniso::ReadResult read = aniso::read_mesh(aniso::test::mesh_path("open/plane.off"));
  REQUIRE(read.attributes.vertex_colors.rows() == read.mesh.V.rows());
  CHECK((read.attributes.vertex_colors.array() - 192.0 / 255.0).abs().maxCoeff() < 1e-12);
  for (const aniso::MeshFormat format : {aniso::MeshFormat::Off, aniso::MeshFormat::Ply, aniso::MeshFormat::Obj}) {
    const aniso::SurfaceAttributes attributes =
        aniso::attributes_for_format(read.attributes, format, static_cast<int>(read.mesh.V.rows()));
    aniso::WriteOptions options;
    options.attributes = &attributes;
    const std::string bytes = aniso::write_mesh_to_memory(read.mesh, format, options);
    const aniso::ReadResult back = aniso::read_mesh_from_memory(bytes.data(), bytes.size(), format);
    INFO(aniso::format_name(format));
    CHECK((aniso::vertex_colors(back.attributes, static_cast<int>(back.mesh.V.rows())) -
           read.attributes.vertex_colors).cwiseAbs().maxCoeff() < 1e-6);
    CHECK((back.mesh.V - read.mesh.V).cwiseAbs().maxCoeff() == 0.0);
  }
  // A plain OFF stays plain.
  const aniso::ReadResult plain = aniso::read_mesh(aniso::test::mesh_path("formats/spot_lowres.off"));
  CHECK(plain.attributes.vertex_colors.rows() == 0);
  CHECK(aniso::write_mesh_to_memory(plain.mesh, aniso::MeshFormat::Off).rfind("OFF\n", 0) == 0);
}

TEST_CASE("mesh_io: ASCII STL keywords are read in any case", "[io]") {
  // SOLID / FACET / VERTEX (as some exporters write them) was read as binary
  // and refused: "the binary STL is truncated: its header declares 774909216
  // triangles".
  const Mesh mesh = load("formats/spot_lowres.obj");
  aniso::WriteOptions ascii;
  ascii.binary = false;
  const std::string lower = aniso::write_mesh_to_memory(mesh, MeshFormat::Stl, ascii);
  const Mesh expected = read_text(lower, MeshFormat::Stl).mesh;
  std::string upper = lower, mixed = lower;
  for (const std::string keyword :
       {"endsolid", "solid", "endfacet", "facet", "normal", "outer", "endloop", "loop", "vertex"}) {
    std::string big = keyword;
    for (char& c : big) c = static_cast<char>(c - 'a' + 'A');
    std::string title = keyword;
    title[0] = big[0];
    for (std::size_t at = upper.find(keyword); at != std::string::npos; at = upper.find(keyword, at + 1)) {
      upper.replace(at, keyword.size(), big);
      mixed.replace(at, keyword.size(), title);
    }
  }
  REQUIRE(upper.compare(0, 5, "SOLID") == 0);
  REQUIRE(upper.find("ENDFACET") != std::string::npos);
  REQUIRE(mixed.compare(0, 5, "Solid") == 0);
  for (const std::string& text : {upper, mixed}) {
    const Mesh back = read_text(text, MeshFormat::Stl).mesh;
    CHECK(back.V == expected.V);
    CHECK(back.F == expected.F);
  }
  // A word that is no keyword in any case is still named.
  CHECK_THAT(error_message([&] { read_text(with_replaced(upper, "OUTER", "OTHER"), MeshFormat::Stl); }),
             Catch::Contains("expected 'outer' but found 'OTHER'"));
}
