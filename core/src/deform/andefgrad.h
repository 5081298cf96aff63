// AnDefGrad (METHOD §6): one Poisson solve per change of the targets.
//
//   min_{v'} sum_t A_t || grad_t v' - T_t grad_t v ||_F^2
//     = sum_t sum_{edges (a,b) of t} W_t,ab || e'_ab - T_t e_ab ||^2
// (the identity holds per triangle with W = half cotangents), so the normal
// equations are L v' = b with the same cotangent Laplacian as AnARAP and
// b_a = sum_t sum_b W_t,ab T_t (v_a - v_b): one factorization serves both.
#pragma once

#include <vector>

#include "anisoform/laplacian.h"
#include "anisoform/mesh.h"

namespace aniso {

// b (#V by 3) from per-triangle targets T (#F).
void gradient_rhs(const Mesh& rest, const CotanWeights& weights,
                  const std::vector<Eigen::Matrix3d>& T, Positions& b);

// sum_t sum_edges W || e'_ab - T_t e_ab ||^2 at positions V.
double gradient_energy(const Mesh& rest, const CotanWeights& weights,
                       const std::vector<Eigen::Matrix3d>& T, const Positions& V);

}  // namespace aniso
