#include "directions/line_orientation.h"

#include <cmath>
#include <queue>
#include <tuple>

namespace aniso {

void orient_line_field(const VertexAdjacency& adjacency, const std::vector<char>& seed,
                       const std::vector<char>& free, Positions& direction) {
  const int n = static_cast<int>(seed.size());
  std::vector<char> oriented(n, 0);
  // (|cos| across the edge, -to, from): the most parallel edge first; ties
  // in index order, so the result does not depend on the queue's internals.
  using PendingEdge = std::tuple<double, int, int>;
  std::priority_queue<PendingEdge> pending;
  const auto reach_from = [&](int i) {
    for (int k = adjacency.offsets[i]; k < adjacency.offsets[i + 1]; ++k) {
      const int j = adjacency.neighbors[k];
      if (oriented[j] || !free[j]) continue;
      pending.emplace(std::abs(direction.row(i).dot(direction.row(j))), -j, i);
    }
  };
  const auto grow = [&] {
    while (!pending.empty()) {
      const auto [alignment, minus_to, from] = pending.top();
      pending.pop();
      const int to = -minus_to;
      if (oriented[to]) continue;
      if (direction.row(to).dot(direction.row(from)) < 0.0) direction.row(to) *= -1.0;
      oriented[to] = 1;
      reach_from(to);
    }
  };
  for (int i = 0; i < n; ++i) {
    if (!seed[i]) continue;
    oriented[i] = 1;
    reach_from(i);
  }
  grow();
  for (int i = 0; i < n; ++i) {
    if (oriented[i] || !free[i]) continue;
    oriented[i] = 1;  // a part no seed reached: its first vertex keeps its sign
    reach_from(i);
    grow();
  }
}

}  // namespace aniso
