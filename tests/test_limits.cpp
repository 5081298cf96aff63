// The valid ranges of limits.h: amounts and coordinates outside them are
// refused by name (CLI exit 2 for parameters, 3 for the mesh), nothing
// non-finite is printed, and within them the result does not depend on the
// mesh's units (the deformer solves on a unit-size copy).
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "anisoform/deformer.h"
#include "anisoform/error.h"
#include "anisoform/flatten.h"
#include "anisoform/limits.h"
#include "anisoform/mesh_check.h"
#include "anisoform/mesh_io.h"
#include "anisoform/op.h"
#include "anisoform/selection.h"
#include "anisoform/session.h"
#include "cli_runner.h"
#include "test_support.h"

namespace {

using aniso::test::CliRun;
using aniso::test::run_cli;
using aniso::test::temp_path;

CliRun run_limits_case(const std::vector<std::string>& args, int expected_exit) {
  const CliRun run = aniso::test::run_cli_expecting(args, expected_exit);
  // No null, NaN or inf ever reaches stdout.
  CHECK(run.out.find("null") == std::string::npos);
  CHECK(run.out.find("nan") == std::string::npos);
  CHECK(run.out.find("inf") == std::string::npos);
  return run;
}

std::string spot_scaled_by(double factor, const std::string& name) {
  aniso::Mesh mesh = aniso::test::load("closed/spot_triangulated.obj");
  mesh.V *= factor;
  const std::string path = temp_path(name);
  aniso::write_mesh(path, mesh);
  return path;
}

}  // namespace

TEST_CASE("limits: huge amounts on the command line are refused by name with exit 2", "[limits]") {
  const std::string in = aniso::test::mesh_path("closed/spot_triangulated.obj");
  const std::string out = temp_path("limits_out.obj");
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"deform", in, out, "--scale", "1e300"}, "scale su = 1e+300 is out of range (0.01 .. 100)"},
      {{"deform", in, out, "--scale", "1.797e308"}, "scale su = 1.797e+308 is out of range"},
      {{"deform", in, out, "--shear", "1e300"}, "shear = 1e+300 is out of range (-100 .. 100)"},
      {{"deform", in, out, "--twist", "0,1,0:1e300"}, "twist rate = 1e+300"},
      {{"deform", in, out, "--rotate", "n:1e300"}, "rotation angle (degrees) = 1e+300 is out of range"},
      {{"deform", in, out, "--method", "arap", "--move", "1e300,0,0"},
       "--move: move = (1e+300, 0, 0) is 1e+300 long; at most 100 times the mesh's bounding-box diagonal"},
      {{"flatten", aniso::test::mesh_path("open/spothead.obj"), temp_path("limits_pattern.obj"), "--compress",
        "1e300"},
       "su = 1e+300 is out of range (0.01 .. 100)"},
      {{"deform", aniso::test::mesh_path("open/plane.off"), out, "--select", "sphere:0,0,0,0.3", "--rotate", "n:10",
        "--rotation-coupling", "1e308"},
       "--rotation-coupling = 1e+308 is out of range (0.0001 .. 10000)"},
      {{"deform", in, out, "--rotate", "n:10", "--rotation-coupling", "1e-9"},
       "--rotation-coupling = 1e-09 is out of range (0.0001 .. 10000)"},
      {{"deform", in, out, "--scale", "1.2", "--iterations", "10001"},
       "--iterations must be an integer from 1 to 10000, got 10001"},
      {{"deform", in, out, "--scale", "1.2", "--iterations", "0"},
       "--iterations must be an integer from 1 to 10000, got 0"},
      {{"flatten", aniso::test::mesh_path("open/spothead.obj"), temp_path("limits_pattern.obj"), "--iterations",
        "2147483647"},
       "--iterations must be an integer from 1 to 10000, got 2147483647"},
  };
  for (const Case& c : cases) {
    const CliRun run = run_limits_case(c.args, 2);
    CHECK_THAT(run.err, Catch::Contains(c.message));
  }
}

TEST_CASE("limits: coordinates beyond 1e150 are refused naming the vertex, exit 3", "[limits]") {
  const CliRun run = run_limits_case({"deform", spot_scaled_by(1e200, "spot_1e200.obj"), temp_path("o.obj")}, 3);
  CHECK_THAT(run.err, Catch::Contains("vertex 0 has a coordinate out of range"));
  aniso::Mesh mesh = aniso::test::load("closed/spot_triangulated.obj");
  mesh.V(7, 1) = 1e200;
  const aniso::MeshReport report = aniso::check_mesh(mesh);
  CHECK_FALSE(report.solvable());
  CHECK_THAT(report.blocking_summary(), Catch::Contains("vertex 7 has a coordinate out of range"));
  CHECK_THROWS_AS(aniso::Deformer(mesh), aniso::Error);
  mesh.V(7, 1) = aniso::limits::kMaxCoordinate;  // the bound itself is valid
  CHECK(aniso::check_mesh(mesh).solvable());
}

TEST_CASE("limits: binary STL refuses a coordinate beyond float range", "[limits]") {
  aniso::Mesh mesh = aniso::test::load("closed/spot_triangulated.obj");
  mesh.V(0, 0) = 1e39;
  try {
    aniso::write_mesh_to_memory(mesh, aniso::MeshFormat::Stl);
    FAIL("a coordinate of 1e39 was written to binary STL");
  } catch (const aniso::Error& e) {
    CHECK_THAT(e.what(), Catch::Contains("vertex 0") && Catch::Contains("binary STL"));
  }
  // The CLI: deform of that mesh into .stl fails instead of writing inf.
  const std::string in = temp_path("spot_1e39.obj");
  aniso::write_mesh(in, mesh);
  const CliRun run = run_cli({"deform", in, temp_path("spot_1e39_out.stl")}, 60);
  CHECK(run.exit_status != 0);
  CHECK_THAT(run.err, Catch::Contains("binary STL"));
}

TEST_CASE("limits: binary STL refuses a mesh whose shape its 32-bit floats cannot keep", "[limits]") {
  // Spot scaled by 1e-4 and moved by 1e6: 32-bit floats there are 0.0625
  // apart, 240 times the mesh's size. It was written without a word and
  // read back as one vertex.
  const aniso::Mesh spot = aniso::test::load("formats/spot_lowres.obj");
  aniso::Mesh far{(spot.V * 1e-4).array() + 1e6, spot.F};
  try {
    aniso::write_mesh_to_memory(far, aniso::MeshFormat::Stl);
    FAIL("spot moved 1e6 away at 1e-4 of its size was written to binary STL");
  } catch (const aniso::Error& e) {
    CHECK(e.code() == aniso::ErrorCode::BadMesh);
    CHECK_THAT(e.what(), Catch::Contains("binary STL stores 32-bit floats") && Catch::Contains("0.0625 apart") &&
                             Catch::Contains("of face 0") && Catch::Contains("1654 of 1654 faces") &&
                             Catch::Contains("--ascii"));
  }
  // ASCII STL keeps it.
  aniso::WriteOptions ascii;
  ascii.binary = false;
  const std::string text = aniso::write_mesh_to_memory(far, aniso::MeshFormat::Stl, ascii);
  CHECK(aniso::read_mesh_from_memory(text.data(), text.size(), aniso::MeshFormat::Stl).mesh.num_vertices() == 829);
  // A mesh its floats do keep is written: Spot moved by 1000 (rounded, but
  // every edge kept), and, read back from that, written again as it is.
  const aniso::Mesh moved{spot.V.array() + 1000.0, spot.F};
  const std::string binary = aniso::write_mesh_to_memory(moved, aniso::MeshFormat::Stl);
  const aniso::Mesh back = aniso::read_mesh_from_memory(binary.data(), binary.size(), aniso::MeshFormat::Stl).mesh;
  CHECK(back.num_vertices() == 829);
  const std::string again = aniso::write_mesh_to_memory(back, aniso::MeshFormat::Stl);
  CHECK(aniso::read_mesh_from_memory(again.data(), again.size(), aniso::MeshFormat::Stl).mesh.V == back.V);
  // The CLI: exit 3 naming the way out, no file.
  const std::string in = temp_path("spot_tiny_far.obj");
  aniso::write_mesh(in, far);
  const std::string out = temp_path("spot_tiny_far_out.stl");
  std::remove(out.c_str());
  const CliRun run = run_cli({"deform", in, out, "--select", "all", "--scale", "1,1"}, 60);
  CHECK(run.exit_status == 3);
  CHECK_THAT(run.err, Catch::Contains("32-bit floats") && Catch::Contains("--ascii"));
  CHECK(aniso::test::slurp(out).empty());
}

TEST_CASE("limits: spot scaled by 1e78 deforms like spot, scaled", "[limits]") {
  // The low-resolution Spot (829 vertices): units are a property of the
  // solve, not of the mesh's size, and each factor costs two solves.
  const aniso::Mesh spot = aniso::test::load("formats/spot_lowres.obj");
  aniso::DeformRequest request;
  request.transform.su = 1.4;
  request.transform.sv = 0.8;
  request.direction.vector = Eigen::Vector3d(0, 0, 1);
  // The unscaled solve, once: every factor is compared with it.
  const aniso::DeformResult expected = aniso::Deformer(spot).deform(request);
  const double diagonal = aniso::bounding_box(spot.V).diagonal();
  for (const double factor : {1e78, 1e120, 1e-78}) {
    INFO("factor " << factor);
    aniso::Deformer scaled(aniso::Mesh{spot.V * factor, spot.F});
    const aniso::DeformResult result = scaled.deform(request);
    CHECK((result.V / factor - expected.V).cwiseAbs().maxCoeff() <= 1e-9 * diagonal);
    CHECK(result.energy / (factor * factor) == Approx(expected.energy).epsilon(1e-9).margin(1e-12));
  }
  // And through the CLI: no null in the JSON.
  run_limits_case({"deform", spot_scaled_by(1e78, "spot_1e78.obj"), temp_path("spot_1e78_out.obj"), "--scale", "1.3"},
                  0);
}

TEST_CASE("limits: spot in units of 1e-200 or 9e149 deforms like spot, scaled, and has no zero-area faces",
          "[limits]") {
  // The squares of such a mesh's lengths underflow (or overflow): the
  // bounding-box diagonal was 0, so the solve ran on the mesh as it was and
  // came back unmoved (max_displacement 0, exit 0), and every face was
  // reported as of zero area.
  const aniso::Mesh spot = aniso::test::load("formats/spot_lowres.obj");
  aniso::DeformRequest request;
  request.transform.su = 1.5;
  request.direction.vector = Eigen::Vector3d(0, 0, 1);
  const aniso::DeformResult expected = aniso::Deformer(spot).deform(request);
  const double diagonal = aniso::bounding_box(spot.V).diagonal();
  REQUIRE(aniso::check_mesh(spot).degenerate_triangles == 0);
  // 9e149: Spot reaches 1.08 from its origin, and coordinates up to 1e150 are read.
  for (const double factor : {1e-200, 1e-160, 9e149}) {
    INFO("factor " << factor);
    const aniso::Mesh scaled{spot.V * factor, spot.F};
    CHECK(aniso::bounding_box(scaled.V).diagonal() / factor == Approx(diagonal).epsilon(1e-12));
    CHECK(aniso::check_mesh(scaled).degenerate_triangles == 0);
    const aniso::DeformResult result = aniso::Deformer(scaled).deform(request);
    CHECK((result.V / factor - expected.V).cwiseAbs().maxCoeff() <= 1e-9 * diagonal);
    // A sphere and a falloff scaled with the mesh give the same weights.
    aniso::Region sphere;
    sphere.kind = aniso::Region::Kind::Sphere;
    sphere.center = Eigen::Vector3d(0, 0.5, 0);
    sphere.radius = 0.4;
    const Eigen::VectorXd weights = aniso::selection_weights(spot, sphere, 0.2);
    REQUIRE(weights.sum() > 10);
    sphere.center *= factor;
    sphere.radius *= factor;
    CHECK((aniso::selection_weights(scaled, sphere, 0.2 * factor) - weights).cwiseAbs().maxCoeff() <= 1e-9);
  }
  // Through the CLI: moved by half the extent, no zero-area warning.
  const CliRun run = run_limits_case(
      {"deform", spot_scaled_by(1e-200, "spot_1e-200.obj"), temp_path("spot_1e-200_out.obj"), "--scale", "1.5"}, 0);
  const nlohmann::json result = nlohmann::json::parse(run.out);
  CHECK(result["max_displacement"].get<double>() > 0.1e-200);
  CHECK(result["warnings"].dump().find("zero-area") == std::string::npos);
}

TEST_CASE("limits: a twist's range is relative to the mesh size", "[limits]") {
  const aniso::Mesh spot = aniso::test::load("closed/spot_triangulated.obj");
  aniso::DeformRequest request;
  request.method = aniso::Method::AnDefGrad;
  request.transform.twist = true;
  request.transform.twist_axis = Eigen::Vector3d(0, 1, 0);
  request.transform.twist_degrees_per_unit = 1e6;
  aniso::Deformer deformer(spot);
  const std::string message = aniso::test::bad_parameter_message([&] { deformer.deform(request); });
  CHECK_THAT(message, Catch::Contains("twist rate = 1e+06") && Catch::Contains("36000"));
  // The same rate on spot a thousand times smaller is 1000 turns... / 1000.
  aniso::Deformer small(aniso::Mesh{spot.V * 1e-3, spot.F});
  CHECK(small.deform(request).V.allFinite());
}

// A move of 1e300 used to be solved: the output held coordinates the readers
// refuse, and the session could not flatten afterwards.
TEST_CASE("limits: an ARAP move's range is relative to the mesh size", "[limits]") {
  const aniso::Mesh spot = aniso::test::load("closed/spot_triangulated.obj");
  const double diagonal = (spot.V.colwise().maxCoeff() - spot.V.colwise().minCoeff()).norm();
  aniso::DeformRequest request;
  request.method = aniso::Method::Arap;
  request.handles = {0};
  request.pins = {100};
  request.handle_offset = Eigen::Vector3d(1e300, 0, 0);
  aniso::Deformer deformer(spot);
  const std::string message = aniso::test::bad_parameter_message([&] { deformer.deform(request); });
  CHECK_THAT(message, Catch::Contains("move = (1e+300, 0, 0)") && Catch::Contains("at most 100 times"));
  request.handle_offset = Eigen::Vector3d(0, 0, 101 * diagonal);
  CHECK_THAT(aniso::test::bad_parameter_message([&] { deformer.deform(request); }),
             Catch::Contains("at most 100 times"));
  // Within the range the handle lands where it was sent.
  request.handle_offset = Eigen::Vector3d(0, 0, 99 * diagonal);
  const aniso::DeformResult moved = deformer.deform(request);
  CHECK(moved.V.row(0) == spot.V.row(0) + request.handle_offset.transpose());
  // A session refuses it before any change: its pose stays as it was.
  aniso::Session session;
  session.adopt_mesh(spot, {});
  aniso::DeformOp op = aniso::deform_op_from_json(nlohmann::json::parse(R"({"method":"arap","move":[1e300,0,0]})"));
  const aniso::Positions before = session.positions();
  CHECK_THAT(aniso::test::bad_parameter_message([&] { session.deform(op); }), Catch::Contains("move = (1e+300"));
  CHECK(session.positions() == before);
}

// A crafted request with tolerance 0 would otherwise hold the solver for as
// many iterations as it asks (2^31 - 1 passed every check).
TEST_CASE("limits: iteration counts and rotation steps above 10000 are refused before any solve", "[limits]") {
  const aniso::Mesh spot = aniso::test::load("closed/spot_triangulated.obj");
  aniso::Deformer deformer(spot);
  aniso::DeformRequest request;
  request.transform.su = 1.2;
  request.tolerance = 0.0;
  request.max_iterations = aniso::limits::kMaxIterations + 1;
  CHECK(aniso::test::bad_parameter_message([&] { deformer.deform(request); }) ==
        "iterations must be an integer from 1 to 10000, got 10001");
  request.max_iterations = 3;
  request.rotation_steps = std::numeric_limits<int>::max();
  CHECK(aniso::test::bad_parameter_message([&] { deformer.deform(request); }) ==
        "rotation steps must be an integer from 1 to 10000, got 2147483647");
  request.rotation_steps = 1;
  CHECK(deformer.deform(request).iterations == 3);  // the deformer is still usable

  const aniso::Mesh head = aniso::test::load("open/spothead.obj");
  aniso::FlattenOptions options;
  options.solver.max_iterations = 0;
  CHECK(aniso::test::bad_parameter_message([&] { aniso::flatten(head, {}, options); }) ==
        "flatten: maxIterations must be an integer from 1 to 10000, got 0");
  options.solver.max_iterations = 10;
  options.solver.tolerance = std::numeric_limits<double>::quiet_NaN();
  CHECK(aniso::test::bad_parameter_message([&] { aniso::flatten(head, {}, options); }) ==
        "flatten: the tolerance must be a finite number >= 0");
}

TEST_CASE("limits: a session's vertex limit refuses a bigger mesh by name and keeps the one it has", "[limits]") {
  aniso::Session session;
  CHECK(session.vertex_limit() == 0);  // none by default (the CLI, the tests)
  const aniso::Mesh face = aniso::test::load("open/nefertiti_face.off");
  const aniso::Mesh spot = aniso::test::load("closed/spot_triangulated.obj");
  REQUIRE(face.num_vertices() < 1000);
  REQUIRE(spot.num_vertices() > 1000);
  session.set_vertex_limit(1000, "for this test");
  session.adopt_mesh(face, {});
  try {
    session.adopt_mesh(spot, {});
    FAIL("a mesh over the limit was accepted");
  } catch (const aniso::Error& error) {
    CHECK(error.code() == aniso::ErrorCode::BadMesh);
    CHECK(std::string(error.what()) ==
          "the mesh has " + std::to_string(spot.num_vertices()) + " vertices, more than the 1000 for this test");
  }
  CHECK(session.info().report.vertices == face.num_vertices());
  CHECK(session.positions() == face.V);
  CHECK_THROWS_AS(session.set_vertex_limit(-1, ""), aniso::Error);
  session.set_vertex_limit(0, "");
  CHECK(session.adopt_mesh(spot, {}).report.vertices == spot.num_vertices());
}

TEST_CASE("limits: over half the vertex limit a session keeps one factorized pose, and undo gives the same positions",
          "[limits]") {
  // The browser's limit allows one factorized pose; two do not fit from
  // half of it on (Session::install_rest). Below that half the previous pose
  // keeps its factorization for undo; above it undo factorizes it again.
  const aniso::Mesh face = aniso::test::load("open/nefertiti_face.off");
  const int n = face.num_vertices();
  const aniso::DeformOp first = aniso::deform_op_from_json(nlohmann::json::parse(
      R"({"method":"anarap","direction":{"type":"global","vector":[0,1,0]},"transform":{"scale":[1.3,1]},)"
      R"("warmStart":false,"maxIterations":20})"));
  const aniso::DeformOp second = aniso::deform_op_from_json(nlohmann::json::parse(
      R"({"method":"anarap","direction":{"type":"global","vector":[1,0,0]},"transform":{"scale":[0.8,1]},)"
      R"("warmStart":false,"maxIterations":20})"));
  struct Run {
    std::vector<aniso::Positions> steps;
    int undo_factorizations = 0;
  };
  const auto run = [&](int vertex_limit) {
    aniso::Session session;
    session.set_vertex_limit(vertex_limit, "for this test");
    session.adopt_mesh(face, {});
    session.select(aniso::parse_region("all"), 0.0, aniso::SelectionMode::Replace);
    // Positions are rows of x, y, z: the layout set_positions takes.
    const std::vector<double> rest(session.positions().data(), session.positions().data() + 3 * n);
    Run out;
    session.deform(first);
    out.steps.push_back(session.positions());
    session.commit();
    session.deform(second);
    out.steps.push_back(session.positions());
    session.set_positions(rest);  // undo: back to the first rest pose
    const int before = session.factorizations();
    session.deform(second);
    out.undo_factorizations = session.factorizations() - before;
    out.steps.push_back(session.positions());
    return out;
  };
  const Run kept = run(0);            // no limit: the previous pose stays factorized
  const Run roomy = run(2 * n);       // two poses fit
  const Run one_pose = run(2 * n - 1);
  CHECK(kept.undo_factorizations == 0);
  CHECK(roomy.undo_factorizations == 0);
  CHECK(one_pose.undo_factorizations == 1);
  for (std::size_t s = 0; s < kept.steps.size(); ++s) {
    INFO("step " << s);
    CHECK(roomy.steps[s] == kept.steps[s]);
    CHECK(one_pose.steps[s] == kept.steps[s]);
  }
}

TEST_CASE("limits: spothead scaled by 1e-4 and moved 1e6 away deforms like spothead, scaled and moved",
          "[limits]") {
  // The unit-size copy was scaled but not centred: this mesh was solved at
  // 2^33 of its sizes from the origin, where a coordinate keeps 20 bits fewer
  // below the mesh's size. The stretch stopped at the 50-iteration cap,
  // converged false, 1.2e-3 of the size off. The reference is the moved
  // mesh brought back (so both start from the same rounded positions), and
  // the tolerance is what a coordinate near 1e6 can hold (its unit in the
  // last place, 1.2e-10, is 4.5e-7 of this mesh's diagonal) plus 1e-9 of the
  // diagonal.
  const aniso::Mesh head = aniso::test::load("open/spothead.obj");
  const auto check_moved = [&](double factor, double offset) {
    INFO("factor " << factor << ", moved by " << offset);
    aniso::Mesh moved{(head.V * factor).array() + offset, head.F};
    const aniso::Mesh back{(moved.V.array() - offset) / factor, head.F};
    const double diagonal = aniso::bounding_box(back.V).diagonal();
    const double tolerance = 1e-9 * diagonal + (std::nextafter(offset, 2.0 * offset) - offset) / factor;
    const Eigen::Vector3d far(offset, offset, offset);
    aniso::Deformer here(back), there(moved);
    const auto compare = [&](const aniso::DeformRequest& request, const aniso::DeformRequest& moved_request,
                             bool converges = false) {
      const aniso::DeformResult expected = here.deform(request);
      const aniso::DeformResult result = there.deform(moved_request);
      if (converges) CHECK(expected.converged);
      CHECK(result.converged == expected.converged);
      CHECK(std::abs(result.iterations - expected.iterations) <= 2);
      const double off = ((result.V.array() - offset) / factor - expected.V.array()).abs().maxCoeff();
      CHECK(off <= tolerance);
      CHECK(result.energy / (factor * factor) == Approx(expected.energy).epsilon(1e-5).margin(1e-12));
      for (const int p : moved_request.pins) CHECK(result.V.row(p) == moved.V.row(p));
    };
    // The user's stretch: everything, along y, 1.3.
    aniso::DeformRequest stretch;
    stretch.direction.vector = Eigen::Vector3d(0, 1, 0);
    stretch.transform.su = 1.3;
    compare(stretch, stretch, true);
    // A twist about an axis through a point: the point is moved and scaled, the rate per unit scaled.
    aniso::DeformRequest twist;
    twist.direction.vector = Eigen::Vector3d(0, 1, 0);
    twist.selection = Eigen::VectorXd::Zero(head.num_vertices());
    for (int v = 0; v < head.num_vertices(); ++v) twist.selection[v] = back.V(v, 1) > 0.2 ? 1.0 : 0.0;
    for (int v = 0; v < head.num_vertices(); ++v) {
      if (back.V(v, 1) < -0.2) twist.pins.push_back(v);
    }
    REQUIRE(twist.selection.sum() > 100);
    REQUIRE(twist.pins.size() > 100);
    twist.transform.twist = true;
    twist.transform.twist_axis = Eigen::Vector3d(0, 1, 0);
    twist.transform.twist_origin = Eigen::Vector3d(0.1, 0.3, 0.0);
    twist.transform.twist_degrees_per_unit = 20.0;
    aniso::DeformRequest moved_twist = twist;
    moved_twist.transform.twist_origin = twist.transform.twist_origin * factor + far;
    moved_twist.transform.twist_degrees_per_unit = 20.0 / factor;
    compare(twist, moved_twist);
    // ARAP: handles moved by an offset (a length), pins held to the bit.
    aniso::DeformRequest arap;
    arap.method = aniso::Method::Arap;
    arap.pins = twist.pins;
    for (int v = 0; v < head.num_vertices(); ++v) {
      if (back.V(v, 1) > 0.3) arap.handles.push_back(v);
    }
    REQUIRE(!arap.handles.empty());
    arap.handle_offset = Eigen::Vector3d(0.05, 0.1, 0.0);
    aniso::DeformRequest moved_arap = arap;
    moved_arap.handle_offset = arap.handle_offset * factor;
    compare(arap, moved_arap);
  };
  check_moved(1e-4, 1e6);  // the user's spothead_tiny_far.obj
  check_moved(1.0, 1e3);   // a millimetre mesh placed on a build plate
}
