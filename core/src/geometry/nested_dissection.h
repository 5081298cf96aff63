// A fill-reducing ordering for the sparse factorizations of large mesh
// matrices (Laplacians, the flattening's Newton systems): nested dissection
// (George 1973) with separators by multilevel bisection
// (geometry/graph_bisection.h), AMD (Eigen's) on the pieces too small to
// split. Why not AMD alone: on the graphs of surface meshes, which are
// nearly planar, nested dissection's separators of about sqrt(n) vertices
// leave less fill and far fewer operations as the mesh grows; CHOLMOD
// switches to METIS's nested dissection for the same reason, and METIS is
// not available to the WASM build.
#pragma once

#include <vector>

#include <Eigen/SparseCore>

namespace aniso {

// The elimination order of the symmetric pattern of A (its lower triangle
// is read, values ignored): order[k] is the row of A eliminated k-th, as the
// indices of Eigen's orderings' permutations. Rows with the same neighbours
// (u and v of one vertex in the Newton systems) are ordered together.
std::vector<int> nested_dissection_order(const Eigen::SparseMatrix<double>& A);

}  // namespace aniso
