// Connectivity queries: components (union-find), boundary loops (walks over
// directed boundary half-edges) and vertex adjacency (counting sort by vertex).
// All run in O(#F + #V) apart from sorting each vertex's few edges, so an
// armadillo-size mesh takes a few milliseconds.
//
// A face with an index out of range is left out of every query (the callers
// reject such meshes first; this only keeps a bad mesh from crashing us).
// A face with a repeated corner still connects its vertices, and its sides
// between distinct vertices count as edges; its zero-length side does not.
#include "mesh/topology.h"

#include <algorithm>
#include <numeric>

namespace aniso {

bool face_in_range(const Triangles& F, Eigen::Index f, int num_vertices) {
  for (int k = 0; k < 3; ++k) {
    if (F(f, k) < 0 || F(f, k) >= num_vertices) return false;
  }
  return true;
}

namespace {

class UnionFind {
 public:
  explicit UnionFind(int size) : parent_(static_cast<std::size_t>(size)) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int find(int i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];  // path halving
      i = parent_[i];
    }
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

UnionFind vertices_joined_by_faces(const Triangles& F, int num_vertices) {
  UnionFind sets(num_vertices);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (!face_in_range(F, f, num_vertices)) continue;
    sets.unite(F(f, 0), F(f, 1));
    sets.unite(F(f, 0), F(f, 2));
  }
  return sets;
}

struct HalfEdge {
  int from, to;
};

// Half-edges of edges used by exactly one face side, in order of their
// smaller vertex, then larger vertex.
std::vector<HalfEdge> boundary_half_edges(const Triangles& F, int num_vertices) {
  // Counting sort of all sides by their smaller vertex...
  std::vector<int> start(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (!face_in_range(F, f, num_vertices)) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a != b) ++start[std::min(a, b) + 1];
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<HalfEdge> sides(static_cast<std::size_t>(start.back()));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (!face_in_range(F, f, num_vertices)) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a != b) sides[fill[std::min(a, b)]++] = {a, b};
    }
  }
  // ...then, within a vertex's few sides, group by the larger vertex.
  std::vector<HalfEdge> boundary;
  for (int v = 0; v < num_vertices; ++v) {
    auto begin = sides.begin() + start[v];
    auto end = sides.begin() + start[v + 1];
    auto other = [v](const HalfEdge& e) { return e.from == v ? e.to : e.from; };
    std::sort(begin, end, [&](const HalfEdge& x, const HalfEdge& y) { return other(x) < other(y); });
    for (auto run = begin; run != end;) {
      auto run_end = run + 1;
      while (run_end != end && other(*run_end) == other(*run)) ++run_end;
      if (run_end - run == 1) boundary.push_back(*run);
      run = run_end;
    }
  }
  return boundary;
}

}  // namespace

std::vector<int> vertex_components(const Triangles& F, int num_vertices, int* count) {
  UnionFind sets = vertices_joined_by_faces(F, num_vertices);
  std::vector<int> label(static_cast<std::size_t>(num_vertices), -1);
  int labels = 0;
  for (int v = 0; v < num_vertices; ++v) {
    const int root = sets.find(v);  // roots are the smallest index of their set
    label[v] = root == v ? labels++ : label[root];
  }
  if (count) *count = labels;
  return label;
}

int count_face_components(const Triangles& F, int num_vertices) {
  UnionFind sets = vertices_joined_by_faces(F, num_vertices);
  std::vector<char> counted(static_cast<std::size_t>(num_vertices), 0);
  int components = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (!face_in_range(F, f, num_vertices)) continue;
    const int root = sets.find(F(f, 0));
    if (!counted[root]) {
      counted[root] = 1;
      ++components;
    }
  }
  return components;
}

std::vector<std::vector<int>> boundary_loops(const Triangles& F, int num_vertices) {
  const std::vector<HalfEdge> boundary = boundary_half_edges(F, num_vertices);
  // Outgoing boundary half-edges per vertex (CSR), and how many of each
  // vertex's are used up: every half-edge is walked exactly once.
  std::vector<int> start(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (const HalfEdge& e : boundary) ++start[e.from + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> target(boundary.size());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const HalfEdge& e : boundary) target[fill[e.from]++] = e.to;
  std::vector<int> used(start.begin(), start.end() - 1);  // next unused outgoing index

  std::vector<std::vector<int>> loops;
  for (int v = 0; v < num_vertices; ++v) {
    while (used[v] < start[v + 1]) {
      std::vector<int> loop{v};
      int current = target[used[v]++];
      // Stops back at the start, or where the boundary runs against itself
      // (inconsistent orientation): then the loop is an open chain.
      while (current != v && used[current] < start[current + 1]) {
        loop.push_back(current);
        current = target[used[current]++];
      }
      if (current != v) loop.push_back(current);
      loops.push_back(std::move(loop));
    }
  }
  return loops;
}

std::vector<char> boundary_vertex_mask(const Triangles& F, int num_vertices) {
  std::vector<char> mask(static_cast<std::size_t>(num_vertices), 0);
  for (const HalfEdge& e : boundary_half_edges(F, num_vertices)) mask[e.from] = mask[e.to] = 1;
  return mask;
}

VertexAdjacency vertex_adjacency(const Triangles& F, int num_vertices) {
  VertexAdjacency adjacency;
  std::vector<int>& offsets = adjacency.offsets;
  offsets.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (!face_in_range(F, f, num_vertices)) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a == b) continue;
      ++offsets[a + 1];
      ++offsets[b + 1];
    }
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<int> all(static_cast<std::size_t>(offsets.back()));
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (!face_in_range(F, f, num_vertices)) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a == b) continue;
      all[fill[a]++] = b;
      all[fill[b]++] = a;
    }
  }
  // Each edge was listed once per face side: sort and drop the repeats in place.
  std::vector<int>& neighbors = adjacency.neighbors;
  neighbors.reserve(all.size() / 2);
  int written = 0;
  for (int v = 0; v < num_vertices; ++v) {
    auto begin = all.begin() + offsets[v];
    auto end = all.begin() + offsets[v + 1];
    std::sort(begin, end);
    offsets[v] = written;
    neighbors.insert(neighbors.end(), begin, std::unique(begin, end));
    written = static_cast<int>(neighbors.size());
  }
  offsets[num_vertices] = written;
  return adjacency;
}

std::vector<int> breadth_first_order(const Triangles& F, int num_vertices) {
  const VertexAdjacency adjacency = vertex_adjacency(F, num_vertices);
  std::vector<int> order;
  order.reserve(static_cast<std::size_t>(num_vertices));
  std::vector<char> seen(static_cast<std::size_t>(num_vertices), 0);
  for (int start = 0; start < num_vertices; ++start) {
    if (seen[start]) continue;
    seen[start] = 1;
    std::size_t next = order.size();
    order.push_back(start);
    // `order` doubles as the queue: the vertices from `next` on are still to visit.
    for (; next < order.size(); ++next) {
      const int v = order[next];
      for (int q = adjacency.offsets[v]; q < adjacency.offsets[v + 1]; ++q) {
        const int u = adjacency.neighbors[q];
        if (!seen[u]) {
          seen[u] = 1;
          order.push_back(u);
        }
      }
    }
  }
  return order;
}

}  // namespace aniso
