#include "anisoform/distortion.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "anisoform/error.h"

namespace aniso {
namespace {

// Largest singular value of the linear map taking the rest triangle (a, b, c)
// onto the deformed one (A, B, C), both seen in their own planes.
double max_singular_value(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c, const Eigen::Vector3d& A,
                          const Eigen::Vector3d& B, const Eigen::Vector3d& C) {
  // Rest edges in an orthonormal 2D frame of the rest triangle's plane.
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d x = e1.normalized();
  const Eigen::Vector3d y = (e2 - e2.dot(x) * x).normalized();
  Eigen::Matrix2d rest_edges;
  rest_edges << e1.dot(x), e2.dot(x), e1.dot(y), e2.dot(y);
  Eigen::Matrix<double, 3, 2> deformed_edges;
  deformed_edges << B - A, C - A;
  const Eigen::Matrix<double, 3, 2> J = deformed_edges * rest_edges.inverse();
  // sigma_max^2 is the larger eigenvalue of the 2x2 J^T J.
  const Eigen::Matrix2d G = J.transpose() * J;
  const double half_trace = 0.5 * (G(0, 0) + G(1, 1));
  const double det = G.determinant();
  const double largest = half_trace + std::sqrt(std::max(0.0, half_trace * half_trace - det));
  return std::sqrt(largest);
}

}  // namespace

Eigen::VectorXd vertex_distortion(const Mesh& rest, const Positions& deformed,
                                  DistortionKind kind) {
  const int n = rest.num_vertices();
  if (deformed.rows() != n) {
    fail(ErrorCode::BadParameter, "distortion: the deformed mesh has " +
                                      std::to_string(deformed.rows()) + " vertices, the rest " +
                                      std::to_string(n));
  }
  Eigen::VectorXd rest_area = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd measure = Eigen::VectorXd::Zero(n);
  for (int t = 0; t < rest.num_triangles(); ++t) {
    const Eigen::Vector3d a = rest.V.row(rest.F(t, 0)), b = rest.V.row(rest.F(t, 1)),
                          c = rest.V.row(rest.F(t, 2));
    const Eigen::Vector3d A = deformed.row(rest.F(t, 0)), B = deformed.row(rest.F(t, 1)),
                          C = deformed.row(rest.F(t, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    // Same relative threshold as the cotangent weights use for zero area.
    if (!(area > 0.5e-12 * std::max({(b - a).squaredNorm(), (c - b).squaredNorm(),
                                      (a - c).squaredNorm()}))) {
      continue;
    }
    const double value = kind == DistortionKind::AreaRatio
                             ? 0.5 * (B - A).cross(C - A).norm()
                             : area * max_singular_value(a, b, c, A, B, C);
    for (int k = 0; k < 3; ++k) {
      rest_area[rest.F(t, k)] += area;
      measure[rest.F(t, k)] += value;
    }
  }
  Eigen::VectorXd result(n);
  for (int i = 0; i < n; ++i) result[i] = rest_area[i] > 0.0 ? measure[i] / rest_area[i] : 1.0;
  return result;
}

}  // namespace aniso
