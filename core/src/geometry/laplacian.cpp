#include "anisoform/laplacian.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

namespace aniso {
namespace {

// Key of an undirected edge for the floor pass.
inline std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

}  // namespace

CotanWeights cotangent_weights(const Mesh& mesh) {
  const int m = mesh.num_triangles();
  CotanWeights out;
  out.weight.setZero(m, 3);
  for (int t = 0; t < m; ++t) {
    const Eigen::Vector3d p[3] = {mesh.V.row(mesh.F(t, 0)).transpose(),
                                  mesh.V.row(mesh.F(t, 1)).transpose(),
                                  mesh.V.row(mesh.F(t, 2)).transpose()};
    double longest2 = 0.0;
    for (int k = 0; k < 3; ++k) longest2 = std::max(longest2, (p[(k + 1) % 3] - p[k]).squaredNorm());
    const double twice_area = (p[1] - p[0]).cross(p[2] - p[0]).norm();
    Eigen::Vector3d cot = Eigen::Vector3d::Zero();
    bool ok = twice_area > 1e-12 * longest2;
    for (int k = 0; k < 3 && ok; ++k) {
      // |a x b| is twice the area for every corner.
      cot[k] = (p[(k + 1) % 3] - p[k]).dot(p[(k + 2) % 3] - p[k]) / twice_area;
      ok = std::abs(cot[k]) <= kMaxCot;
    }
    if (!ok) {
      ++out.degenerate_triangles;
      continue;
    }
    out.weight.row(t) = 0.5 * cot.transpose();
  }
  // Rule 2: every edge weight at least the floor (edges of obtuse pairs, of
  // right-angled grids and of degenerate triangles only).
  std::unordered_map<std::uint64_t, std::pair<double, int>> edge_sum;  // (sum, uses)
  edge_sum.reserve(static_cast<std::size_t>(m) * 2);
  for (int t = 0; t < m; ++t) {
    for (int k = 0; k < 3; ++k) {
      auto& entry = edge_sum[edge_key(mesh.F(t, (k + 1) % 3), mesh.F(t, (k + 2) % 3))];
      entry.first += out.weight(t, k);
      entry.second += 1;
    }
  }
  double total = 0.0;
  for (const auto& kv : edge_sum) total += std::abs(kv.second.first);
  // A mesh of degenerate triangles only still needs a connected system.
  const double floor = total > 0.0 ? kMinWeightFraction * total / static_cast<double>(edge_sum.size()) : 1.0;
  for (auto& kv : edge_sum) {
    // From here on `first` holds the raise each of the edge's triangles adds.
    const double sum = kv.second.first;
    kv.second.first = sum < floor ? (floor - sum) / kv.second.second : 0.0;
    if (sum < floor) ++out.raised_edges;
  }
  if (out.raised_edges == 0) return out;
  for (int t = 0; t < m; ++t) {
    for (int k = 0; k < 3; ++k) {
      out.weight(t, k) += edge_sum[edge_key(mesh.F(t, (k + 1) % 3), mesh.F(t, (k + 2) % 3))].first;
    }
  }
  return out;
}

Eigen::SparseMatrix<double> cotangent_laplacian(const Mesh& mesh, const CotanWeights& weights) {
  const int n = mesh.num_vertices();
  const int m = mesh.num_triangles();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(m) * 12);
  for (int t = 0; t < m; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int i = mesh.F(t, (k + 1) % 3);
      const int j = mesh.F(t, (k + 2) % 3);
      const double w = weights.weight(t, k);
      triplets.emplace_back(i, j, -w);
      triplets.emplace_back(j, i, -w);
      triplets.emplace_back(i, i, w);
      triplets.emplace_back(j, j, w);
    }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

}  // namespace aniso
