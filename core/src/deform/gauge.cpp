#include "deform/gauge.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include "mesh/topology.h"

namespace aniso {

Gauge make_gauge(const Mesh& mesh, const std::vector<int>& user_pins) {
  int components = 0;
  std::vector<int> component = vertex_components(mesh.F, mesh.num_vertices(), &components);
  return make_gauge(std::move(component), components, user_pins);
}

Gauge make_gauge(std::vector<int> component, int components, const std::vector<int>& user_pins) {
  Gauge gauge;
  gauge.component = std::move(component);
  gauge.components = components;
  gauge.realign.assign(gauge.components, 1);
  for (int p : user_pins) gauge.realign[gauge.component[p]] = 0;
  gauge.pins = user_pins;
  // The first vertex of each component: the result is re-aligned afterwards,
  // so any vertex serves, and one independent of the selection keeps the pin
  // set (and so the factorization) the same across selections.
  std::vector<int> first(gauge.components, -1);
  for (std::size_t i = 0; i < gauge.component.size(); ++i) {
    const int c = gauge.component[i];
    if (gauge.realign[c] && first[c] < 0) first[c] = static_cast<int>(i);
  }
  for (int c = 0; c < gauge.components; ++c) {
    if (first[c] >= 0) gauge.pins.push_back(first[c]);
  }
  return gauge;
}

namespace {

// Rigid (R, t) minimizing sum |R x_k + t - y_k|^2 over the listed vertices.
void fit_and_apply(const Positions& rest, const std::vector<int>& fit_set,
                   const std::vector<int>& move_set, Alignment alignment, Positions& V) {
  if (fit_set.empty()) return;
  Eigen::Vector3d mean_x = Eigen::Vector3d::Zero(), mean_y = Eigen::Vector3d::Zero();
  for (int i : fit_set) {
    mean_x += V.row(i).transpose();
    mean_y += rest.row(i).transpose();
  }
  mean_x /= static_cast<double>(fit_set.size());
  mean_y /= static_cast<double>(fit_set.size());
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  if (alignment == Alignment::Rigid && fit_set.size() >= 3) {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    for (int i : fit_set) H += (V.row(i).transpose() - mean_x) * (rest.row(i).transpose() - mean_y).transpose();
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
    R = svd.matrixV() * D * svd.matrixU().transpose();
  }
  for (int i : move_set) {
    V.row(i) = (R * (V.row(i).transpose() - mean_x) + mean_y).transpose();
  }
}

}  // namespace

void realign(const Mesh& rest, const Gauge& gauge, const Eigen::VectorXd& weights,
             Alignment alignment, Positions& V) {
  std::vector<std::vector<int>> members(gauge.components), unaffected(gauge.components);
  for (int i = 0; i < rest.num_vertices(); ++i) {
    const int c = gauge.component[i];
    if (!gauge.realign[c]) continue;
    members[c].push_back(i);
    if (weights[i] <= 0.0) unaffected[c].push_back(i);
  }
  for (int c = 0; c < gauge.components; ++c) {
    if (members[c].empty()) continue;
    const std::vector<int>& fit = unaffected[c].empty() ? members[c] : unaffected[c];
    fit_and_apply(rest.V, fit, members[c], alignment, V);
  }
}

}  // namespace aniso
