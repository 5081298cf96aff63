// ARAP's handles pull the mesh; what holds it is the pins or, with none
// given, the unselected vertices (resolve_edit, the rule every host uses; the
// WASM side: wasm/test/deform.test.mjs). Given handles without pins used to
// leave every other vertex free: the whole mesh followed them rigidly, the
// selection ignored (energy ~1e-11, pins 0, no warning).
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "anisoform/mesh_io.h"
#include "anisoform/op.h"
#include "cli_runner.h"
#include "test_support.h"

namespace {

using nlohmann::json;
using aniso::test::contains;
using aniso::test::run_expecting;
using aniso::test::stdout_json;
using aniso::test::temp_path;

const std::string kHandle = "box:-1,-1,0.9,1,2,2";  // spot's snout (z > 0.9)

}  // namespace

TEST_CASE("cli: ARAP's given handles without --pin hold the unselected vertices, so --select counts", "[cli]") {
  const std::string in = aniso::test::mesh_path("formats/spot_lowres.obj");
  const aniso::Mesh rest = aniso::read_mesh(in).mesh;
  struct Run {
    double select_from_z;
    std::string out;
  };
  const Run runs[] = {{0.5, temp_path("held_05.obj")}, {0.0, temp_path("held_00.obj")}};
  for (const Run& run : runs) {
    const std::string select = "box:-1,-1," + std::to_string(run.select_from_z) + ",1,2,2";
    const json result = stdout_json(run_expecting(
        {"deform", in, run.out, "--method", "arap", "--move", "0,0.2,0", "--handle", kHandle, "--select", select}, 0));
    const aniso::Mesh deformed = aniso::read_mesh(run.out).mesh;
    int unselected = 0;
    for (int i = 0; i < rest.num_vertices(); ++i) {
      if (rest.V(i, 2) >= run.select_from_z) continue;
      ++unselected;
      CHECK(deformed.V.row(i) == rest.V.row(i));  // pinned: at rest to the bit
    }
    CHECK(unselected > 0);
    CHECK(result["pins"] == unselected);
    for (int i = 0; i < rest.num_vertices(); ++i) {
      if (rest.V(i, 2) > 0.9) CHECK((deformed.V.row(i) - rest.V.row(i) - Eigen::RowVector3d(0, 0.2, 0)).norm() < 1e-9);
    }
  }
  // The selection decides how much bends: the two results differ.
  CHECK((aniso::read_mesh(runs[0].out).mesh.V - aniso::read_mesh(runs[1].out).mesh.V).cwiseAbs().maxCoeff() > 1e-3);
}

TEST_CASE("cli: ARAP's given handles with everything selected and no --pin are refused: nothing holds the mesh",
          "[cli]") {
  const std::string in = aniso::test::mesh_path("formats/spot_lowres.obj");
  const auto run = run_expecting({"deform", in, temp_path("unheld.obj"), "--method", "arap", "--move", "0,0.2,0",
                                  "--handle", kHandle},
                                 2);
  CHECK(contains(run.err, "anisoform deform: error: ARAP holds the mesh by its pins or, with none given, by the "
                          "unselected vertices"));
  CHECK(contains(run.err, "nothing holds it"));
  CHECK(run.out.empty());
  // With pins, the same handles are fine.
  run_expecting({"deform", in, temp_path("unheld.obj"), "--method", "arap", "--move", "0,0.2,0", "--handle", kHandle,
                 "--pin", "box:-1,-1,-1,1,2,-0.4"},
                0);
}

TEST_CASE("resolve_edit: ARAP without pins pins the unselected vertices that are not handles", "[op]") {
  const aniso::Mesh mesh = aniso::test::load("formats/spot_lowres.obj");
  const int n = mesh.num_vertices();
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(n);
  weights.head(10).setOnes();
  aniso::DeformOp edit;
  edit.request.method = aniso::Method::Arap;
  edit.request.handles = {0, 1, 20};  // 20 is unselected: a handle, not a pin
  edit.request.handle_offset = Eigen::Vector3d(0, 0.1, 0);
  const aniso::DeformRequest resolved = aniso::resolve_edit(edit, mesh.V, aniso::bounding_box(mesh.V), weights);
  std::vector<int> expected;
  for (int i = 10; i < n; ++i) {
    if (i != 20) expected.push_back(i);
  }
  CHECK(resolved.pins == expected);
  CHECK(resolved.handles == std::vector<int>{0, 1, 20});
  // Pins given are kept as they are.
  edit.request.pins = {500};
  CHECK(aniso::resolve_edit(edit, mesh.V, aniso::bounding_box(mesh.V), weights).pins == std::vector<int>{500});
}
