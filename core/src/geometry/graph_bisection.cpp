#include "geometry/graph_bisection.h"

#include <algorithm>
#include <cstdint>
#include <queue>
#include <utility>

namespace aniso {

namespace {

// Coarsening stops at this many vertices (or when a matching leaves more
// than kMinShrink of them), and no coarse vertex weighs more than
// kMaxVertexShare / kCoarsest of the whole: heavier ones would make the
// coarsest bisections lopsided.
constexpr int kCoarsest = 120;
constexpr double kMinShrink = 0.9;
constexpr double kMaxVertexShare = 1.5;
// Greedy growings of the coarsest graph's bisection, the best kept.
constexpr int kInitialTries = 8;
// A side may weigh up to (1 + kImbalance) / 2 of the whole: a looser
// balance lets the separators be shorter, a tighter one keeps the
// dissection's pieces even. Operations of the flattening refinement's
// systems (one separator a piece) with 0.05 / 0.1 / 0.2 / 0.3 / 0.4 / 0.5:
// the koala head 1.28e9 / 1.21e9 / 1.14e9 / 1.08e9 / 1.11e9 / 1.06e9, the
// bunny 9.7e8 / 1.00e9 / 1.00e9 / 9.4e8 / 8.8e8 / 9.7e8, spothead 4.8e7 /
// 4.3e7 / 4.2e7 / 4.0e7 / 4.6e7 / 4.2e7.
constexpr double kImbalance = 0.3;
// Fiduccia-Mattheyses passes per level, and the moves without a better
// bisection after which a pass gives up (METIS's limits).
constexpr int kRefinePasses = 8;
constexpr int kMinPatience = 15, kMaxPatience = 100;

// splitmix64: the same numbers on every platform.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // In [0, n): the high 32 bits scaled (Lemire's multiply-shift), no division.
  int below(int n) { return static_cast<int>(((next() >> 32) * static_cast<std::uint64_t>(n)) >> 32); }
  std::vector<int> permutation(int n) {
    std::vector<int> p(n);
    for (int i = 0; i < n; ++i) p[i] = i;
    for (int i = n - 1; i > 0; --i) std::swap(p[i], p[below(i + 1)]);
    return p;
  }

 private:
  std::uint64_t state_;
};

// Heavy-edge matching: each vertex, in random order, is merged with the
// unmatched neighbour it shares the heaviest edge with (none: alone).
// Returns the group of every vertex and sets `groups`.
std::vector<int> heavy_edge_groups(const WeightedGraph& g, int max_weight, Random& random, int& groups) {
  const int n = g.size();
  std::vector<int> mate(n, -1);
  for (const int v : random.permutation(n)) {
    if (mate[v] >= 0) continue;
    int best = v, best_weight = 0;
    for (int e = g.start[v]; e < g.start[v + 1]; ++e) {
      const int u = g.neighbour[e];
      if (mate[u] < 0 && u != v && g.edge_weight[e] > best_weight &&
          g.vertex_weight[v] + g.vertex_weight[u] <= max_weight) {
        best = u;
        best_weight = g.edge_weight[e];
      }
    }
    mate[v] = best;
    mate[best] = v;
  }
  std::vector<int> group(n, -1);
  groups = 0;
  for (int v = 0; v < n; ++v) {
    if (group[v] < 0) group[v] = group[mate[v]] = groups++;
  }
  return group;
}

// Which side each vertex of a bisection is on, and the sides' weights.
struct Bisection {
  std::vector<std::int8_t> side;
  long long weight[2] = {0, 0};
  long long cut = 0;

  // How far the heavier side is over `limit` (0: balanced).
  long long excess(long long limit) const { return std::max<long long>(0, std::max(weight[0], weight[1]) - limit); }
  bool better_than(const Bisection& other, long long limit) const {
    const long long mine = excess(limit), theirs = other.excess(limit);
    return mine < theirs || (mine == theirs && cut < other.cut);
  }
};

// Fiduccia-Mattheyses refinement: per pass, the boundary vertex whose move
// to the other side lowers the cut most (within the balance) moves and is
// locked, its neighbours' gains follow, and the pass goes back to the best
// bisection it passed through.
class Refinement {
 public:
  // The bisection of g with these sides: its weights, cut and gains.
  Refinement(const WeightedGraph& g, long long limit, std::vector<std::int8_t> side)
      : g_(g), limit_(limit), internal_(g.size(), 0), external_(g.size(), 0), locked_(g.size(), 0),
        listed_(g.size(), 0) {
    b_.side = std::move(side);
    for (int v = 0; v < g.size(); ++v) {
      b_.weight[b_.side[v]] += g.vertex_weight[v];
      for (int e = g.start[v]; e < g.start[v + 1]; ++e) {
        (b_.side[g.neighbour[e]] == b_.side[v] ? internal_[v] : external_[v]) += g.edge_weight[e];
      }
      if (external_[v] > 0) boundary_.push_back(v);
      b_.cut += external_[v];
    }
    b_.cut /= 2;
  }

  Bisection run() {
    const int patience = std::clamp(g_.size() / 100, kMinPatience, kMaxPatience);
    for (int pass = 0; pass < kRefinePasses; ++pass) {
      for (int s = 0; s < 2; ++s) heap_[s] = {};
      for (const int v : boundary_) heap_[b_.side[v]].emplace(gain(v), v);
      moved_.clear();
      long long best_cut = b_.cut, best_excess = b_.excess(limit_);
      std::size_t best_moves = 0;
      int since_best = 0;
      while (since_best < patience) {
        const int v = next_move();
        if (v < 0) break;
        move(v);
        locked_[v] = 1;
        moved_.push_back(v);
        const long long excess = b_.excess(limit_);
        if (excess < best_excess || (excess == best_excess && b_.cut < best_cut)) {
          best_cut = b_.cut;
          best_excess = excess;
          best_moves = moved_.size();
          since_best = 0;
        } else {
          ++since_best;
        }
      }
      for (const int v : moved_) locked_[v] = 0;
      for (std::size_t k = moved_.size(); k > best_moves; --k) move(moved_[k - 1]);
      if (best_moves == 0) break;
      update_boundary();
    }
    return std::move(b_);
  }

 private:
  // The boundary after a pass: only the moved vertices and their neighbours
  // can have joined or left it.
  void update_boundary() {
    std::vector<int> next;
    auto consider = [&](int v) {
      if (listed_[v] || external_[v] <= 0) return;
      listed_[v] = 1;
      next.push_back(v);
    };
    for (const int v : boundary_) consider(v);
    for (std::size_t k = 0; k < moved_.size(); ++k) {
      const int v = moved_[k];
      consider(v);
      for (int e = g_.start[v]; e < g_.start[v + 1]; ++e) consider(g_.neighbour[e]);
    }
    for (const int v : next) listed_[v] = 0;
    boundary_ = std::move(next);
  }

  int gain(int v) const { return external_[v] - internal_[v]; }

  // The move to make: each side's best valid entry (stale ones, of moved or
  // re-gained vertices, dropped), allowed if it leaves the other side within
  // the limit or comes off a side over it; the larger gain, or from the
  // heavier side. -1: none.
  int next_move() {
    int candidate[2] = {-1, -1};
    for (int s = 0; s < 2; ++s) {
      while (!heap_[s].empty()) {
        const auto [g, v] = heap_[s].top();
        if (!locked_[v] && b_.side[v] == s && g == gain(v)) {
          const bool allowed = b_.weight[1 - s] + g_.vertex_weight[v] <= limit_ || b_.weight[s] > limit_;
          if (allowed) candidate[s] = v;
          break;
        }
        heap_[s].pop();
      }
    }
    if (candidate[0] < 0 || candidate[1] < 0) return std::max(candidate[0], candidate[1]);
    const int g0 = gain(candidate[0]), g1 = gain(candidate[1]);
    if (g0 != g1) return g0 > g1 ? candidate[0] : candidate[1];
    return b_.weight[0] >= b_.weight[1] ? candidate[0] : candidate[1];
  }

  // v to the other side, the cut, the weights and its neighbours' gains updated.
  void move(int v) {
    const int from = b_.side[v], to = 1 - from;
    b_.cut -= gain(v);
    b_.weight[from] -= g_.vertex_weight[v];
    b_.weight[to] += g_.vertex_weight[v];
    b_.side[v] = static_cast<std::int8_t>(to);
    std::swap(internal_[v], external_[v]);
    for (int e = g_.start[v]; e < g_.start[v + 1]; ++e) {
      const int u = g_.neighbour[e], w = g_.edge_weight[e];
      if (b_.side[u] == to) {
        internal_[u] += w;
        external_[u] -= w;
      } else {
        internal_[u] -= w;
        external_[u] += w;
      }
      if (!locked_[u] && external_[u] > 0) heap_[b_.side[u]].emplace(gain(u), u);
    }
  }

  const WeightedGraph& g_;
  const long long limit_;
  Bisection b_;
  std::vector<int> internal_, external_;  // per vertex: its edges' weight to its own side, to the other
  std::vector<char> locked_, listed_;
  std::vector<int> boundary_;  // the vertices with an edge to the other side
  std::priority_queue<std::pair<int, int>> heap_[2];  // per side: (gain, vertex)
  std::vector<int> moved_;
};

Bisection refined(const WeightedGraph& g, long long limit, std::vector<std::int8_t> side) {
  return Refinement(g, limit, std::move(side)).run();
}

// The coarsest graph's bisection: side A grown breadth-first from a random
// vertex to half the weight (jumping to another component when one is
// used up), refined; the best of kInitialTries.
Bisection initial_bisection(const WeightedGraph& g, long long limit, Random& random) {
  const int n = g.size();
  long long total = 0;
  for (const int w : g.vertex_weight) total += w;
  Bisection best;
  std::vector<int> queue;
  for (int attempt = 0; attempt < kInitialTries; ++attempt) {
    std::vector<std::int8_t> side(n, kSideB);
    std::vector<char> reached(n, 0);
    const int first = random.below(n);
    long long grown = 0;
    int next_start = first;
    queue.assign(1, first);
    reached[first] = 1;
    std::size_t head = 0;
    while (2 * grown < total) {
      if (head == queue.size()) {
        while (reached[next_start]) next_start = (next_start + 1) % n;
        reached[next_start] = 1;
        queue.push_back(next_start);
      }
      const int v = queue[head++];
      side[v] = kSideA;
      grown += g.vertex_weight[v];
      for (int e = g.start[v]; e < g.start[v + 1]; ++e) {
        const int u = g.neighbour[e];
        if (!reached[u]) {
          reached[u] = 1;
          queue.push_back(u);
        }
      }
    }
    Bisection b = refined(g, limit, std::move(side));
    if (attempt == 0 || b.better_than(best, limit)) best = std::move(b);
  }
  return best;
}

// The cut edges' minimum vertex cover: a maximum matching of the bipartite
// graph they form (augmenting paths by breadth-first search), then König's
// construction from the vertices of side A it leaves unmatched.
void cover_cut(const WeightedGraph& g, std::vector<std::int8_t>& part) {
  const int n = g.size();
  std::vector<int> boundary_a, mate(n, -1);
  auto crosses = [&](int v, int e) {
    const int u = g.neighbour[e];
    return part[u] != part[v] && part[u] != kSeparator;
  };
  for (int v = 0; v < n; ++v) {
    if (part[v] != kSideA) continue;
    for (int e = g.start[v]; e < g.start[v + 1]; ++e) {
      if (crosses(v, e)) {
        boundary_a.push_back(v);
        break;
      }
    }
  }
  // via[u]: for a side-B vertex reached in a search, the side-A vertex it was reached from.
  std::vector<int> via(n, -1), seen(n, -1), queue;
  for (std::size_t k = 0; k < boundary_a.size(); ++k) {
    const int root = boundary_a[k];
    queue.assign(1, root);
    int free_end = -1;
    for (std::size_t head = 0; head < queue.size() && free_end < 0; ++head) {
      const int a = queue[head];
      for (int e = g.start[a]; e < g.start[a + 1]; ++e) {
        const int b = g.neighbour[e];
        if (!crosses(a, e) || seen[b] == static_cast<int>(k)) continue;
        seen[b] = static_cast<int>(k);
        via[b] = a;
        if (mate[b] < 0) {
          free_end = b;
          break;
        }
        queue.push_back(mate[b]);
      }
    }
    // Flip the augmenting path back to the root.
    for (int b = free_end; b >= 0;) {
      const int a = via[b], next = mate[a];
      mate[a] = b;
      mate[b] = a;
      b = next;
    }
  }
  // Z: reached from unmatched side-A vertices by alternating paths.
  std::vector<char> in_z(n, 0);
  queue.clear();
  for (const int a : boundary_a) {
    if (mate[a] < 0) {
      in_z[a] = 1;
      queue.push_back(a);
    }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int a = queue[head];
    for (int e = g.start[a]; e < g.start[a + 1]; ++e) {
      const int b = g.neighbour[e];
      if (!crosses(a, e) || in_z[b]) continue;
      in_z[b] = 1;
      if (mate[b] >= 0 && !in_z[mate[b]]) {
        in_z[mate[b]] = 1;
        queue.push_back(mate[b]);
      }
    }
  }
  // The cover: side-A boundary vertices not in Z, side-B ones in Z. Marked
  // after the search (crosses() reads the sides).
  std::vector<int> cover;
  for (const int a : boundary_a) {
    if (!in_z[a]) cover.push_back(a);
    for (int e = g.start[a]; e < g.start[a + 1]; ++e) {
      const int b = g.neighbour[e];
      if (crosses(a, e) && in_z[b]) cover.push_back(b);
    }
  }
  for (const int v : cover) part[v] = kSeparator;
}

}  // namespace

WeightedGraph contract(const WeightedGraph& g, const std::vector<int>& group, int groups) {
  const int n = g.size();
  // The members of each group, in vertex order.
  std::vector<int> member_start(groups + 1, 0), members(n);
  for (int v = 0; v < n; ++v) ++member_start[group[v] + 1];
  for (int c = 0; c < groups; ++c) member_start[c + 1] += member_start[c];
  {
    std::vector<int> filled(member_start.begin(), member_start.end() - 1);
    for (int v = 0; v < n; ++v) members[filled[group[v]]++] = v;
  }
  WeightedGraph coarse;
  coarse.start.reserve(groups + 1);
  coarse.vertex_weight.assign(groups, 0);
  coarse.neighbour.reserve(g.neighbour.size());
  coarse.edge_weight.reserve(g.neighbour.size());
  std::vector<int> slot(groups, -1);
  for (int c = 0; c < groups; ++c) {
    const std::size_t first = coarse.neighbour.size();
    for (int k = member_start[c]; k < member_start[c + 1]; ++k) {
      const int v = members[k];
      coarse.vertex_weight[c] += g.vertex_weight[v];
      for (int e = g.start[v]; e < g.start[v + 1]; ++e) {
        const int d = group[g.neighbour[e]];
        if (d == c) continue;
        if (slot[d] < 0) {
          slot[d] = static_cast<int>(coarse.neighbour.size());
          coarse.neighbour.push_back(d);
          coarse.edge_weight.push_back(g.edge_weight[e]);
        } else {
          coarse.edge_weight[slot[d]] += g.edge_weight[e];
        }
      }
    }
    for (std::size_t k = first; k < coarse.neighbour.size(); ++k) slot[coarse.neighbour[k]] = -1;
    coarse.start.push_back(static_cast<int>(coarse.neighbour.size()));
  }
  return coarse;
}

std::vector<std::int8_t> vertex_separator(const WeightedGraph& g, std::uint64_t seed) {
  const int n = g.size();
  if (n == 0) return {};
  Random random(seed);
  long long total = 0;
  for (const int w : g.vertex_weight) total += w;
  const long long limit = static_cast<long long>((1.0 + kImbalance) * 0.5 * static_cast<double>(total)) + 1;
  const int max_weight = std::max(1, static_cast<int>(kMaxVertexShare * static_cast<double>(total) / kCoarsest));
  // The levels: graphs[0] is g's first coarsening, groups[k] maps level k's
  // vertices (g's for k = 0) to level k + 1's.
  std::vector<WeightedGraph> graphs;
  std::vector<std::vector<int>> groups;
  const WeightedGraph* current = &g;
  while (current->size() > kCoarsest) {
    int count = 0;
    std::vector<int> group = heavy_edge_groups(*current, max_weight, random, count);
    if (count > kMinShrink * current->size()) break;
    graphs.push_back(contract(*current, group, count));
    groups.push_back(std::move(group));
    current = &graphs.back();
  }
  Bisection b = initial_bisection(*current, limit, random);
  for (int level = static_cast<int>(groups.size()) - 1; level >= 0; --level) {
    const WeightedGraph& fine = level == 0 ? g : graphs[level - 1];
    std::vector<std::int8_t> side(fine.size());
    for (int v = 0; v < fine.size(); ++v) side[v] = b.side[groups[level][v]];
    b = refined(fine, limit, std::move(side));
  }
  std::vector<std::int8_t> part = std::move(b.side);
  cover_cut(g, part);
  return part;
}

}  // namespace aniso
