// Flattening through aniso::Session (session_flatten.h): the same result as
// the one-shot aniso::flatten, one factorization per patch and positions, the
// per-input-vertex layout, the refusals that leave the session as it was, and
// pattern export of the last result only.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "anisoform/error.h"
#include "anisoform/flatten.h"
#include "anisoform/session.h"
#include "test_support.h"

namespace {

using namespace aniso;

void load_into(Session& session, const std::string& relative) {
  std::ifstream file(test::mesh_path(relative), std::ios::binary);
  REQUIRE(file);
  std::stringstream bytes;
  bytes << file.rdbuf();
  const std::string data = bytes.str();
  session.load_mesh(reinterpret_cast<const std::uint8_t*>(data.data()), data.size(), relative);
}

ErrorCode error_code_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.code();
  }
  FAIL("no aniso::Error was thrown");
  return ErrorCode::Numerical;
}

int count_occurrences(const std::string& text, const std::string& needle) {
  int count = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++count;
  return count;
}

SessionFlatten torso_request(double su) {
  SessionFlatten request;
  request.su = su;
  request.directions.global = Eigen::Vector3d(0.0, 1.0, 0.0);
  return request;
}

}  // namespace

TEST_CASE("session flatten: equals the one-shot flatten of the session's positions",
          "[flatten][session]") {
  Session session;
  load_into(session, "open/human_woman_torso_front_patch.obj");
  const SessionFlattenResult ours = session.flatten(torso_request(0.8));

  FlattenOptions options;
  options.su = 0.8;
  options.directions.global = Eigen::Vector3d(0.0, 1.0, 0.0);
  const FlattenOutput oneshot = flatten(session.rest(), {}, options);
  const FlattenMetrics& a = ours.metrics;
  const FlattenMetrics& b = oneshot.result.metrics;
  CHECK(a.triangles == b.triangles);
  CHECK(a.vertices == b.vertices);
  CHECK(a.components == b.components);
  CHECK(a.boundary_loops == b.boundary_loops);
  CHECK(a.flipped == b.flipped);
  CHECK(a.iterations == b.iterations);
  CHECK(a.compression_error_mean == Approx(b.compression_error_mean).epsilon(1e-12));
  CHECK(a.compression_error_max == Approx(b.compression_error_max).epsilon(1e-12));
  CHECK(a.cross_error_mean == Approx(b.cross_error_mean).epsilon(1e-12));
  CHECK(a.area_distortion_mean == Approx(b.area_distortion_mean).epsilon(1e-12));
  CHECK(a.energy == Approx(b.energy).epsilon(1e-12));

  // The layout per input vertex and patch triangle.
  const int n = session.rest().num_vertices();
  REQUIRE(ours.uv.size() == 2 * static_cast<std::size_t>(n));
  REQUIRE(ours.vertex_error.size() == static_cast<std::size_t>(n));
  REQUIRE(ours.triangles.size() == 3 * static_cast<std::size_t>(a.triangles));
  REQUIRE(ours.compression_error.size() == static_cast<std::size_t>(a.triangles));
  REQUIRE(ours.cross_error.size() == static_cast<std::size_t>(a.triangles));
  REQUIRE(ours.outlines.size() == static_cast<std::size_t>(a.boundary_loops));
  REQUIRE(ours.grainlines.size() == static_cast<std::size_t>(a.components));
  double uv_difference = 0.0;
  for (std::size_t p = 0; p < oneshot.patch.input_vertex.size(); ++p) {
    const auto i = static_cast<std::size_t>(oneshot.patch.input_vertex[p]);
    const auto row = static_cast<Eigen::Index>(p);
    uv_difference = std::max({uv_difference, std::abs(ours.uv[2 * i] - oneshot.result.uv(row, 0)),
                              std::abs(ours.uv[2 * i + 1] - oneshot.result.uv(row, 1))});
  }
  CHECK(uv_difference <= 1e-5);  // float32 of the same numbers
  double max_error = 0.0;
  for (float e : ours.compression_error) max_error = std::max(max_error, double(e));
  CHECK(max_error == Approx(b.compression_error_max).epsilon(1e-6));
}

TEST_CASE("session flatten: the factorization is reused until the positions or the patch change",
          "[flatten][session]") {
  Session session;
  load_into(session, "open/human_woman_torso_front_patch.obj");
  const int before = session.factorizations();
  session.flatten(torso_request(0.8));
  const int after_first = session.factorizations();
  CHECK(after_first == before + 1);

  SessionFlatten other = torso_request(0.9);
  other.sv = 1.1;
  other.method = FlattenMethod::UniformBaseline;
  const SessionFlattenResult second = session.flatten(other);
  CHECK(session.factorizations() == after_first);
  CHECK(second.factorizations == after_first);
  CHECK(second.metrics.method == "uniform-baseline");

  // Another patch: the selection's.
  session.select(Region{}, 0.0, SelectionMode::Replace);  // Region{} = all: the same faces, new mask
  SessionFlatten selected = torso_request(0.8);
  selected.use_selection = true;
  session.flatten(selected);
  CHECK(session.factorizations() == after_first + 1);
  session.flatten(selected);
  CHECK(session.factorizations() == after_first + 1);

  // New positions: a new factorization, and the old pattern is gone.
  std::vector<double> xyz(session.positions().data(),
                          session.positions().data() + session.positions().size());
  for (double& x : xyz) x *= 2.0;
  session.set_positions(xyz);
  CHECK(error_code_of([&] { session.export_pattern("svg", 1.0); }) == ErrorCode::BadParameter);
  const int before_new_pose = session.factorizations();
  const SessionFlattenResult scaled = session.flatten(selected);
  CHECK(session.factorizations() > before_new_pose);
  CHECK(scaled.metrics.flipped == 0);
}

TEST_CASE("session flatten: the plane stays isometric and a selection leaves the rest NaN",
          "[flatten][session]") {
  Session session;
  load_into(session, "open/plane.off");
  const SessionFlattenResult whole = session.flatten(SessionFlatten{});
  const Positions& V = session.positions();
  double worst = 0.0;
  for (std::size_t t = 0; t < whole.triangles.size() / 3; ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = whole.triangles[3 * t + k], j = whole.triangles[3 * t + (k + 1) % 3];
      const double flat = std::hypot(whole.uv[2 * i] - whole.uv[2 * j], whole.uv[2 * i + 1] - whole.uv[2 * j + 1]);
      const double rest = (V.row(i) - V.row(j)).norm();
      worst = std::max(worst, std::abs(flat / rest - 1.0));
    }
  }
  CHECK(worst <= 1e-5);  // float32 uv
  CHECK(whole.metrics.compression_error_max <= 1e-9);
  CHECK(*std::max_element(whole.vertex_error.begin(), whole.vertex_error.end()) <= 1e-6f);

  // Half the plane (x < 0), selected.
  Region half;
  half.kind = Region::Kind::Box;
  half.min = Eigen::Vector3d(-10.0, -1.0, -10.0);
  half.max = Eigen::Vector3d(0.0, 1.0, 10.0);
  session.select(half, 0.0, SelectionMode::Replace);
  SessionFlatten request;
  request.use_selection = true;
  const SessionFlattenResult part = session.flatten(request);
  CHECK(part.metrics.triangles < whole.metrics.triangles);
  int outside = 0, outside_nan = 0, finite = 0;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    finite += std::isfinite(part.uv[2 * k]) && std::isfinite(part.vertex_error[k]);
    if (!(session.selection()[i] > 0.0)) {
      ++outside;
      outside_nan += std::isnan(part.uv[2 * k]) && std::isnan(part.uv[2 * k + 1]) &&
                     std::isnan(part.vertex_error[k]);
    }
  }
  CHECK(outside > 0);
  CHECK(outside_nan == outside);
  CHECK(finite == part.metrics.vertices);  // exactly the patch's vertices have a uv
}

TEST_CASE("session flatten: refusals leave the session unchanged", "[flatten][session]") {
  Session session;
  CHECK(error_code_of([&] { session.flatten(SessionFlatten{}); }) == ErrorCode::BadParameter);

  load_into(session, "closed/torus.obj");
  const Positions before = session.positions();
  const int factorizations = session.factorizations();
  CHECK(error_code_of([&] { session.flatten(SessionFlatten{}); }) == ErrorCode::BadMesh);
  CHECK(session.positions() == before);
  CHECK(session.factorizations() == factorizations);
  CHECK(error_code_of([&] { session.export_pattern("svg", 1.0); }) == ErrorCode::BadParameter);

  // An open mesh: an empty selection is refused, the earlier pattern survives.
  load_into(session, "open/hemisphere.obj");
  CHECK(error_code_of([&] { session.export_pattern("svg", 1.0); }) == ErrorCode::BadParameter);
  session.flatten(SessionFlatten{});
  SessionFlatten selected;
  selected.use_selection = true;
  CHECK(error_code_of([&] { session.flatten(selected); }) == ErrorCode::BadParameter);
  CHECK_NOTHROW(session.export_pattern("svg", 1.0));
  SessionFlatten bad;
  bad.su = 0.0;
  CHECK(error_code_of([&] { session.flatten(bad); }) == ErrorCode::BadParameter);
  CHECK(error_code_of([&] { session.export_pattern("pdf", 1.0); }) == ErrorCode::BadParameter);
  CHECK(error_code_of([&] { session.export_pattern("svg", 0.0); }) == ErrorCode::BadParameter);
}

TEST_CASE("session flatten: the SVG has one outline per boundary loop and the DXF one polyline",
          "[flatten][session]") {
  Session session;
  load_into(session, "open/human_woman_torso_front_patch.obj");
  CHECK(error_code_of([&] { session.export_pattern("svg", 1.0); }) == ErrorCode::BadParameter);
  const SessionFlattenResult result = session.flatten(torso_request(0.8));
  const std::string svg = session.export_pattern("svg", 10.0);
  CHECK(count_occurrences(svg, "<path class=\"outline\"") == result.metrics.boundary_loops);
  CHECK(svg.find("su 0.8 sv 1") != std::string::npos);
  const std::string dxf = session.export_pattern("dxf", 10.0);
  CHECK(count_occurrences(dxf, "POLYLINE") == result.metrics.boundary_loops);

  // A deform or cancel changes the positions: export needs a new flatten.
  session.cancel();
  CHECK(error_code_of([&] { session.export_pattern("svg", 1.0); }) == ErrorCode::BadParameter);
}
