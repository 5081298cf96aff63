// Procedural test meshes shared by the native and the WASM benchmarks, so both
// time exactly the same input.
#pragma once

#include "anisoform/mesh.h"

namespace aniso {

// Closed, capped cylinder around the z axis, centred at the origin (z from
// -height/2 to height/2), built from near-equilateral triangles of one edge
// length chosen so that the mesh has about `approx_vertices` vertices.
// The side is a stack of rings, alternate rings rotated by half a step; each
// cap is a set of concentric rings closed by a centre vertex. Faces are
// counter-clockwise seen from outside. Throws BadParameter if
// approx_vertices < 16 or radius/height are not positive.
Mesh capped_cylinder(int approx_vertices, double radius = 1.0, double height = 4.0);

}  // namespace aniso
