#include "anisoform/laplacian.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

namespace aniso {
namespace {

// An undirected edge as one number: lower vertex in the high half.
inline std::uint64_t cotan_edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// The triangle sides (3 t + k: the side opposite corner k of triangle t)
// grouped by undirected edge, each edge's sides in triangle order: a
// counting sort by the edge's lower vertex, then a sort of those few by key
// and side. It replaces a hash map keyed by edge, which took a quarter of a
// 1.6M-triangle load.
struct CotanSides {
  std::vector<std::uint64_t> key;  // per side
  std::vector<int> order;          // sides, grouped by edge
};

CotanSides cotan_sides_by_edge(const Mesh& mesh) {
  const int num_sides = 3 * mesh.num_triangles();
  CotanSides out;
  out.key.resize(static_cast<std::size_t>(num_sides));
  for (int side = 0; side < num_sides; ++side) {
    const int t = side / 3, k = side % 3;
    out.key[static_cast<std::size_t>(side)] = cotan_edge_key(mesh.F(t, (k + 1) % 3), mesh.F(t, (k + 2) % 3));
  }
  std::vector<int> start(static_cast<std::size_t>(mesh.num_vertices()) + 1, 0);
  for (const std::uint64_t key : out.key) ++start[(key >> 32) + 1];
  for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  out.order.resize(static_cast<std::size_t>(num_sides));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int side = 0; side < num_sides; ++side) out.order[static_cast<std::size_t>(fill[out.key[static_cast<std::size_t>(side)] >> 32]++)] = side;
  const auto by_key_then_side = [&](int a, int b) {
    const std::uint64_t ka = out.key[static_cast<std::size_t>(a)], kb = out.key[static_cast<std::size_t>(b)];
    return ka != kb ? ka < kb : a < b;
  };
  for (std::size_t v = 0; v + 1 < start.size(); ++v) {
    std::sort(out.order.begin() + start[v], out.order.begin() + start[v + 1], by_key_then_side);
  }
  return out;
}

// Calls visit(first, last) for each edge's run of sides in `sides.order`.
template <class Visit>
void for_each_cotan_edge(const CotanSides& sides, Visit visit) {
  const std::vector<int>& order = sides.order;
  std::size_t begin = 0;
  while (begin < order.size()) {
    const std::uint64_t key = sides.key[static_cast<std::size_t>(order[begin])];
    std::size_t end = begin + 1;
    while (end < order.size() && sides.key[static_cast<std::size_t>(order[end])] == key) ++end;
    visit(order.data() + begin, order.data() + end);
    begin = end;
  }
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
  const CotanSides sides = cotan_sides_by_edge(mesh);
  std::vector<double> edge_sums;
  edge_sums.reserve(sides.order.size() / 2);
  double total = 0.0;
  for_each_cotan_edge(sides, [&](const int* first, const int* last) {
    double sum = 0.0;
    for (const int* side = first; side != last; ++side) sum += out.weight(*side / 3, *side % 3);
    edge_sums.push_back(sum);
    total += std::abs(sum);
  });
  // A mesh of degenerate triangles only still needs a connected system.
  const double floor = total > 0.0 ? kMinWeightFraction * total / static_cast<double>(edge_sums.size()) : 1.0;
  std::size_t edge = 0;
  for_each_cotan_edge(sides, [&](const int* first, const int* last) {
    const double sum = edge_sums[edge++];
    if (sum >= floor) return;
    ++out.raised_edges;
    // Each of the edge's triangles adds an equal share of the raise.
    const double raise = (floor - sum) / static_cast<double>(last - first);
    for (const int* side = first; side != last; ++side) out.weight(*side / 3, *side % 3) += raise;
  });
  return out;
}

Eigen::SparseMatrix<double> cotangent_laplacian(const Mesh& mesh, const CotanWeights& weights) {
  const int n = mesh.num_vertices();
  const int m = mesh.num_triangles();
  // The diagonal is summed here, in the order setFromTriplets would sum it,
  // so the matrix is the same to the last bit with 6 triplets per triangle
  // instead of 12 (the triplets of a 1.6M-triangle mesh were 300 MB).
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(m) * 6 + static_cast<std::size_t>(n));
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(n);
  std::vector<char> used(static_cast<std::size_t>(n), 0);  // an unused vertex keeps an empty column
  for (int t = 0; t < m; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int i = mesh.F(t, (k + 1) % 3);
      const int j = mesh.F(t, (k + 2) % 3);
      const double w = weights.weight(t, k);
      triplets.emplace_back(i, j, -w);
      triplets.emplace_back(j, i, -w);
      diagonal[i] += w;
      diagonal[j] += w;
      used[static_cast<std::size_t>(i)] = used[static_cast<std::size_t>(j)] = 1;
    }
  }
  for (int i = 0; i < n; ++i) {
    if (used[static_cast<std::size_t>(i)]) triplets.emplace_back(i, i, diagonal[i]);
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

}  // namespace aniso
