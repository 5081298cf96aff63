#include "deform/gauge.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include <Eigen/Eigenvalues>
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

// The component's own deformation as a linear map about its centroid: the
// least-squares fit of V - c' to rest - c over its vertices. Directions the
// component does not span (a flat part's normal) map to themselves.
Eigen::Matrix3d component_map(const Positions& rest, const Positions& V, const std::vector<int>& members,
                              const Eigen::Vector3d& c, const Eigen::Vector3d& c_moved) {
  Eigen::Matrix3d xx = Eigen::Matrix3d::Zero(), yx = Eigen::Matrix3d::Zero();
  for (int i : members) {
    const Eigen::Vector3d x = rest.row(i).transpose() - c;
    const Eigen::Vector3d y = V.row(i).transpose() - c_moved;
    xx += x * x.transpose();
    yx += y * x.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(xx);
  const double largest = eigen.eigenvalues().maxCoeff();
  Eigen::Matrix3d inverse = Eigen::Matrix3d::Zero(), spanned = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const double lambda = eigen.eigenvalues()[k];
    if (!(lambda > 1e-10 * largest)) continue;
    const Eigen::Vector3d e = eigen.eigenvectors().col(k);
    inverse += e * e.transpose() / lambda;
    spanned += e * e.transpose();
  }
  return yx * inverse + (Eigen::Matrix3d::Identity() - spanned);
}

Eigen::Vector3d centroid_of(const Positions& P, const std::vector<int>& members) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i : members) sum += P.row(i).transpose();
  return sum / static_cast<double>(members.size());
}

// The anchored vertex nearest `point` (rest positions), or -1 when none is
// anchored: a uniform grid over them, searched ring by ring.
class NearestAnchor {
 public:
  NearestAnchor(const Positions& rest, std::vector<int> anchored) : rest_(rest), anchored_(std::move(anchored)) {
    if (anchored_.empty()) return;
    lo_ = rest.row(anchored_[0]).transpose();
    Eigen::Vector3d hi = lo_;
    for (int i : anchored_) {
      lo_ = lo_.cwiseMin(rest.row(i).transpose());
      hi = hi.cwiseMax(rest.row(i).transpose());
    }
    const double extent = std::max((hi - lo_).maxCoeff(), 1e-300);
    cells_ = std::max(1, std::min(128, static_cast<int>(std::cbrt(static_cast<double>(anchored_.size())))));
    size_ = extent / cells_;
    for (int i : anchored_) grid_[key(cell_of(rest.row(i).transpose()))].push_back(i);
  }

  int operator()(const Eigen::Vector3d& point) const {
    if (anchored_.empty()) return -1;
    const Eigen::Vector3i home = cell_of(point);
    int best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring <= 3 * cells_ + 3; ++ring) {
      // Every cell of this ring lies at least (ring - 1) cells from the point.
      const double reach = std::max(0, ring - 1) * size_;
      if (best >= 0 && reach * reach > best_d2) break;
      for (int dx = -ring; dx <= ring; ++dx)
        for (int dy = -ring; dy <= ring; ++dy)
          for (int dz = -ring; dz <= ring; ++dz) {
            if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != ring) continue;
            const Eigen::Vector3i cell = home + Eigen::Vector3i(dx, dy, dz);
            if (cell.minCoeff() < -1 || cell.maxCoeff() > cells_ + 1) continue;  // no vertex's cell
            const auto found = grid_.find(key(cell));
            if (found == grid_.end()) continue;
            for (int i : found->second) {
              const double d2 = (rest_.row(i).transpose() - point).squaredNorm();
              if (d2 < best_d2 || (d2 == best_d2 && i < best)) {
                best_d2 = d2;
                best = i;
              }
            }
          }
    }
    return best;
  }

 private:
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = ((p - lo_) / size_).array().floor();
    return q.cwiseMax(-1.0).cwiseMin(cells_ + 1.0).cast<int>();
  }
  // Cells run from -1 to cells_ + 1 (cell_of clamps to them).
  std::int64_t key(const Eigen::Vector3i& c) const {
    const std::int64_t side = cells_ + 3;
    return ((static_cast<std::int64_t>(c.x()) + 1) * side + (c.y() + 1)) * side + (c.z() + 1);
  }
  const Positions& rest_;
  std::vector<int> anchored_;
  Eigen::Vector3d lo_ = Eigen::Vector3d::Zero();
  double size_ = 1.0;
  int cells_ = 1;
  std::unordered_map<std::int64_t, std::vector<int>> grid_;
};

// A loose component (no pin, no unselected vertex) is solved about its own
// centroid, which nothing in it holds: left there, a part selected with its
// surroundings stayed put while they moved (an eye in a stretched head, a
// separate part of a whole-mesh scale, which then was no similarity). Its
// centroid goes where the edit takes it: by its own map about the nearest
// anchored vertex, as far as that vertex is selected (an unselected one
// holds it where it was), or, when nothing is anchored, about the centroid
// of the whole mesh, which stays (METHOD §7).
void place_loose_components(const Mesh& rest, const Gauge& gauge, const Eigen::VectorXd& weights,
                            const std::vector<std::vector<int>>& members, const std::vector<int>& loose,
                            Positions& V) {
  // One part, wholly selected: its centroid stays, and nothing else is to
  // be read (a whole-mesh live preview frame would scan every face).
  if (loose.empty() || gauge.components < 2) return;
  // Vertices of no face (their own components) are left where they are, by
  // every solver: they neither move nor hold anything.
  std::vector<char> surface(gauge.components, 0);
  for (Eigen::Index t = 0; t < rest.F.rows(); ++t) surface[gauge.component[rest.F(t, 0)]] = 1;
  std::vector<int> placed;
  for (int c : loose) {
    if (surface[c]) placed.push_back(c);
  }
  if (placed.empty()) return;
  std::vector<char> is_loose(gauge.components, 0);
  for (int c : placed) is_loose[c] = 1;
  std::vector<int> anchored, everything;
  for (int i = 0; i < rest.num_vertices(); ++i) {
    const int c = gauge.component[i];
    if (!surface[c]) continue;
    (is_loose[c] ? everything : anchored).push_back(i);
  }
  if (anchored.empty() && placed.size() < 2) return;  // one part, wholly selected: its centroid stays
  const NearestAnchor nearest(rest.V, anchored);
  const Eigen::Vector3d whole = anchored.empty() ? centroid_of(rest.V, everything) : Eigen::Vector3d::Zero();
  for (int c : placed) {
    const Eigen::Vector3d rest_c = centroid_of(rest.V, members[c]);
    const Eigen::Vector3d moved_c = centroid_of(V, members[c]);
    const Eigen::Matrix3d map = component_map(rest.V, V, members[c], rest_c, moved_c);
    Eigen::Vector3d target;
    if (anchored.empty()) {
      target = whole + map * (rest_c - whole);
    } else {
      const int j = nearest(rest_c);
      const Eigen::Matrix3d at_anchor = Eigen::Matrix3d::Identity() + weights[j] * (map - Eigen::Matrix3d::Identity());
      target = V.row(j).transpose() + at_anchor * (rest_c - rest.V.row(j).transpose());
    }
    const Eigen::RowVector3d shift = (target - moved_c).transpose();
    for (int i : members[c]) V.row(i) += shift;
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
  std::vector<int> loose;
  for (int c = 0; c < gauge.components; ++c) {
    if (members[c].empty()) continue;
    const std::vector<int>& fit = unaffected[c].empty() ? members[c] : unaffected[c];
    fit_and_apply(rest.V, fit, members[c], alignment, V);
    if (unaffected[c].empty()) loose.push_back(c);
  }
  place_loose_components(rest, gauge, weights, members, loose, V);
}

}  // namespace aniso
