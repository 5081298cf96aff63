// What `anisoform deform` says moved agrees with what moved: an empty or
// soft-only selection with ARAP, vertices in no face under the linear map,
// energies at a perfect fit, and the advice at the iteration cap.
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "anisoform/deformer.h"
#include "anisoform/mesh_io.h"
#include "cli_runner.h"
#include "test_support.h"

namespace {

using nlohmann::json;
using aniso::test::run_expecting;
using aniso::test::stdout_json;
using aniso::test::temp_path;
using aniso::test::write_temp_text;

const std::string kEmpty = "the selection holds no vertex: the mesh is left unchanged";
const std::string kNoHandle = "ARAP's handles are the vertices selected with weight 1; the selection has none";

bool warns(const json& result, const std::string& start) {
  for (const auto& w : result["warnings"]) {
    if (w.get<std::string>().rfind(start, 0) == 0) return true;
  }
  return false;
}

double moved_most(const aniso::Mesh& rest, const std::string& out) {
  return (aniso::read_mesh(out).mesh.V - rest.V).rowwise().norm().maxCoeff();
}

}  // namespace

// An empty selection made every vertex an ARAP handle: the whole mesh moved
// by the offset while the warning said it was left unchanged.
TEST_CASE("cli: ARAP with an empty selection and no handle moves nothing, and says so", "[cli]") {
  const std::string in = aniso::test::mesh_path("closed/spot_triangulated.obj");
  const std::string out = temp_path("empty_arap.obj");
  const aniso::Mesh rest = aniso::read_mesh(in).mesh;
  const json result = stdout_json(run_expecting(
      {"deform", in, out, "--method", "arap", "--move", "0,0.1,0", "--select", "sphere:0,0,0,0"}, 0));
  CHECK(warns(result, kEmpty));
  CHECK(result["handles"] == 0);
  CHECK(result["max_displacement"] == 0.0);
  CHECK(moved_most(rest, out) == 0.0);
}

TEST_CASE("cli: ARAP's given handles move with an empty selection, without a warning that nothing does", "[cli]") {
  const std::string in = aniso::test::mesh_path("closed/spot_triangulated.obj");
  const std::string out = temp_path("empty_handles.obj");
  const aniso::Mesh rest = aniso::read_mesh(in).mesh;
  const json result = stdout_json(run_expecting({"deform", in, out, "--method", "arap", "--handle",
                                                 "sphere:0,0.3,0.9,0.25", "--pin", "box:-9,-9,-9,9,0,9", "--move",
                                                 "0,0.2,0.1", "--select", "sphere:0,0,0,0"},
                                                0));
  CHECK_FALSE(warns(result, kEmpty));
  CHECK(result["handles"].get<int>() > 0);
  CHECK(moved_most(rest, out) == Approx(std::sqrt(0.05)).epsilon(1e-6));
}

// An empty selection was solved in full: the output differed from the input
// by ~1e-14 in 2462 of spot's 2487 coordinates, after a factorization (the
// 200k koala: 6.7 s, 476 MB), while the warning said it was left unchanged.
TEST_CASE("deformer: an edit that selects nothing returns the rest pose to the bit, without factorizing", "[cli]") {
  const aniso::Mesh spot = aniso::test::load("closed/spot_triangulated.obj");
  aniso::Deformer deformer(spot);
  for (const aniso::Method method :
       {aniso::Method::AnArap, aniso::Method::AnDefGrad, aniso::Method::Linear, aniso::Method::Arap}) {
    INFO(aniso::method_name(method));
    aniso::DeformRequest request;
    request.method = method;
    request.selection = Eigen::VectorXd::Zero(spot.num_vertices());
    request.transform.su = 1.5;
    request.transform.shear = 0.3;
    if (method == aniso::Method::Arap) request.transform = aniso::TransformSpec();
    const aniso::DeformResult result = deformer.deform(request);
    CHECK(result.V == spot.V);
    CHECK(result.selected == 0);
    CHECK(result.factorizations == 0);
  }
  CHECK(deformer.factorizations() == 0);
}

// Without the solve, a bad field is still refused, as the solve refused it.
TEST_CASE("deformer: an edit that selects nothing still refuses a direction along the normal", "[cli]") {
  aniso::Deformer deformer(aniso::test::load("open/plane.off"));  // in y = 0: y is its normal
  aniso::DeformRequest request;
  request.selection = Eigen::VectorXd::Zero(deformer.rest().num_vertices());
  request.direction.kind = aniso::DirectionSource::Kind::Constraints;
  aniso::DirectionConstraint along_normal;
  along_normal.direction = Eigen::Vector3d::UnitY();
  request.direction.constraints = {along_normal};
  CHECK_THROWS_WITH(deformer.deform(request), Catch::Contains("(nearly) parallel to the surface normal"));
  request.direction.constraints[0].direction = Eigen::Vector3d::UnitX();
  CHECK(deformer.deform(request).V == deformer.rest().V);
}

TEST_CASE("cli: deform with an empty selection writes the input's positions unchanged", "[cli]") {
  const std::string in = aniso::test::mesh_path("formats/spot_lowres.obj");
  const std::string out = temp_path("empty_selection.obj");
  for (const std::string method : {"anarap", "andefgrad"}) {
    const json result = stdout_json(run_expecting(
        {"deform", in, out, "--method", method, "--scale", "1.5", "--select", "sphere:100,100,100,0.1"}, 0));
    INFO(method);
    CHECK(warns(result, kEmpty));
    CHECK(result["factorizations"] == 0);
    CHECK(result["max_displacement"] == 0.0);
    CHECK(aniso::read_mesh(out).mesh.V == aniso::read_mesh(in).mesh.V);
  }
}

// Weights below 1 only: no handle, so nothing moved, and nothing said so.
TEST_CASE("cli: ARAP on a selection with no fully selected vertex names the rule that leaves the mesh unchanged",
          "[cli]") {
  const std::string in = aniso::test::mesh_path("closed/spot_triangulated.obj");
  const std::string out = temp_path("soft_arap.obj");
  const aniso::Mesh rest = aniso::read_mesh(in).mesh;
  const std::string soft = write_temp_text("soft_selection.txt", "100 0.5\n");
  const json result = stdout_json(
      run_expecting({"deform", in, out, "--method", "arap", "--move", "0,0.1,0", "--select", "file:" + soft}, 0));
  CHECK(warns(result, kNoHandle));
  CHECK_FALSE(warns(result, kEmpty));
  CHECK(moved_most(rest, out) == 0.0);
  // A fully selected vertex is a handle: it moves, and nothing warns.
  const std::string full = write_temp_text("full_selection.txt", "100 1\n");
  const json moved = stdout_json(
      run_expecting({"deform", in, out, "--method", "arap", "--move", "0,0.1,0", "--select", "file:" + full}, 0));
  CHECK_FALSE(warns(moved, kNoHandle));
  CHECK(moved_most(rest, out) == Approx(0.1).epsilon(1e-6));
}

// The linear map moved vertices of no face by the selection's map, as if
// they were part of the shape; the warning says they are left where they are.
TEST_CASE("deformer: every method leaves a vertex in no face where it is", "[cli]") {
  const aniso::Mesh spot = aniso::test::load("closed/spot_triangulated.obj");
  aniso::Mesh with_loose{Eigen::MatrixXd(spot.num_vertices() + 2, 3), spot.F};
  with_loose.V << spot.V, Eigen::RowVector3d(5, 5, 5), Eigen::RowVector3d(0, 0, 0);
  aniso::Deformer loose(with_loose), plain(spot);
  for (const aniso::Method method : {aniso::Method::Linear, aniso::Method::AnArap, aniso::Method::AnDefGrad}) {
    INFO(aniso::method_name(method));
    aniso::DeformRequest request;
    request.method = method;
    request.transform.su = 1.5;
    request.direction.vector = Eigen::Vector3d::UnitZ();
    const aniso::Positions V = loose.deform(request).V;
    CHECK(V.bottomRows(2) == with_loose.V.bottomRows(2));
    if (method == aniso::Method::Linear) {
      // And the rest is the mesh's own linear map, about its own centroid.
      // (The copies solved on are scaled to the two meshes' own sizes, so
      // the results agree to round-off.)
      const double off = (V.topRows(spot.num_vertices()) - plain.deform(request).V).cwiseAbs().maxCoeff();
      CHECK(off < 1e-12);
    }
  }
}

TEST_CASE("deformer: the energy of a perfect fit is 0, never below", "[cli]") {
  aniso::Deformer deformer(aniso::test::load("closed/spot_triangulated.obj"));
  for (const aniso::Method method : {aniso::Method::AnArap, aniso::Method::Arap, aniso::Method::AnDefGrad}) {
    INFO(aniso::method_name(method));
    aniso::DeformRequest request;
    request.method = method;
    const aniso::DeformResult result = deformer.deform(request);
    CHECK(result.energy >= 0.0);
    CHECK(result.energy < 1e-12);
    for (const double energy : result.energy_history) CHECK(energy >= 0.0);
  }
}

// At --iterations 10000 (limits.h kMaxIterations) there is no more to raise
// (Anderson mixing at tolerance 0 on this mesh: 2 s to the cap natively).
TEST_CASE("cli: a deformation stopped at the most iterations allowed does not say to raise them", "[cli]") {
  // Spot's control mesh (188 vertices): 10000 iterations of it take a
  // quarter of the time of spot_lowres's 829.
  const std::string in = aniso::test::mesh_path("formats/spot_control_mesh.obj");
  const std::string out = temp_path("max_iterations.obj");
  const auto cap_warning = [&](const std::string& iterations) {
    const json result = stdout_json(run_expecting({"deform", in, out, "--scale", "1.5", "--select", "all",
                                                   "--iterations", iterations, "--tolerance", "0",
                                                   "--acceleration", "anderson"},
                                                  0));
    for (const auto& w : result["warnings"]) {
      if (w.get<std::string>().rfind("stopped at the iteration cap", 0) == 0) return w.get<std::string>();
    }
    return std::string();
  };
  CHECK(cap_warning("3") == "stopped at the iteration cap (3) before the energy settled: raise --iterations for a "
                            "closer result");
  CHECK(cap_warning("10000") ==
        "stopped at the iteration cap (10000, the most --iterations allows) before the energy settled: a larger "
        "--tolerance (the default is 1e-06) ends the solve where the energy changes less");
}
