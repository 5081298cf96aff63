#include "anisoform/distortion.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "anisoform/error.h"
#include "geometry/frames.h"
#include "mesh/topology.h"

namespace aniso {
namespace {

// The singular value farthest from 1 by ratio (|log s| largest) of the linear
// map taking the rest triangle (a, b, c) onto the deformed one (A, B, C),
// both seen in their own planes. A collapsed triangle gives 0.
double most_deviating_singular_value(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
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
  // The squared singular values are the eigenvalues of the 2x2 J^T J.
  const Eigen::Matrix2d G = J.transpose() * J;
  // sqrt(half_trace^2 - det), written without the cancellation that would
  // leave an unchanged triangle about 1e-8 away from 1.
  const double half_trace = 0.5 * (G(0, 0) + G(1, 1));
  const double root = std::hypot(0.5 * (G(0, 0) - G(1, 1)), G(0, 1));
  const double largest = std::sqrt(half_trace + root);
  const double smallest = std::sqrt(std::max(0.0, half_trace - root));
  // largest * smallest >= 1 means the larger one is farther from 1 by ratio.
  return largest * smallest >= 1.0 ? largest : smallest;
}

// A rest triangle with area, by the same relative threshold the cotangent
// weights use for zero area.
bool rest_triangle_has_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double area = 0.5 * (b - a).cross(c - a).norm();
  return area > 0.5e-12 * std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
}

void require_same_vertex_count(const Mesh& rest, const Positions& deformed, const char* what) {
  if (deformed.rows() != rest.num_vertices()) {
    fail(ErrorCode::BadParameter, std::string(what) + ": the deformed mesh has " +
                                      std::to_string(deformed.rows()) + " vertices, the rest " +
                                      std::to_string(rest.num_vertices()));
  }
}

// The rotation best taking vertex i's rest one-ring edges onto its deformed
// ones (Kabsch: H = sum q p^T = U S V^T, R = U diag(1, 1, det) V^T).
Eigen::Matrix3d one_ring_rotation(const Mesh& rest, const Positions& deformed,
                                  const VertexAdjacency& adjacency, int i) {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (int k = adjacency.offsets[i]; k < adjacency.offsets[i + 1]; ++k) {
    const int j = adjacency.neighbors[k];
    H += (deformed.row(j) - deformed.row(i)).transpose() * (rest.V.row(j) - rest.V.row(i));
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

}  // namespace

InversionCounter::InversionCounter(const Mesh& rest) : rest_normals_(triangle_normals(rest)) {
  has_area_.resize(static_cast<std::size_t>(rest.num_triangles()));
  for (int t = 0; t < rest.num_triangles(); ++t) {
    has_area_[t] = rest_triangle_has_area(rest.V.row(rest.F(t, 0)), rest.V.row(rest.F(t, 1)),
                                          rest.V.row(rest.F(t, 2)));
  }
}

int count_inverted(const Mesh& rest, const Positions& deformed) {
  return InversionCounter(rest).count(rest, deformed);
}

void InversionCounter::build_adjacency(const Mesh& rest) const {
  if (!adjacency_) adjacency_ = std::make_shared<const VertexAdjacency>(vertex_adjacency(rest.F, rest.num_vertices()));
}

int InversionCounter::count(const Mesh& rest, const Positions& deformed) const {
  require_same_vertex_count(rest, deformed, "inverted count");
  const Positions& rest_normals = rest_normals_;
  const Positions normals = triangle_normals(deformed, rest.F);
  // Only a triangle whose normal turned past 90 deg in world space can be
  // folded; most edits have none, and then no rotation is fitted at all.
  std::vector<int> candidates;
  for (int t = 0; t < rest.num_triangles(); ++t) {
    if (has_area_[t] && rest_normals.row(t).dot(normals.row(t)) < 0.0) candidates.push_back(t);
  }
  if (candidates.empty()) return 0;
  build_adjacency(rest);
  const VertexAdjacency& adjacency = *adjacency_;
  std::vector<Eigen::Matrix3d> rotation(static_cast<std::size_t>(rest.num_vertices()));
  std::vector<char> fitted(rotation.size(), 0);
  int inverted = 0;
  for (int t : candidates) {
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const int i = rest.F(t, k);
      if (!fitted[i]) {
        rotation[i] = one_ring_rotation(rest, deformed, adjacency, i);
        fitted[i] = 1;
      }
      sum += rotation[i];
    }
    if (normals.row(t).dot(sum * rest_normals.row(t).transpose()) < 0.0) ++inverted;
  }
  return inverted;
}

Eigen::VectorXd vertex_distortion(const Mesh& rest, const Positions& deformed,
                                  DistortionKind kind) {
  const int n = rest.num_vertices();
  require_same_vertex_count(rest, deformed, "distortion");
  Eigen::VectorXd rest_area = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd measure = Eigen::VectorXd::Zero(n);
  for (int t = 0; t < rest.num_triangles(); ++t) {
    const Eigen::Vector3d a = rest.V.row(rest.F(t, 0)), b = rest.V.row(rest.F(t, 1)),
                          c = rest.V.row(rest.F(t, 2));
    const Eigen::Vector3d A = deformed.row(rest.F(t, 0)), B = deformed.row(rest.F(t, 1)),
                          C = deformed.row(rest.F(t, 2));
    if (!rest_triangle_has_area(a, b, c)) continue;
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double value = kind == DistortionKind::AreaRatio
                             ? 0.5 * (B - A).cross(C - A).norm()
                             : area * most_deviating_singular_value(a, b, c, A, B, C);
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
