// One op, three ways in, one result: the public op through `anisoform deform
// --op`, through a native Session (deform_op_from_json, as the WASM module's
// op), and as the CLI's own flags gives the same positions, coordinate for
// coordinate (the mesh files are written with round-trip precision).
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "anisoform/mesh_io.h"
#include "anisoform/op.h"
#include "anisoform/selection.h"
#include "anisoform/session.h"
#include "test_support.h"

namespace {

using namespace aniso;
using test::run_expecting;
using test::temp_path;

const char* const kParityMesh = "formats/spot_lowres.obj";

// The vertices a CLI region gives weight > 0 (what --pin / --handle hold).
Json vertices_of(const Mesh& mesh, const std::string& region) {
  const Eigen::VectorXd w = region_weights(mesh, parse_region(region));
  Json out = Json::array();
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    if (w[i] > 0.0) out.push_back(i);
  }
  REQUIRE_FALSE(out.empty());
  return out;
}

Positions positions_through_session(const Json& op, const std::string& select, double falloff) {
  Session session;
  session.adopt_mesh(test::load(kParityMesh), {});
  session.select(parse_region(select), falloff, SelectionMode::Replace);
  session.deform(deform_op_from_json(op));
  return session.positions();
}

Positions positions_through_cli(const std::vector<std::string>& options, const std::string& name) {
  const std::string out = temp_path(name);
  std::vector<std::string> args{"deform", test::mesh_path(kParityMesh), out};
  args.insert(args.end(), options.begin(), options.end());
  const test::CliRun run = run_expecting(args, 0);
  INFO(test::describe(args, run));
  return read_mesh(out).mesh.V;
}

struct ParityCase {
  const char* name;
  Json op;
  std::vector<std::string> flags;  // the same edit as flags, without --select / --falloff
  std::string select;
  double falloff;
};

}  // namespace

TEST_CASE("op parity: CLI --op, native Session and CLI flags give the same positions", "[op][cli]") {
  const Mesh mesh = test::load(kParityMesh);
  const std::string top = "box:-1,0.2,-1,1,2,1";
  const std::string bottom = "box:-1,-2,-1,1,-0.5,1";
  const std::vector<ParityCase> cases{
      {"stretch",
       Json::parse(R"({"method":"anarap","direction":{"type":"global","vector":[0,1,0]},
                       "transform":{"scale":[1.3,0.9]},"maxIterations":20,"tolerance":1e-5})"),
       {"--method", "anarap", "--direction", "global:0,1,0", "--scale", "1.3,0.9", "--iterations", "20",
        "--tolerance", "1e-5"},
       top, 0.1},
      {"twist",
       Json::parse(R"({"method":"andefgrad","transform":{"twist":{"axis":[0,1,0],"degreesPerUnit":60}}})"),
       {"--method", "andefgrad", "--twist", "0,1,0:60"},
       top, 0.0},
      {"arap-handles",
       {{"method", "arap"}, {"handles", vertices_of(mesh, top)}, {"pins", vertices_of(mesh, bottom)},
        {"move", {0.0, 0.05, 0.02}}, {"maxIterations", 30}},
       {"--method", "arap", "--handle", top, "--pin", bottom, "--move", "0,0.05,0.02", "--iterations", "30"},
       "all", 0.0},
  };
  for (const ParityCase& c : cases) {
    INFO(c.name);
    const std::string op_file = test::write_temp_text(std::string(c.name) + ".json", c.op.dump());
    const std::vector<std::string> region{"--select", c.select, "--falloff", std::to_string(c.falloff)};
    std::vector<std::string> with_op{"--op", op_file};
    with_op.insert(with_op.end(), region.begin(), region.end());
    std::vector<std::string> with_flags = c.flags;
    with_flags.insert(with_flags.end(), region.begin(), region.end());

    const Positions native = positions_through_session(c.op, c.select, c.falloff);
    const Positions cli_op = positions_through_cli(with_op, std::string(c.name) + "-op.obj");
    const Positions cli_flags = positions_through_cli(with_flags, std::string(c.name) + "-flags.obj");
    REQUIRE(native.rows() == mesh.num_vertices());
    // The edit did something (a parity of unchanged meshes would prove nothing).
    CHECK((native - mesh.V).rowwise().norm().maxCoeff() > 1e-3);
    CHECK(cli_op == native);
    CHECK(cli_flags == native);
  }
}

TEST_CASE("op parity: --op refuses the edit's flags beside it and names bad fields", "[op][cli]") {
  const std::string in = test::mesh_path(kParityMesh);
  const std::string op_file = test::write_temp_text("scale.json", R"({"transform":{"scale":1.2}})");
  const test::CliRun both = run_expecting({"deform", in, temp_path("o.obj"), "--op", op_file, "--scale", "2"}, 2);
  CHECK(both.err.find("--scale cannot be combined with --op") != std::string::npos);
  const std::string bad = test::write_temp_text("bad.json", R"({"transform":{"scale":["NaN"]}})");
  const test::CliRun refused = run_expecting({"deform", in, temp_path("o.obj"), "--op", bad}, 2);
  CHECK(refused.err.find("--op: op.transform.scale[0] must be a finite number, got 'NaN'") != std::string::npos);
  // The twist's mesh-dependent range, named as the op's too.
  const std::string twist = test::write_temp_text(
      "twist.json", R"({"transform":{"twist":{"axis":[0,1,0],"degreesPerUnit":1e6}}})");
  CHECK(run_expecting({"deform", in, temp_path("o.obj"), "--op", twist, "--select", "all"}, 2)
            .err.find("--op: twist rate = 1e+06 degrees per unit") != std::string::npos);
  const std::string broken = test::write_temp_text("broken.json", "{\"method\":");
  CHECK(run_expecting({"deform", in, temp_path("o.obj"), "--op", broken}, 2).err.find("is not valid JSON") !=
        std::string::npos);
}

// A number no double holds was "internal error: [json.exception.out_of_range.406] ...", exit 3.
TEST_CASE("op parity: a number out of range in --op or a document is a bad parameter naming the value", "[op][cli]") {
  const std::string in = test::mesh_path(kParityMesh);
  const std::string huge = test::write_temp_text("huge.json", R"({"transform":{"scale":1e400}})");
  const test::CliRun op = run_expecting({"deform", in, temp_path("o.obj"), "--op", huge}, 2);
  CHECK(op.err == "anisoform deform: error: --op: " + huge + " holds a number out of range: 1e400 (a JSON number must "
                  "be a finite double, at most about 1.8e308)\n");
  const std::string document = test::write_temp_text("huge_doc.json", R"({"format":"anisoform-document","x":-1e400})");
  const test::CliRun replay = run_expecting({"replay", document, temp_path("o.obj")}, 2);
  CHECK(replay.err.find("DOC: the document holds a number out of range: -1e400") != std::string::npos);
  CHECK_THROWS_WITH(json_from_text("[1, 2e999]", "the list"), Catch::StartsWith("the list holds a number out of range: 2e999"));
}
