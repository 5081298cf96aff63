// Where a patch needs a dart or a cut: the edge-connected regions whose
// triangles miss the wanted stretch by more than kCutRegionError (flatten.h),
// so that a host can mark them instead of only saying "not one piece".
#include <algorithm>
#include <cmath>
#include <queue>
#include <utility>
#include <vector>

#include "flatten/flatten_pipeline.h"

namespace aniso {

double cut_region_error(const FlattenTargets& targets, const TriangleStretch& stretch, int t) {
  return std::max(std::abs(stretch.along[t] / targets.su[t] - 1.0),
                  std::abs(stretch.across[t] / targets.sv[t] - 1.0));
}

namespace {

// A region above kCutRegionMaxArea of the patch is cut down to its worst
// part: grown from its worst triangle, the worst neighbour first, until it
// holds that much area. On the hand, 1082 of 1602 triangles missed by more
// than kCutRegionError in one connected region, and the whole of it was
// suggested as a dart: no pattern maker cuts one over most of a piece.
std::vector<int> worst_part(const std::vector<int>& faces, const TriangleCharts& charts,
                            const std::vector<int>& offsets, const std::vector<int>& adjacent,
                            const std::vector<double>& error, double max_area) {
  std::vector<char> in_region(error.size(), 0), taken(error.size(), 0);
  int worst = faces.front();
  for (int t : faces) {
    in_region[t] = 1;
    if (error[t] > error[worst]) worst = t;
  }
  std::priority_queue<std::pair<double, int>> frontier;  // (error, triangle): the worst first
  frontier.emplace(error[worst], worst);
  taken[worst] = 1;
  std::vector<int> part;
  double area = 0.0;
  while (!frontier.empty() && area < max_area) {
    const int t = frontier.top().second;
    frontier.pop();
    part.push_back(t);
    area += charts.area[t];
    for (int k = offsets[t]; k < offsets[t + 1]; ++k) {
      const int n = adjacent[k];
      if (in_region[n] && !taken[n]) {
        taken[n] = 1;
        frontier.emplace(error[n], n);
      }
    }
  }
  return part;
}

}  // namespace

std::vector<FlattenRegion> find_cut_regions(const FlattenPatch& patch, const TriangleCharts& charts,
                                            const TriangleNeighbours& neighbours,
                                            const FlattenTargets& targets,
                                            const TriangleStretch& stretch) {
  const Triangles& F = patch.mesh.F;
  const int m = static_cast<int>(F.rows());
  std::vector<char> above(m, 0);
  std::vector<double> error(m, 0.0);
  bool any = false;
  for (int t = 0; t < m; ++t) {
    above[t] = !stretch.degenerate[t] && cut_region_error(targets, stretch, t) > kCutRegionError;
    if (above[t]) error[t] = cut_region_error(targets, stretch, t);
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
  std::vector<std::pair<double, FlattenRegion>> found;  // (connected 3D area, region)
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
    double connected_area = 0.0;
    for (int t : faces) connected_area += charts.area[t];
    if (!(connected_area >= kCutRegionMinArea * patch_area)) continue;
    if (connected_area > kCutRegionMaxArea * patch_area) {
      faces = worst_part(faces, charts, offsets, adjacent, error, kCutRegionMaxArea * patch_area);
    }
    double area = 0.0, error_sum = 0.0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    // The region's vertices, each once (marked with the region's seed rather
    // than sorted out of all corners: sorting those took a tenth of a 50k
    // flatten call).
    std::vector<int> corners;
    for (int t : faces) {
      const double a = charts.area[t];
      area += a;
      error_sum += a * error[t];
      for (int k = 0; k < 3; ++k) {
        centroid += a / 3.0 * patch.mesh.V.row(F(t, k)).transpose();
        if (region_of_vertex[F(t, k)] != seed) {
          region_of_vertex[F(t, k)] = seed;
          corners.push_back(F(t, k));
        }
      }
    }
    FlattenRegion region;
    region.triangles = static_cast<int>(faces.size());
    region.centroid = centroid / area;
    region.error_mean = error_sum / area;
    region.area_share = area / patch_area;
    region.connected_area_share = connected_area / patch_area;
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
    // The largest problem first: by the connected area above the error (a
    // region cut down to its worst part has less of its own).
    found.emplace_back(connected_area, std::move(region));
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<FlattenRegion> regions;
  for (auto& entry : found) regions.push_back(std::move(entry.second));
  return regions;
}

}  // namespace aniso
