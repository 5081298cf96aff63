// Garment flattening (flatten.h): the exact oracles of METHOD §9 on developable
// patches built procedurally (a cylinder and a cone piece: exact math, not
// test data), the planar mesh that must stay itself, the paper's claim (ours
// reaches the wanted compression where the uniform baseline does not) on a
// cone and on the real torso panel, no folds on any real open mesh, and the
// CLI contract of `anisoform flatten`.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>
#include <sys/wait.h>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "anisoform/error.h"
#include "anisoform/op.h"
#include "flatten/flatten_pipeline.h"
#include "cli_runner.h"
#include "figure_record.h"
#include "test_support.h"

namespace {

using namespace aniso;

using aniso::test::kPi;

// A (rows+1) x (cols+1) vertex grid over [0,1]^2 mapped by `surface`, two
// triangles per cell, counter-clockwise in (s, t).
Mesh grid_surface(int cols, int rows, const std::function<Eigen::Vector3d(double, double)>& surface) {
  Mesh mesh;
  mesh.V.resize((cols + 1) * (rows + 1), 3);
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= cols; ++i) {
      mesh.V.row(j * (cols + 1) + i) = surface(double(i) / cols, double(j) / rows).transpose();
    }
  }
  mesh.F.resize(2 * cols * rows, 3);
  int t = 0;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      const int a = j * (cols + 1) + i, b = a + 1, c = a + cols + 1, d = c + 1;
      mesh.F.row(t++) << a, b, d;
      mesh.F.row(t++) << a, d, c;
    }
  }
  return mesh;
}

// Part of a cylinder of radius 1 along z: 2 rad around, 2 high.
Mesh cylinder_piece() {
  return grid_surface(30, 20, [](double s, double t) {
    const double angle = 2.0 * s;
    return Eigen::Vector3d(std::cos(angle), std::sin(angle), 2.0 * t);
  });
}

// Part of a cone with its apex at the origin, axis z, half-angle 30 degrees:
// generator distance 1..3 from the apex, 3 rad around (a 1.5 rad sector flat).
constexpr double kConeHalfAngle = kPi / 6.0;
Mesh cone_piece() {
  return grid_surface(36, 16, [](double s, double t) {
    const double around = 3.0 * s, distance = 1.0 + 2.0 * t;
    return Eigen::Vector3d(distance * std::sin(kConeHalfAngle) * std::cos(around),
                           distance * std::sin(kConeHalfAngle) * std::sin(around),
                           distance * std::cos(kConeHalfAngle));
  });
}

// The cone's generators at every vertex (a dense field: used as is). In the
// pattern they fan out over the sector, so no single 2D direction fits them.
std::vector<DirectionConstraint> cone_generators(const Mesh& cone) {
  std::vector<DirectionConstraint> field;
  for (int i = 0; i < cone.num_vertices(); ++i) {
    DirectionConstraint c;
    c.vertex = i;
    c.direction = cone.V.row(i).transpose().normalized();
    field.push_back(c);
  }
  return field;
}

double max_relative_edge_change(const Mesh& mesh, const Eigen::MatrixX2d& uv) {
  double worst = 0.0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(t, k), b = mesh.F(t, (k + 1) % 3);
      const double rest = (mesh.V.row(a) - mesh.V.row(b)).norm();
      const double flat = (uv.row(a) - uv.row(b)).norm();
      worst = std::max(worst, std::abs(flat / rest - 1.0));
    }
  }
  return worst;
}

FlattenOptions dense_field_options(const std::vector<DirectionConstraint>& field, double su,
                                   FlattenMethod method) {
  FlattenOptions options;
  options.method = method;
  options.su = su;
  options.directions.kind = FlattenDirections::Kind::Constraints;
  options.directions.constraints = field;
  return options;
}

// The vertex nearest to (x, y) in the xy-plane (the torso panel faces +z).
// Per patch vertex, the area-weighted mean over its triangles of the
// compression error |achieved / wanted - 1| (what the app's heat map shows).
Eigen::VectorXd fig11_vertex_error(const FlattenPatch& patch, const TriangleCharts& charts, const FlattenResult& r) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(patch.mesh.num_vertices()), area = sum;
  for (int t = 0; t < patch.mesh.num_triangles(); ++t) {
    const double error = std::abs(r.stretch.along[t] / r.targets.su[t] - 1.0);
    if (!std::isfinite(error)) continue;
    for (int k = 0; k < 3; ++k) {
      sum[patch.mesh.F(t, k)] += charts.area[t] * error;
      area[patch.mesh.F(t, k)] += charts.area[t];
    }
  }
  return sum.cwiseQuotient(area.cwiseMax(1e-300));
}

// The gallery's pictures of Fig. 11: the panel in 3D and both flat patterns,
// coloured by the compression error; the arrows' vertices are marked.
void record_fig11(const Flattener& flattener, const std::vector<DirectionConstraint>& arrows,
                  const FlattenResult& ours, const FlattenResult& baseline) {
  const FlattenPatch& patch = flattener.patch();
  Eigen::VectorXd marked = Eigen::VectorXd::Zero(patch.mesh.num_vertices());
  for (const DirectionConstraint& arrow : arrows) {
    for (int p = 0; p < patch.mesh.num_vertices(); ++p) marked[p] = patch.input_vertex[p] == arrow.vertex ? 1.0 : marked[p];
  }
  test::record_figure_mesh("11-rest", patch.mesh.V, patch.mesh.F, marked);
  for (const auto& [name, result] : {std::pair{"ours", &ours}, std::pair{"baseline", &baseline}}) {
    const Eigen::VectorXd error = fig11_vertex_error(patch, flattener.charts(), *result);
    test::record_figure_mesh(std::string("11-") + name + "-3d", patch.mesh.V, patch.mesh.F, Eigen::VectorXd(), error,
                             "compression");
    test::record_figure_mesh(std::string("11-") + name + "-pattern", result->uv, patch.mesh.F, Eigen::VectorXd(), error,
                             "compression");
    const std::string key = std::string("11.") + name;
    test::record_figure_value(key + ".compression_error_mean", result->metrics.compression_error_mean);
    test::record_figure_value(key + ".compression_error_max", result->metrics.compression_error_max);
    test::record_figure_value(key + ".cross_error_mean", result->metrics.cross_error_mean);
    test::record_figure_value(key + ".flipped", result->metrics.flipped);
    test::record_figure_value(key + ".iterations", result->metrics.iterations);
  }
}

int nearest_vertex_xy(const Mesh& mesh, double x, double y) {
  int best = 0;
  double best_distance = HUGE_VAL;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const double distance = std::hypot(mesh.V(i, 0) - x, mesh.V(i, 1) - y);
    if (distance < best_distance) {
      best_distance = distance;
      best = i;
    }
  }
  return best;
}

}  // namespace

TEST_CASE("flatten: a cylinder piece flattens isometrically with su = sv = 1", "[flatten]") {
  const Mesh cylinder = cylinder_piece();
  const FlattenOutput out = flatten(cylinder, {}, FlattenOptions{});
  CHECK(out.result.metrics.flipped == 0);
  CHECK(out.result.metrics.boundary_loops == 1);
  CHECK(max_relative_edge_change(out.patch.mesh, out.result.uv) < 1e-6);
  CHECK(out.result.metrics.compression_error_max < 1e-6);
  CHECK(out.result.metrics.area_distortion_mean < 1e-6);
}

TEST_CASE("flatten: a cone piece flattens isometrically with su = sv = 1", "[flatten]") {
  const Mesh cone = cone_piece();
  const FlattenOutput out = flatten(cone, {}, FlattenOptions{});
  CHECK(out.result.metrics.flipped == 0);
  CHECK(max_relative_edge_change(out.patch.mesh, out.result.uv) < 1e-6);
}

TEST_CASE("flatten: su = 0.8 along a cone's generators is reached, and the uniform baseline is 3x worse",
          "[flatten]") {
  const Mesh cone = cone_piece();
  const auto field = cone_generators(cone);
  Flattener flattener(cone);
  const FlattenResult ours =
      flattener.flatten(dense_field_options(field, 0.8, FlattenMethod::Anisotropic));
  const FlattenResult baseline =
      flattener.flatten(dense_field_options(field, 0.8, FlattenMethod::UniformBaseline));
  std::printf("[flatten] cone su=0.8 along generators: ours mean %.5f max %.5f (cross mean %.5f, "
              "%d it, %.3f s) | baseline mean %.5f max %.5f (cross mean %.5f)\n",
              ours.metrics.compression_error_mean, ours.metrics.compression_error_max,
              ours.metrics.cross_error_mean, ours.metrics.iterations, ours.metrics.seconds,
              baseline.metrics.compression_error_mean, baseline.metrics.compression_error_max,
              baseline.metrics.cross_error_mean);
  CHECK(ours.metrics.flipped == 0);
  CHECK(baseline.metrics.flipped == 0);
  CHECK(ours.metrics.compression_error_mean <= 0.01);
  CHECK(ours.metrics.compression_error_max <= 0.01);  // everywhere, not just on average
  CHECK(baseline.metrics.compression_error_mean >= 3.0 * ours.metrics.compression_error_mean);
  // The target metric 0.64 dr^2 + r^2 dphi^2 is flat (a wider sector), so
  // ours reaches it exactly up to the iteration tolerance, across too.
  CHECK(ours.metrics.cross_error_mean <= 0.01);
  CHECK(flattener.factorizations() == 1);
}

TEST_CASE("flatten: the results hold at 1e-4 and 1e4 model scale", "[flatten]") {
  const Mesh cone = cone_piece();
  const auto field = cone_generators(cone);
  for (double scale : {1e-4, 1e4}) {
    Mesh scaled = cone;
    scaled.V *= scale;
    const FlattenOutput out =
        flatten(scaled, {}, dense_field_options(field, 0.8, FlattenMethod::Anisotropic));
    INFO("scale " << scale);
    CHECK(out.result.metrics.flipped == 0);
    CHECK(out.result.metrics.compression_error_mean <= 0.01);
  }
}

TEST_CASE("flatten: open/plane.off stays itself up to a rigid motion", "[flatten]") {
  const Mesh plane = test::load("open/plane.off");
  const FlattenOutput out = flatten(plane, {}, FlattenOptions{});
  REQUIRE(out.result.metrics.flipped == 0);
  // The plane's own 2D coordinates in the chart of triangle 0 (same
  // orientation), then the best 2D rotation + translation onto uv.
  const Mesh& mesh = out.patch.mesh;
  const TriangleCharts charts = triangle_charts(mesh);
  const Eigen::Vector3d axis_u = charts.axis_u.row(0), axis_v = charts.axis_v.row(0);
  Eigen::MatrixX2d rest(mesh.num_vertices(), 2);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d p = mesh.V.row(i);
    rest.row(i) = Eigen::RowVector2d(p.dot(axis_u), p.dot(axis_v));
  }
  const Eigen::RowVector2d rest_mean = rest.colwise().mean(), flat_mean = out.result.uv.colwise().mean();
  const Eigen::MatrixX2d P = rest.rowwise() - rest_mean, Q = out.result.uv.rowwise() - flat_mean;
  const Eigen::Matrix2d S = Q.transpose() * P;  // rotation maximizing tr(R^T S)
  const double angle = std::atan2(S(1, 0) - S(0, 1), S(0, 0) + S(1, 1));
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(angle).toRotationMatrix();
  const Eigen::MatrixX2d aligned = P * R.transpose();
  const double diameter = (rest.colwise().maxCoeff() - rest.colwise().minCoeff()).norm();
  CHECK((aligned - Q).rowwise().norm().maxCoeff() <= 1e-9 * diameter);
}

TEST_CASE("flatten: a plane with su along a global direction is exactly diag(su, 1), baseline too",
          "[flatten]") {
  const Mesh plane = test::load("open/plane.off");
  Flattener flattener(plane);
  FlattenOptions options;
  options.su = 0.8;
  options.directions.global = Eigen::Vector3d(1.0, 0.0, 1.0);  // in the plane y = 0
  for (FlattenMethod method : {FlattenMethod::Anisotropic, FlattenMethod::UniformBaseline}) {
    options.method = method;
    const FlattenResult result = flattener.flatten(options);
    INFO(result.metrics.method);
    CHECK(result.metrics.flipped == 0);
    CHECK(result.metrics.compression_error_max <= 1e-9);
    CHECK(result.metrics.cross_error_max <= 1e-9);
    CHECK(result.metrics.area_distortion_mean <= 1e-9);
  }
}

TEST_CASE("flatten: no folded triangle on any open mesh", "[flatten]") {
  // Boundary loop counts from the MANIFEST. stanford-bunny (69k triangles,
  // 5 small holes: nearly closed) folds under LSCM, so it takes the fold-free
  // Tutte start; it is the slowest case here, a few seconds.
  const std::vector<std::pair<std::string, int>> meshes = {
      {"open/cube_no_bottom.obj", 1},       {"open/demosthenes-low-res.obj", 1},
      {"open/hand_lowres.obj", 1},          {"open/hemisphere.obj", 1},
      {"open/human_woman_torso_front_patch.obj", 1}, {"open/nefertiti_face.off", 1},
      {"open/plane.off", 1},                {"open/spothead.obj", 1},
      {"open/stanford-bunny.obj", 5},
  };
  // Folds are what is checked, at any iteration of either stage: a cap of
  // 40 keeps the refinement's Newton steps (a factorization each) few. On
  // demosthenes and the bunny a step takes most of a second under the
  // sanitizers: they are checked without the refinement here (its result
  // on them is fold-free in the README's survey, and its folds are checked
  // to convergence on the other meshes in test_flatten_cut_regions).
  FlattenOptions options;
  options.solver.max_iterations = 40;
  for (const auto& [name, loops] : meshes) {
    options.solver.refine = name != "open/demosthenes-low-res.obj" && name != "open/stanford-bunny.obj";
    const Mesh mesh = test::load(name);
    const FlattenOutput out = flatten(mesh, {}, options);
    const FlattenMetrics& m = out.result.metrics;
    std::printf("[flatten] %-42s %6d tris %d loops: flipped %d, %3d it (%s start%s), %.3f s\n",
                name.c_str(), m.triangles, m.boundary_loops, m.flipped, m.iterations,
                m.initialization.c_str(), m.converged ? "" : ", not converged", m.seconds);
    INFO(name);
    CHECK(m.flipped == 0);
    CHECK(m.boundary_loops == loops);
    CHECK(out.result.uv.allFinite());
  }
}

TEST_CASE("flatten: the fold guard keeps hard anisotropic targets fold-free", "[flatten]") {
  // su = 0.5 along global x on curved, non-developable patches: targets that
  // no flat map meets, where unguarded ARAP folds triangles over.
  for (const char* name : {"open/hand_lowres.obj", "open/spothead.obj", "open/hemisphere.obj"}) {
    const Mesh mesh = test::load(name);
    FlattenOptions options;
    options.su = 0.5;
    options.solver.max_iterations = 80;  // folds are checked at any iteration; this keeps it short
    const FlattenOutput out = flatten(mesh, {}, options);
    INFO(name);
    CHECK(out.result.metrics.flipped == 0);
  }
}

TEST_CASE("flatten (fig. 11): the torso panel's curving compression band is met within a bound and beats the uniform baseline",
          "[flatten]") {
  const Mesh torso = test::load("open/human_woman_torso_front_patch.obj");
  // An under-bust band: 20 % shrinkage along a horizontal-ish line that sags
  // in the middle (a smile-shaped curve), given by four arrows.
  std::vector<DirectionConstraint> arrows(4);
  const double points[4][2] = {{-0.12, 1.10}, {-0.04, 1.04}, {0.04, 1.04}, {0.12, 1.10}};
  const double directions[4][2] = {{1.0, -0.6}, {1.0, -0.2}, {1.0, 0.2}, {1.0, 0.6}};
  for (int k = 0; k < 4; ++k) {
    arrows[k].vertex = nearest_vertex_xy(torso, points[k][0], points[k][1]);
    arrows[k].direction = Eigen::Vector3d(directions[k][0], directions[k][1], 0.0);
  }
  Flattener flattener(torso);
  FlattenOptions options;
  options.su = 0.8;
  options.directions.kind = FlattenDirections::Kind::Constraints;
  options.directions.constraints = arrows;
  const FlattenResult ours = flattener.flatten(options);
  options.method = FlattenMethod::UniformBaseline;
  const FlattenResult baseline = flattener.flatten(options);
  std::printf("[flatten] torso panel band su=0.8 (4 arrows): ours mean %.5f max %.5f cross %.5f "
              "area %.5f (%d it, %.3f s) | baseline mean %.5f max %.5f cross %.5f area %.5f\n",
              ours.metrics.compression_error_mean, ours.metrics.compression_error_max,
              ours.metrics.cross_error_mean, ours.metrics.area_distortion_mean,
              ours.metrics.iterations, ours.metrics.seconds, baseline.metrics.compression_error_mean,
              baseline.metrics.compression_error_max, baseline.metrics.cross_error_mean,
              baseline.metrics.area_distortion_mean);
  if (!test::figures_dir().empty()) record_fig11(flattener, arrows, ours, baseline);
  CHECK(ours.metrics.flipped == 0);
  CHECK(baseline.metrics.flipped == 0);
  CHECK(ours.metrics.compression_error_mean < baseline.metrics.compression_error_mean);
  CHECK(ours.metrics.compression_error_max < baseline.metrics.compression_error_max);
  // Stated bounds on ours (measured 0.0089 mean, 0.124 max with the stretch
  // refinement, 0.0354 and 0.141 without; baseline 0.067, 0.255).
  CHECK(ours.metrics.compression_error_mean < 0.015);
  CHECK(ours.metrics.compression_error_max < 0.15);
}

namespace {

// The ARAP phase's inputs for a whole mesh with one global direction: the
// patch, its charts and targets, and the LSCM start scaled to the wanted area.
struct ArapProblem {
  FlattenPatch patch;
  TriangleCharts charts;
  FlattenTargets targets;
  Eigen::MatrixX2d start;

  ArapProblem(const Mesh& mesh, const Eigen::Vector3d& direction, double su, double sv)
      : patch(extract_flatten_patch(mesh, {})), charts(triangle_charts(patch.mesh)) {
    FlattenDirections directions;
    directions.global = direction;
    targets = flatten_targets(mesh, patch, charts, TriangleNeighbours(patch), directions, su, sv);
    lscm_free_boundary(patch, charts, start);
    scale_to_area(patch, charts.area.cwiseProduct(targets.su).cwiseProduct(targets.sv), start);
  }
};

}  // namespace

TEST_CASE("flatten: the energy decreases monotonically over the iterations", "[flatten]") {
  const ArapProblem problem(test::load("open/human_woman_torso_front_patch.obj"), Eigen::Vector3d(1.0, 0.3, 0.0),
                            0.8, 1.1);
  const auto& [patch, charts, targets, uv] = problem;
  const ArapFlattening arap(patch, charts);
  for (const bool accelerate : {false, true}) {
    INFO("L-BFGS: " << accelerate);
    ArapFlattenSettings settings;
    settings.accelerate = accelerate;
    Eigen::MatrixX2d solved = uv;
    const ArapFlattenReport report = arap.solve(targets, settings, solved);
    REQUIRE(report.energy_history.size() >= 3);
    for (std::size_t k = 1; k < report.energy_history.size(); ++k) {
      CHECK(report.energy_history[k] <= report.energy_history[k - 1] * (1.0 + 1e-12));
    }
    CHECK(report.energy_history.back() < 0.5 * report.energy_history.front());
    CHECK(count_folded(patch.mesh.F, charts, solved) == 0);
  }
}

// L-BFGS on the ARAP energy (flatten_arap.cpp) against the plain
// local/global iterations, from the same LSCM start to the same tolerance.
TEST_CASE("flatten: L-BFGS reaches the plain iterations' energy in a fraction of them", "[flatten]") {
  for (const char* name : {"open/human_woman_torso_front_patch.obj", "open/nefertiti_face.off", "open/hemisphere.obj"}) {
    INFO(name);
    const ArapProblem problem(test::load(name), Eigen::Vector3d(0.0, 1.0, 0.2), 0.8, 1.0);
    const auto& [patch, charts, targets, start] = problem;
    const ArapFlattening arap(patch, charts);
    ArapFlattenSettings settings;
    settings.accelerate = false;
    Eigen::MatrixX2d plain_uv = start, lbfgs_uv = start;
    const ArapFlattenReport plain = arap.solve(targets, settings, plain_uv);
    settings.accelerate = true;
    const ArapFlattenReport lbfgs = arap.solve(targets, settings, lbfgs_uv);
    std::printf("[flatten] %s ARAP phase to 1e-8: plain %d iterations, L-BFGS %d, energy L-BFGS/plain - 1 = %.2e\n",
                name, plain.iterations, lbfgs.iterations, lbfgs.energy / plain.energy - 1.0);
    CHECK(plain.converged);
    CHECK(lbfgs.converged);
    CHECK(lbfgs.folded == 0);
    CHECK(std::abs(lbfgs.energy / plain.energy - 1.0) < 1e-6);
    CHECK(2 * lbfgs.iterations <= plain.iterations);  // measured 3.3x, 2.8x, 2.5x fewer
    // The same map up to a rotation (the energy has no preferred one): the
    // achieved stretches agree.
    const TriangleStretch a = measure_stretch(patch.mesh.F, charts, targets, plain_uv);
    const TriangleStretch b = measure_stretch(patch.mesh.F, charts, targets, lbfgs_uv);
    CHECK((a.along - b.along).cwiseAbs().maxCoeff() < 1e-3);
    CHECK((a.across - b.across).cwiseAbs().maxCoeff() < 1e-3);
  }
}

// A tolerance of 0 means "to round-off" (kRoundOffDecrease): the
// local/global stage used to wait for an exactly zero change, which native
// code met on the hemisphere after 90 iterations and WASM never did (its
// 1000 iterations went to this stage, and the refinement never ran).
TEST_CASE("flatten: with tolerance 0 the local/global stage stops at round-off, where a tolerance of 1e-11 does",
          "[flatten]") {
  const Mesh hemisphere = test::load("open/hemisphere.obj");
  const ArapProblem problem(hemisphere, longest_axis(bounding_box(hemisphere.V)), 0.8, 1.0);
  const auto& [patch, charts, targets, start] = problem;
  const ArapFlattening arap(patch, charts);
  for (const bool accelerate : {false, true}) {
    INFO("L-BFGS: " << accelerate);
    ArapFlattenSettings settings;
    settings.accelerate = accelerate;
    settings.tolerance = 0.0;
    Eigen::MatrixX2d exact_uv = start, round_off_uv = start;
    const ArapFlattenReport exact = arap.solve(targets, settings, exact_uv);
    settings.tolerance = kRoundOffDecrease;
    const ArapFlattenReport round_off = arap.solve(targets, settings, round_off_uv);
    INFO("tolerance 0: " << exact.iterations << " iterations; 1e-11: " << round_off.iterations);
    CHECK(exact.converged);
    CHECK(exact.iterations < settings.max_iterations);
    CHECK(exact.energy == round_off.energy);
    CHECK(exact_uv == round_off_uv);
    // And not before: the last step gained no more than round-off.
    const std::vector<double>& history = exact.energy_history;
    REQUIRE(history.size() >= 2);
    CHECK(history[history.size() - 2] - history.back() <= kRoundOffDecrease * history[history.size() - 2]);
  }
}

// Where the fold guard cuts the steps short, L-BFGS must not stall above
// where plain steps stall: the hand (su 0.8 along its longest axis), whose
// every step the guard cuts, ended 3.3 % above plain's energy when the pairs
// of cut steps were kept (flatten_arap.cpp).
TEST_CASE("flatten: where the fold guard cuts every step, L-BFGS ends no higher than the plain iterations",
          "[flatten]") {
  const Mesh hand = test::load("open/hand_lowres.obj");
  const ArapProblem problem(hand, longest_axis(bounding_box(hand.V)), 0.8, 1.0);
  const auto& [patch, charts, targets, start] = problem;
  const ArapFlattening arap(patch, charts);
  ArapFlattenSettings settings;
  settings.tolerance = 1e-6;
  settings.accelerate = false;
  Eigen::MatrixX2d plain_uv = start, lbfgs_uv = start;
  const ArapFlattenReport plain = arap.solve(targets, settings, plain_uv);
  settings.accelerate = true;
  const ArapFlattenReport lbfgs = arap.solve(targets, settings, lbfgs_uv);
  INFO("plain: " << plain.iterations << " iterations, " << plain.shortened_steps << " cut short, E " << plain.energy
                 << "; L-BFGS: " << lbfgs.iterations << ", " << lbfgs.shortened_steps << ", E " << lbfgs.energy);
  REQUIRE(plain.shortened_steps == plain.iterations);  // the case this is about
  CHECK(lbfgs.folded == 0);
  CHECK(lbfgs.energy <= plain.energy * (1.0 + 1e-9));
}

TEST_CASE("flatten: one factorization serves every amount, direction and method", "[flatten]") {
  const Mesh torso = test::load("open/human_woman_torso_front_patch.obj");
  Flattener flattener(torso);
  FlattenOptions options;
  for (double su : {1.0, 0.9, 0.8}) {
    options.su = su;
    options.directions.global = Eigen::Vector3d(1.0, su, 0.0);
    options.method = su < 0.85 ? FlattenMethod::UniformBaseline : FlattenMethod::Anisotropic;
    flattener.flatten(options);
  }
  CHECK(flattener.factorizations() == 1);
}

TEST_CASE("flatten: a selection flattens only its faces, and unreferenced vertices are ignored",
          "[flatten]") {
  const Mesh plane = test::load("open/plane.off");
  std::vector<char> mask(plane.num_vertices(), 0);
  for (int i = 0; i < plane.num_vertices(); ++i) mask[i] = plane.V(i, 0) < 0.0;  // half the square
  const FlattenOutput out = flatten(plane, mask, FlattenOptions{});
  CHECK(out.result.metrics.flipped == 0);
  CHECK(out.result.metrics.triangles < plane.num_triangles());
  for (int i = 0; i < out.patch.mesh.num_vertices(); ++i) CHECK(mask[out.patch.input_vertex[i]]);
  CHECK(max_relative_edge_change(out.patch.mesh, out.result.uv) < 1e-9);

  Mesh with_extra = plane;  // a vertex no face uses, far away
  with_extra.V.conservativeResize(plane.num_vertices() + 1, 3);
  with_extra.V.row(plane.num_vertices()) << 1e6, 1e6, 1e6;
  const FlattenOutput extra = flatten(with_extra, {}, FlattenOptions{});
  CHECK(extra.patch.mesh.num_vertices() == plane.num_vertices());
  CHECK(extra.result.metrics.flipped == 0);
}

TEST_CASE("flatten: several components are flattened each and laid out without overlap",
          "[flatten]") {
  const Mesh cylinder = cylinder_piece();
  const Mesh cone = cone_piece();
  Mesh both;
  both.V.resize(cylinder.num_vertices() + cone.num_vertices(), 3);
  both.V << cylinder.V, cone.V;
  both.F.resize(cylinder.num_triangles() + cone.num_triangles(), 3);
  both.F << cylinder.F, (cone.F.array() + cylinder.num_vertices()).matrix();
  const FlattenOutput out = flatten(both, {}, FlattenOptions{});
  REQUIRE(out.patch.num_components == 2);
  CHECK(out.result.metrics.flipped == 0);
  CHECK(out.result.metrics.boundary_loops == 2);
  CHECK(max_relative_edge_change(out.patch.mesh, out.result.uv) < 1e-6);
  Eigen::RowVector2d lo[2], hi[2];
  for (int c = 0; c < 2; ++c) {
    lo[c] = Eigen::RowVector2d::Constant(HUGE_VAL);
    hi[c] = Eigen::RowVector2d::Constant(-HUGE_VAL);
  }
  for (int i = 0; i < out.patch.mesh.num_vertices(); ++i) {
    const int c = out.patch.component[i];
    lo[c] = lo[c].cwiseMin(out.result.uv.row(i));
    hi[c] = hi[c].cwiseMax(out.result.uv.row(i));
  }
  const bool apart = hi[0].x() < lo[1].x() || hi[1].x() < lo[0].x() || hi[0].y() < lo[1].y() ||
                     hi[1].y() < lo[0].y();
  CHECK(apart);
}

TEST_CASE("flatten: a closed mesh or patch is refused with a clear message", "[flatten]") {
  const Mesh torus = test::load("closed/torus.obj");
  try {
    flatten(torus, {}, FlattenOptions{});
    FAIL("a closed mesh was flattened");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::BadMesh);
    CHECK(std::string(e.what()).find("the patch is closed: flattening needs a boundary") !=
          std::string::npos);
  }
  const Mesh plane = test::load("open/plane.off");
  std::vector<char> nothing(plane.num_vertices(), 0);
  nothing[0] = 1;
  CHECK_THROWS_AS(flatten(plane, nothing, FlattenOptions{}), Error);
  FlattenOptions bad;
  bad.su = 0.0;
  CHECK_THROWS_AS(flatten(plane, {}, bad), Error);
}

TEST_CASE("flatten: a direction constraint outside the patch is refused", "[flatten]") {
  const Mesh plane = test::load("open/plane.off");
  std::vector<char> mask(plane.num_vertices(), 0);
  int outside = -1;
  for (int i = 0; i < plane.num_vertices(); ++i) {
    mask[i] = plane.V(i, 0) < 0.0;
    if (!mask[i]) outside = i;
  }
  FlattenOptions options;
  options.directions.kind = FlattenDirections::Kind::Constraints;
  DirectionConstraint arrow;
  arrow.vertex = outside;
  options.directions.constraints = {arrow};
  try {
    flatten(plane, mask, options);
    FAIL("a constraint outside the patch was accepted");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::BadParameter);
  }
}

// ---- the CLI contract ------------------------------------------------------

namespace {

using test::CliRun;
using test::run_cli;
using test::slurp;
using test::count_of;

std::string temp_file(const std::string& name) { return test::temp_path("flatten_" + name); }

}  // namespace

TEST_CASE("flatten CLI: pattern files, JSON keys and exit statuses", "[flatten][cli]") {
  const std::string torso = test::mesh_path("open/human_woman_torso_front_patch.obj");
  const std::vector<std::string> keys = {
      "triangles", "boundary_loops", "flipped", "compression_error_mean", "compression_error_max",
      "cross_error_mean", "area_distortion_mean", "iterations", "seconds"};

  SECTION("SVG, DXF and OBJ outputs") {
    for (const std::string extension : {".svg", ".dxf", ".obj"}) {
      const std::string out = temp_file("torso" + extension);
      const CliRun run = run_cli({"flatten", torso, out, "--compress", "0.8", "--direction",
                                     "global:1,0,0", "--mm-per-unit", "1000"});
      INFO(extension << ": " << run.err);
      REQUIRE(run.exit_status == 0);
      REQUIRE(count_of(run.out, "\n") == 1);
      const nlohmann::json json = nlohmann::json::parse(run.out);
      for (const std::string& key : keys) CHECK(json.contains(key));
      CHECK(json["triangles"] == 972);
      CHECK(json["boundary_loops"] == 1);
      CHECK(json["flipped"] == 0);
      const std::string text = slurp(out);
      if (extension == ".svg") CHECK(count_of(text, "<path class=\"outline\"") == 1);
      if (extension == ".dxf") CHECK(count_of(text, "\nPOLYLINE\n") == 1);
      if (extension == ".obj") {
        CHECK(count_of(text, "\nvt ") == 531);
        CHECK(count_of(text, "\nf ") == 972);
        CHECK(text.find("/") != std::string::npos);
      }
      std::remove(out.c_str());
    }
  }

  SECTION("the uniform baseline with a field file") {
    const std::string field = temp_file("band.txt");
    std::ofstream(field) << "# two arrows\n10 1 0 0 0.8 1\n200 1 0.3 0 0.8\n";
    const std::string out = temp_file("baseline.svg");
    const CliRun run =
        run_cli({"flatten", torso, out, "--direction", "field:" + field, "--baseline", "uniform"});
    INFO(run.err);
    REQUIRE(run.exit_status == 0);
    const nlohmann::json json = nlohmann::json::parse(run.out);
    CHECK(json["method"] == "uniform-baseline");
    CHECK(json["flipped"] == 0);
    std::remove(out.c_str());
    std::remove(field.c_str());
  }

  SECTION("a closed mesh exits 3 with the reason") {
    const CliRun run =
        run_cli({"flatten", test::mesh_path("closed/torus.obj"), temp_file("torus.svg")});
    CHECK(run.exit_status == 3);
    CHECK(run.err.find("the patch is closed") != std::string::npos);
    CHECK(run.out.empty());
  }

  SECTION("a patch whose zero-area triangles leave no conformal start says which") {
    const CliRun run = run_cli({"flatten", test::mesh_path("malformed/degtri_sliding.off"), temp_file("degenerate.svg")});
    CHECK(run.exit_status == 3);
    CHECK(run.err.find("(LSCM): the patch has 4 zero-area triangle(s) (faces 2, 3, 4 ...)") != std::string::npos);
  }

  SECTION("--mm-per-unit out of range is refused up front, naming it, whatever the output") {
    // 1e308 and 1e-320 were taken for an .obj pattern (exit 0), and refused
    // for .svg and .dxf only after the flattening, without the option's name.
    const std::string plane = test::mesh_path("open/plane.off");
    for (const std::string& name : {"scale.obj", "scale.svg", "scale.dxf"}) {
      for (const auto& [given, shown] : std::vector<std::pair<std::string, std::string>>{
               {"1e308", "1e+308"}, {"1e-320", "9.99989e-321"}, {"1000000.5", "1000000.5"}}) {
        INFO(name << " " << given);
        const std::string out = temp_file(name);
        std::filesystem::remove(out);
        const CliRun run = run_cli({"flatten", plane, out, "--mm-per-unit", given});
        CHECK(run.exit_status == 2);
        CHECK(run.err.find("flatten: error: --mm-per-unit: millimetres per unit must be a number from 0.001 to "
                           "1000000, got " + shown) != std::string::npos);
        CHECK(run.out.empty());
        CHECK_FALSE(std::filesystem::exists(out));
      }
      // Before the mesh is read.
      CHECK(run_cli({"flatten", temp_file("none.obj"), temp_file(name), "--mm-per-unit", "1e308"}).exit_status == 2);
    }
  }

  SECTION("bad parameters exit 2") {
    const std::string out = temp_file("bad.svg");
    const std::vector<std::vector<std::string>> bad = {
        {"flatten", torso, out, "--compress", "0"},
        {"flatten", torso, out, "--compress", "0.8,0.9,1"},
        {"flatten", torso, out, "--baseline", "scaled"},
        {"flatten", torso, out, "--mm-per-unit", "-1"},
        {"flatten", torso, out, "--mm-per-unit", "1e200"},
        {"flatten", torso, out, "--mm-per-unit", "1e-9"},
        {"flatten", torso, out, "--direction", "curvature:min"},
        {"flatten", torso, temp_file("bad.ply")},
        {"flatten", torso, out, "--select", "box:1,1,1,2,2,2"},
    };
    for (const auto& args : bad) {
      const CliRun run = run_cli(args);
      std::string command;
      for (const std::string& arg : args) command += arg + " ";
      INFO(command << ": " << run.err);
      CHECK(run.exit_status == 2);
      CHECK_FALSE(run.err.empty());
    }
  }
}

TEST_CASE("flatten CLI: a pattern smaller than a millimetre keeps its shape, with a warning; the unit is guessed",
          "[flatten][cli]") {
  // Spothead at 1e-4 of its size, at the CLI's old default of 1 mm per unit:
  // 0.0001 mm across, printed to 3 decimals, every outline point was
  // "10.000 10.000", a pattern collapsed to a dot, exit 0 without a word.
  // The app guesses the unit from the mesh's size (guess_model_unit): so does
  // the CLI now without --mm-per-unit.
  Mesh tiny = test::load("open/spothead.obj");
  tiny.V *= 1e-4;
  const std::string in = temp_file("spothead_tiny.obj");
  write_mesh(in, tiny);
  const auto distinct_points = [](const std::string& svg) {
    std::vector<std::string> points;
    const std::string start = "<path class=\"outline\" d=\"";
    for (std::size_t at = svg.find(start); at != std::string::npos; at = svg.find(start, at + 1)) {
      std::istringstream path(svg.substr(at + start.size(), svg.find('"', at + start.size()) - at - start.size()));
      std::string command, x, y;
      while (path >> command >> x >> y) points.push_back(x + " " + y);
    }
    const std::size_t all = points.size();
    std::sort(points.begin(), points.end());
    const auto distinct = static_cast<std::size_t>(std::unique(points.begin(), points.end()) - points.begin());
    return std::make_pair(distinct, all);
  };
  const auto all_distinct = [&](const std::string& svg) {
    const auto [distinct, all] = distinct_points(svg);
    INFO(distinct << " distinct of " << all << " outline points");
    CHECK(all > 20);  // spothead's neck: 32
    CHECK(distinct == all);
  };
  const std::string out = temp_file("spothead_tiny.svg");
  // The unit and the digits are what is checked, not the pattern's quality:
  // a few ARAP iterations, no refinement (spothead does not flatten as one
  // piece: to convergence, 179 iterations and the refinement, 3 s natively
  // and 16 s under the sanitizers, per run).
  const std::vector<std::string> quick{"--compress", "0.8,1", "--direction", "global:0,1,0", "--iterations", "20",
                                       "--no-refine"};
  std::vector<std::string> flatten{"flatten", in, out};
  flatten.insert(flatten.end(), quick.begin(), quick.end());
  std::vector<std::string> at_one = flatten;
  at_one.insert(at_one.end(), {"--mm-per-unit", "1"});
  const CliRun one = run_cli(at_one);
  REQUIRE(one.exit_status == 0);
  const nlohmann::json given = nlohmann::json::parse(one.out);
  CHECK_THAT(given["warnings"].dump(), Catch::Contains("mm across at 1 mm per model unit (written with") &&
                                           Catch::Contains("check the millimetres per unit (--mm-per-unit)"));
  CHECK_FALSE(given.contains("unit_guess"));
  all_distinct(test::slurp(out));
  // Not given: metres (1000 mm per unit), as the app would export it.
  const CliRun guessed = run_cli(flatten);
  REQUIRE(guessed.exit_status == 0);
  const nlohmann::json result = nlohmann::json::parse(guessed.out);
  CHECK(result["unit_guess"] == "m");
  CHECK(result["mm_per_unit"] == 1000.0);
  CHECK_THAT(result["warnings"].dump(), Catch::Contains("guessed from the mesh's size as m; give --mm-per-unit"));
  all_distinct(test::slurp(out));
  // Spothead itself: a pattern of some 900 mm, no such warning, 3 decimals.
  const std::string head = temp_file("spothead_m.svg");
  std::vector<std::string> at_size{"flatten", test::mesh_path("open/spothead.obj"), head};
  at_size.insert(at_size.end(), quick.begin(), quick.end());
  const CliRun normal = run_cli(at_size);
  REQUIRE(normal.exit_status == 0);
  CHECK(nlohmann::json::parse(normal.out)["warnings"].dump().find("mm across") == std::string::npos);
  CHECK(test::slurp(head).find(".0000") == std::string::npos);
}
