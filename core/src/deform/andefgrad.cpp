#include "deform/andefgrad.h"

namespace aniso {

void gradient_rhs(const Mesh& rest, const CotanWeights& weights,
                  const std::vector<Eigen::Matrix3d>& T, Positions& b) {
  b.setZero(rest.num_vertices(), 3);
  for (int t = 0; t < rest.num_triangles(); ++t) {
    const Eigen::Matrix3d& M = T[t];
    for (int k = 0; k < 3; ++k) {
      const int a = rest.F(t, (k + 1) % 3), c = rest.F(t, (k + 2) % 3);
      const Eigen::RowVector3d d =
          (weights.weight(t, k) * (M * (rest.V.row(a) - rest.V.row(c)).transpose())).transpose();
      b.row(a) += d;
      b.row(c) -= d;
    }
  }
}

double gradient_energy(const Mesh& rest, const CotanWeights& weights,
                       const std::vector<Eigen::Matrix3d>& T, const Positions& V) {
  double energy = 0.0;
  for (int t = 0; t < rest.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = rest.F(t, (k + 1) % 3), c = rest.F(t, (k + 2) % 3);
      const Eigen::Vector3d deformed = (V.row(c) - V.row(a)).transpose();
      const Eigen::Vector3d target = T[t] * (rest.V.row(c) - rest.V.row(a)).transpose();
      energy += weights.weight(t, k) * (deformed - target).squaredNorm();
    }
  }
  return energy;
}

}  // namespace aniso
