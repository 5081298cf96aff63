// Cotangent weights and the cotangent Laplacian.
//
// Weights are kept per triangle corner so that every energy built on them
// (AnARAP spokes or spokes-and-rims, AnDefGrad, the flattening) uses exactly
// the weights the Laplacian was assembled from; that keeps the exact
// properties (linear maps reproduced, rest pose a fixed point) true whatever
// the clamping did.
//
// Handling of bad triangles (METHOD §2):
//  1. a triangle is "degenerate" when it has (nearly) zero area
//     (|cross| <= 1e-12 * longest edge^2) or a corner whose |cot| exceeds
//     kMaxCot (an angle under ~0.06 deg or over ~179.94 deg): it contributes
//     nothing, since its cotangents are meaningless;
//  2. every edge whose summed weight is below kMinWeightFraction * (mean |edge
//     weight|) is raised to that floor, the raise shared among its triangles:
//     edges of obtuse pairs (negative weights), of right-angled grids (zero)
//     and of degenerate triangles only (zero). With every weight positive, each
//     ARAP cell energy is a sum of squares (with negative weights it is not,
//     and on real meshes, e.g. the Loop-subdivided koala, the AnARAP energy
//     went negative and kept falling), L is an M-matrix, and every vertex stays
//     connected. The floor is tiny, so linear functions stay harmonic on flat
//     regions to ~1e-8 relative (exactly where no edge was raised).
// L is then positive semidefinite with exactly the constants of each connected
// component as its null space.
#pragma once

#include <Eigen/Sparse>

#include "anisoform/mesh.h"

namespace aniso {

constexpr double kMaxCot = 1e3;
constexpr double kMinWeightFraction = 1e-8;

struct CotanWeights {
  // #F by 3: weight(t, k) belongs to the edge opposite corner k of triangle t,
  // i.e. the edge (F(t,(k+1)%3), F(t,(k+2)%3)); it is half the cotangent of
  // corner k (0 in a degenerate triangle) plus its share of any floor weight.
  Eigen::MatrixX3d weight;
  int degenerate_triangles = 0;  // triangles left out (rule 1)
  int raised_edges = 0;          // edges raised to the floor weight (rule 2)
};

CotanWeights cotangent_weights(const Mesh& mesh);

// Symmetric positive semidefinite Laplacian (#V by #V): L(i,j) = -w_ij,
// L(i,i) = sum_j w_ij.
Eigen::SparseMatrix<double> cotangent_laplacian(const Mesh& mesh, const CotanWeights& weights);

}  // namespace aniso
