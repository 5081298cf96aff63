// Signs for a line field's vectors. A line field (curvature lines, the field
// propagated from arrows) has no sign, but the transforms that turn one way
// (a shear along cu, a rotation about cu or cv) do: neighbours whose vectors
// point opposite ways are sheared or turned opposite ways, and the shape tears
// between them. So the vectors are given signs that agree across edges.
#pragma once

#include <vector>

#include "anisoform/mesh.h"
#include "mesh/topology.h"

namespace aniso {

// Flips rows of `direction` (#V by 3) so that neighbours agree in sign
// (positive dot product). Signs grow outwards from the `seed` vertices, which
// keep theirs; a connected part without a seed starts from its lowest-index
// free vertex. Only vertices with `free` set are flipped or passed through.
//
// The growth takes the most nearly parallel pending edge first (a maximum
// spanning tree on |d_i . d_j|, Prim's order): an edge across which the line
// turns by nearly 90 degrees says little about the sign, so it is decided
// last. Where the field turns half-way round a singularity no consistent
// choice exists; the one seam then falls on such edges.
void orient_line_field(const VertexAdjacency& adjacency, const std::vector<char>& seed,
                       const std::vector<char>& free, Positions& direction);

}  // namespace aniso
