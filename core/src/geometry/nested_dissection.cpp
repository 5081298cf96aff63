#include "geometry/nested_dissection.h"

#include <algorithm>
#include <cstdint>

#include <Eigen/OrderingMethods>

#include "geometry/graph_bisection.h"

namespace aniso {

namespace {

// Pieces of at most this many vertices (after merging indistinguishable
// ones) are ordered by minimum degree: their separators would save little.
// METIS switches at about the same size. Operations of the flattening
// refinement's systems (one separator a piece, sides within 55 %) with
// leaves of 60 / 120 / 200: demosthenes 1.42e8 / 1.43e8 / 1.42e8, the bunny
// 9.8e8 / 9.87e8 / 9.69e8, spothead 4.59e7 / 4.75e7 / 4.86e7 (AMD: 2.31e8,
// 1.31e9, 5.51e7); leaves of 1,000 order the 200k koala's Laplacian twice
// as fast for 3 % more operations.
constexpr int kLeafSize = 120;
// Pieces above this many vertices are bisected from kSeparatorTries seeds
// and the smallest separator kept (METIS's nseps): each coarsening is a
// random draw, and the separators they lead to differ by a tenth or more.
// Operations of the refinement's systems (sides within 65 %) with 1 / 3 / 5
// tries: the koala head 1.08e9 / 1.02e9 / 1.01e9, the bunny 9.4e8 / 8.3e8 /
// 8.4e8, demosthenes 1.44e8 / 1.36e8 / 1.34e8; the koala head's ordering
// takes 0.25 / 0.42 / 0.67 s, next to 228 factorizations of about 0.1 s.
constexpr int kRetriedAbove = 1000;
constexpr int kSeparatorTries = 3;

long long separator_weight(const WeightedGraph& g, const std::vector<std::int8_t>& part) {
  long long weight = 0;
  for (int v = 0; v < g.size(); ++v) {
    if (part[v] == kSeparator) weight += g.vertex_weight[v];
  }
  return weight;
}

// The graph of A's pattern (both directions, no self-loops), every vertex
// and edge of weight 1.
WeightedGraph pattern_graph(const Eigen::SparseMatrix<double>& A) {
  const int n = static_cast<int>(A.cols());
  WeightedGraph g;
  g.start.assign(n + 1, 0);
  for (int c = 0; c < n; ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      if (it.row() > c) {
        ++g.start[it.row() + 1];
        ++g.start[c + 1];
      }
    }
  }
  for (int v = 0; v < n; ++v) g.start[v + 1] += g.start[v];
  g.neighbour.resize(g.start[n]);
  std::vector<int> filled(g.start.begin(), g.start.end() - 1);
  // Column by column: each vertex's neighbours come out ascending.
  for (int c = 0; c < n; ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      if (r > c) {
        g.neighbour[filled[r]++] = c;
        g.neighbour[filled[c]++] = r;
      }
    }
  }
  for (int v = 0; v < n; ++v) std::sort(g.neighbour.begin() + g.start[v], g.neighbour.begin() + g.start[v + 1]);
  g.edge_weight.assign(g.neighbour.size(), 1);
  g.vertex_weight.assign(n, 1);
  return g;
}

// Groups of vertices with the same neighbours, themselves included
// (indistinguishable: one ordering for all of them is as good as any).
// Compared only between neighbours with the same degree and neighbour sum.
std::vector<int> indistinguishable_groups(const WeightedGraph& g, int& groups) {
  const int n = g.size();
  std::vector<long long> sum(n);
  for (int v = 0; v < n; ++v) {
    sum[v] = v;
    for (int e = g.start[v]; e < g.start[v + 1]; ++e) sum[v] += g.neighbour[e];
  }
  // Closed neighbourhoods are equal when the open ones are equal but for u and v themselves.
  auto same = [&](int u, int v) {
    int i = g.start[u], j = g.start[v];
    while (true) {
      while (i < g.start[u + 1] && g.neighbour[i] == v) ++i;
      while (j < g.start[v + 1] && g.neighbour[j] == u) ++j;
      const bool u_done = i == g.start[u + 1], v_done = j == g.start[v + 1];
      if (u_done || v_done) return u_done && v_done;
      if (g.neighbour[i++] != g.neighbour[j++]) return false;
    }
  };
  std::vector<int> group(n, -1);
  groups = 0;
  for (int v = 0; v < n; ++v) {
    for (int e = g.start[v]; e < g.start[v + 1] && group[v] < 0; ++e) {
      const int u = g.neighbour[e];
      if (u < v && sum[u] == sum[v] && g.start[u + 1] - g.start[u] == g.start[v + 1] - g.start[v] && same(u, v)) {
        group[v] = group[u];
      }
    }
    if (group[v] < 0) group[v] = groups++;
  }
  return group;
}

class Dissection {
 public:
  explicit Dissection(int n) : local_(n, -1) {}

  // Appends the elimination order of `piece` (its vertices: ids) to order_.
  void dissect(const WeightedGraph& piece, const std::vector<int>& ids) {
    if (piece.size() <= kLeafSize) {
      order_minimum_degree(piece, ids);
      return;
    }
    std::vector<std::int8_t> part = vertex_separator(piece, ++pieces_);
    if (piece.size() > kRetriedAbove) {
      long long weight = separator_weight(piece, part);
      for (int attempt = 1; attempt < kSeparatorTries; ++attempt) {
        std::vector<std::int8_t> other = vertex_separator(piece, ++pieces_);
        const long long other_weight = separator_weight(piece, other);
        if (other_weight < weight) {
          part = std::move(other);
          weight = other_weight;
        }
      }
    }
    std::vector<int> side_ids[2], separator;
    for (int v = 0; v < piece.size(); ++v) {
      (part[v] == kSeparator ? separator : side_ids[part[v]]).push_back(v);
    }
    if (side_ids[0].empty() || side_ids[1].empty()) {
      order_minimum_degree(piece, ids);
      return;
    }
    for (const auto& side : side_ids) {
      std::vector<int> global(side.size());
      for (std::size_t k = 0; k < side.size(); ++k) global[k] = ids[side[k]];
      dissect(induced(piece, side), global);
    }
    for (const int v : separator) order_.push_back(ids[v]);
  }

  std::vector<int> take_order() { return std::move(order_); }

 private:
  // The subgraph of `g` on `vertices` (renumbered in their order).
  WeightedGraph induced(const WeightedGraph& g, const std::vector<int>& vertices) {
    for (std::size_t k = 0; k < vertices.size(); ++k) local_[vertices[k]] = static_cast<int>(k);
    WeightedGraph sub;
    sub.start.reserve(vertices.size() + 1);
    for (const int v : vertices) {
      sub.vertex_weight.push_back(g.vertex_weight[v]);
      for (int e = g.start[v]; e < g.start[v + 1]; ++e) {
        const int u = local_[g.neighbour[e]];
        if (u < 0) continue;
        sub.neighbour.push_back(u);
        sub.edge_weight.push_back(g.edge_weight[e]);
      }
      sub.start.push_back(static_cast<int>(sub.neighbour.size()));
    }
    for (const int v : vertices) local_[v] = -1;
    return sub;
  }

  void order_minimum_degree(const WeightedGraph& piece, const std::vector<int>& ids) {
    const int m = piece.size();
    if (m <= 2) {
      order_.insert(order_.end(), ids.begin(), ids.end());
      return;
    }
    Eigen::SparseMatrix<double> pattern(m, m);
    pattern.reserve(Eigen::VectorXi::Constant(m, 1) + Eigen::Map<const Eigen::VectorXi>(piece.start.data() + 1, m) -
                    Eigen::Map<const Eigen::VectorXi>(piece.start.data(), m));
    for (int v = 0; v < m; ++v) {
      pattern.insert(v, v) = 1.0;
      for (int e = piece.start[v]; e < piece.start[v + 1]; ++e) pattern.insert(piece.neighbour[e], v) = 1.0;
    }
    pattern.makeCompressed();
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
    Eigen::AMDOrdering<int>()(pattern, order);
    for (int k = 0; k < m; ++k) order_.push_back(ids[order.indices()[k]]);
  }

  std::vector<int> local_;  // scratch of induced(): each vertex's number in the subgraph, or -1
  std::vector<int> order_;
  std::uint64_t pieces_ = 0;  // the seed of each piece's bisection
};

}  // namespace

std::vector<int> nested_dissection_order(const Eigen::SparseMatrix<double>& A) {
  const WeightedGraph fine = pattern_graph(A);
  int groups = 0;
  const std::vector<int> group = indistinguishable_groups(fine, groups);
  const WeightedGraph graph = contract(fine, group, groups);
  Dissection dissection(groups);
  std::vector<int> all(groups);
  for (int v = 0; v < groups; ++v) all[v] = v;
  dissection.dissect(graph, all);
  // Each group's members in place of the group, in ascending order.
  std::vector<int> member_start(groups + 1, 0), members(fine.size());
  for (const int c : group) ++member_start[c + 1];
  for (int c = 0; c < groups; ++c) member_start[c + 1] += member_start[c];
  std::vector<int> filled(member_start.begin(), member_start.end() - 1);
  for (int v = 0; v < fine.size(); ++v) members[filled[group[v]]++] = v;
  std::vector<int> order;
  order.reserve(fine.size());
  for (const int c : dissection.take_order()) {
    order.insert(order.end(), members.begin() + member_start[c], members.begin() + member_start[c + 1]);
  }
  return order;
}

}  // namespace aniso
