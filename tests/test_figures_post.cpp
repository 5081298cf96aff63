// The paper's post and chess-piece figures (METHOD §10: Figs. 4, 5, 6, 7, 9)
// on the MANIFEST's stand-in, closed/spool.off. The spool is a surface of
// revolution about x, its SHORTEST bounding-box side (0.52 long, 1.0 across):
// every scene runs along x, never along the longest side (a diameter). Its
// vertices lie on rings of constant x (33 each), which the measurements use.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "anisoform/selection.h"
#include "figure_record.h"
#include "mesh/topology.h"
#include "solver_test_support.h"
#include "test_support.h"

using namespace aniso;

namespace {

constexpr int kSpoolAxis = 0;  // x: the axis of revolution

struct SpoolRing {
  double height = 0.0;   // rest x
  std::vector<int> ids;  // its vertices (off the axis)
};

// The spool's axis line passes through the bounding-box centre (the vertex
// centroid does not: the cap is densely meshed).
Eigen::RowVector3d spool_center(const Positions& V) {
  return 0.5 * (V.colwise().maxCoeff() + V.colwise().minCoeff());
}

// Vertices grouped by rest height (to 1e-4), rings of at least 20 vertices.
std::vector<SpoolRing> spool_rings(const Mesh& mesh) {
  const Eigen::RowVector3d c = spool_center(mesh.V);
  std::map<long, SpoolRing> by_height;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::RowVector3d p = mesh.V.row(i) - c;
    if (std::hypot(p[1], p[2]) < 0.05) continue;
    SpoolRing& ring = by_height[std::lround(mesh.V(i, kSpoolAxis) * 1e4)];
    ring.height = mesh.V(i, kSpoolAxis);
    ring.ids.push_back(i);
  }
  std::vector<SpoolRing> rings;
  for (const auto& entry : by_height) {
    if (entry.second.ids.size() >= 20) rings.push_back(entry.second);
  }
  return rings;
}

Eigen::RowVector3d ring_mean(const Positions& V, const SpoolRing& ring) {
  Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
  for (int i : ring.ids) sum += V.row(i);
  return sum / static_cast<double>(ring.ids.size());
}

// Mean turn (degrees) of a ring about the x axis through its own centre, rest
// to deformed (a translation of the result does not count).
double ring_turn_degrees(const Mesh& mesh, const Positions& V, const SpoolRing& ring) {
  const Eigen::RowVector3d rc = ring_mean(mesh.V, ring), dc = ring_mean(V, ring);
  double sum = 0.0;
  for (int i : ring.ids) {
    const Eigen::RowVector3d p = mesh.V.row(i) - rc, q = V.row(i) - dc;
    sum += std::remainder(std::atan2(q[2], q[1]) - std::atan2(p[2], p[1]), 2.0 * M_PI);
  }
  return sum / static_cast<double>(ring.ids.size()) * 180.0 / M_PI;
}

// The unit normal of the plane best fitting a deformed ring, oriented to +x.
Eigen::Vector3d ring_plane_normal(const Positions& V, const SpoolRing& ring) {
  const Eigen::RowVector3d c = ring_mean(V, ring);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int i : ring.ids) {
    const Eigen::Vector3d d = (V.row(i) - c).transpose();
    cov += d * d.transpose();
  }
  Eigen::Vector3d n = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0);
  return n[0] < 0 ? Eigen::Vector3d(-n) : n;
}

// Least-squares slope of ys against xs.
double fitted_slope(const std::vector<double>& xs, const std::vector<double>& ys) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(xs.size());
  for (std::size_t k = 0; k < xs.size(); ++k) {
    sx += xs[k]; sy += ys[k]; sxx += xs[k] * xs[k]; sxy += xs[k] * ys[k];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// Weight 1 on the vertices above `level` (rest x).
Eigen::VectorXd spool_above(const Mesh& mesh, double level) {
  Eigen::VectorXd w(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) w[i] = mesh.V(i, kSpoolAxis) > level ? 1.0 : 0.0;
  return w;
}

// Dihedral angle at an interior edge (a, b) with opposite vertices c, d.
double spool_dihedral(const Positions& V, const std::array<int, 4>& q) {
  const Eigen::Vector3d a = V.row(q[0]), b = V.row(q[1]), c = V.row(q[2]), d = V.row(q[3]);
  const Eigen::Vector3d n1 = (b - a).cross(c - a).normalized();
  const Eigen::Vector3d n2 = (d - a).cross(b - a).normalized();
  return std::acos(std::clamp(n1.dot(n2), -1.0, 1.0));
}

// Edges whose rest dihedral exceeds min_angle (the rims), as (a, b, c, d).
std::vector<std::array<int, 4>> spool_rims(const Mesh& mesh, double min_angle) {
  std::map<std::pair<int, int>, std::vector<int>> opposite;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(t, k), b = mesh.F(t, (k + 1) % 3), c = mesh.F(t, (k + 2) % 3);
      opposite[{std::min(a, b), std::max(a, b)}].push_back(a < b ? c : -c - 1);
    }
  }
  std::vector<std::array<int, 4>> out;
  for (const auto& [edge, opp] : opposite) {
    if (opp.size() != 2) continue;
    // The face traversing a->b gives c (stored >= 0), the other gives d.
    const int c = opp[0] >= 0 ? opp[0] : opp[1];
    const int d = opp[0] >= 0 ? -opp[1] - 1 : -opp[0] - 1;
    if (c < 0 || d < 0) continue;
    const std::array<int, 4> q = {edge.first, edge.second, c, d};
    if (spool_dihedral(mesh.V, q) > min_angle) out.push_back(q);
  }
  return out;
}

// Mean |change| of the rims' dihedral angles, in degrees; `only` restricts to
// rims whose vertices all have weight > 0 in it (empty: all rims).
double rim_change_degrees(const Mesh& mesh, const Positions& V, const std::vector<std::array<int, 4>>& rims,
                          const Eigen::VectorXd& only = Eigen::VectorXd()) {
  double sum = 0.0;
  int count = 0;
  for (const auto& q : rims) {
    if (only.size() > 0 && !(only[q[0]] > 0 && only[q[1]] > 0 && only[q[2]] > 0 && only[q[3]] > 0)) continue;
    sum += std::abs(spool_dihedral(V, q) - spool_dihedral(mesh.V, q));
    ++count;
  }
  return sum / count * 180.0 / M_PI;
}

}  // namespace

TEST_CASE("fig. 4: shearing the top of the spool along y moves it along the shear, the rest stays", "[figures]") {
  // No closed post among the shared meshes; the spool is the MANIFEST's stand-in.
  const Mesh mesh = test::load("closed/spool.off");
  const int up = kSpoolAxis, side = 1;
  const double lo = mesh.V.col(up).minCoeff(), hi = mesh.V.col(up).maxCoeff();
  const Eigen::VectorXd w = spool_above(mesh, lo + 0.5 * (hi - lo));
  test::record_figure_mesh("4-rest", mesh.V, mesh.F, w);
  Deformer deformer(mesh);
  for (Method method : {Method::AnDefGrad, Method::AnArap}) {
    for (double h : {0.5, -0.5}) {
      DeformRequest request;
      request.method = method;
      request.selection = w;
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
      if (h > 0) {
        const std::string key = std::string("4.") + method_name(method);
        test::record_figure_value(key + ".top_shift", top_shift / (hi - lo));
        test::record_figure_value(key + ".bottom_motion", bottom_motion / (hi - lo));
        test::record_figure_mesh(std::string("4-") + method_name(method), r.V, mesh.F, w);
      }
      CHECK(top_shift * h > 0.05 * (hi - lo));           // visible shear, in the shear's sense
      CHECK(bottom_motion < 0.15 * std::abs(top_shift));  // unselected part unaffected
    }
  }
}

namespace {

// The ring nearest to rest height x.
const SpoolRing& spool_ring_at(const std::vector<SpoolRing>& rings, double x) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < rings.size(); ++k) {
    if (std::abs(rings[k].height - x) < std::abs(rings[best].height - x)) best = k;
  }
  return rings[best];
}

// RMS distance of the vertices `ids` from the best rigid motion of their rest
// positions (Kabsch): how much that part changed shape, whatever it moved as a
// whole (so the methods' gauges do not count).
double non_rigid_residual(const Positions& rest, const Positions& V, const std::vector<int>& ids) {
  Eigen::RowVector3d cp = Eigen::RowVector3d::Zero(), cq = Eigen::RowVector3d::Zero();
  for (int i : ids) { cp += rest.row(i); cq += V.row(i); }
  cp /= static_cast<double>(ids.size());
  cq /= static_cast<double>(ids.size());
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (int i : ids) H += (rest.row(i) - cp).transpose() * (V.row(i) - cq);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d flip = Eigen::Matrix3d::Identity();
  flip(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  const Eigen::Matrix3d R = svd.matrixV() * flip * svd.matrixU().transpose();
  double sum = 0.0;
  for (int i : ids) sum += ((V.row(i) - cq).transpose() - R * (rest.row(i) - cp).transpose()).squaredNorm();
  return std::sqrt(sum / static_cast<double>(ids.size()));
}

// Tilt (degrees) of a ring's plane about z: + turns its normal from +x to +y.
double ring_tilt_about_z(const Positions& V, const SpoolRing& ring) {
  const Eigen::Vector3d n = ring_plane_normal(V, ring);
  return std::atan2(n[1], n[0]) * 180.0 / M_PI;
}

}  // namespace

TEST_CASE("fig. 5: rotating the spool's top elements about z bends it into a hook towards +y, the base stays",
          "[figures]") {
  const Mesh mesh = test::load("closed/spool.off");
  const double lo = mesh.V.col(kSpoolAxis).minCoeff(), hi = mesh.V.col(kSpoolAxis).maxCoeff();
  const Eigen::VectorXd w = spool_above(mesh, lo + 0.6 * (hi - lo));
  const std::vector<SpoolRing> rings = spool_rings(mesh);
  const SpoolRing& top = spool_ring_at(rings, 0.1439);   // the upper flange's rim (selected)
  const SpoolRing& base = spool_ring_at(rings, -0.26);   // the bottom face's rim (not selected)
  REQUIRE(w[top.ids[0]] == 1.0);
  REQUIRE(w[base.ids[0]] == 0.0);
  test::record_figure_mesh("5-rest", mesh.V, mesh.F, w);
  auto below = [&](int i) { return mesh.V(i, kSpoolAxis) < lo + 0.45 * (hi - lo); };
  std::vector<int> below_ids;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (below(i)) below_ids.push_back(i);
  }
  // The rest dihedral angle of every interior edge whose four vertices lie below.
  std::vector<std::array<int, 4>> below_edges;
  for (const auto& q : spool_rims(mesh, -1.0)) {
    if (below(q[0]) && below(q[1]) && below(q[2]) && below(q[3])) below_edges.push_back(q);
  }
  REQUIRE(below_edges.size() > 100);
  Deformer deformer(mesh);
  std::map<Method, double> strain_below, reshape_below, bend_below;
  for (Method method : {Method::AnDefGrad, Method::AnArap}) {
    for (double theta : {30.0, -30.0}) {
      // Each selected element turns about the global z (projected on it):
      // together they turn the top about z, bending it sideways.
      DeformRequest request;
      request.method = method;
      request.selection = w;
      request.direction.vector = Eigen::Vector3d::UnitZ();
      request.transform.rotate_axis = RotateAxis::U;
      request.transform.rotate_degrees = theta;
      const DeformResult r = deformer.deform(request);
      const double top_tilt = ring_tilt_about_z(r.V, top), base_tilt = ring_tilt_about_z(r.V, base);
      const Eigen::RowVector3d shift = ring_mean(r.V, top) - ring_mean(mesh.V, top);
      const double height = hi - lo;
      INFO(method_name(method) << " theta=" << theta);
      WARN("fig5 " << method_name(method) << " theta=" << theta << ": top rim tilt " << top_tilt
                   << " deg, base rim tilt " << base_tilt << " deg, top shift y " << shift[1] / height
                   << " z " << shift[2] / height << " of the height");
      // Hook: the top turns in the rotation's sense by a good part of theta,
      // the base stays upright ...
      if (theta > 0) {
        const std::string key = std::string("5.") + method_name(method);
        test::record_figure_value(key + ".top_tilt", top_tilt);
        test::record_figure_value(key + ".base_tilt", base_tilt);
        test::record_figure_value(key + ".top_shift_y", shift[1] / height);
        test::record_figure_value(key + ".top_shift_z", shift[2] / height);
        test::record_figure_mesh(std::string("5-") + method_name(method), r.V, mesh.F, w);
      }
      CHECK(top_tilt / theta > 0.3);
      CHECK(top_tilt / theta < 1.2);
      CHECK(std::abs(base_tilt) < 0.1 * std::abs(top_tilt));
      // ... and it bends towards +y for a positive turn about z (x -> y), not along z.
      CHECK(shift[1] * theta > 0.0);
      CHECK(std::abs(shift[1]) > 0.03 * height);
      CHECK(std::abs(shift[2]) < 0.25 * std::abs(shift[1]));
      if (theta > 0) {
        double strain = 0.0;
        int edges = 0;
        for (int t = 0; t < mesh.num_triangles(); ++t) {
          for (int k = 0; k < 3; ++k) {
            const int a = mesh.F(t, k), b = mesh.F(t, (k + 1) % 3);
            if (!below(a) || !below(b)) continue;
            strain += std::abs((r.V.row(a) - r.V.row(b)).norm() / (mesh.V.row(a) - mesh.V.row(b)).norm() - 1.0);
            ++edges;
          }
        }
        strain_below[method] = strain / edges;
        reshape_below[method] = non_rigid_residual(mesh.V, r.V, below_ids) / height;
        bend_below[method] = rim_change_degrees(mesh, r.V, below_edges);
        WARN("fig5 " << method_name(method) << ": below the selection, mean edge strain " << strain_below[method]
                     << ", change of shape (RMS off the best rigid motion) " << reshape_below[method]
                     << " of the height, mean dihedral change " << bend_below[method] << " deg");
        const std::string key = std::string("5.") + method_name(method);
        test::record_figure_value(key + ".strain_below", strain_below[method]);
        test::record_figure_value(key + ".reshape_below", reshape_below[method]);
        test::record_figure_value(key + ".bend_below", bend_below[method]);
      }
    }
  }
  CHECK(strain_below[Method::AnDefGrad] < 0.015);
  CHECK(strain_below[Method::AnArap] < 0.015);
  // The paper's Fig. 5: "AnARAP exhibits more global deformation while
  // AnDefGrad has more local control", the organic bend of ARAP reaching past
  // the selection. ARAP bends by rotating its fans, which stretches no edge:
  // the edge strain above cannot show it (AnARAP's is the smaller). The part
  // below the selection changes shape more under AnARAP: it leaves its best
  // rigid motion further, and its dihedral angles turn more.
  CHECK(reshape_below[Method::AnDefGrad] < reshape_below[Method::AnArap]);
  CHECK(bend_below[Method::AnDefGrad] < bend_below[Method::AnArap]);
}

namespace {

// Per ring: rest height and turn about x (degrees).
struct RingTurns {
  std::vector<double> heights, turns, weights;
};

RingTurns spool_ring_turns(const Mesh& mesh, const Positions& V, const std::vector<SpoolRing>& rings,
                           const Eigen::VectorXd& w) {
  RingTurns out;
  for (const SpoolRing& ring : rings) {
    out.heights.push_back(ring.height);
    out.turns.push_back(ring_turn_degrees(mesh, V, ring));
    double weight = 1.0;
    for (int i : ring.ids) weight = std::min(weight, w.size() > 0 ? w[i] : 1.0);
    out.weights.push_back(weight);
  }
  return out;
}

// For the gallery's pictures of a twist: 1 on one meridian (per ring of
// constant x and radius, the vertex nearest to the +z direction), 0
// elsewhere; drawn as a line that the twist turns into a helix.
Eigen::VectorXd spool_meridian(const Mesh& mesh) {
  const Eigen::RowVector3d c = spool_center(mesh.V);
  std::map<std::pair<long, long>, int> nearest;  // (x, radius) -> vertex
  auto off_z = [&](int i) { return std::abs(std::atan2(mesh.V(i, 1) - c[1], mesh.V(i, 2) - c[2])); };
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const double radius = std::hypot(mesh.V(i, 1) - c[1], mesh.V(i, 2) - c[2]);
    if (radius < 0.05) continue;
    const auto key = std::make_pair(std::lround(mesh.V(i, kSpoolAxis) * 1e4), std::lround(radius * 1e2));
    const auto it = nearest.find(key);
    if (it == nearest.end() || off_z(i) < off_z(it->second)) nearest[key] = i;
  }
  Eigen::VectorXd line = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (const auto& entry : nearest) {
    if (off_z(entry.second) < 10.0 * M_PI / 180.0) line[entry.second] = 1.0;
  }
  return line;
}

DeformRequest spool_twist(Method method, const Mesh& mesh, double rate, double origin_x) {
  DeformRequest request;
  request.method = method;
  request.transform.twist = true;
  request.transform.twist_axis = Eigen::Vector3d::UnitX();
  // Explicit origin on the axis line: the scene must not depend on the default.
  request.transform.twist_origin = spool_center(mesh.V).transpose();
  request.transform.twist_origin[kSpoolAxis] = origin_x;
  request.transform.twist_degrees_per_unit = rate;
  return request;
}

}  // namespace

TEST_CASE("fig. 6: twisting the whole spool about x turns each ring by k per unit height (both methods)",
          "[figures]") {
  const Mesh mesh = test::load("closed/spool.off");
  const std::vector<SpoolRing> rings = spool_rings(mesh);
  REQUIRE(rings.size() >= 10);
  const double lo = mesh.V.col(kSpoolAxis).minCoeff();
  const double k = 60.0;  // degrees per unit: 31 degrees over the spool's 0.52
  test::record_figure_value("6.rate", k);
  const Eigen::VectorXd meridian = spool_meridian(mesh);
  test::record_figure_mesh("6-rest", mesh.V, mesh.F, Eigen::VectorXd(), meridian, "marker");
  Deformer deformer(mesh);
  for (Method method : {Method::AnDefGrad, Method::AnArap}) {
    const DeformResult r = deformer.deform(spool_twist(method, mesh, k, lo));
    const RingTurns t = spool_ring_turns(mesh, r.V, rings, Eigen::VectorXd());
    const double slope = fitted_slope(t.heights, t.turns);
    double worst = 0.0;  // largest deviation of a ring from the fitted line
    const double mean_h = std::accumulate(t.heights.begin(), t.heights.end(), 0.0) / t.heights.size();
    const double mean_t = std::accumulate(t.turns.begin(), t.turns.end(), 0.0) / t.turns.size();
    for (std::size_t j = 0; j < t.heights.size(); ++j) {
      worst = std::max(worst, std::abs(t.turns[j] - (mean_t + slope * (t.heights[j] - mean_h))));
    }
    INFO(method_name(method));
    test::record_figure_value(std::string("6.") + method_name(method) + ".whole_rate", slope);
    test::record_figure_value(std::string("6.") + method_name(method) + ".whole_worst_ring", worst);
    test::record_figure_mesh(std::string("6-") + method_name(method) + "-whole", r.V, mesh.F, Eigen::VectorXd(), meridian,
                             "marker");
    WARN("fig6 " << method_name(method) << ": fitted twist " << slope << " deg/unit for k = " << k
                 << ", worst ring off the line " << worst << " deg over " << t.heights.size() << " rings");
    if (method == Method::AnDefGrad) {
      CHECK(slope == Approx(k).epsilon(0.05));
      CHECK(worst < 1.5);
    } else {
      CHECK(slope == Approx(k).epsilon(0.1));
      CHECK(worst < 1.5);
    }
  }
}

TEST_CASE("fig. 6: a twist of the spool's top with a geodesic falloff: k per unit on the selection, none below",
          "[figures]") {
  const Mesh mesh = test::load("closed/spool.off");
  const std::vector<SpoolRing> rings = spool_rings(mesh);
  const double level = 0.1;  // the selection: the upper flange and the cap (x > 0.1)
  const Eigen::VectorXd w = apply_falloff(mesh, spool_above(mesh, level), 0.35);
  const double k = 60.0;
  Deformer deformer(mesh);
  for (Method method : {Method::AnDefGrad, Method::AnArap}) {
    DeformRequest request = spool_twist(method, mesh, k, level);
    request.selection = w;
    const DeformResult r = deformer.deform(request);
    const RingTurns t = spool_ring_turns(mesh, r.V, rings, w);
    RingTurns full;
    double still = 0.0;  // largest turn of an unselected ring (weight 0)
    std::ostringstream soft;
    for (std::size_t j = 0; j < t.heights.size(); ++j) {
      if (t.weights[j] == 1.0) {
        full.heights.push_back(t.heights[j]);
        full.turns.push_back(t.turns[j]);
      } else if (t.weights[j] == 0.0) {
        still = std::max(still, std::abs(t.turns[j]));
      } else {
        soft << " x=" << t.heights[j] << " w=" << t.weights[j] << " turn " << t.turns[j];
      }
    }
    REQUIRE(full.heights.size() >= 8);
    const double slope = fitted_slope(full.heights, full.turns);
    INFO(method_name(method));
    const std::string key = std::string("6.") + method_name(method);
    test::record_figure_value(key + ".falloff_rate", slope);
    test::record_figure_value(key + ".falloff_unselected_turn", still);
    test::record_figure_mesh(std::string("6-") + method_name(method) + "-falloff", r.V, mesh.F, w, spool_meridian(mesh),
                             "marker");
    WARN("fig6 falloff " << method_name(method) << ": twist on the selection " << slope << " deg/unit for k = " << k
                         << " (" << full.heights.size() << " rings); largest unselected ring turn " << still
                         << " deg; soft rings:" << soft.str());
    if (method == Method::AnDefGrad) {
      CHECK(slope == Approx(k).epsilon(0.05));
    } else {
      CHECK(slope == Approx(k).epsilon(0.1));
    }
    CHECK(still < 2.0);
  }
}

namespace {

// Extent of a ring along a coordinate axis.
double ring_extent(const Positions& V, const SpoolRing& ring, int axis) {
  double a = HUGE_VAL, b = -HUGE_VAL;
  for (int i : ring.ids) { a = std::min(a, V(i, axis)); b = std::max(b, V(i, axis)); }
  return b - a;
}

}  // namespace

TEST_CASE("fig. 7: a local stretch of the spool's top follows its direction and keeps the rims", "[figures]") {
  const Mesh mesh = test::load("closed/spool.off");
  const double lo = mesh.V.col(kSpoolAxis).minCoeff(), hi = mesh.V.col(kSpoolAxis).maxCoeff();
  const Eigen::VectorXd w = spool_above(mesh, lo + 0.5 * (hi - lo));
  const std::vector<SpoolRing> rings = spool_rings(mesh);
  const SpoolRing& top = spool_ring_at(rings, 0.1439);  // upper flange rim, selected
  const SpoolRing& base = spool_ring_at(rings, -0.26);  // bottom rim, not selected
  const auto rims = spool_rims(mesh, 40.0 * M_PI / 180.0);
  test::record_figure_mesh("7-rest", mesh.V, mesh.F, w);
  Deformer deformer(mesh);
  for (Method method : {Method::AnDefGrad, Method::AnArap}) {
    DeformRequest request = test::stretch_request(method, Eigen::Vector3d::UnitY(), 1.4);
    request.selection = w;
    const DeformResult r = deformer.deform(request);
    const double along = ring_extent(r.V, top, 1) / ring_extent(mesh.V, top, 1);
    const double across = ring_extent(r.V, top, 2) / ring_extent(mesh.V, top, 2);
    const double base_along = ring_extent(r.V, base, 1) / ring_extent(mesh.V, base, 1);
    const double rim_change = rim_change_degrees(mesh, r.V, rims, w);
    INFO(method_name(method));
    const std::string key = std::string("7.") + method_name(method);
    test::record_figure_value(key + ".stretch_along", along);
    test::record_figure_value(key + ".stretch_across", across);
    test::record_figure_value(key + ".stretch_base", base_along);
    test::record_figure_value(key + ".stretch_rim_change", rim_change);
    test::record_figure_mesh(std::string("7-") + method_name(method) + "-stretch", r.V, mesh.F, w);
    WARN("fig7 stretch " << method_name(method) << " su=1.4 along y: top rim y x" << along << ", z x" << across
                         << ", base rim y x" << base_along << "; selected rims' dihedral change " << rim_change
                         << " deg");
    CHECK(along == Approx(1.4).epsilon(0.05));        // stretched along the direction ...
    CHECK(across == Approx(1.0).margin(0.1));         // ... much less across it
    CHECK(along - across > 0.25);
    CHECK(base_along == Approx(1.0).margin(0.05));    // the unselected part stays
    CHECK(rim_change < (method == Method::AnDefGrad ? 2.0 : 6.0));  // features kept
  }
}

TEST_CASE("fig. 7: a local rotation of the spool's top turns it about the chosen axis, for two axes", "[figures]") {
  const Mesh mesh = test::load("closed/spool.off");
  const double lo = mesh.V.col(kSpoolAxis).minCoeff(), hi = mesh.V.col(kSpoolAxis).maxCoeff();
  const Eigen::VectorXd w = spool_above(mesh, lo + 0.5 * (hi - lo));
  const std::vector<SpoolRing> rings = spool_rings(mesh);
  const SpoolRing& top = spool_ring_at(rings, 0.1439);
  Deformer deformer(mesh);
  for (Method method : {Method::AnDefGrad, Method::AnArap}) {
    for (int axis : {2, 1}) {  // rotate about z, then about y
      DeformRequest request;
      request.method = method;
      request.selection = w;
      request.direction.vector = Eigen::Vector3d::Unit(axis);
      request.transform.rotate_axis = RotateAxis::U;
      request.transform.rotate_degrees = 30.0;
      const DeformResult r = deformer.deform(request);
      const Eigen::Vector3d n = ring_plane_normal(r.V, top);
      // A turn about `axis` moves the rim's normal (rest +x) towards the third axis.
      const int toward = 3 - axis;
      const double tilt = std::asin(std::min(1.0, std::abs(n[toward]))) * 180.0 / M_PI;
      const double off = std::asin(std::min(1.0, std::abs(n[axis]))) * 180.0 / M_PI;
      INFO(method_name(method) << " about axis " << axis);
      const std::string about = std::string(1, "xyz"[axis]);
      test::record_figure_value(std::string("7.") + method_name(method) + ".rotate_" + about + "_tilt", tilt);
      test::record_figure_value(std::string("7.") + method_name(method) + ".rotate_" + about + "_off", off);
      test::record_figure_mesh(std::string("7-") + method_name(method) + "-rotate-" + about, r.V, mesh.F, w);
      WARN("fig7 rotate " << method_name(method) << " 30 deg about " << "xyz"[axis] << ": top rim normal tilts "
                          << tilt << " deg towards " << "xyz"[toward] << ", " << off << " deg towards "
                          << "xyz"[axis]);
      CHECK(tilt > 9.0);
      CHECK(off < 0.1 * tilt);
    }
  }
}

TEST_CASE("fig. 9: elongating the spool along x, AnDefGrad keeps the rims best, isotropic ARAP worst of the solvers, "
          "the linear map blunts them most",
          "[figures]") {
  const Mesh mesh = test::load("closed/spool.off");
  const int axis = kSpoolAxis;
  const auto rims = spool_rims(mesh, 40.0 * M_PI / 180.0);
  REQUIRE(rims.size() > 20);
  test::record_figure_mesh("9-rest", mesh.V, mesh.F);
  const double lo = mesh.V.col(axis).minCoeff(), hi = mesh.V.col(axis).maxCoeff();
  const double height = hi - lo;
  // The core: the cylinder between the flanges, the part whose surface runs
  // along x (its wall's direction is x itself, nowhere projected).
  const std::vector<SpoolRing> rings = spool_rings(mesh);
  const SpoolRing& core_bottom = spool_ring_at(rings, -0.1637);
  const SpoolRing& core_top = spool_ring_at(rings, 0.1252);
  const double core = core_top.height - core_bottom.height;
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
    change[method] = rim_change_degrees(mesh, r.V, rims);
    const double new_height = r.V.col(axis).maxCoeff() - r.V.col(axis).minCoeff();
    const double new_core = ring_mean(r.V, core_top)[axis] - ring_mean(r.V, core_bottom)[axis];
    test::record_figure_value(std::string("9.") + method_name(method) + ".rim_change", change[method]);
    test::record_figure_value(std::string("9.") + method_name(method) + ".height_ratio", new_height / height);
    test::record_figure_value(std::string("9.") + method_name(method) + ".core_ratio", new_core / core);
    test::record_figure_mesh(std::string("9-") + method_name(method), r.V, mesh.F);
    WARN("fig9 " << method_name(method) << ": mean rim dihedral change " << change[method] << " deg, height x"
                 << new_height / height << ", core x" << new_core / core);
    INFO(method_name(method));
    CHECK(new_height > 1.25 * height);
    if (method == Method::AnArap || method == Method::AnDefGrad) {
      // Where the surface contains the direction, the elongation is su.
      CHECK(new_core / core == Approx(1.5).epsilon(0.03));
    }
    // AnARAP's whole height overshoots (x2.01): its targets are AnDefGrad's,
    // su = 1.5 along the direction projected on each face (paper eq. 5-6),
    // also on the flanges' walls, nearly perpendicular to x (the faces square
    // to x are kept: Frames::along_normal): their meridians are asked to grow by half with their circumferences
    // kept, and ARAP, free to rotate its fans, turns them up into cones (the
    // gradient domain cannot rotate them, and widens them instead). Measured
    // and explained in FIGURES-measured.md; the paper claims nothing about the
    // height, only the rims.
  }
  CHECK(change[Method::AnDefGrad] < 5.0);
  CHECK(change[Method::AnDefGrad] < change[Method::AnArap]);
  CHECK(change[Method::AnDefGrad] < change[Method::Arap]);
  // "Feature sharpness is lost using an isotropic energy formulation": AnARAP
  // keeps the rims better than isotropic ARAP with handles.
  CHECK(change[Method::AnArap] < change[Method::Arap]);
  // The cage-like linear map stretches uniformly: the rims lose sharpness.
  CHECK(change[Method::Linear] > 2.0 * change[Method::AnDefGrad]);
}

namespace {

// The three rotational scenes on the spool (METHOD §5): the top's elements
// rotated 30 degrees about z (Fig. 5), sheared along y (Fig. 4), and the top
// twisted with a geodesic falloff (Fig. 6).
std::vector<std::pair<std::string, DeformRequest>> rotational_scenes(const Mesh& mesh) {
  const double lo = mesh.V.col(kSpoolAxis).minCoeff(), hi = mesh.V.col(kSpoolAxis).maxCoeff();
  std::vector<std::pair<std::string, DeformRequest>> scenes;
  DeformRequest rotate;
  rotate.selection = spool_above(mesh, lo + 0.6 * (hi - lo));
  rotate.direction.vector = Eigen::Vector3d::UnitZ();
  rotate.transform.rotate_axis = RotateAxis::U;
  rotate.transform.rotate_degrees = 30.0;
  scenes.emplace_back("rotate", rotate);
  DeformRequest shear;
  shear.selection = spool_above(mesh, lo + 0.5 * (hi - lo));
  shear.direction.vector = Eigen::Vector3d::UnitY();
  shear.transform.shear = 0.5;
  scenes.emplace_back("shear", shear);
  DeformRequest twist = spool_twist(Method::AnArap, mesh, 60.0, 0.1);
  twist.selection = apply_falloff(mesh, spool_above(mesh, 0.1), 0.35);
  scenes.emplace_back("twist", twist);
  return scenes;
}

}  // namespace

TEST_CASE("AnARAP's coupled rotations have a fixed point: 100 and 110 iterations agree; the paper's steps keep turning",
          "[figures][anarap]") {
  const Mesh mesh = test::load("closed/spool.off");
  const double diag = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  Deformer deformer(mesh);
  auto run = [&](DeformRequest request, RotationScheme scheme, int iterations) {
    request.method = Method::AnArap;
    request.rotations = scheme;
    request.max_iterations = iterations;
    request.rotation_steps = iterations;
    request.tolerance = 0.0;  // exactly that many iterations
    request.warm_start = false;
    return deformer.deform(request);
  };
  for (const auto& [name, request] : rotational_scenes(mesh)) {
    const DeformResult hundred = run(request, RotationScheme::Coupled, 100);
    const DeformResult more = run(request, RotationScheme::Coupled, 110);
    const double coupled_change = (more.V - hundred.V).rowwise().norm().maxCoeff() / diag;
    const double paper_change = (run(request, RotationScheme::Steps, 110).V -
                                 run(request, RotationScheme::Steps, 100).V).rowwise().norm().maxCoeff() / diag;
    WARN("coupled rotations, " << name << ": 100 -> 110 iterations move a vertex by at most " << coupled_change
                               << " of the diagonal (the paper's steps: " << paper_change << "); energy "
                               << hundred.energy << " -> " << more.energy << ", folded " << more.inverted);
    INFO(name);
    CHECK(coupled_change < 1e-4);
    CHECK(paper_change > 100 * coupled_change);
    // Each Gauss-Seidel sweep and each solve is exact: the energy never rises.
    for (std::size_t k = 1; k < more.energy_history.size(); ++k) {
      CHECK(more.energy_history[k] <= more.energy_history[k - 1] * (1.0 + 1e-9) + 1e-15);
    }
    CHECK(more.inverted == 0);
  }
}

TEST_CASE("AnARAP's coupled rotations reach the requested twist: within 5 % on the whole spool, 10 % with falloff",
          "[figures][anarap]") {
  const Mesh mesh = test::load("closed/spool.off");
  const std::vector<SpoolRing> rings = spool_rings(mesh);
  const double lo = mesh.V.col(kSpoolAxis).minCoeff();
  const double k = 60.0;
  Deformer deformer(mesh);
  DeformRequest whole = spool_twist(Method::AnArap, mesh, k, lo);
  whole.max_iterations = 300;
  const DeformResult r = deformer.deform(whole);
  const RingTurns t = spool_ring_turns(mesh, r.V, rings, Eigen::VectorXd());
  const double slope = fitted_slope(t.heights, t.turns);

  DeformRequest local = rotational_scenes(mesh).back().second;
  local.max_iterations = 300;
  const DeformResult rl = deformer.deform(local);
  const RingTurns tl = spool_ring_turns(mesh, rl.V, rings, local.selection);
  RingTurns full;
  for (std::size_t j = 0; j < tl.heights.size(); ++j) {
    if (tl.weights[j] < 1.0) continue;
    full.heights.push_back(tl.heights[j]);
    full.turns.push_back(tl.turns[j]);
  }
  REQUIRE(full.heights.size() >= 8);
  const double local_slope = fitted_slope(full.heights, full.turns);
  WARN("coupled rotations: twist " << slope << " deg/unit on the whole spool (" << r.iterations
                                   << " iterations, converged " << r.converged << "), " << local_slope
                                   << " on the selection with falloff (" << rl.iterations << " iterations) for k = "
                                   << k);
  CHECK(r.converged);
  CHECK(rl.converged);
  CHECK(slope == Approx(k).epsilon(0.05));
  // With a falloff the selected rings turn at 55 deg/unit whatever the
  // coupling (alpha 1 to 30: 55.1-55.4): the soft border holds the selection
  // back, not the rotations' coupling (AnDefGrad: 58).
  CHECK(local_slope == Approx(k).epsilon(0.1));
}

