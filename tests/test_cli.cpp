// The `anisoform` command-line contract, tested on the real binary: exit
// statuses, the JSON on stdout, messages on stderr, the output files, and that
// no malformed input or bad option ends the process with a signal or a hang.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "anisoform/deform_request.h"
#include "anisoform/flatten.h"
#include "anisoform/mesh_io.h"
#include "anisoform/session.h"
#include "cli_runner.h"
#include "test_support.h"

namespace {

using nlohmann::json;
using aniso::test::CliRun;
using aniso::test::contains;
using aniso::test::describe;
using aniso::test::run_cli;
using aniso::test::run_expecting;
using aniso::test::slurp;
using aniso::test::stdout_json;
using aniso::test::temp_path;
using aniso::test::write_temp_text;

json info_of(const std::string& path) { return stdout_json(run_expecting({"info", path}, 0)); }

std::string mesh(const std::string& relative) { return aniso::test::mesh_path(relative); }

}  // namespace

TEST_CASE("cli: info reports the torus's size and topology as JSON", "[cli]") {
  const json info = info_of(mesh("closed/torus.obj"));
  CHECK(info["vertices"] == 2304);
  CHECK(info["triangles"] == 4608);
  CHECK(info["components"] == 1);
  CHECK(info["boundary_loops"] == 0);
  CHECK(info["edge_manifold"] == true);
  CHECK(info["vertex_manifold"] == true);
  CHECK(info["consistently_oriented"] == true);
  CHECK(info["degenerate_triangles"] == 0);
  CHECK(info["duplicate_faces"] == 0);
  CHECK(info["non_manifold_edges"] == 0);
  CHECK(info["non_manifold_vertices"] == 0);
  CHECK(info["non_finite_vertices"] == 0);
  CHECK(info["unreferenced_vertices"] == 0);
  CHECK(info["triangle_soup"] == false);
  CHECK(info["solvable"] == true);
  CHECK(info["problem_count"] == 0);
  CHECK(info["problems"].empty());
  CHECK(info["bbox"]["min"][0].get<double>() == Approx(-1.25));
  CHECK(info["bbox"]["max"][1].get<double>() == Approx(0.25));
  CHECK(info["read"].is_object());
}

TEST_CASE("cli: info counts the hemisphere's one boundary loop", "[cli]") {
  const json info = info_of(mesh("open/hemisphere.obj"));
  CHECK(info["vertices"] == 2051);
  CHECK(info["triangles"] == 4000);
  CHECK(info["boundary_loops"] == 1);
  CHECK(info["components"] == 1);
  CHECK(info["edge_manifold"] == true);
}

TEST_CASE("cli: info reports what the reader did to a polygon mesh", "[cli]") {
  const json info = info_of(mesh("formats/spot_quadrangulated.obj"));
  CHECK(info["vertices"] == 2930);
  CHECK(info["triangles"] == 2 * 2928);
  CHECK(info["read"]["polygons_triangulated"] == 2928);
}

namespace {

// What `info` and `deform` must do with one malformed file. For exit 0, info
// must report the defect (`info_check`); for exit 3, stderr must name the
// problem (`stderr_names`, or any message when empty).
struct MalformedCase {
  std::string file;
  int info_exit;
  int deform_exit;
  std::string stderr_names;
  std::function<void(const json&)> info_check;
};

std::vector<MalformedCase> malformed_cases() {
  const auto has_problems = [](const json& info) { CHECK(info["problem_count"] > 0); };
  return {
      {"Spider_binary.stl", 0, 0, "",
       [](const json& info) {
         CHECK(info["edge_manifold"] == false);
         CHECK(info["components"] == 18);
         CHECK(info["degenerate_triangles"] == 56);
         CHECK(info["consistently_oriented"] == false);
       }},
      {"bad_degenerate_faces.obj", 0, 0, "",
       [](const json& info) { CHECK(info["degenerate_triangles"] == 6); }},
      {"bad_flipped_faces.obj", 0, 0, "",
       [](const json& info) { CHECK(info["consistently_oriented"] == false); }},
      // Two bad faces (21 uses vertex 840, 1655 uses index 0): the first in
      // the file is named.
      {"bad_index_out_of_range.obj", 3, 3, "vertex 840", nullptr},
      {"bad_index_out_of_range.off", 3, 3, "829", nullptr},
      // Counted from 0, and said so: an OBJ's own 'f' lines count from 1.
      {"bad_nan_coordinate.obj", 0, 3,
       "vertex 5 has a non-finite coordinate (nan, 0.343383, -0.678339); vertices and faces are counted from 0 here: "
       "vertex 0 is the file's first 'v' line",
       [](const json& info) {
         CHECK(info["non_finite_vertices"] == 1);
         CHECK(info["solvable"] == false);
         CHECK(info["problems"][0]["element"] == 5);
       }},
      {"bad_nonmanifold_edge.obj", 0, 0, "",
       [](const json& info) {
         CHECK(info["edge_manifold"] == false);
         CHECK(info["non_manifold_edges"] == 1);
       }},
      {"bad_triangle_soup.obj", 0, 0, "",
       [](const json& info) {
         CHECK(info["vertices"] == 829);  // welded, as deform welds it
         CHECK(info["components"] == 1);
         CHECK(info["triangle_soup"] == true);
       }},
      // GLB is not one of the formats we read: an unknown extension is a bad
      // parameter (exit 2), as for any other file name.
      {"boxNotManifold.glb", 2, 2, "", nullptr},
      {"boxNotManifold.obj", 0, 0, "",
       [](const json& info) { CHECK(info["boundary_loops"] == 1); }},
      {"box_UTF16BE.obj", 0, 0, "",
       [](const json& info) {
         CHECK(info["vertices"] == 8);
         CHECK(info["triangles"] == 12);
         CHECK(contains(info["read"]["notes"].dump(), "UTF-16"));
       }},
      {"box_without_lineending.obj", 0, 0, "",
       [](const json& info) {
         CHECK(info["vertices"] == 8);
         CHECK(info["triangles"] == 12);
         CHECK(info["problem_count"] == 0);
       }},
      {"degtri_sliding.off", 0, 0, "",
       [](const json& info) { CHECK(info["degenerate_triangles"] == 4); }},
      {"empty.obj", 3, 3, "is empty", nullptr},
      {"empty.off", 3, 3, "is empty", nullptr},
      {"empty.ply", 3, 3, "is empty", nullptr},
      {"empty.stl", 3, 3, "is empty", nullptr},
      {"empty_mesh_header_only.off", 0, 3, "no vertices",
       [has_problems](const json& info) {
         CHECK(info["vertices"] == 0);
         has_problems(info);
       }},
      {"empty_mesh_header_only.ply", 0, 3, "no vertices",
       [has_problems](const json& info) {
         CHECK(info["vertices"] == 0);
         has_problems(info);
       }},
      {"empty_mesh_zero_triangles.stl", 0, 3, "no triangles",
       [has_problems](const json& info) {
         CHECK(info["triangles"] == 0);
         has_problems(info);
       }},
      {"multi_component.obj", 0, 0, "",
       [](const json& info) { CHECK(info["components"] == 2); }},
      {"number_formats.obj", 3, 3, "3.1+e2", nullptr},
      {"openscad-nonmanifold-crash.obj", 0, 0, "",
       [](const json& info) {
         CHECK(info["components"] == 2);
         CHECK(info["degenerate_triangles"] == 1);
       }},
      {"testmixed.obj", 0, 0, "",
       [](const json& info) {
         CHECK(info["vertices"] == 8);
         CHECK(info["triangles"] == 12);
         CHECK(info["read"]["elements_skipped"] > 0);
       }},
      {"truncated_binary.ply", 3, 3, "", nullptr},
      {"truncated_binary.stl", 3, 3, "", nullptr},
  };
}

void check_refusal_names_problem(const CliRun& run, const std::string& stderr_names) {
  CHECK_FALSE(run.err.empty());
  CHECK(run.out.empty());
  if (!stderr_names.empty()) CHECK(contains(run.err, stderr_names));
}

}  // namespace

TEST_CASE("cli: the malformed-case table covers every file in malformed/", "[cli]") {
  std::vector<std::string> listed;
  for (const MalformedCase& c : malformed_cases()) listed.push_back(c.file);
  std::vector<std::string> present;
  for (const auto& entry : std::filesystem::directory_iterator(mesh("malformed"))) {
    present.push_back(entry.path().filename().string());
  }
  std::sort(listed.begin(), listed.end());
  std::sort(present.begin(), present.end());
  CHECK(listed == present);
}

TEST_CASE("cli: info on every malformed file reports the problem or refuses it by name", "[cli]") {
  for (const MalformedCase& c : malformed_cases()) {
    SECTION(c.file) {
      const std::vector<std::string> args{"info", mesh("malformed/" + c.file)};
      const CliRun run = run_expecting(args, c.info_exit);
      INFO(describe(args, run));
      if (c.info_exit == 0) {
        const json info = stdout_json(run);
        if (c.info_check) c.info_check(info);
      } else {
        check_refusal_names_problem(run, c.stderr_names);
      }
    }
  }
}

TEST_CASE("cli: deform on every malformed file repairs, warns or refuses by name", "[cli]") {
  for (const MalformedCase& c : malformed_cases()) {
    SECTION(c.file) {
      const std::vector<std::string> args{
          "deform", mesh("malformed/" + c.file), temp_path("malformed_out.obj"),
          "--scale", "1.3", "--iterations", "5"};
      const CliRun run = run_expecting(args, c.deform_exit);
      INFO(describe(args, run));
      if (c.deform_exit == 0) {
        const json result = stdout_json(run);
        CHECK(result["vertices"] > 0);
      } else {
        check_refusal_names_problem(run, c.stderr_names);
      }
    }
  }
}

// The shape changes, the texture mapping does not: an OBJ written by deform
// has the input OBJ's vt list and per-corner indices, its materials and
// vertex colours, as read (replay writes through the same Session::attributes()).
TEST_CASE("cli: deform keeps an OBJ's texture coordinates, materials and vertex colours", "[cli]") {
  const std::string in = mesh("closed/spot_triangulated.obj");
  const aniso::ReadResult input = aniso::read_mesh(in);
  REQUIRE(input.attributes.texture.uv.rows() == 3225);
  const std::string out = temp_path("textured.obj");
  run_expecting({"deform", in, out, "--scale", "1.3", "--select", "sphere:0,0.5,0.6,0.4"}, 0);
  const aniso::ReadResult deformed = aniso::read_mesh(out);
  CHECK(deformed.attributes.texture.uv == input.attributes.texture.uv);
  CHECK(deformed.attributes.texture.faces == input.attributes.texture.faces);
  CHECK(deformed.mesh.F == input.mesh.F);
  CHECK((deformed.mesh.V - input.mesh.V).cwiseAbs().maxCoeff() > 0.05);
  // And its materials (a LightWave export's mtllib and usemtl).
  const std::string concave = temp_path("concave.obj");
  run_expecting({"deform", mesh("formats/concave_polygon.obj"), concave, "--scale", "1.3"}, 0);
  CHECK(aniso::read_mesh(concave).attributes.materials.runs ==
        aniso::read_mesh(mesh("formats/concave_polygon.obj")).attributes.materials.runs);
  CHECK(aniso::read_mesh(concave).attributes.materials.libraries == std::vector<std::string>{"concave_polygon.mtl"});
  // And its vertex colours (Spot written with a colour per vertex).
  aniso::SurfaceAttributes coloured;
  coloured.vertex_colors = (input.mesh.V.array().tanh() * 0.25 + 0.5).matrix();
  aniso::WriteOptions with_colours;
  with_colours.attributes = &coloured;
  const std::string colours_in = temp_path("coloured.obj");
  aniso::write_mesh(colours_in, input.mesh, with_colours);
  const std::string colours_out = temp_path("coloured_out.obj");
  run_expecting({"deform", colours_in, colours_out, "--scale", "1.3", "--select", "sphere:0,0.5,0.6,0.4"}, 0);
  CHECK(aniso::read_mesh(colours_out).attributes.vertex_colors == coloured.vertex_colors);
  // Other formats have no per-corner coordinates: the shape alone.
  const std::string ply = temp_path("textured.ply");
  run_expecting({"deform", in, ply, "--scale", "1.3", "--select", "sphere:0,0.5,0.6,0.4"}, 0);
  CHECK(aniso::read_mesh(ply).mesh.V == deformed.mesh.V);
}

// A scan's colours stay on their vertices: the input PLY's vertex properties
// come out in the output PLY, in their types (Spot given a colour per vertex).
TEST_CASE("cli: deform keeps a PLY's vertex colours", "[cli]") {
  aniso::Mesh spot = aniso::read_mesh(mesh("formats/spot_lowres_binary.ply")).mesh;
  aniso::VertexProperties colours = {{"red", "uchar", {}}, {"green", "uchar", {}}, {"blue", "uchar", {}}};
  for (Eigen::Index i = 0; i < spot.V.rows(); ++i) {
    for (int k = 0; k < 3; ++k) colours[k].values.push_back(static_cast<double>((i * (k + 3)) % 256));
  }
  aniso::SurfaceAttributes attributes;
  attributes.vertex_properties = colours;
  aniso::WriteOptions options;
  options.attributes = &attributes;
  const std::string in = temp_path("coloured.ply");
  aniso::write_mesh(in, spot, options);
  for (const char* ascii : {"", "--ascii"}) {
    INFO(ascii);
    const std::string out = temp_path("coloured_out.ply");
    std::vector<std::string> args{"deform", in, out, "--scale", "1.3", "--select", "sphere:0,0.5,0.6,0.4"};
    if (*ascii) args.push_back(ascii);
    run_expecting(args, 0);
    const aniso::ReadResult deformed = aniso::read_mesh(out);
    REQUIRE(deformed.attributes.vertex_properties.size() == 3);
    for (int k = 0; k < 3; ++k) {
      CHECK(deformed.attributes.vertex_properties[k].name == colours[k].name);
      CHECK(deformed.attributes.vertex_properties[k].type == "uchar");
      CHECK(deformed.attributes.vertex_properties[k].values == colours[k].values);
    }
    CHECK((deformed.mesh.V - spot.V).cwiseAbs().maxCoeff() > 0.05);
  }
}

TEST_CASE("cli: info reports a triangle soup as deform and the browser edit it: welded", "[cli]") {
  // spot_lowres as an OBJ soup (each face its own 3 vertices): info said
  // 4962 vertices in 1654 components, deform edited 829 in one.
  const aniso::Mesh spot = aniso::test::load("formats/spot_lowres.obj");
  aniso::Mesh soup;
  soup.V.resize(3 * spot.num_triangles(), 3);
  soup.F.resize(spot.num_triangles(), 3);
  for (int f = 0; f < spot.num_triangles(); ++f) {
    for (int k = 0; k < 3; ++k) {
      soup.V.row(3 * f + k) = spot.V.row(spot.F(f, k));
      soup.F(f, k) = 3 * f + k;
    }
  }
  const std::string path = temp_path("spot_soup.obj");
  aniso::write_mesh(path, soup);
  const json info = info_of(path);
  const json deformed =
      stdout_json(run_expecting({"deform", path, temp_path("spot_soup_out.obj"), "--scale", "1.2"}, 0));
  CHECK(info["vertices"] == 829);
  CHECK(info["vertices"] == deformed["vertices"]);
  CHECK(info["components"] == 1);
  CHECK(info["boundary_loops"] == 0);
  CHECK(info["triangle_soup"] == true);
  CHECK(info["read"]["vertices_welded"] == deformed["read"]["vertices_welded"]);
  CHECK(info["read"]["notes"].dump().find("4962 -> 829") != std::string::npos);
  // The browser's session says the same.
  const std::string bytes = aniso::test::slurp(path);
  aniso::Session session;
  const aniso::SessionMeshInfo& loaded =
      session.load_mesh(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), "spot_soup.obj");
  CHECK(loaded.report.vertices == 829);
  const std::string weld_note = info["read"]["notes"].back().get<std::string>();
  CHECK(std::find(loaded.notes.begin(), loaded.notes.end(), weld_note) != loaded.notes.end());
}

TEST_CASE("cli: deform welds a triangle soup and says so", "[cli]") {
  const std::string out = temp_path("welded.obj");
  const json result = stdout_json(run_expecting(
      {"deform", mesh("malformed/bad_triangle_soup.obj"), out, "--scale", "1.2"}, 0));
  CHECK(result["vertices"] == 829);
  CHECK(result["triangles"] == 1654);
  bool warned = false;
  for (const json& warning : result["warnings"]) {
    warned = warned || contains(warning.get<std::string>(), "welded");
  }
  CHECK(warned);
  // The read report counts the weld as the warning does (4962 -> 829).
  CHECK(result["read"]["vertices_welded"] == 4962 - 829);
  CHECK(info_of(out)["components"] == 1);
}

TEST_CASE("cli: deform warns about the problems it solves through", "[cli]") {
  const json result = stdout_json(run_expecting(
      {"deform", mesh("malformed/bad_degenerate_faces.obj"), temp_path("degenerate.obj"),
       "--method", "andefgrad", "--scale", "1.2"},
      0));
  REQUIRE(result["warnings"].size() > 0);
  CHECK(contains(result["warnings"].dump(), "zero-area"));
}

TEST_CASE("cli: bad command lines and parameters exit with status 2", "[cli]") {
  const std::string in = mesh("formats/spot_lowres.obj");
  const std::string out = temp_path("bad_usage.obj");
  const std::vector<std::vector<std::string>> bad_command_lines{
      {},
      {"frobnicate"},
      {"info"},
      {"deform", in},  // missing OUT
      {"deform", in, out, "--frobnicate"},
      {"deform", in, out, "--method", "unknown"},
      {"deform", in, out, "--scale", "0"},
      {"deform", in, out, "--scale", "-1"},
      {"deform", in, out, "--scale", "abc"},
      {"deform", in, out, "--scale", "1.5x"},
      {"deform", in, out, "--scale", "nan"},
      {"deform", in, out, "--scale", "inf"},
      {"deform", in, out, "--scale", "1,2,3"},
      {"deform", in, out, "--scale", "1,,2"},
      {"deform", in, out, "--scale", " 1"},
      {"deform", in, out, "--thicken", "0"},
      {"deform", in, out, "--shear", "1e999"},
      {"deform", in, out, "--select", "box:0,0,0,1,1"},
      {"deform", in, out, "--select", "sphere:0,0,0,-1"},
      {"deform", in, out, "--select", "cone:1"},
      {"deform", in, out, "--rotate", "q:10"},
      {"deform", in, out, "--rotate", "n:ten"},
      {"deform", in, out, "--rotate", "n"},
      {"deform", in, out, "--twist", "0,0,0:10"},
      {"deform", in, out, "--twist", "0,0,1"},
      {"deform", in, out, "--direction", "global:0,0,0"},
      {"deform", in, out, "--direction", "curvature:mean"},
      {"deform", in, out, "--direction", "north"},
      {"deform", in, out, "--handle", "all", "--move", "0,0,1"},  // not arap
      {"deform", in, out, "--method", "andefgrad", "--move", "0,0,1"},  // moves ARAP's handles only
      {"deform", in, out, "--method", "arap", "--handle", "all", "--move", "0,1"},
      {"deform", in, out, "--pin", "box:10,10,10,11,11,11"},  // holds no vertex
      {"deform", in, out, "--falloff", "-1"},
      {"deform", in, out, "--iterations", "0"},
      {"deform", in, out, "--iterations", "-3"},
      {"deform", in, out, "--iterations", "2.5"},
      {"deform", in, out, "--tolerance", "-1e-3"},
      {"deform", in, out, "--elements", "rims"},
      {"deform", in, out, "--rotations", "spin"},
      {"deform", in, out, "--rotation-coupling", "0"},
      {"deform", in, out, "--rotation-coupling", "nan"},
      {"deform", in, temp_path("out.xyz")},                 // unknown output format
      {"deform", in, "/nonexistent-directory/out.obj"},     // unwritable output
      {"deform", in, out, "--scale", "1.2", "--scale", "1.3"},  // given twice
  };
  for (const std::vector<std::string>& args : bad_command_lines) {
    const CliRun run = run_expecting(args, 2);
    INFO(describe(args, run));
    CHECK_FALSE(run.err.empty());
    // Every error in one form, CLI11's own ("--scale: At Most 1 required") too.
    const bool command = !args.empty() && (args[0] == "info" || args[0] == "deform" || args[0] == "flatten");
    CHECK(run.err.rfind(command ? "anisoform " + args[0] + ": error: " : "anisoform: error: ", 0) == 0);
    CHECK(run.out.empty());
  }
}

TEST_CASE("cli: command-line errors name the command, an unknown one included, and field files their line", "[cli]") {
  const std::string in = mesh("formats/spot_lowres.obj");
  const std::string out = temp_path("out.obj");
  CHECK(run_expecting({"deform", in, out, "--scale", "1.2", "--scale", "1.3"}, 2).err ==
        "anisoform deform: error: --scale: At Most 1 required but received 2 (see anisoform deform --help)\n");
  CHECK(run_expecting({"deform", in}, 2).err == "anisoform deform: error: OUT is required (see anisoform deform --help)\n");
  // It said "A subcommand is required".
  CHECK(run_expecting({"bogus", in}, 2).err ==
        "anisoform: error: unknown command 'bogus' (the commands are info, deform, flatten, replay; see anisoform "
        "--help)\n");
  CHECK(contains(run_expecting({}, 2).err, "anisoform: error: A subcommand is required (see anisoform --help)"));
  // It said "direction constraint 2 (vertex 5000): ..." without the file or the line.
  const std::string field = write_temp_text("far_field.txt", "0 1 0 0\n\n5000 0 0 1\n");
  for (const std::string command : {"deform", "flatten"}) {
    const std::string target = command == "deform" ? in : mesh("open/hemisphere.obj");
    const std::string result = temp_path(command == "deform" ? "far.obj" : "far.svg");
    const CliRun run = run_expecting({command, target, result, "--direction", "field:" + field}, 2);
    CHECK(run.err.rfind("anisoform " + command + ": error: --direction: " + field +
                            " line 3 (vertex 5000): vertex index out of range, the mesh has ",
                        0) == 0);
  }
}

TEST_CASE("cli: an index out of range in a selection file is a bad parameter", "[cli]") {
  const std::string selection = write_temp_text("selection.txt", "1\n5000\n");
  const CliRun run = run_expecting({"deform", mesh("formats/spot_lowres.obj"),
                                    temp_path("out.obj"), "--select", "file:" + selection},
                                   2);
  CHECK(contains(run.err, "5000"));
}

TEST_CASE("cli: field-file amounts SU/SV <= 0 are refused like --scale -1, naming the line", "[cli]") {
  // Vertex 400's line carries the bad amount; the first line is fine.
  const std::vector<std::pair<std::string, std::string>> cases{
      {"0 1 0 0 1.2 1\n400 0 1 0 0\n", "field.txt line 2: SU must be positive, got 0"},
      {"0 1 0 0\n400 0 1 0 1 -1\n", "field.txt line 2: SV must be positive, got -1"},
  };
  for (const auto& [text, message] : cases) {
    const std::string field = write_temp_text("field.txt", text);
    for (const std::string& command : {"deform", "flatten"}) {
      const std::string out = temp_path(command == std::string("deform") ? "out.obj" : "out.svg");
      const CliRun run = run_expecting(
          {command, mesh("formats/spot_lowres.obj"), out, "--direction", "field:" + field}, 2);
      INFO(command << ": " << run.err);
      CHECK(contains(run.err, message));
    }
  }
  CHECK(contains(run_expecting({"deform", mesh("formats/spot_lowres.obj"), temp_path("out.obj"), "--scale", "-1"}, 2).err,
                 "must be positive, got -1"));
}

TEST_CASE("cli: a field file's amounts replace --scale and --compress, and a warning says so", "[cli]") {
  // Without the warning, --scale 1.3 and --scale 2 gave the same mesh, warnings [].
  const std::string with_amounts = write_temp_text("amounts.txt", "0 1 0 0 0.8\n100 1 0 0 0.9\n");
  const std::string without = write_temp_text("no_amounts.txt", "0 1 0 0\n100 1 0 0\n");
  const struct {
    std::string command, in, out, option, value;
  } cases[] = {
      {"deform", mesh("formats/spot_lowres.obj"), temp_path("amounts.obj"), "--scale", "1.3"},
      {"flatten", mesh("open/hemisphere.obj"), temp_path("amounts_pattern.obj"), "--compress", "0.7"},
  };
  for (const auto& c : cases) {
    const std::string expected = c.option + " " + c.value + " is not used: the field file " + with_amounts +
                                 " gives amounts (its SU SV columns), which replace it everywhere";
    const CliRun replaced =
        run_expecting({c.command, c.in, c.out, c.option, c.value, "--direction", "field:" + with_amounts}, 0);
    INFO(c.command << ": " << replaced.err);
    // The warning about the amounts, once, among any others (the hemisphere's
    // pattern also warns of its shear).
    const auto amounts_warnings = [](const json& result) {
      int count = 0;
      for (const auto& warning : result["warnings"]) count += contains(warning.get<std::string>(), "is not used");
      return count;
    };
    const json result = stdout_json(replaced);
    REQUIRE(amounts_warnings(result) == 1);
    bool said = false;
    for (const auto& warning : result["warnings"]) said = said || contains(warning.get<std::string>(), expected);
    CHECK(said);
    CHECK(contains(replaced.err, "anisoform " + c.command + ": warning: " + expected));
    // A file without amounts leaves the option its say: no such warning.
    const CliRun kept = run_expecting({c.command, c.in, c.out, c.option, c.value, "--direction", "field:" + without}, 0);
    CHECK(amounts_warnings(stdout_json(kept)) == 0);
    CHECK_FALSE(contains(kept.err, "is not used"));
  }
}

TEST_CASE("cli: --rotations steps without --iterations runs the number of steps --help states", "[cli]") {
  // --help said the steps were --iterations' default 50; one step ran.
  const CliRun help = run_expecting({"deform", "--help"}, 0);
  std::string text;
  std::istringstream words(help.out);
  for (std::string word; words >> word;) text += word + " ";  // however CLI11 wraps it
  const std::string stated = "the number of steps (default ";
  const std::size_t at = text.find(stated);
  REQUIRE(at != std::string::npos);
  const int steps = std::stoi(text.substr(at + stated.size()));
  const std::string in = mesh("formats/spot_lowres.obj");
  const std::vector<std::string> edit{"--select", "box:-1,-1,0.5,1,2,2", "--rotate", "n:30", "--rotations", "steps"};
  std::vector<std::string> by_default{"deform", in, temp_path("steps_default.obj")};
  by_default.insert(by_default.end(), edit.begin(), edit.end());
  std::vector<std::string> stated_count{"deform", in, temp_path("steps_stated.obj"), "--iterations", std::to_string(steps)};
  stated_count.insert(stated_count.end(), edit.begin(), edit.end());
  const json unset = stdout_json(run_expecting(by_default, 0));
  const json given = stdout_json(run_expecting(stated_count, 0));
  CHECK(unset["iterations"] == steps);
  CHECK(given["iterations"] == steps);
  CHECK(slurp(temp_path("steps_default.obj")) == slurp(temp_path("steps_stated.obj")));
}

// A flat panel `length` units long (x) and 100 wide (y), as an OBJ grid.
static std::string panel_obj(double length) {
  std::string text;
  const int columns = 10, rows = 3;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      text += "v " + std::to_string(length * i / (columns - 1)) + " " + std::to_string(100.0 * j / (rows - 1)) + " 0\n";
    }
  }
  for (int j = 0; j + 1 < rows; ++j) {
    for (int i = 0; i + 1 < columns; ++i) {
      const int a = j * columns + i + 1, b = a + 1, c = a + columns, d = c + 1;
      text += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + "\n";
      text += "f " + std::to_string(a) + " " + std::to_string(d) + " " + std::to_string(c) + "\n";
    }
  }
  return text;
}

// The guess decides the pattern's size in mm: a 450 mm panel was written as
// 450 cm (10x too large), a 520 mm one right, both with warnings [].
TEST_CASE("cli: flatten says which unit it guessed, from which size, and how to set it", "[cli]") {
  const struct {
    double length;
    std::string guessed;
  } panels[] = {{450, "the mesh's unit was guessed as cm (10 mm per unit) from its largest side, 450 units"},
                {520, "the mesh's unit was guessed as mm (1 mm per unit) from its largest side, 520 units"}};
  for (const auto& panel : panels) {
    const std::string in = write_temp_text("panel.obj", panel_obj(panel.length));
    const CliRun guessed = run_expecting({"flatten", in, temp_path("panel.svg"), "--direction", "global:1,0,0"}, 0);
    const json result = stdout_json(guessed);
    INFO(guessed.err);
    REQUIRE(result["warnings"].size() == 1);
    CHECK(result["warnings"][0].get<std::string>() ==
          panel.guessed + "; give --mm-per-unit if it is in another unit (1 for mm, 10 for cm, 1000 for m, 25.4 for "
                          "inches)");
    CHECK(contains(guessed.err, "anisoform flatten: warning: " + panel.guessed));
    const json given = stdout_json(run_expecting(
        {"flatten", in, temp_path("panel.svg"), "--direction", "global:1,0,0", "--mm-per-unit", "1"}, 0));
    CHECK(given["warnings"].empty());
  }
}

TEST_CASE("cli: a missing input says cannot open and exits 3", "[cli]") {
  for (const std::string& command : {"info", "deform"}) {
    std::vector<std::string> args{command, "/nonexistent/mesh.obj"};
    if (command == "deform") args.push_back(temp_path("out.obj"));
    const CliRun run = run_expecting(args, 3);
    CHECK(contains(run.err, "cannot open"));
    CHECK(run.out.empty());
  }
}

TEST_CASE("cli: an input of unknown format exits 2", "[cli]") {
  const std::string path = write_temp_text("mesh.xyz", "0 0 0\n");
  const CliRun run = run_expecting({"info", path}, 2);
  CHECK(contains(run.err, "xyz"));
}

TEST_CASE("cli: --help succeeds with the usage on stdout", "[cli]") {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--help"}, {"info", "--help"}, {"deform", "--help"}}) {
    const CliRun run = run_expecting(args, 0);
    CHECK(contains(run.out, "Usage"));
  }
  CHECK(contains(run_expecting({"deform", "--help"}, 0).out, "--thicken"));
  // The defaults the help states are the core's (the flatten cap read 500
  // after the core's became 1,000).
  CHECK(contains(run_expecting({"deform", "--help"}, 0).out,
                 "(default " + std::to_string(aniso::DeformRequest().max_iterations) + ")"));
  CHECK(contains(run_expecting({"flatten", "--help"}, 0).out,
                 "(default " + std::to_string(aniso::ArapFlattenSettings().max_iterations) + ")"));
}

TEST_CASE("cli: deform prints every contract key with its type", "[cli]") {
  const std::string out = temp_path("keys.obj");
  const json result = stdout_json(
      run_expecting({"deform", mesh("formats/spot_lowres.obj"), out, "--scale", "1.5,0.9",
                     "--select", "sphere:0,0.5,0.8,0.3", "--falloff", "0.1"},
                    0));
  CHECK(result["method"] == "anarap");
  CHECK(result["vertices"] == 829);
  CHECK(result["triangles"] == 1654);
  CHECK(result["selected"].is_number_integer());
  CHECK(result["selected"] > 0);
  CHECK(result["selected"] < 829);
  CHECK(result["iterations"].is_number_integer());
  CHECK(result["iterations"] >= 1);
  CHECK(result["energy"].is_number());
  CHECK(result["factorizations"].is_number_integer());
  CHECK(result["factorizations"] >= 1);
  CHECK(result["precompute_ms"].is_number());
  CHECK(result["solve_ms"].is_number());
  CHECK(result["converged"].is_boolean());
  CHECK(result["energy_history"].is_array());
  CHECK(result["energy_history"].size() == result["iterations"].get<std::size_t>());
  CHECK(result["directions_filled"].is_number_integer());
  CHECK(result["warnings"].is_array());
  CHECK(result["max_displacement"].get<double>() > 0.0);
  CHECK(result["direction"] == "global:0,0,1 (longest axis)");
}

TEST_CASE("cli: deform writes every output format and info reads it back", "[cli]") {
  for (const std::string& extension : {"obj", "off", "ply", "stl"}) {
    SECTION(extension) {
      const std::string out = temp_path("spot." + extension);
      run_expecting({"deform", mesh("formats/spot_lowres.obj"), out, "--method", "andefgrad",
                     "--scale", "1.4", "--select", "box:-1,-1,0.5,1,2,2"},
                    0);
      const json info = info_of(out);
      CHECK(info["vertices"] == 829);
      CHECK(info["triangles"] == 1654);
    }
  }
  SECTION("ascii ply") {
    const std::string out = temp_path("spot_ascii.ply");
    run_expecting({"deform", mesh("formats/spot_lowres.obj"), out, "--ascii"}, 0);
    CHECK(contains(slurp(out), "format ascii"));
  }
}

TEST_CASE("cli: andefgrad with scale 1 leaves the mesh where it was", "[cli]") {
  const std::string in = mesh("closed/spool.off");
  const std::string out = temp_path("identity.off");
  run_expecting({"deform", in, out, "--method", "andefgrad", "--scale", "1"}, 0);
  const aniso::Mesh rest = aniso::read_mesh(in).mesh;
  const aniso::Mesh deformed = aniso::read_mesh(out).mesh;
  REQUIRE(deformed.num_vertices() == rest.num_vertices());
  REQUIRE(deformed.num_triangles() == rest.num_triangles());
  CHECK(deformed.F == rest.F);
  const double diagonal = aniso::bounding_box(rest.V).diagonal();
  CHECK((deformed.V - rest.V).cwiseAbs().maxCoeff() <= 1e-6 * diagonal);
}

TEST_CASE("cli: pinned vertices stay and arap handles move by the offset", "[cli]") {
  const std::string in = mesh("formats/spot_lowres.obj");
  const std::string out = temp_path("handles.obj");
  // Handle: the tip of the head (z > 0.9); pins: the back (z < -0.4).
  const json result = stdout_json(run_expecting(
      {"deform", in, out, "--method", "arap", "--handle", "box:-1,-1,0.9,1,2,2", "--move",
       "0,0.1,0", "--pin", "box:-1,-1,-1,1,2,-0.4"},
      0));
  CHECK(result["method"] == "arap");
  CHECK(result["handles"] > 0);
  CHECK(result["pins"] > 0);
  const aniso::Mesh rest = aniso::read_mesh(in).mesh;
  const aniso::Mesh deformed = aniso::read_mesh(out).mesh;
  REQUIRE(deformed.num_vertices() == rest.num_vertices());
  int handles = 0;
  int pins = 0;
  for (int i = 0; i < rest.num_vertices(); ++i) {
    const Eigen::RowVector3d moved = deformed.V.row(i) - rest.V.row(i);
    if (rest.V(i, 2) >= 0.9) {
      ++handles;
      CHECK((moved - Eigen::RowVector3d(0, 0.1, 0)).norm() < 1e-5);
    } else if (rest.V(i, 2) <= -0.4) {
      ++pins;
      CHECK(moved.norm() < 1e-5);
    }
  }
  CHECK(result["handles"] == handles);
  CHECK(result["pins"] == pins);
}

TEST_CASE("cli: arap --move without --handle moves the fully selected vertices and pins the rest", "[cli]") {
  const std::string in = mesh("formats/spot_lowres.obj");
  const std::string out = temp_path("selection_handles.obj");
  const json result = stdout_json(
      run_expecting({"deform", in, out, "--method", "arap", "--select", "box:-1,-1,0.9,1,2,2", "--move", "0,0.1,0"}, 0));
  const aniso::Mesh rest = aniso::read_mesh(in).mesh;
  const aniso::Mesh deformed = aniso::read_mesh(out).mesh;
  int selected = 0;
  for (int i = 0; i < rest.num_vertices(); ++i) {
    const Eigen::RowVector3d moved = deformed.V.row(i) - rest.V.row(i);
    if (rest.V(i, 2) >= 0.9) {
      ++selected;
      CHECK((moved - Eigen::RowVector3d(0, 0.1, 0)).norm() < 1e-5);
    } else {
      CHECK(moved.norm() < 1e-5);  // no falloff: everything else is pinned
    }
  }
  CHECK(selected > 0);
  CHECK(result["handles"] == selected);
  CHECK(result["pins"] == rest.num_vertices() - selected);
}

TEST_CASE("cli: an edit that folds triangles over says so in its warnings", "[cli]") {
  const json result = stdout_json(run_expecting({"deform", mesh("formats/spot_lowres.obj"), temp_path("folded.obj"),
                                                 "--method", "linear", "--scale", "3", "--select", "sphere:0,0.5,0.5,0.4"},
                                                0));
  REQUIRE(result["inverted"].get<int>() > 0);
  bool warned = false;
  for (const auto& warning : result["warnings"]) {
    warned |= warning.get<std::string>() == std::to_string(result["inverted"].get<int>()) +
                                                " triangle(s) folded over: reduce the amount or the falloff";
  }
  CHECK(warned);
}

TEST_CASE("cli: deform runs every method and direction source", "[cli]") {
  const std::string in = mesh("formats/spot_lowres.obj");
  const std::string field = write_temp_text("field.txt", "# two arrows\n0 1 0 0\n400 0 1 0\n");
  const std::string selection = write_temp_text("selection.txt", "0\n1 0.5\n2\n3 1\n400\n");
  const std::vector<std::vector<std::string>> edits{
      {"--method", "anarap", "--rotate", "n:20", "--iterations", "3", "--select", "box:-1,-1,0,1,2,2"},
      {"--method", "anarap", "--elements", "spokes-rims", "--scale", "1.3"},
      {"--method", "andefgrad", "--shear", "0.4", "--direction", "global:0,1,0"},
      {"--method", "andefgrad", "--twist", "0,0,1:45", "--select", "box:-1,-1,0,1,2,2"},
      {"--method", "linear", "--scale", "1.5", "--direction", "curvature:max"},
      {"--method", "andefgrad", "--scale", "0.8", "--direction", "curvature:min"},
      {"--method", "andefgrad", "--scale", "1.2", "--direction", "field:" + field},
      {"--method", "anarap", "--scale", "1,1.3", "--select", "file:" + selection,
       "--falloff", "0.05", "--tolerance", "1e-4"},
      {"--method", "arap"},  // no handles: the mesh stays as it is
  };
  for (const std::vector<std::string>& edit : edits) {
    std::vector<std::string> args{"deform", in, temp_path("edit.obj")};
    args.insert(args.end(), edit.begin(), edit.end());
    const json result = stdout_json(run_expecting(args, 0));
    CHECK(result["vertices"] == 829);
  }
}

TEST_CASE("cli: --direction echoes the source it was given", "[cli]") {
  const json result = stdout_json(run_expecting(
      {"deform", mesh("closed/torus.obj"), temp_path("torus.obj"), "--direction", "global:0,1,0",
       "--method", "andefgrad"},
      0));
  CHECK(result["direction"] == "global:0,1,0");
  const json default_direction = stdout_json(run_expecting(
      {"deform", mesh("closed/torus.obj"), temp_path("torus.obj"), "--method", "andefgrad"}, 0));
  CHECK(default_direction["direction"] == "global:1,0,0 (longest axis)");
}

TEST_CASE("cli: signed numbers are values, not options", "[cli]") {
  const std::string in = mesh("formats/spot_lowres.obj");
  const json result = stdout_json(run_expecting(
      {"deform", in, temp_path("signed.obj"), "--method", "arap", "--handle",
       "box:-1,-1,0.9,1,2,2", "--move", "-0.05,0,+0.02", "--pin", "box:-1,-1,-1,1,2,-0.4"},
      0));
  CHECK(result["handles"] > 0);
  run_expecting({"deform", in, temp_path("signed.obj"), "--scale", "+1.2", "--shear", "-0.3",
                 "--method", "andefgrad"},
                0);
}

TEST_CASE("cli: flatten --no-refine keeps the paper's ARAP result, with the larger error the refinement removes",
          "[cli]") {
  const std::string torso = mesh("open/human_woman_torso_front_patch.obj");
  const std::string out = temp_path("refine.obj");
  const json refined = stdout_json(run_expecting({"flatten", torso, out, "--compress", "0.8", "--direction", "global:0,1,0"}, 0));
  const json paper = stdout_json(
      run_expecting({"flatten", torso, out, "--compress", "0.8", "--direction", "global:0,1,0", "--no-refine"}, 0));
  INFO("refined " << refined["compression_error_mean"] << ", paper " << paper["compression_error_mean"]);
  // Measured 0.0081 and 0.0265 (the uniform baseline: 0.0248).
  CHECK(refined["compression_error_mean"].get<double>() < 0.5 * paper["compression_error_mean"].get<double>());
  CHECK(refined["flipped"] == 0);
  CHECK(paper["flipped"] == 0);
}

TEST_CASE("cli: --acceleration lbfgs, anderson and none reach the same shape, the accelerated ones sooner", "[cli]") {
  const std::string in = mesh("closed/spool.off");
  const aniso::Mesh rest = aniso::read_mesh(in).mesh;
  const double diagonal = aniso::bounding_box(rest.V).diagonal();
  struct Run {
    int iterations;
    aniso::Mesh mesh;
  };
  const auto run = [&](const std::string& acceleration) {
    const std::string out = temp_path("acceleration-" + acceleration + ".off");
    const json result = stdout_json(run_expecting({"deform", in, out, "--method", "anarap", "--scale", "1.4",
                                                   "--direction", "global:0,1,0", "--select",
                                                   "box:-9,0.1,-9,9,9,9", "--iterations", "3000",
                                                   "--tolerance", "1e-9", "--acceleration", acceleration},
                                                  0));
    return Run{result["iterations"].get<int>(), aniso::read_mesh(out).mesh};
  };
  const Run plain = run("none"), anderson = run("anderson"), lbfgs = run("lbfgs");
  INFO("iterations: none " << plain.iterations << ", anderson " << anderson.iterations << ", lbfgs "
                           << lbfgs.iterations);
  CHECK(2 * anderson.iterations < plain.iterations);
  CHECK(2 * lbfgs.iterations < plain.iterations);
  CHECK((anderson.mesh.V - plain.mesh.V).rowwise().norm().maxCoeff() <= 1e-3 * diagonal);
  CHECK((lbfgs.mesh.V - plain.mesh.V).rowwise().norm().maxCoeff() <= 1e-3 * diagonal);
  // The moved part did move: the comparison is not of three copies of the input.
  CHECK((lbfgs.mesh.V - rest.V).rowwise().norm().maxCoeff() >= 0.05 * diagonal);
}

TEST_CASE("cli: an edit whose selected vertices are all pinned warns that nothing moves", "[cli]") {
  const std::string in = mesh("formats/spot_lowres.obj");
  const std::string out = temp_path("all_pinned.obj");
  const std::string warning = "every selected vertex is pinned: the mesh is left unchanged";
  const auto warned = [&](const json& result) {
    bool found = false;
    for (const auto& w : result["warnings"]) found |= w.get<std::string>() == warning;
    return found;
  };
  const aniso::Mesh rest = aniso::read_mesh(in).mesh;
  for (const char* method : {"anarap", "andefgrad", "linear"}) {
    const json result = stdout_json(run_expecting(
        {"deform", in, out, "--method", method, "--scale", "2", "--select", "box:-1,-1,0.9,1,2,2", "--pin", "all"}, 0));
    CHECK(warned(result));
    CHECK((aniso::read_mesh(out).mesh.V - rest.V).cwiseAbs().maxCoeff() == 0.0);
  }
  // A selected vertex left free moves, and no warning says otherwise.
  const json free = stdout_json(run_expecting({"deform", in, out, "--scale", "2", "--select", "box:-1,-1,0.9,1,2,2",
                                               "--pin", "box:-1,-1,1.0,1,2,2"},
                                              0));
  CHECK_FALSE(warned(free));
  CHECK((aniso::read_mesh(out).mesh.V - rest.V).cwiseAbs().maxCoeff() > 1e-3);
}

TEST_CASE("cli: flatten with a field file's amounts reports and labels those amounts, not --compress's", "[cli]") {
  const std::string in = mesh("open/plane.off");
  const std::string svg = temp_path("field_amounts.svg");
  // The plane's two opposite corners along x, both asking 0.7 along x: the pattern is 0.7 as wide.
  const std::string uniform = write_temp_text("field_07.txt", "0 1 0 0 0.7 1\n800 1 0 0 0.7 1\n");
  json result = stdout_json(run_expecting({"flatten", in, svg, "--direction", "field:" + uniform, "--compress", "0.9",
                                           "--mm-per-unit", "100"},
                                          0));
  CHECK(result["su"] == 0.7);
  CHECK(result["sv"] == 1.0);
  CHECK(result["amounts"] == "field");
  CHECK(contains(slurp(svg), "su 0.7 sv 1 (the field's)"));
  CHECK_FALSE(contains(slurp(svg), "su 0.9"));
  // Amounts that vary: their range.
  const std::string varying = write_temp_text("field_07_09.txt", "0 1 0 0 0.7 1\n800 1 0 0 0.9 1\n");
  result = stdout_json(run_expecting({"flatten", in, svg, "--direction", "field:" + varying}, 0));
  CHECK(result["su"] == json::array({0.7, 0.9}));
  CHECK(contains(slurp(svg), "su 0.7-0.9 sv 1 (the field's)"));
  // Without amounts in the field, --compress's.
  const std::string arrows = write_temp_text("field_arrows.txt", "0 1 0 0\n800 1 0 0\n");
  result = stdout_json(run_expecting({"flatten", in, svg, "--direction", "field:" + arrows, "--compress", "0.9"}, 0));
  CHECK(result["su"] == 0.9);
  CHECK(result["amounts"] == "compress");
  CHECK(contains(slurp(svg), "su 0.9 sv 1,"));
}

TEST_CASE("cli: a direction that gives none along the surface is refused, not replaced by an arbitrary one", "[cli]") {
  // plane.off lies in y = 0: y is its normal everywhere, and it is flat (no principal directions).
  const std::string in = mesh("open/plane.off");
  for (const char* direction : {"global:0,1,0", "curvature:min", "curvature:max"}) {
    const CliRun run = run_expecting({"deform", in, temp_path("no_direction.obj"), "--direction", direction,
                                      "--scale", "1.5"},
                                     2);
    CHECK(contains(run.err, std::string(direction) == "global:0,1,0" ? "parallel to the surface normal everywhere"
                                                                      : "no principal curvature directions"));
  }
  const CliRun flatten = run_expecting({"flatten", in, temp_path("no_direction.svg"), "--direction", "global:0,1,0",
                                        "--compress", "0.8"},
                                       2);
  CHECK(contains(flatten.err, "parallel to the surface normal everywhere"));
  // Along the surface, the edit is made.
  run_expecting({"deform", in, temp_path("along.obj"), "--direction", "global:1,0,0", "--scale", "1.5"}, 0);
}

TEST_CASE("cli: any non-zero finite direction means its unit vector, however large or small", "[cli]") {
  const std::string in = mesh("formats/spot_lowres.obj");
  const auto deformed = [&](const std::string& direction) {
    const std::string out = temp_path("scaled_direction.obj");
    run_expecting({"deform", in, out, "--direction", direction, "--scale", "1.4", "--select", "box:-1,-1,0.5,1,2,2"}, 0);
    return aniso::read_mesh(out).mesh.V;
  };
  const aniso::Positions unit = deformed("global:0,0,1");
  CHECK((unit - aniso::read_mesh(in).mesh.V).cwiseAbs().maxCoeff() > 0.05);  // the edit moves the part
  // Past 1e154 the plain norm overflowed (the edit barely moved); below 1e-154 it underflowed.
  for (const char* direction : {"global:0,0,1e200", "global:0,0,1e-160", "global:0,0,1e300"}) {
    INFO(direction);
    CHECK((deformed(direction) - unit).cwiseAbs().maxCoeff() == 0.0);
  }
  CHECK(contains(run_expecting({"deform", in, temp_path("zero.obj"), "--direction", "global:0,0,0"}, 2).err,
                 "has no direction"));
}

TEST_CASE("cli: a flattening stopped by its iteration cap says to raise it, and a tolerance of 0 runs to round-off", "[cli]") {
  const std::vector<std::string> torso{"flatten", mesh("open/human_woman_torso_front_patch.obj"),
                                       temp_path("capped.obj"), "--compress", "0.8", "--direction", "global:0,1,0"};
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = torso;
    args.insert(args.end(), extra.begin(), extra.end());
    return stdout_json(run_expecting(args, 0));
  };
  const json capped = with({"--iterations", "5"});
  CHECK(capped["converged"] == false);
  REQUIRE(capped["warnings"].size() == 1);
  // Not the patch's fault: the advice to cut it along a seam would be wrong.
  CHECK(capped["warnings"][0] ==
        "the flattening stopped at the iteration cap (5) before it settled: raise the iterations for the finished pattern");
  // Iterated until no step lowers the energy: converged within the cap it was
  // given, nothing about the cap; only the shear the refinement leaves (11°).
  const json exact = with({"--iterations", "10000", "--tolerance", "0"});
  CHECK(exact["converged"] == true);
  REQUIRE(exact["warnings"].size() == 1);
  CHECK_THAT(exact["warnings"][0].get<std::string>(), Catch::StartsWith("the pattern shears the fabric"));
  CHECK(exact["compression_error_mean"].get<double>() < with({})["compression_error_mean"].get<double>() + 1e-6);
}

TEST_CASE("cli: a whole mesh flattened to OBJ keeps its vertex numbering, so the JSON's indices name the same vertices", "[cli]") {
  const std::string in = mesh("open/human_woman_torso_front_patch.obj");
  const std::string out = temp_path("torso_pattern.obj");
  const json result = stdout_json(run_expecting({"flatten", in, out, "--compress", "0.8"}, 0));
  const aniso::Mesh input = aniso::read_mesh(in).mesh;
  const aniso::Mesh pattern = aniso::read_mesh(out).mesh;
  REQUIRE(pattern.num_vertices() == input.num_vertices());
  CHECK((pattern.V - input.V).cwiseAbs().maxCoeff() < 1e-5);  // the OBJ's printed precision
  CHECK(pattern.F == input.F);
  for (const auto& cut : result["suggested_cuts"]) {
    const int v = cut["vertex"].get<int>();
    CHECK((pattern.V.row(v) - input.V.row(v)).norm() < 1e-5);
  }
}

TEST_CASE("cli: a selection whose pieces meet at single vertices names them when the conformal start fails", "[cli]") {
  // Every vertex i of the plane's grid with (7919 i) mod 11 < 7: scattered pieces, many joined at one vertex.
  std::string lines;
  for (int i = 0; i < 841; ++i) {
    if ((7919 * i) % 11 < 7) lines += std::to_string(i) + "\n";
  }
  const std::string selection = write_temp_text("bowties.txt", lines);
  const CliRun run = run_expecting(
      {"flatten", mesh("open/plane.off"), temp_path("bowties.obj"), "--select", "file:" + selection}, 3);
  CHECK(contains(run.err, "the conformal start map could not be factored (LSCM): the patch's pieces meet at single "
                          "vertices ("));
  CHECK(contains(run.err, "select whole faces around them, or flatten the pieces one at a time"));
  // The vertices it names are selected ones (the input's numbering).
  const std::size_t at = run.err.find("vertices ", run.err.find("single vertices (") + 17);
  REQUIRE(at != std::string::npos);
  const int named = std::stoi(run.err.substr(at + 9));
  CHECK((7919 * named) % 11 < 7);
}

TEST_CASE("cli: a vertex both pinned and a handle is refused by name", "[cli]") {
  const std::string op = write_temp_text("pinned_handle.json",
                                         R"({"method":"arap","pins":[2,1],"handles":[1],"move":[0,0.1,0]})");
  const CliRun run = run_expecting({"deform", mesh("formats/spot_lowres.obj"), temp_path("pinned_handle.obj"), "--op", op}, 2);
  CHECK(contains(run.err, "vertex 1 is both pinned and a handle"));
  // Apart, the handle moves and the pin stays.
  const std::string apart = write_temp_text("apart.json", R"({"method":"arap","pins":[2],"handles":[1],"move":[0,0.1,0]})");
  const json moved = stdout_json(run_expecting(
      {"deform", mesh("formats/spot_lowres.obj"), temp_path("apart.obj"), "--op", apart}, 0));
  CHECK(moved["max_displacement"].get<double>() > 0.09);
}
