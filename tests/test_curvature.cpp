// Principal curvatures and directions, checked against what the real meshes
// are: a torus (directions and curvatures known in closed form once its axis
// and radii are read off the data) and a knotted tube (the min-curvature
// direction runs along the tube).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <Eigen/Dense>

#include "directions/curvature.h"
#include "anisoform/deformer.h"
#include "anisoform/error.h"
#include "geometry/frames.h"
#include "mesh/topology.h"
#include "solver_test_support.h"
#include "test_support.h"

namespace {

using aniso::test::kPi;

// A torus described by its data: centre, axis (the direction of least
// variance of the vertices) and the radii of the big circle (R) and the tube (r).
struct TorusShape {
  Eigen::Vector3d center;
  Eigen::Vector3d axis;
  double R = 0.0;
  double r = 0.0;

  Eigen::Vector3d radial(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = p - center;
    return (q - q.dot(axis) * axis).normalized();
  }
  // Unit tangent of the big circle through p.
  Eigen::Vector3d big_circle_tangent(const Eigen::Vector3d& p) const { return axis.cross(radial(p)); }
  // cos of the angle around the tube (1 on the outer equator, -1 on the inner).
  double cos_around_tube(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d tube_center = center + R * radial(p);
    return (p - tube_center).normalized().dot(radial(p));
  }
};

TorusShape fit_torus(const aniso::Positions& V) {
  TorusShape torus;
  torus.center = V.colwise().mean().transpose();
  const Eigen::MatrixXd centered = V.rowwise() - torus.center.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(centered.transpose() * centered);
  torus.axis = pca.eigenvectors().col(0);  // eigenvalues ascending
  double rho_min = INFINITY;
  double rho_max = 0.0;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d q = V.row(i).transpose() - torus.center;
    const double rho = (q - q.dot(torus.axis) * torus.axis).norm();
    rho_min = std::min(rho_min, rho);
    rho_max = std::max(rho_max, rho);
  }
  torus.R = 0.5 * (rho_max + rho_min);
  torus.r = 0.5 * (rho_max - rho_min);
  return torus;
}

double fraction_where(const std::vector<double>& values, double limit, bool below) {
  const auto count = std::count_if(values.begin(), values.end(),
                                   [&](double v) { return below ? v < limit : v > limit; });
  return double(count) / double(values.size());
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Mean angle (radians) between the lines of neighbouring vertices.
double mean_neighbour_line_angle(const aniso::Mesh& mesh, const aniso::Positions& directions) {
  const aniso::VertexAdjacency adjacency = aniso::vertex_adjacency(mesh.F, mesh.num_vertices());
  double sum = 0.0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    for (int k = adjacency.offsets[i]; k < adjacency.offsets[i + 1]; ++k) {
      const double c = std::abs(directions.row(i).dot(directions.row(adjacency.neighbors[k])));
      sum += std::acos(std::min(1.0, c));
    }
  }
  return sum / double(adjacency.neighbors.size());
}

// The local tube axis at every vertex, independent of any curvature estimate:
// the normals of a tube's neighbourhood are all perpendicular to its axis, so
// the axis is the direction of least spread of the normals within three rings.
aniso::Positions tube_axes(const aniso::Mesh& mesh) {
  const aniso::Positions normals = aniso::vertex_normals(mesh);
  const aniso::VertexAdjacency adjacency = aniso::vertex_adjacency(mesh.F, mesh.num_vertices());
  aniso::Positions axes(mesh.num_vertices(), 3);
  std::vector<int> ring_of(mesh.num_vertices(), -1);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    std::vector<int> reached{i};
    ring_of[i] = 0;
    for (std::size_t head = 0; head < reached.size(); ++head) {
      const int v = reached[head];
      if (ring_of[v] == 3) continue;
      for (int k = adjacency.offsets[v]; k < adjacency.offsets[v + 1]; ++k) {
        const int w = adjacency.neighbors[k];
        if (ring_of[w] >= 0) continue;
        ring_of[w] = ring_of[v] + 1;
        reached.push_back(w);
      }
    }
    Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
    for (int v : reached) {
      spread += normals.row(v).transpose() * normals.row(v);
      ring_of[v] = -1;
    }
    axes.row(i) = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(spread).eigenvectors().col(0).transpose();
  }
  return axes;
}

void check_unit_tangent(const aniso::Mesh& mesh, const aniso::Positions& directions) {
  const aniso::Positions normals = aniso::vertex_normals(mesh);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    REQUIRE(directions.row(i).norm() == Approx(1.0).margin(1e-12));
    REQUIRE(std::abs(directions.row(i).dot(normals.row(i))) < 1e-12);
  }
}

}  // namespace

TEST_CASE("curvature: on a torus max directions follow the tube, min directions the big circle",
          "[curvature]") {
  const aniso::Mesh mesh = aniso::test::load("closed/torus.obj");
  const TorusShape torus = fit_torus(mesh.V);
  REQUIRE(torus.r > 0.1 * torus.R);

  const aniso::PrincipalCurvature pc = aniso::principal_curvature(mesh);
  check_unit_tangent(mesh, pc.max_direction);
  check_unit_tangent(mesh, pc.min_direction);

  // |cos| of the angle between each principal direction and the big circle.
  std::vector<double> max_along_big, min_along_big;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d t = torus.big_circle_tangent(mesh.V.row(i).transpose());
    max_along_big.push_back(std::abs(pc.max_direction.row(i).dot(t)));
    min_along_big.push_back(std::abs(pc.min_direction.row(i).dot(t)));
  }
  const double within_3_degrees = std::sin(3.0 * kPi / 180.0);
  INFO("R = " << torus.R << ", r = " << torus.r << "; within 3 degrees: max "
              << fraction_where(max_along_big, within_3_degrees, true) << ", min "
              << fraction_where(min_along_big, std::cos(3.0 * kPi / 180.0), false));
  CHECK(fraction_where(max_along_big, within_3_degrees, true) > 0.9);
  CHECK(fraction_where(min_along_big, std::cos(3.0 * kPi / 180.0), false) > 0.9);
}

TEST_CASE("curvature: torus curvatures are 1/r around the tube and cos/(R + r cos) along it",
          "[curvature]") {
  const aniso::Mesh mesh = aniso::test::load("closed/torus.obj");
  const TorusShape torus = fit_torus(mesh.V);
  const aniso::PrincipalCurvature pc = aniso::principal_curvature(mesh);

  std::vector<double> k_max_error, k_min_error;
  int sign_checked = 0, sign_right = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const double c = torus.cos_around_tube(mesh.V.row(i).transpose());
    const double k_along = c / (torus.R + torus.r * c);  // the big circle's normal curvature
    REQUIRE(pc.k_min[i] <= pc.k_max[i]);
    k_max_error.push_back(std::abs(pc.k_max[i] * torus.r - 1.0));
    k_min_error.push_back(std::abs(pc.k_min[i] - k_along) * torus.r);
    if (std::abs(c) > 0.3) {
      ++sign_checked;
      // Outer half convex (k_min > 0), inner half saddle-shaped (k_min < 0).
      if ((pc.k_min[i] > 0) == (c > 0)) ++sign_right;
    }
  }
  INFO("median |k_max r - 1| = " << median(k_max_error) << ", median |k_min - k_along| r = "
                                  << median(k_min_error));
  CHECK(median(k_max_error) < 0.03);
  CHECK(fraction_where(k_max_error, 0.1, true) > 0.95);
  CHECK(median(k_min_error) < 0.03);
  CHECK(sign_right == sign_checked);
}

TEST_CASE("curvature: curvatures scale with 1/size and directions do not change", "[curvature]") {
  aniso::Mesh mesh = aniso::test::load("closed/spot_triangulated.obj");
  const aniso::PrincipalCurvature original = aniso::principal_curvature(mesh);
  mesh.V *= 1e3;
  const aniso::PrincipalCurvature scaled = aniso::principal_curvature(mesh);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    CHECK(scaled.k_max[i] * 1e3 == Approx(original.k_max[i]).margin(1e-9 * std::abs(original.k_max[i]) + 1e-9));
    CHECK(scaled.k_min[i] * 1e3 == Approx(original.k_min[i]).margin(1e-9 * std::abs(original.k_min[i]) + 1e-9));
    if (original.k_max[i] - original.k_min[i] > 1e-3) {
      CHECK(std::abs(scaled.max_direction.row(i).dot(original.max_direction.row(i))) > 1.0 - 1e-9);
    }
  }
}

TEST_CASE("curvature: a flat mesh has zero curvature, and no principal direction field to give", "[curvature]") {
  const aniso::Mesh mesh = aniso::test::load("open/plane.off");
  const aniso::PrincipalCurvature pc = aniso::principal_curvature(mesh);
  CHECK(pc.k_min.cwiseAbs().maxCoeff() < 1e-12);
  CHECK(pc.k_max.cwiseAbs().maxCoeff() < 1e-12);
  check_unit_tangent(mesh, pc.min_direction);
  // Its "principal directions" are the eigen-solver's arbitrary choice: an
  // edit along them would silently go some way; it is refused instead.
  for (const aniso::CurvatureDirection which : {aniso::CurvatureDirection::Min, aniso::CurvatureDirection::Max}) {
    for (const int steps : {0, 5}) {
      CHECK_THROWS_WITH(aniso::curvature_direction_field(mesh, which, steps),
                        Catch::Contains("the surface has no principal curvature directions"));
    }
  }
  // Flat faces meeting at curved edges: the edges give the field its directions.
  const aniso::Mesh box = aniso::test::load("open/cube_no_bottom.obj");
  check_unit_tangent(box, aniso::curvature_direction_field(box, aniso::CurvatureDirection::Max, 5));
}

TEST_CASE("curvature: on a knotted tube the smoothed min direction runs along the tube", "[curvature]") {
  const aniso::Mesh mesh = aniso::test::load("closed/knot1.off");
  const aniso::Positions axes = tube_axes(mesh);
  const aniso::Positions raw = aniso::curvature_direction_field(mesh, aniso::CurvatureDirection::Min, 0);
  const aniso::Positions smooth = aniso::curvature_direction_field(mesh, aniso::CurvatureDirection::Min, 10);
  const aniso::Positions across = aniso::curvature_direction_field(mesh, aniso::CurvatureDirection::Max, 10);
  check_unit_tangent(mesh, smooth);
  check_unit_tangent(mesh, across);

  std::vector<double> along, across_axis;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    along.push_back(std::abs(smooth.row(i).dot(axes.row(i))));
    across_axis.push_back(std::abs(across.row(i).dot(axes.row(i))));
  }
  const double mean_along = std::accumulate(along.begin(), along.end(), 0.0) / along.size();
  const double mean_across = std::accumulate(across_axis.begin(), across_axis.end(), 0.0) / along.size();
  INFO("mean |d_min . axis| = " << mean_along << ", mean |d_max . axis| = " << mean_across);
  CHECK(mean_along > 0.97);
  CHECK(fraction_where(along, std::cos(10.0 * kPi / 180.0), false) > 0.9);
  CHECK(mean_across < 0.1);

  const double raw_angle = mean_neighbour_line_angle(mesh, raw);
  const double smooth_angle = mean_neighbour_line_angle(mesh, smooth);
  INFO("mean neighbour angle raw " << raw_angle * 180 / kPi << " deg, smoothed " << smooth_angle * 180 / kPi);
  CHECK(smooth_angle < raw_angle);  // the raw field of this clean tube is already smooth
}

TEST_CASE("curvature: smoothing makes a noisy organic field more coherent", "[curvature]") {
  const aniso::Mesh mesh = aniso::test::load("closed/cat-low-resolution.obj");
  const aniso::Positions raw = aniso::curvature_direction_field(mesh, aniso::CurvatureDirection::Min, 0);
  const aniso::Positions smooth = aniso::curvature_direction_field(mesh, aniso::CurvatureDirection::Min, 10);
  check_unit_tangent(mesh, smooth);
  const double raw_angle = mean_neighbour_line_angle(mesh, raw);
  const double smooth_angle = mean_neighbour_line_angle(mesh, smooth);
  INFO("mean neighbour angle raw " << raw_angle * 180 / kPi << " deg, smoothed " << smooth_angle * 180 / kPi);
  CHECK(smooth_angle < 0.6 * raw_angle);
}

TEST_CASE("curvature: smoothing steps outside 0..kMaxCurvatureSmoothing are refused", "[curvature]") {
  const aniso::Mesh mesh = aniso::test::load("open/plane.off");
  // 1e9 steps once ran for 12+ minutes inside one WASM call: without the
  // bound this test would not end within ctest's timeout.
  for (const int steps : {-1, aniso::kMaxCurvatureSmoothing + 1, 1000000000}) {
    try {
      aniso::curvature_direction_field(mesh, aniso::CurvatureDirection::Min, steps);
      FAIL("no error");
    } catch (const aniso::Error& e) {
      CHECK(e.code() == aniso::ErrorCode::BadParameter);
      CHECK_THAT(e.what(), Catch::Contains("smoothing steps must be an integer from 0 to 1000, got " +
                                           std::to_string(steps)));
    }
  }
  CHECK_NOTHROW(aniso::validate_curvature_smoothing(aniso::kMaxCurvatureSmoothing));
}

namespace {

aniso::Mesh wound_the_other_way(aniso::Mesh mesh) {
  mesh.F.col(1).swap(mesh.F.col(2));
  return mesh;
}

// Fraction of the mesh's edges whose two end vectors point opposite ways.
double opposite_sign_edge_fraction(const aniso::Mesh& mesh, const aniso::Positions& directions) {
  const aniso::VertexAdjacency adjacency = aniso::vertex_adjacency(mesh.F, mesh.num_vertices());
  int opposite = 0, edges = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    for (int k = adjacency.offsets[i]; k < adjacency.offsets[i + 1]; ++k) {
      const int j = adjacency.neighbors[k];
      if (j < i) continue;
      ++edges;
      if (directions.row(i).dot(directions.row(j)) < 0.0) ++opposite;
    }
  }
  return double(opposite) / double(edges);
}

}  // namespace

TEST_CASE("curvature: min and max are by magnitude, so they do not swap with the faces' winding", "[curvature]") {
  // Ordered by signed value, the knot's inward-wound copy had "min" around the
  // tube: x1.3 along it thickened the knot instead of lengthening it.
  const aniso::Mesh mesh = aniso::test::load("closed/knot1.off");
  const aniso::Mesh flipped = wound_the_other_way(mesh);
  const aniso::PrincipalCurvature pc = aniso::principal_curvature(mesh);
  const aniso::PrincipalCurvature pf = aniso::principal_curvature(flipped);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    REQUIRE(std::abs(pc.k_min[i]) <= std::abs(pc.k_max[i]));
    REQUIRE(pf.k_min[i] == Approx(-pc.k_min[i]).margin(1e-9 * std::abs(pc.k_max[i])));
    REQUIRE(pf.k_max[i] == Approx(-pc.k_max[i]).margin(1e-9 * std::abs(pc.k_max[i])));
  }
  for (const auto which : {aniso::CurvatureDirection::Min, aniso::CurvatureDirection::Max}) {
    for (const int steps : {0, 10}) {
      const aniso::Positions a = aniso::curvature_direction_field(mesh, which, steps);
      const aniso::Positions b = aniso::curvature_direction_field(flipped, which, steps);
      double worst = 1.0;
      for (int i = 0; i < mesh.num_vertices(); ++i) worst = std::min(worst, std::abs(a.row(i).dot(b.row(i))));
      INFO("steps " << steps << ": smallest |cos| between the two windings' lines " << worst);
      CHECK(worst > 1.0 - 1e-9);
    }
  }
  // The same edit on either gives the same shape: longer along the tube.
  aniso::DeformRequest request;
  request.method = aniso::Method::AnDefGrad;
  request.direction.kind = aniso::DirectionSource::Kind::CurvatureMin;
  request.transform.su = 1.3;
  const aniso::Positions as_given = aniso::Deformer(mesh).deform(request).V;
  const aniso::Positions reversed = aniso::Deformer(flipped).deform(request).V;
  const double size = aniso::test::diagonal(mesh.V);
  CHECK((as_given - reversed).rowwise().norm().maxCoeff() < 1e-6 * size);
  CHECK(aniso::test::diagonal(as_given) > 1.1 * size);
}

TEST_CASE("curvature: the field's signs agree across edges, so a shear along it stays whole", "[curvature]") {
  // The eigen-solver's signs were arbitrary per vertex: on the knot about a
  // twenty-fifth of the edges (406 of 9600) joined opposite signs.
  const aniso::Mesh knot = aniso::test::load("closed/knot1.off");
  for (const auto which : {aniso::CurvatureDirection::Min, aniso::CurvatureDirection::Max}) {
    for (const int steps : {0, 10}) {
      const double opposite = opposite_sign_edge_fraction(knot, aniso::curvature_direction_field(knot, which, steps));
      INFO((which == aniso::CurvatureDirection::Min ? "min" : "max") << ", steps " << steps
                                                                    << ": edges joining opposite signs " << opposite);
      CHECK(opposite < 0.002);  // a tube's lines are orientable: at most a few around the odd noisy vertex
    }
  }
  // Shear along the lines around an open cylinder, on its top half: each
  // ring turns as a whole and stays round. With arbitrary signs the top
  // ring's radius ranged over 0.47..1.53 (vertices sheared opposite ways).
  const aniso::Mesh cylinder = aniso::test::open_cylinder(48, 41, 1.0, 4.0);
  const aniso::Positions around = aniso::curvature_direction_field(cylinder, aniso::CurvatureDirection::Max, 10);
  CHECK(opposite_sign_edge_fraction(cylinder, around) == 0.0);
  aniso::DeformRequest request;
  request.method = aniso::Method::AnDefGrad;
  request.direction.kind = aniso::DirectionSource::Kind::CurvatureMax;
  request.transform.shear = 0.5;
  request.selection = (cylinder.V.col(2).array() >= 2.0).cast<double>().matrix();
  const aniso::Positions V = aniso::Deformer(cylinder).deform(request).V;
  Eigen::VectorXd top_radius(48);
  for (int s = 0; s < 48; ++s) {
    const Eigen::RowVector3d p = V.row(40 * 48 + s);
    top_radius[s] = std::hypot(p.x(), p.y());
  }
  INFO("top ring radius " << top_radius.minCoeff() << " .. " << top_radius.maxCoeff());
  CHECK(top_radius.maxCoeff() - top_radius.minCoeff() < 0.02 * top_radius.mean());
}

TEST_CASE("curvature: a field without clear principal directions over much of the selection is warned about",
          "[curvature]") {
  // A hemisphere is curved alike every way: its "min curvature" field follows
  // the triangulation. Before, only a surface exactly umbilic at every vertex
  // was refused, and this one was edited silently.
  const aniso::Mesh hemisphere = aniso::test::load("open/hemisphere.obj");
  const std::vector<char> lacking = aniso::lacks_principal_direction(hemisphere);
  const double share = double(std::count(lacking.begin(), lacking.end(), 1)) / double(lacking.size());
  INFO("hemisphere: share without a clear direction " << share);
  CHECK(share > 0.5);
  aniso::DeformRequest request;
  request.method = aniso::Method::AnDefGrad;
  request.direction.kind = aniso::DirectionSource::Kind::CurvatureMin;
  request.transform.su = 1.3;
  const aniso::DeformResult on_sphere = aniso::Deformer(hemisphere).deform(request);
  REQUIRE(on_sphere.warnings.size() == 1);
  const std::string percent = std::to_string(static_cast<int>(std::lround(100.0 * share))) + " % of the selected vertices";
  CHECK_THAT(on_sphere.warnings[0], Catch::StartsWith(percent) && Catch::Contains("no clear principal curvature direction"));

  // A tube has clear directions nearly everywhere: nothing to say.
  const aniso::Mesh knot = aniso::test::load("closed/knot1.off");
  CHECK(aniso::Deformer(knot).deform(request).warnings.empty());
  request.direction.kind = aniso::DirectionSource::Kind::CurvatureMax;
  CHECK(aniso::Deformer(aniso::test::load("closed/torus.obj")).deform(request).warnings.empty());

  // The CLI lists it with its other warnings.
  const std::string out = std::string(aniso::test::kScratchDir) + "/hemisphere_curvature.obj";
  const aniso::test::CliRun run = aniso::test::run_cli_expecting(
      {"deform", aniso::test::mesh_path("open/hemisphere.obj"), out, "--method", "andefgrad", "--direction",
       "curvature:min", "--scale", "1.3"},
      0);
  CHECK_THAT(run.out, Catch::Contains(percent) && Catch::Contains("no clear principal curvature direction"));
}
