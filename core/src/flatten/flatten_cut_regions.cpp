// Where a patch needs a dart or a cut: the edge-connected regions whose
// triangles miss the wanted stretch by more than kCutRegionError (flatten.h),
// so that a host can mark them instead of only saying "not one piece".
#include <algorithm>
#include <cmath>
#include <vector>

#include "flatten/flatten_pipeline.h"

namespace aniso {

double cut_region_error(const FlattenTargets& targets, const TriangleStretch& stretch, int t) {
  return std::max(std::abs(stretch.along[t] / targets.su[t] - 1.0),
                  std::abs(stretch.across[t] / targets.sv[t] - 1.0));
}

std::vector<FlattenRegion> find_cut_regions(const FlattenPatch& patch, const TriangleCharts& charts,
                                            const TriangleNeighbours& neighbours,
                                            const FlattenTargets& targets,
                                            const TriangleStretch& stretch) {
  const Triangles& F = patch.mesh.F;
  const int m = static_cast<int>(F.rows());
  std::vector<char> above(m, 0);
  bool any = false;
  for (int t = 0; t < m; ++t) {
    above[t] = !stretch.degenerate[t] && cut_region_error(targets, stretch, t) > kCutRegionError;
    any = any || above[t];
  }
  if (!any) return {};
  const double patch_area = charts.area.sum();
  // The neighbours are linear in size for any topology: the faces of an edge
  // shared by k > 2 are linked in a ring, not all pairs (k^2: 192 million
  // links for a face repeated 8000 times, 12.6 s of the sanitizer build's
  // flatten).
  const std::vector<int>& offsets = neighbours.get().offsets;
  const std::vector<int>& adjacent = neighbours.get().neighbors;
  std::vector<char> visited(m, 0);
  std::vector<int> region_of_vertex(patch.mesh.num_vertices(), -1);
  std::vector<std::pair<double, FlattenRegion>> found;  // (3D area, region)
  for (int seed = 0; seed < m; ++seed) {
    if (!above[seed] || visited[seed]) continue;
    std::vector<int> faces{seed}, stack{seed};
    visited[seed] = 1;
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int k = offsets[t]; k < offsets[t + 1]; ++k) {
        const int n = adjacent[k];
        if (above[n] && !visited[n]) {
          visited[n] = 1;
          faces.push_back(n);
          stack.push_back(n);
        }
      }
    }
    double area = 0.0, error = 0.0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    // The region's vertices, each once (marked with the region's seed rather
    // than sorted out of all corners: sorting those took a tenth of a 50k
    // flatten call).
    std::vector<int> corners;
    for (int t : faces) {
      const double a = charts.area[t];
      area += a;
      error += a * cut_region_error(targets, stretch, t);
      for (int k = 0; k < 3; ++k) {
        centroid += a / 3.0 * patch.mesh.V.row(F(t, k)).transpose();
        if (region_of_vertex[F(t, k)] != seed) {
          region_of_vertex[F(t, k)] = seed;
          corners.push_back(F(t, k));
        }
      }
    }
    if (!(area >= kCutRegionMinArea * patch_area)) continue;
    FlattenRegion region;
    region.triangles = static_cast<int>(faces.size());
    region.centroid = centroid / area;
    region.error_mean = error / area;
    std::sort(corners.begin(), corners.end());  // the nearest vertex's ties go to the lowest index
    double nearest = HUGE_VAL;
    for (int i : corners) {
      const double d = (patch.mesh.V.row(i).transpose() - region.centroid).squaredNorm();
      if (d < nearest) {
        nearest = d;
        region.vertex = patch.input_vertex[i];
      }
      region.vertices.push_back(patch.input_vertex[i]);
    }
    std::sort(region.vertices.begin(), region.vertices.end());
    found.emplace_back(area, std::move(region));
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<FlattenRegion> regions;
  for (auto& entry : found) regions.push_back(std::move(entry.second));
  return regions;
}

}  // namespace aniso
