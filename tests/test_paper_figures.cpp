// The paper's figures as measurable scenes (METHOD §10), on the real meshes
// the shared MANIFEST names for each figure.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include "anisoform/distortion.h"
#include "directions/curvature.h"
#include "figure_record.h"
#include "geometry/frames.h"
#include "anisoform/selection.h"
#include "mesh/topology.h"
#include "solver_test_support.h"
#include "test_support.h"

using namespace aniso;
using test::diagonal;

namespace {

int shortest_axis(const Positions& V) {
  Eigen::RowVector3d extent = V.colwise().maxCoeff() - V.colwise().minCoeff();
  int axis = 0;
  extent.minCoeff(&axis);
  return axis;
}

// Mean |log(area ratio)| difference over pairs of edge-adjacent triangles that
// straddle the selection border (one fully selected, the other not).
double border_area_jump(const Mesh& mesh, const Positions& V, const Eigen::VectorXd& w) {
  const Eigen::VectorXd rest = test::triangle_areas(mesh.V, mesh.F);
  const Eigen::VectorXd now = test::triangle_areas(V, mesh.F);
  std::vector<int> offsets, neighbors;
  triangle_adjacency(mesh.F, mesh.num_vertices(), offsets, neighbors);
  auto inside = [&](int t) { return w[mesh.F(t, 0)] > 0 && w[mesh.F(t, 1)] > 0 && w[mesh.F(t, 2)] > 0; };
  double sum = 0.0;
  int count = 0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    if (!inside(t)) continue;
    for (int k = offsets[t]; k < offsets[t + 1]; ++k) {
      const int s = neighbors[k];
      if (inside(s)) continue;
      sum += std::abs(std::log(now[t] / rest[t]) - std::log(now[s] / rest[s]));
      ++count;
    }
  }
  return count > 0 ? sum / count : 0.0;
}

}  // namespace

TEST_CASE("fig. 2: on a torus AnARAP spreads an elongation over the selection border more smoothly than AnDefGrad",
          "[figures]") {
  const Mesh mesh = test::load("closed/torus.obj");
  const int axis = shortest_axis(mesh.V);  // the torus' symmetry axis
  const int across = (axis + 1) % 3;
  Eigen::RowVector3d center = mesh.V.colwise().mean();
  int far = 0;
  mesh.V.col(across).maxCoeff(&far);
  const double radius = 0.25 * diagonal(mesh.V);
  Eigen::VectorXd w(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) w[i] = (mesh.V.row(i) - mesh.V.row(far)).norm() < radius ? 1.0 : 0.0;
  // Elongate along the big circle at the selected point.
  Eigen::Vector3d along = Eigen::Vector3d::Zero();
  along[3 - axis - across] = 1.0;
  (void)center;
  Deformer deformer(mesh);
  DeformRequest request = test::stretch_request(Method::AnArap, along, 1.6);
  request.selection = w;
  const DeformResult arap = deformer.deform(request);
  request.method = Method::AnDefGrad;
  const DeformResult defgrad = deformer.deform(request);
  const double jump_arap = border_area_jump(mesh, arap.V, w);
  const double jump_defgrad = border_area_jump(mesh, defgrad.V, w);
  WARN("fig2 border log-area jump: anarap " << jump_arap << ", andefgrad " << jump_defgrad);
  CHECK(jump_arap < jump_defgrad);
  test::record_figure_value("2.anarap.border_jump", jump_arap);
  test::record_figure_value("2.andefgrad.border_jump", jump_defgrad);
  if (!test::figures_dir().empty()) {
    test::record_figure_mesh("2-rest", mesh.V, mesh.F, w);
    for (const auto& [name, result] : {std::pair{"2-andefgrad", &defgrad}, std::pair{"2-anarap", &arap}}) {
      const Eigen::VectorXd area = vertex_distortion(mesh, result->V, DistortionKind::AreaRatio);
      test::record_figure_mesh(name, result->V, mesh.F, w, area.array().log() / std::log(2.0), "area");
    }
  }
  // Both really elongated the part.
  const Eigen::VectorXd rest_area = test::triangle_areas(mesh.V, mesh.F);
  CHECK(test::triangle_areas(arap.V, mesh.F).sum() > 1.05 * rest_area.sum());
  CHECK(test::triangle_areas(defgrad.V, mesh.F).sum() > 1.05 * rest_area.sum());
}

namespace {

// Length ratio of edges by how they lie against a per-vertex direction field:
// mean ratio of edges within ~25 deg of the field and of edges within ~25 deg
// of its perpendicular.
std::pair<double, double> along_across_ratios(const Mesh& mesh, const Positions& V, const Positions& field) {
  double along = 0, across = 0;
  int n_along = 0, n_across = 0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(t, k), b = mesh.F(t, (k + 1) % 3);
      if (a > b) continue;  // each interior edge once
      const Eigen::Vector3d e = (mesh.V.row(b) - mesh.V.row(a)).transpose();
      Eigen::Vector3d d = field.row(a).transpose();
      const Eigen::Vector3d db = field.row(b).transpose();
      d = (d + (d.dot(db) < 0 ? -db : db)).normalized();
      const double c = std::abs(e.normalized().dot(d));
      const double ratio = (V.row(b) - V.row(a)).norm() / e.norm();
      if (c > 0.9) { along += ratio; ++n_along; }
      if (c < 0.42) { across += ratio; ++n_across; }
    }
  }
  return {along / n_along, across / n_across};
}

}  // namespace

TEST_CASE("fig. 8: scaling a tube along its curvature field lengthens it, across it thickens it", "[figures]") {
  const Mesh mesh = test::load("closed/knot1.off");
  const Positions field = curvature_direction_field(mesh, CurvatureDirection::Min, 10);
  Deformer deformer(mesh);
  for (Method method : {Method::AnDefGrad, Method::AnArap}) {
    DeformRequest request;
    request.method = method;
    request.direction.kind = DirectionSource::Kind::CurvatureMin;
    request.transform.su = 1.3;
    const DeformResult parallel = deformer.deform(request);
    const auto [p_along, p_across] = along_across_ratios(mesh, parallel.V, field);
    request.transform.su = 1.0;
    request.transform.sv = 1.3;
    const DeformResult perpendicular = deformer.deform(request);
    const auto [q_along, q_across] = along_across_ratios(mesh, perpendicular.V, field);
    WARN("fig8 " << method_name(method) << ": parallel along " << p_along << " across " << p_across
                 << "; perpendicular along " << q_along << " across " << q_across);
    INFO(method_name(method));
    const std::string key = std::string("8.") + method_name(method);
    test::record_figure_value(key + ".parallel_along", p_along);
    test::record_figure_value(key + ".parallel_across", p_across);
    test::record_figure_value(key + ".perpendicular_along", q_along);
    test::record_figure_value(key + ".perpendicular_across", q_across);
    if (method == Method::AnDefGrad) {
      test::record_figure_mesh("8-rest", mesh.V, mesh.F);
      test::record_figure_mesh("8-andefgrad-parallel", parallel.V, mesh.F);
      test::record_figure_mesh("8-andefgrad-perpendicular", perpendicular.V, mesh.F);
    }
    CHECK(p_along == Approx(1.3).epsilon(0.06));   // longer ...
    CHECK(p_across == Approx(1.0).epsilon(0.05));  // ... diameter kept
    CHECK(q_along == Approx(1.0).epsilon(0.05));   // length kept ...
    CHECK(q_across == Approx(1.3).epsilon(0.08));  // ... thicker
  }
}

TEST_CASE("fig. 1: a quadruped's leg is elongated along its direction and the body stays", "[figures]") {
  const Mesh mesh = test::load("closed/cat-low-resolution.obj");
  // The cat stands on its legs: the lowest vertex is a foot; select that leg
  // up to a third of the way to the top.
  int up_axis = 1;
  int foot = 0;
  mesh.V.col(up_axis).minCoeff(&foot);
  const double lo = mesh.V.col(up_axis).minCoeff(), hi = mesh.V.col(up_axis).maxCoeff();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(mesh.num_vertices());
  const double reach = 0.12 * diagonal(mesh.V);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::RowVector3d d = mesh.V.row(i) - mesh.V.row(foot);
    const double horizontal = std::hypot(d[0], d[2]);
    if (horizontal < reach && mesh.V(i, up_axis) < lo + 0.3 * (hi - lo)) w[i] = 1.0;
  }
  REQUIRE(w.sum() > 30);
  Deformer deformer(mesh);
  DeformRequest request = test::stretch_request(Method::AnArap, Eigen::Vector3d::Unit(up_axis), 1.5);
  request.selection = w;
  const DeformResult r = deformer.deform(request);
  // The leg's vertical extent grows ...
  double rest_lo = 1e9, rest_hi = -1e9, new_lo = 1e9, new_hi = -1e9;
  double body_motion = 0.0;
  int body = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (w[i] > 0) {
      rest_lo = std::min(rest_lo, mesh.V(i, up_axis)); rest_hi = std::max(rest_hi, mesh.V(i, up_axis));
      new_lo = std::min(new_lo, r.V(i, up_axis)); new_hi = std::max(new_hi, r.V(i, up_axis));
    } else if (mesh.V(i, up_axis) > lo + 0.6 * (hi - lo)) {
      body_motion += (r.V.row(i) - mesh.V.row(i)).norm();
      ++body;
    }
  }
  WARN("fig1 leg height x" << (new_hi - new_lo) / (rest_hi - rest_lo) << ", body mean motion "
                           << body_motion / body / diagonal(mesh.V) << " of the diagonal");
  test::record_figure_value("1.anarap.leg_height_ratio", (new_hi - new_lo) / (rest_hi - rest_lo));
  test::record_figure_value("1.anarap.body_motion", body_motion / body / diagonal(mesh.V));
  test::record_figure_mesh("1-rest", mesh.V, mesh.F, w);
  test::record_figure_mesh("1-anarap", r.V, mesh.F, w);
  CHECK((new_hi - new_lo) > 1.2 * (rest_hi - rest_lo));
  // ... while the upper body stays where it was (the rigid re-alignment holds it).
  CHECK(body_motion / body < 0.02 * diagonal(mesh.V));
}


namespace {

// Mean vertical (y) displacement of the selected vertices at the ends of a
// band (|x - xc| > 0.6 r) minus that of its middle (|x - xc| < 0.3 r).
double band_end_rise(const Mesh& mesh, const Positions& V, const Eigen::VectorXd& w, double xc, double r) {
  double ends = 0, middle = 0;
  int n_ends = 0, n_middle = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (w[i] < 1.0) continue;
    const double u = std::abs(mesh.V(i, 0) - xc), dy = V(i, 1) - mesh.V(i, 1);
    if (u > 0.6 * r) { ends += dy; ++n_ends; }
    if (u < 0.3 * r) { middle += dy; ++n_middle; }
  }
  return ends / n_ends - middle / n_middle;
}

}  // namespace

TEST_CASE("fig. 10: a stretch along a field bent upwards at its ends lifts the ends of the band (a smile)",
          "[figures]") {
  // The MANIFEST's stand-in for the Roman bust; y is up, the face looks
  // along +z. The band: a sphere around the head's frontmost point.
  const Mesh mesh = test::load("open/demosthenes-low-res.obj");
  int front = -1;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.V(i, 1) > 1.5 && (front < 0 || mesh.V(i, 2) > mesh.V(front, 2))) front = i;
  }
  const Eigen::RowVector3d c = mesh.V.row(front);
  const double r = 0.15;
  Region region;
  region.kind = Region::Kind::Sphere;
  region.center = c.transpose();
  region.radius = r;
  const Eigen::VectorXd w = selection_weights(mesh, region, 0.05);
  REQUIRE(w.sum() > 50);
  test::record_figure_mesh("10-rest", mesh.V, mesh.F, w);
  Deformer deformer(mesh);
  std::map<double, double> rise;
  for (double bend : {0.0, 1.0}) {
    // The field turns upwards away from the middle: tangent of y = bend (x - xc)^2 / (2 r).
    Positions field(mesh.num_vertices(), 3);
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      field.row(i) << 1.0, bend * (mesh.V(i, 0) - c[0]) / r, 0.0;
    }
    DeformRequest request;
    request.method = Method::AnArap;
    request.selection = w;
    request.direction.kind = DirectionSource::Kind::Dense;
    request.direction.dense = field;
    request.transform.su = 1.3;
    const DeformResult result = deformer.deform(request);
    rise[bend] = band_end_rise(mesh, result.V, w, c[0], r) / r;
    const std::string name = bend > 0 ? "bent" : "straight";
    test::record_figure_value("10.anarap." + name + "_rise", rise[bend]);
    if (!test::figures_dir().empty()) {
      const Eigen::VectorXd stretch = vertex_distortion(mesh, result.V, DistortionKind::Stretch);
      test::record_figure_mesh("10-anarap-" + name, result.V, mesh.F, w, stretch.array().log() / std::log(2.0), "stretch");
    }
    WARN("fig10 bend " << bend << ": band ends rise " << rise[bend] << " of the radius relative to the middle");
  }
  // The bent field lifts the ends; the straight one does not.
  CHECK(rise[1.0] > 0.04);
  CHECK(std::abs(rise[0.0]) < 0.3 * rise[1.0]);
}
