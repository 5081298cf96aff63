// Least-squares conformal map with a free boundary (Levy et al. 2002): the
// start of the ARAP iterations. Conformal maps of a developable patch are
// isometries up to a similarity, so after scaling to the 3D area the start is
// already exact there and ARAP has nothing left to do.
#include <array>
#include <cmath>
#include <complex>
#include <vector>

#include <Eigen/SparseCholesky>

#include "anisoform/error.h"
#include "flatten/flatten_pipeline.h"

namespace aniso {

namespace {

// Two boundary vertices per component, far apart: a double sweep over its
// boundary vertices (farthest from any, then farthest from that one), which
// finds the diameter or close to it. Pinning them far apart keeps LSCM from
// collapsing towards a pin.
std::vector<std::array<int, 2>> pin_pairs(const FlattenPatch& patch) {
  std::vector<std::vector<int>> boundary(patch.num_components);
  for (std::size_t l = 0; l < patch.boundary_loops.size(); ++l) {
    const std::vector<int>& loop = patch.boundary_loops[l];
    auto& list = boundary[patch.loop_component[l]];
    list.insert(list.end(), loop.begin(), loop.end());
  }
  const Positions& V = patch.mesh.V;
  const auto farthest_from = [&V](const std::vector<int>& candidates, int from) {
    int best = candidates.front();
    double best_distance = -1.0;
    for (int i : candidates) {
      const double distance = (V.row(i) - V.row(from)).squaredNorm();
      if (distance > best_distance) {
        best_distance = distance;
        best = i;
      }
    }
    return best;
  };
  std::vector<std::array<int, 2>> pins(patch.num_components);
  for (int c = 0; c < patch.num_components; ++c) {
    const int first = farthest_from(boundary[c], boundary[c].front());
    const int second = farthest_from(boundary[c], first);
    pins[c] = {first, second};
  }
  return pins;
}

}  // namespace

void lscm_free_boundary(const FlattenPatch& patch, const TriangleCharts& charts,
                        Eigen::MatrixX2d& uv) {
  using Complex = std::complex<double>;
  const int n = patch.mesh.num_vertices();
  const Triangles& F = patch.mesh.F;

  // Unknowns z_i = u_i + i v_i; the pinned ones get no column of their own.
  std::vector<Complex> pinned_value(n, Complex(0.0, 0.0));
  std::vector<char> is_pinned(n, 0);
  for (const auto& pair : pin_pairs(patch)) {
    const double distance = (patch.mesh.V.row(pair[0]) - patch.mesh.V.row(pair[1])).norm();
    pinned_value[pair[1]] = Complex(distance > 0.0 ? distance : 1.0, 0.0);
    is_pinned[pair[0]] = is_pinned[pair[1]] = 1;
  }
  std::vector<int> free_index(n, -1);
  int free_count = 0;
  for (int i = 0; i < n; ++i) {
    if (!is_pinned[i]) free_index[i] = free_count++;
  }

  // One complex residual per triangle, sqrt(area) * (grad u + i grad v) with
  // gradients written as complex numbers: (u_x - v_y) + i (u_y + v_x), the
  // Cauchy-Riemann equations in the triangle's chart. Its squared modulus
  // summed is the conformal energy; the complex form keeps the system n by n
  // (Hermitian) instead of 2n by 2n real, a quarter of the factor's fill.
  std::vector<Eigen::Triplet<Complex>> free_entries;
  Eigen::VectorXcd pinned_part = Eigen::VectorXcd::Zero(F.rows());
  free_entries.reserve(static_cast<std::size_t>(F.rows()) * 3);
  for (int t = 0; t < F.rows(); ++t) {
    const double area = charts.area[t];
    if (!(area > 0.0)) continue;
    const double weight = std::sqrt(area) / (2.0 * area);
    for (int k = 0; k < 3; ++k) {
      // Gradient of corner k's hat function = rot90(edge opposite k) / (2 area).
      const int p = (k + 1) % 3, q = (k + 2) % 3;
      const double ex = charts.corners(t, 2 * q) - charts.corners(t, 2 * p);
      const double ey = charts.corners(t, 2 * q + 1) - charts.corners(t, 2 * p + 1);
      const Complex gradient(-ey * weight, ex * weight);
      const int vertex = F(t, k);
      if (is_pinned[vertex]) {
        pinned_part[t] += gradient * pinned_value[vertex];
      } else {
        free_entries.emplace_back(t, free_index[vertex], gradient);
      }
    }
  }
  Eigen::SparseMatrix<Complex> A(F.rows(), free_count);
  A.setFromTriplets(free_entries.begin(), free_entries.end());
  const Eigen::SparseMatrix<Complex> A_adjoint = A.adjoint();
  const Eigen::SparseMatrix<Complex> normal = A_adjoint * A;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<Complex>> solver(normal);
  if (solver.info() != Eigen::Success) {
    fail(ErrorCode::Numerical, "the conformal start map could not be factored (LSCM)");
  }
  const Eigen::VectorXcd free_values = solver.solve(-(A_adjoint * pinned_part));
  if (solver.info() != Eigen::Success || !free_values.allFinite()) {
    fail(ErrorCode::Numerical, "the conformal start map could not be solved (LSCM)");
  }

  uv.resize(n, 2);
  for (int i = 0; i < n; ++i) {
    const Complex z = is_pinned[i] ? pinned_value[i] : free_values[free_index[i]];
    uv.row(i) = Eigen::RowVector2d(z.real(), z.imag());
  }
  scale_to_area(patch, charts.area, uv);
}

}  // namespace aniso
