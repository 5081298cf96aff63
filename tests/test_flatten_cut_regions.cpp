// Where a patch needs a dart or a cut (FlattenMetrics::suggested_cuts,
// flatten.h), and why the uniform baseline can edge out ours on a panel where
// the wanted direction barely turns.
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include <catch2/catch.hpp>

#include "flatten/flatten_pipeline.h"
#include "test_support.h"

using namespace aniso;

TEST_CASE("flatten: a strongly non-developable patch names the regions that need a cut", "[flatten]") {
  const Mesh hand = test::load("open/hand_lowres.obj");
  const FlattenOutput out = flatten(hand, {}, FlattenOptions{});
  const FlattenResult& result = out.result;
  const std::vector<FlattenRegion>& regions = result.metrics.suggested_cuts;
  REQUIRE_FALSE(regions.empty());
  std::set<int> named;
  for (const FlattenRegion& region : regions) {
    INFO("region near vertex " << region.vertex);
    CHECK(region.error_mean > kCutRegionError);
    CHECK(std::is_sorted(region.vertices.begin(), region.vertices.end()));
    CHECK(std::binary_search(region.vertices.begin(), region.vertices.end(), region.vertex));
    for (int v : region.vertices) {
      REQUIRE(v >= 0);
      REQUIRE(v < hand.num_vertices());
      named.insert(v);
    }
    // The representative vertex is the region's vertex nearest its centroid.
    double nearest = HUGE_VAL;
    for (int v : region.vertices) {
      nearest = std::min(nearest, (hand.V.row(v).transpose() - region.centroid).norm());
    }
    CHECK((hand.V.row(region.vertex).transpose() - region.centroid).norm() == Approx(nearest));
  }
  // Every named vertex is a corner of a triangle above the threshold.
  const FlattenPatch& patch = out.patch;
  std::set<int> above;
  for (int t = 0; t < patch.mesh.num_triangles(); ++t) {
    if (result.stretch.degenerate[t] || !(cut_region_error(result.targets, result.stretch, t) > kCutRegionError)) continue;
    for (int k = 0; k < 3; ++k) above.insert(patch.input_vertex[patch.mesh.F(t, k)]);
  }
  for (int v : named) {
    INFO("vertex " << v);
    CHECK(above.count(v) == 1);
  }
}

TEST_CASE("flatten: a plane and a garment panel need no cut", "[flatten]") {
  for (const char* name : {"open/plane.off", "open/human_woman_torso_front_patch.obj"}) {
    const Mesh mesh = test::load(name);
    FlattenOptions options;
    options.su = 0.8;
    const FlattenOutput out = flatten(mesh, {}, options);
    INFO(name);
    CHECK(out.result.metrics.suggested_cuts.empty());
    CHECK(flatten_problem(out.result.metrics).empty());
  }
}

TEST_CASE("flatten: on the torso panel along its (barely turning) long axis the baseline edges out ours only by the targets' anisotropy",
          "[flatten]") {
  // Why the baseline scores 2.5 % against our 2.6 % compression error here
  // (global axis y, su = 0.8): the projected direction barely turns over a
  // front panel, so one uniform scale of the isometric flattening is nearly
  // exact for compression (it adds 0.07 points to the isometric 2.41 %). Ours
  // minimizes the ARAP energy |J - R T|^2 in absolute terms, while the
  // metrics are relative (error / su): with su < sv the unavoidable
  // curvature distortion is pushed into the direction with the smaller
  // target, where it counts 1/su times more. With isotropic targets both are
  // the same map, and the gap grows with the anisotropy. Where the direction
  // turns over the patch (a field, a cone, the band of the Fig. 11 test) the
  // single scale is wrong and ours wins by far.
  const Mesh torso = test::load("open/human_woman_torso_front_patch.obj");
  Flattener flattener(torso);
  const auto errors = [&flattener](double su, double sv, FlattenMethod method) {
    FlattenOptions options;
    options.su = su;
    options.sv = sv;
    options.method = method;
    options.directions.global = Eigen::Vector3d::UnitY();
    return flattener.flatten(options).metrics;
  };
  const FlattenMetrics isotropic_ours = errors(0.8, 0.8, FlattenMethod::Anisotropic);
  const FlattenMetrics isotropic_base = errors(0.8, 0.8, FlattenMethod::UniformBaseline);
  CHECK(isotropic_ours.compression_error_mean == Approx(isotropic_base.compression_error_mean).epsilon(1e-6));
  double previous_gap = 0.0;
  for (double su : {0.9, 0.8, 0.7}) {
    const FlattenMetrics ours = errors(su, 1.0, FlattenMethod::Anisotropic);
    const FlattenMetrics base = errors(su, 1.0, FlattenMethod::UniformBaseline);
    const double gap = ours.compression_error_mean - base.compression_error_mean;
    INFO("su " << su << ": ours " << ours.compression_error_mean << " baseline " << base.compression_error_mean);
    CHECK(gap > previous_gap);
    CHECK(gap < 0.01);  // measured 0.0007 (su 0.9), 0.0017 (su 0.8)
    // The baseline is close to the isometric flattening's own error.
    CHECK(base.compression_error_mean - isotropic_base.compression_error_mean < 0.005);
    previous_gap = gap;
  }
}
