// The one linear solve behind direction-field propagation (private to the
// core): minimise a Laplacian-type energy over free vertices with the other
// vertices held at given values. Templated on the scalar so that the same code
// solves the complex connection Laplacian of line fields and the real
// cotangent Laplacian of amounts.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "anisoform/error.h"
#include "geometry/supernodal_ldlt.h"

namespace aniso::field {

// An undirected mesh edge i-j with its (summed) cotangent weight.
struct WeightedEdge {
  int i;
  int j;
  double weight;
};

template <typename Scalar>
using ValueMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

// Minimises sum over edges k of w_k |x_i - t_k x_j|^2 over the rows with
// is_free[i] != 0, the other rows of `values` (#V by c, one column per field)
// held fixed. t_k = transport(k) carries a value at j into i's basis (|t| = 1;
// t = 1 for scalars). Free rows are overwritten with the minimiser.
//
// The system is Hermitian. Built from whole triangles' cotangent weights it is
// positive semidefinite (each triangle's linear-FEM stiffness is, negative
// cotangents included; for line fields up to the transport's tiny turn within
// one triangle) and definite once every free vertex is connected to a fixed
// one, which the caller guarantees. LDL^T needs only non-zero pivots. Only the
// lower triangle is assembled: that is all the factorization reads, and it
// halves the assembly's memory on large meshes.
template <typename Scalar, typename Transport>
void solve_with_fixed_values(const std::vector<WeightedEdge>& edges, Transport transport,
                             const std::vector<char>& is_free, const std::string& what,
                             ValueMatrix<Scalar>& values) {
  const int n = static_cast<int>(is_free.size());
  std::vector<int> free_index(n, -1);
  int free_count = 0;
  for (int i = 0; i < n; ++i) {
    if (is_free[i]) free_index[i] = free_count++;
  }
  if (free_count == 0) return;

  std::vector<Eigen::Triplet<Scalar>> lower;
  lower.reserve(edges.size() + free_count);
  std::vector<double> diagonal(free_count, 0.0);
  ValueMatrix<Scalar> rhs = ValueMatrix<Scalar>::Zero(free_count, values.cols());
  // Stationarity of the energy in conj(x): edge k adds w (x_i - t x_j) to row
  // i and w (x_j - conj(t) x_i) to row j.
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const WeightedEdge& edge = edges[k];
    const Scalar t = transport(k);
    const int ri = free_index[edge.i];
    const int rj = free_index[edge.j];
    if (ri >= 0) diagonal[ri] += edge.weight;
    if (rj >= 0) diagonal[rj] += edge.weight;
    if (ri >= 0 && rj >= 0) {
      if (ri > rj) {
        lower.emplace_back(ri, rj, -edge.weight * t);
      } else {
        lower.emplace_back(rj, ri, -edge.weight * Eigen::numext::conj(t));
      }
    } else if (ri >= 0) {
      rhs.row(ri) += (edge.weight * t) * values.row(edge.j);
    } else if (rj >= 0) {
      rhs.row(rj) += (edge.weight * Eigen::numext::conj(t)) * values.row(edge.i);
    }
  }
  for (int r = 0; r < free_count; ++r) lower.emplace_back(r, r, Scalar(diagonal[r]));
  Eigen::SparseMatrix<Scalar> system(free_count, free_count);
  system.setFromTriplets(lower.begin(), lower.end());

  // The supernodal LDL^H (geometry/supernodal_ldlt.h): pivots of either sign,
  // only a zero one is refused.
  ValueMatrix<Scalar> solution = rhs;
  if (supernodal_solve(system, 0.0, solution) >= 0) {
    fail(ErrorCode::Numerical, what + ": the system could not be factored");
  }
  if (!solution.allFinite()) fail(ErrorCode::Numerical, what + ": the solve failed");
  for (int i = 0; i < n; ++i) {
    if (free_index[i] >= 0) values.row(i) = solution.row(free_index[i]);
  }
}

}  // namespace aniso::field
