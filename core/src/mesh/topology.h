// Connectivity queries on an indexed triangle mesh: components, boundary loops,
// vertex one-rings. Faces with an out-of-range index must have been rejected
// before these are called (mesh_io and check_mesh do that).
#pragma once

#include <vector>

#include "anisoform/mesh.h"

namespace aniso {

// Whether the three corners of face f are vertex indices in [0, num_vertices):
// the one test the mesh check (which reports such faces) and the queries
// below (which skip them) share.
bool face_in_range(const Triangles& F, Eigen::Index f, int num_vertices);

// Component label per vertex (#V); faces connect the vertices they share.
// Unreferenced vertices get a component of their own each.
// Labels are 0..count-1; returns count through `count` when not null.
std::vector<int> vertex_components(const Triangles& F, int num_vertices, int* count = nullptr);

// Number of face-connected components (faces sharing a vertex are connected;
// unreferenced vertices are not counted). This is what `info` reports.
int count_face_components(const Triangles& F, int num_vertices);

// Boundary loops as ordered vertex lists, following directed boundary half-edges
// (an edge used by exactly one face). Where a boundary vertex is non-manifold the
// walk still terminates; every boundary edge belongs to exactly one loop.
std::vector<std::vector<int>> boundary_loops(const Triangles& F, int num_vertices);

// true for each vertex that lies on a boundary edge (#V).
std::vector<char> boundary_vertex_mask(const Triangles& F, int num_vertices);

// Vertex-to-vertex adjacency in compressed form: neighbours of i are
// neighbors[offsets[i] .. offsets[i+1]), sorted ascending, no duplicates.
struct VertexAdjacency {
  std::vector<int> offsets;    // #V+1
  std::vector<int> neighbors;  // 2 * #edges
};
VertexAdjacency vertex_adjacency(const Triangles& F, int num_vertices);

// The vertices in breadth-first order over the edges (each component from its
// lowest vertex; unreferenced vertices where the index order meets them):
// order[k] is the vertex numbered k. Renumbered so, a vertex's neighbours get
// nearby numbers, whatever order the file had.
std::vector<int> breadth_first_order(const Triangles& F, int num_vertices);

}  // namespace aniso
