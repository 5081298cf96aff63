// Normals and the per-element frames of METHOD §3: C = [cu, cv, n] with cu the
// wanted direction projected into the tangent plane.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "anisoform/mesh.h"
#include "mesh/topology.h"

namespace aniso {

// Unit triangle normals (#F by 3); zero rows for zero-area triangles.
Positions triangle_normals(const Mesh& mesh);
// The same for positions V with triangles F (no Mesh to copy them into).
Positions triangle_normals(const Positions& V, const Triangles& F);

// Area-weighted unit vertex normals (#V by 3); a vertex whose faces are all
// degenerate (or that has none) takes the mean normal of its neighbours, else +z.
Positions vertex_normals(const Mesh& mesh);

struct Frames {
  Positions u;  // #E by 3: cu, the direction in the tangent plane (unit)
  Positions v;  // #E by 3: cv = n x cu
  Positions n;  // #E by 3: the element normal
  int filled = 0;  // elements whose projected direction was degenerate and
                   // were filled from their neighbours (METHOD §3)
  // Per element, 1 where the wanted direction is (nearly) its normal: it
  // gives the element no direction along its surface, and a scale acts on it
  // across the direction only, by sv in every direction of its plane (as
  // the 3D stretch along the direction does to a face square to it: a
  // cylinder's flat cap keeps its shape when the cylinder is stretched along
  // its axis). Its u is still filled, for a turn about u or v (a shear
  // leaves it unsheared: shear_share, element_targets.h).
  std::vector<char> along_normal;
};

// Frames for elements with normals `normals` and wanted directions
// `directions` (both #E by 3). Where the projection of the direction into the
// tangent plane is shorter than `degenerate_fraction` of its length (the
// direction is nearly parallel to the normal), the element takes the mean of its
// non-degenerate neighbours' directions (line-field mean, repeated outwards), as
// given by `neighbors_of()` (CSR: vertex_adjacency, or triangle_adjacency
// below). It is called once, and only when some element needs filling, which
// is rare: building a large mesh's adjacency costs more than its frames. With
// no usable direction at all in a component, an arbitrary tangent is used and
// still counted as filled; with none in any, Error(BadParameter).
using NeighborsOf = std::function<const VertexAdjacency&()>;
Frames build_frames(const Positions& normals, const Positions& directions, const NeighborsOf& neighbors_of,
                    double degenerate_fraction = 1e-3);

// Triangle-to-triangle adjacency through shared edges, CSR as above, each
// face's neighbours once, in index order. Two faces on a manifold edge are
// neighbours; on an edge of k > 2 faces each face is linked to the next one
// around (in index order), which connects them like all pairs would but keeps
// the size linear. O(#F log #F) for any topology.
void triangle_adjacency(const Triangles& F, int num_vertices,
                        std::vector<int>& offsets, std::vector<int>& neighbors);

}  // namespace aniso
