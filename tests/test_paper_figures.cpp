// The paper's figures as measurable scenes (METHOD §10), on the real meshes
// the shared MANIFEST names for each figure.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include "anisoform/curvature.h"
#include "anisoform/frames.h"
#include "anisoform/topology.h"
#include "solver_test_support.h"
#include "test_support.h"

using namespace aniso;
using test::diagonal;

namespace {

int longest_axis(const Positions& V) {
  Eigen::RowVector3d extent = V.colwise().maxCoeff() - V.colwise().minCoeff();
  int axis = 0;
  extent.maxCoeff(&axis);
  return axis;
}

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

// Dihedral angle (radians) at each interior edge with a given rest dihedral.
struct SharpEdges {
  std::vector<std::array<int, 4>> quads;  // edge (a, b), opposite vertices c, d
};

double dihedral(const Positions& V, const std::array<int, 4>& q) {
  const Eigen::Vector3d a = V.row(q[0]), b = V.row(q[1]), c = V.row(q[2]), d = V.row(q[3]);
  const Eigen::Vector3d n1 = (b - a).cross(c - a).normalized();
  const Eigen::Vector3d n2 = (d - a).cross(b - a).normalized();
  return std::acos(std::clamp(n1.dot(n2), -1.0, 1.0));
}

SharpEdges sharp_edges(const Mesh& mesh, double min_angle) {
  std::map<std::pair<int, int>, std::vector<int>> opposite;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(t, k), b = mesh.F(t, (k + 1) % 3), c = mesh.F(t, (k + 2) % 3);
      opposite[{std::min(a, b), std::max(a, b)}].push_back(a < b ? c : -c - 1);
    }
  }
  SharpEdges out;
  for (const auto& [edge, opp] : opposite) {
    if (opp.size() != 2) continue;
    // Orientation: the face where a->b is traversed gives c (stored >= 0).
    const int c = opp[0] >= 0 ? opp[0] : opp[1];
    const int d = opp[0] >= 0 ? -opp[1] - 1 : -opp[0] - 1;
    if (c < 0 || d < 0) continue;
    const std::array<int, 4> q = {edge.first, edge.second, c, d};
    if (dihedral(mesh.V, q) > min_angle) out.quads.push_back(q);
  }
  return out;
}

double mean_dihedral_change(const Mesh& mesh, const Positions& V, const SharpEdges& edges) {
  double sum = 0.0;
  for (const auto& q : edges.quads) sum += std::abs(dihedral(V, q) - dihedral(mesh.V, q));
  return sum / static_cast<double>(edges.quads.size());
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
  request.weights = w;
  const DeformResult arap = deformer.deform(request);
  request.method = Method::AnDefGrad;
  const DeformResult defgrad = deformer.deform(request);
  const double jump_arap = border_area_jump(mesh, arap.V, w);
  const double jump_defgrad = border_area_jump(mesh, defgrad.V, w);
  WARN("fig2 border log-area jump: anarap " << jump_arap << ", andefgrad " << jump_defgrad);
  CHECK(jump_arap < jump_defgrad);
  // Both really elongated the part.
  const Eigen::VectorXd rest_area = test::triangle_areas(mesh.V, mesh.F);
  CHECK(test::triangle_areas(arap.V, mesh.F).sum() > 1.05 * rest_area.sum());
  CHECK(test::triangle_areas(defgrad.V, mesh.F).sum() > 1.05 * rest_area.sum());
}

TEST_CASE("fig. 6: a twist whose angle grows with height turns each height by k*h (AnDefGrad)", "[figures]") {
  const Mesh mesh = test::load("closed/spool.off");
  const int axis = longest_axis(mesh.V);
  const double k = 20.0;  // degrees per unit
  Deformer deformer(mesh);
  DeformRequest request;
  request.method = Method::AnDefGrad;
  request.transform.twist = true;
  request.transform.twist_axis = Eigen::Vector3d::Unit(axis);
  const Eigen::Vector3d centroid = mesh.V.colwise().mean().transpose();
  request.transform.twist_origin = centroid;
  request.transform.twist_origin[axis] = mesh.V.col(axis).minCoeff();
  request.transform.twist_degrees_per_unit = k;
  const DeformResult r = deformer.deform(request);
  // Angle about the axis (through the centroid) of each vertex, rest -> deformed.
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  const Eigen::RowVector3d rc = mesh.V.colwise().mean();
  const Eigen::RowVector3d dc = r.V.colwise().mean();
  double sxx = 0, sxy = 0, sx = 0, sy = 0;
  int count = 0;
  const double max_radius = (mesh.V.rowwise() - rc).rowwise().norm().maxCoeff();
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::RowVector3d p = mesh.V.row(i) - rc, q = r.V.row(i) - dc;
    const double radius = std::hypot(p[a1], p[a2]);
    if (radius < 0.3 * max_radius) continue;
    double delta = std::atan2(q[a2], q[a1]) - std::atan2(p[a2], p[a1]);
    delta = std::remainder(delta, 2.0 * M_PI) * 180.0 / M_PI;
    const double h = mesh.V(i, axis);
    sx += h; sy += delta; sxx += h * h; sxy += h * delta; ++count;
  }
  const double slope = (count * sxy - sx * sy) / (count * sxx - sx * sx);
  WARN("fig6 fitted twist rate " << slope << " deg/unit for k = " << k);
  CHECK(slope == Approx(k).epsilon(0.1));
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
    CHECK(p_along == Approx(1.3).epsilon(0.06));   // longer ...
    CHECK(p_across == Approx(1.0).epsilon(0.05));  // ... diameter kept
    CHECK(q_along == Approx(1.0).epsilon(0.05));   // length kept ...
    CHECK(q_across == Approx(1.3).epsilon(0.08));  // ... thicker
  }
}

TEST_CASE("fig. 9: elongating a piece with sharp rims, AnDefGrad keeps the rims best and ARAP worst", "[figures]") {
  const Mesh mesh = test::load("closed/spool.off");
  const int axis = longest_axis(mesh.V);
  const SharpEdges rims = sharp_edges(mesh, 40.0 * M_PI / 180.0);
  REQUIRE(rims.quads.size() > 20);
  const double lo = mesh.V.col(axis).minCoeff(), hi = mesh.V.col(axis).maxCoeff();
  const double height = hi - lo;
  Deformer deformer(mesh);
  std::map<Method, double> change;
  for (Method method : {Method::Linear, Method::Arap, Method::AnArap, Method::AnDefGrad}) {
    DeformRequest request = test::stretch_request(method, Eigen::Vector3d::Unit(axis), 1.5);
    if (method == Method::Arap) {
      // The baseline elongates by handles: the top 5 % moved by the same amount, the bottom 5 % held.
      for (int i = 0; i < mesh.num_vertices(); ++i) {
        if (mesh.V(i, axis) < lo + 0.05 * height) request.pins.push_back(i);
        if (mesh.V(i, axis) > hi - 0.05 * height) request.handles.push_back(i);
      }
      request.handle_offset = Eigen::Vector3d::Unit(axis) * 0.5 * height;
    }
    const DeformResult r = deformer.deform(request);
    change[method] = mean_dihedral_change(mesh, r.V, rims);
    const double new_height = r.V.col(axis).maxCoeff() - r.V.col(axis).minCoeff();
    WARN("fig9 " << method_name(method) << ": mean rim dihedral change " << change[method] * 180 / M_PI
                 << " deg, height x" << new_height / height);
    CHECK(new_height > 1.25 * height);
  }
  CHECK(change[Method::AnDefGrad] < change[Method::AnArap]);
  CHECK(change[Method::AnDefGrad] < change[Method::Arap]);
  CHECK(change[Method::AnArap] < change[Method::Arap]);
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
  request.weights = w;
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
  CHECK((new_hi - new_lo) > 1.2 * (rest_hi - rest_lo));
  // ... while the upper body stays where it was (the rigid re-alignment holds it).
  CHECK(body_motion / body < 0.02 * diagonal(mesh.V));
}

TEST_CASE("fig. 4: shearing the top of a post moves it along the shear, the rest stays", "[figures]") {
  // No closed post among the shared meshes; the spool is the MANIFEST's stand-in.
  const Mesh mesh = test::load("closed/spool.off");
  const int up = longest_axis(mesh.V);
  const int side = (up + 1) % 3;
  const double lo = mesh.V.col(up).minCoeff(), hi = mesh.V.col(up).maxCoeff();
  Eigen::VectorXd w(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) w[i] = mesh.V(i, up) > lo + 0.5 * (hi - lo) ? 1.0 : 0.0;
  Deformer deformer(mesh);
  for (Method method : {Method::AnDefGrad, Method::AnArap}) {
    for (double h : {0.5, -0.5}) {
      DeformRequest request;
      request.method = method;
      request.weights = w;
      request.direction.vector = Eigen::Vector3d::Unit(side);
      request.transform.shear = h;
      const DeformResult r = deformer.deform(request);
      double top_shift = 0.0, bottom_motion = 0.0;
      int top = 0, bottom = 0;
      for (int i = 0; i < mesh.num_vertices(); ++i) {
        if (mesh.V(i, up) > hi - 0.1 * (hi - lo)) { top_shift += r.V(i, side) - mesh.V(i, side); ++top; }
        if (mesh.V(i, up) < lo + 0.3 * (hi - lo)) { bottom_motion += (r.V.row(i) - mesh.V.row(i)).norm(); ++bottom; }
      }
      top_shift /= top;
      bottom_motion /= bottom;
      INFO(method_name(method) << " h=" << h);
      WARN("fig4 " << method_name(method) << " h=" << h << ": top shift " << top_shift / (hi - lo)
                   << " of the height, bottom motion " << bottom_motion / (hi - lo));
      CHECK(top_shift * h > 0.05 * (hi - lo));           // visible shear, in the shear's sense
      CHECK(bottom_motion < 0.15 * std::abs(top_shift));  // unselected part unaffected
    }
  }
}

TEST_CASE("fig. 5: a local rotation bends the post, and AnDefGrad keeps it more local than AnARAP", "[figures]") {
  const Mesh mesh = test::load("closed/spool.off");
  const int up = longest_axis(mesh.V);
  const double lo = mesh.V.col(up).minCoeff(), hi = mesh.V.col(up).maxCoeff();
  Eigen::VectorXd w(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) w[i] = mesh.V(i, up) > lo + 0.6 * (hi - lo) ? 1.0 : 0.0;
  auto below = [&](int i) { return mesh.V(i, up) < lo + 0.45 * (hi - lo); };
  Deformer deformer(mesh);
  std::map<Method, double> strain_below;
  for (Method method : {Method::AnDefGrad, Method::AnArap}) {
    // Each selected element turns about its own tangent along the post.
    DeformRequest request;
    request.method = method;
    request.weights = w;
    request.direction.vector = Eigen::Vector3d::Unit(up);
    request.transform.rotate_axis = RotateAxis::U;
    request.transform.rotate_degrees = 30.0;
    const DeformResult r = deformer.deform(request);
    // How much the part well below the selection is deformed: mean relative
    // change of its edge lengths (rigid motions do not count).
    double strain = 0.0, moved = 0.0;
    int edges = 0, n_in = 0;
    for (int t = 0; t < mesh.num_triangles(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.F(t, k), b = mesh.F(t, (k + 1) % 3);
        if (!below(a) || !below(b)) continue;
        strain += std::abs((r.V.row(a) - r.V.row(b)).norm() / (mesh.V.row(a) - mesh.V.row(b)).norm() - 1.0);
        ++edges;
      }
    }
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      if (w[i] > 0) { moved += (r.V.row(i) - mesh.V.row(i)).norm(); ++n_in; }
    }
    strain_below[method] = strain / edges;
    WARN("fig5 " << method_name(method) << ": selected part moves " << moved / n_in / (hi - lo)
                 << " of the height; mean edge strain below the selection " << strain_below[method]);
    CHECK(moved / n_in > 0.02 * (hi - lo));  // the rotation visibly changes the selected part
  }
  CHECK(strain_below[Method::AnDefGrad] < strain_below[Method::AnArap]);
}
