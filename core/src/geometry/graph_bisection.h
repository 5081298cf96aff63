// Vertex separators of graphs by multilevel bisection (Karypis & Kumar
// 1998, the scheme of METIS): the graph is coarsened by heavy-edge
// matchings, the coarsest one bisected by greedy growing from several
// starts, and the bisection carried back level by level, refined at each by
// Fiduccia-Mattheyses moves; the cut edges' minimum vertex cover (König) is
// the separator. Used for the nested dissection ordering
// (geometry/nested_dissection.h).
#pragma once

#include <cstdint>
#include <vector>

namespace aniso {

// An undirected graph with weighted vertices and edges: each vertex's
// neighbours in neighbour[start[v] .. start[v + 1]), every edge stored in
// both directions with the same weight, no self-loops.
struct WeightedGraph {
  std::vector<int> start{0};
  std::vector<int> neighbour;
  std::vector<int> edge_weight;
  std::vector<int> vertex_weight;

  int size() const { return static_cast<int>(start.size()) - 1; }
};

// The graph whose vertices are g's merged by `group` (group[v] in [0, groups),
// every group not empty): vertex weights and the weights of parallel edges
// summed, the edges inside a group dropped.
WeightedGraph contract(const WeightedGraph& g, const std::vector<int>& group, int groups);

// Sides of a vertex separator.
enum SeparatorPart : std::int8_t { kSideA = 0, kSideB = 1, kSeparator = 2 };

// Per vertex its part: no edge joins side A to side B, the separator is
// small and the sides' weights are near equal. The same graph and seed give
// the same parts on every platform (no library randomness).
std::vector<std::int8_t> vertex_separator(const WeightedGraph& g, std::uint64_t seed);

}  // namespace aniso
