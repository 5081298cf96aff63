#include "geometry/frames.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <utility>

#include <Eigen/Geometry>

#include "anisoform/error.h"
#include "mesh/topology.h"

namespace aniso {

Positions triangle_normals(const Mesh& mesh) { return triangle_normals(mesh.V, mesh.F); }

Positions triangle_normals(const Positions& V, const Triangles& F) {
  const auto m = F.rows();
  Positions N(m, 3);
  for (Eigen::Index t = 0; t < m; ++t) {
    const Eigen::Vector3d a = V.row(F(t, 0));
    const Eigen::Vector3d b = V.row(F(t, 1));
    const Eigen::Vector3d c = V.row(F(t, 2));
    const Eigen::Vector3d cr = (b - a).cross(c - a);
    const double len = cr.norm();
    N.row(t) = (len > 0.0 && std::isfinite(len)) ? Eigen::Vector3d(cr / len) : Eigen::Vector3d::Zero();
  }
  return N;
}

Positions vertex_normals(const Mesh& mesh) {
  const int n = mesh.num_vertices();
  Positions N = Positions::Zero(n, 3);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(t, 0));
    const Eigen::Vector3d b = mesh.V.row(mesh.F(t, 1));
    const Eigen::Vector3d c = mesh.V.row(mesh.F(t, 2));
    const Eigen::Vector3d area_normal = (b - a).cross(c - a);  // twice the area times the normal
    if (!area_normal.allFinite()) continue;
    for (int k = 0; k < 3; ++k) N.row(mesh.F(t, k)) += area_normal.transpose();
  }
  std::vector<char> ok(n, 0);
  for (int i = 0; i < n; ++i) {
    const double len = N.row(i).norm();
    if (len > 0.0) {
      N.row(i) /= len;
      ok[i] = 1;
    }
  }
  // Vertices with no usable face take their neighbours' mean normal, outwards.
  const VertexAdjacency adj = vertex_adjacency(mesh.F, n);
  bool changed = true;
  while (changed) {
    changed = false;
    for (int i = 0; i < n; ++i) {
      if (ok[i]) continue;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int k = adj.offsets[i]; k < adj.offsets[i + 1]; ++k) {
        if (ok[adj.neighbors[k]]) sum += N.row(adj.neighbors[k]).transpose();
      }
      if (sum.norm() > 0.0) {
        N.row(i) = sum.normalized().transpose();
        ok[i] = 1;
        changed = true;
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!ok[i]) N.row(i) = Eigen::RowVector3d(0, 0, 1);
  }
  return N;
}

namespace {

// Unit tangent direction of d at normal n, or zero when d is (nearly) normal.
Eigen::Vector3d project_tangent(const Eigen::Vector3d& d, const Eigen::Vector3d& n,
                                double degenerate_fraction) {
  const Eigen::Vector3d t = d - d.dot(n) * n;
  const double len = t.norm();
  const double ref = d.norm();
  if (!(ref > 0.0) || !(len > degenerate_fraction * ref) || !std::isfinite(len)) {
    return Eigen::Vector3d::Zero();
  }
  return t / len;
}

// Any unit vector orthogonal to n.
Eigen::Vector3d any_tangent(const Eigen::Vector3d& n) {
  const Eigen::Vector3d axis = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  Eigen::Vector3d t = axis - axis.dot(n) * n;
  return t.norm() > 0 ? Eigen::Vector3d(t.normalized()) : Eigen::Vector3d::UnitX();
}

}  // namespace

Frames build_frames(const Positions& normals, const Positions& directions, const NeighborsOf& neighbors_of,
                    double degenerate_fraction) {
  const int count = static_cast<int>(normals.rows());
  Frames frames;
  frames.u.resize(count, 3);
  frames.v.resize(count, 3);
  frames.n = normals;
  std::vector<char> known(count, 0);
  frames.along_normal.assign(count, 0);
  std::deque<int> pending;
  for (int e = 0; e < count; ++e) {
    const Eigen::Vector3d n = normals.row(e);
    const Eigen::Vector3d t = project_tangent(directions.row(e).transpose(), n, degenerate_fraction);
    frames.u.row(e) = t.transpose();
    if (t.squaredNorm() > 0.0) {
      known[e] = 1;
    } else {
      ++frames.filled;
      frames.along_normal[e] = 1;
    }
  }
  if (count > 0 && frames.filled == count) {
    // Nothing to fill from: any direction chosen here would be arbitrary,
    // and the edit or the pattern would silently go another way.
    fail(ErrorCode::BadParameter,
         "the direction is (nearly) parallel to the surface normal everywhere: it gives no direction along the "
         "surface to stretch along; pick a direction that runs along the surface, e.g. another axis");
  }
  if (frames.filled > 0) {
    const VertexAdjacency& adjacency = neighbors_of();
    const std::vector<int>& neighbor_offsets = adjacency.offsets;
    const std::vector<int>& neighbors = adjacency.neighbors;
    // Breadth-first fill from known elements: each unknown element takes the
    // line-field mean of its known neighbours (signs aligned to the first one),
    // projected into its own tangent plane.
    for (int e = 0; e < count; ++e) {
      if (known[e]) continue;
      for (int k = neighbor_offsets[e]; k < neighbor_offsets[e + 1]; ++k) {
        if (known[neighbors[k]]) {
          pending.push_back(e);
          break;
        }
      }
    }
    while (!pending.empty()) {
      const int e = pending.front();
      pending.pop_front();
      if (known[e]) continue;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      Eigen::Vector3d reference = Eigen::Vector3d::Zero();
      for (int k = neighbor_offsets[e]; k < neighbor_offsets[e + 1]; ++k) {
        const int f = neighbors[k];
        if (!known[f]) continue;
        Eigen::Vector3d d = frames.u.row(f).transpose();
        if (reference.squaredNorm() == 0.0) reference = d;
        if (d.dot(reference) < 0.0) d = -d;
        sum += d;
      }
      const Eigen::Vector3d n = normals.row(e);
      Eigen::Vector3d t = project_tangent(sum, n, degenerate_fraction);
      if (t.squaredNorm() == 0.0) t = project_tangent(reference, n, 0.0);
      if (t.squaredNorm() == 0.0) t = any_tangent(n);
      frames.u.row(e) = t.transpose();
      known[e] = 1;
      for (int k = neighbor_offsets[e]; k < neighbor_offsets[e + 1]; ++k) {
        if (!known[neighbors[k]]) pending.push_back(neighbors[k]);
      }
    }
    for (int e = 0; e < count; ++e) {
      if (!known[e]) frames.u.row(e) = any_tangent(normals.row(e).transpose()).transpose();
    }
  }
  for (int e = 0; e < count; ++e) {
    const Eigen::Vector3d n = normals.row(e);
    const Eigen::Vector3d u = frames.u.row(e);
    frames.v.row(e) = n.cross(u).transpose();
  }
  return frames;
}

void triangle_adjacency(const Triangles& F, int num_vertices, std::vector<int>& offsets,
                        std::vector<int>& neighbors) {
  // Every side between two distinct vertices, grouped by its edge: the sides
  // are bucketed by their lower vertex (a counting sort), and each bucket,
  // a few sides on a mesh, is sorted by its upper vertex and face. O(m log m)
  // whatever the topology, a vertex of k sides costing O(k log k). (A scan
  // of each vertex's faces would be quadratic in a vertex's valence, and a
  // face repeated k times has valence k.) One sort of all the sides and one
  // of all the links took 0.16 s of the 200k-vertex koala's first edit.
  const int m = static_cast<int>(F.rows());
  const auto for_each_side = [&F, m, num_vertices](auto&& visit) {
    for (int t = 0; t < m; ++t) {
      for (int k = 0; k < 3; ++k) {
        const int a = F(t, k), b = F(t, (k + 1) % 3);
        if (a == b || a < 0 || b < 0 || a >= num_vertices || b >= num_vertices) continue;
        visit(std::min(a, b), std::max(a, b), t);
      }
    }
  };
  struct Side {
    int hi, face;
  };
  std::vector<int> bucket(static_cast<std::size_t>(num_vertices) + 1, 0);
  for_each_side([&bucket](int lo, int, int) { ++bucket[lo + 1]; });
  for (int v = 0; v < num_vertices; ++v) bucket[v + 1] += bucket[v];
  std::vector<Side> sides(static_cast<std::size_t>(bucket[num_vertices]));
  {
    std::vector<int> next(bucket.begin(), bucket.end() - 1);
    for_each_side([&sides, &next](int lo, int hi, int t) { sides[next[lo]++] = {hi, t}; });
  }
  // Links (face, neighbour). An edge of two faces links them; an edge of k > 2
  // faces (non-manifold, or one face repeated) links each to the next around
  // a ring in index order: connected like the k-clique, but O(k) links.
  const auto for_each_link = [&sides, &bucket, num_vertices](auto&& link) {
    for (int v = 0; v < num_vertices; ++v) {
      const auto first = sides.begin() + bucket[v], last = sides.begin() + bucket[v + 1];
      std::sort(first, last, [](const Side& x, const Side& y) {
        return x.hi != y.hi ? x.hi < y.hi : x.face < y.face;
      });
      for (auto begin = first; begin != last;) {
        auto end = begin + 1;
        while (end != last && end->hi == begin->hi) ++end;
        const std::ptrdiff_t k = end - begin;
        for (std::ptrdiff_t i = 0; k >= 2 && i < (k == 2 ? 1 : k); ++i) {
          const int s = begin[i].face;
          const int t = begin[(i + 1) % k].face;
          if (s == t) continue;  // a face with a repeated corner uses its edge twice
          link(s, t);
          link(t, s);
        }
        begin = end;
      }
    }
  };
  // Counted, then placed by face (the buckets are sorted by the first pass:
  // the second places the same links in the same order).
  offsets.assign(static_cast<std::size_t>(m) + 1, 0);
  for_each_link([&offsets](int face, int) { ++offsets[face + 1]; });
  for (int t = 0; t < m; ++t) offsets[t + 1] += offsets[t];
  neighbors.resize(static_cast<std::size_t>(offsets[m]));
  {
    std::vector<int> next(offsets.begin(), offsets.end() - 1);
    for_each_link([&neighbors, &next](int face, int other) { neighbors[next[face]++] = other; });
  }
  // Each face's neighbours in increasing order, each once.
  int kept = 0;
  for (int t = 0; t < m; ++t) {
    const auto first = neighbors.begin() + offsets[t], last = neighbors.begin() + offsets[t + 1];
    std::sort(first, last);
    const auto unique_end = std::unique(first, last);
    offsets[t] = kept;
    kept = static_cast<int>(std::copy(first, unique_end, neighbors.begin() + kept) - neighbors.begin());
  }
  offsets[m] = kept;
  neighbors.resize(static_cast<std::size_t>(kept));
}

}  // namespace aniso
