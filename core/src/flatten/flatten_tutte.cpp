// A fold-free start map (Tutte 1963; Floater 2003): the outer boundary on a
// circle and every other vertex a convex combination of its neighbours. Used
// when the conformal start folds triangles over (nearly closed or very curved
// patches, where LSCM's free boundary can overlap itself), because the ARAP
// guard keeps a fold-free map fold-free but cannot unfold a folded one, and as
// a start of the stretch refinement.
//
// With uniform weights, a nearly closed patch (a head, a hand, a bunny open
// at the bottom) is squeezed exponentially towards its far side: the hand's
// smallest triangle gets 5e-9 of its area, 39,847 of the bunny's 69,451
// triangles less than a tenth, and the refinement then spends its whole
// budget growing them back. So the weights are reweighted as Yoshizawa,
// Belyaev and Seidel (2004, "A fast and simple stretch-minimizing mesh
// parameterization") do: each edge's weight is divided by its ends' L2
// stretch (Sander et al. 2001: the RMS of the singular values of the map
// from the plane back to the surface, large where the map squeezes), which
// lets squeezed regions open up; any positive weights keep the map fold-free.
// The rounds stop when the patch's total L2 stretch falls by less than
// kStretchGain, or after the rounds asked for (kDefaultStretchRounds,
// flatten_pipeline.h), and the map with the lowest total
// stretch is kept. Measured (su 0.8; uniform -> reweighted): triangles below
// a tenth of their area, hand 1,360 -> 678 (smallest 5e-9 -> 5e-3 of its
// area), spothead 7,382 -> 280; the refinement's combined error at the
// 500-iteration cap, bunny 1.61 -> 1.04, demosthenes 0.49 -> 0.34, spothead
// 0.52 -> 0.33. More rounds keep lowering the stretch on some patches but
// trade the squeeze for shear the refinement has to undo (with gentler,
// square-root updates: spothead 0.33 after 8 rounds, 0.41 after 14).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/LU>
#include <Eigen/SparseCholesky>

#include "anisoform/error.h"
#include "base/math_constants.h"
#include "flatten/flatten_pipeline.h"

namespace aniso {

namespace {

constexpr double kStretchGain = 0.99;  // a round must lower the total stretch below this share
// Reweighted edges keep at least this share of the largest weight, so that
// the factorization's pivots stay resolvable.
constexpr double kMinWeightShare = 1e-12;

double loop_length(const Positions& V, const std::vector<int>& loop) {
  double length = 0.0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    length += (V.row(loop[(k + 1) % loop.size()]) - V.row(loop[k])).norm();
  }
  return length;
}

// Undirected edges of the patch plus, for every hole (a boundary loop other
// than its component's outer one), a virtual vertex joined to the hole's
// vertices: the holes are filled by fans, so each genus-0 component becomes
// a disk whose only boundary is the outer loop.
std::vector<std::pair<int, int>> fan_filled_edges(const FlattenPatch& patch,
                                                   const std::vector<int>& outer_loop_of_component,
                                                   int& num_nodes) {
  const Triangles& F = patch.mesh.F;
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(F.rows()) * 3);
  for (int t = 0; t < F.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = F(t, k), b = F(t, (k + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  num_nodes = patch.mesh.num_vertices();
  for (std::size_t l = 0; l < patch.boundary_loops.size(); ++l) {
    if (outer_loop_of_component[patch.loop_component[l]] == static_cast<int>(l)) continue;
    const int center = num_nodes++;
    for (int vertex : patch.boundary_loops[l]) edges.emplace_back(vertex, center);
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

// Every free node the weighted mean of its neighbours (weights per edge of
// `edges`), the fixed ones where `position` has them; writes the free rows.
void solve_convex_combination(const std::vector<std::pair<int, int>>& edges, const std::vector<double>& weights,
                              const std::vector<char>& fixed, Eigen::MatrixX2d& position) {
  const int num_nodes = static_cast<int>(fixed.size());
  std::vector<int> free_index(num_nodes, -1);
  int free_count = 0;
  for (int i = 0; i < num_nodes; ++i) {
    if (!fixed[i]) free_index[i] = free_count++;
  }
  if (free_count == 0) return;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(free_count, 2);
  entries.reserve(edges.size() * 4);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const int ends[2] = {edges[e].first, edges[e].second};
    for (int s = 0; s < 2; ++s) {
      const int i = ends[s], j = ends[1 - s];
      if (fixed[i]) continue;
      entries.emplace_back(free_index[i], free_index[i], weights[e]);
      if (fixed[j]) {
        rhs.row(free_index[i]) += weights[e] * position.row(j);
      } else {
        entries.emplace_back(free_index[i], free_index[j], -weights[e]);
      }
    }
  }
  Eigen::SparseMatrix<double> L(free_count, free_count);
  L.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
  if (solver.info() != Eigen::Success) {
    fail(ErrorCode::Numerical, "the fold-free start map could not be factored (Tutte)");
  }
  const Eigen::MatrixX2d free_values = solver.solve(rhs);
  if (!free_values.allFinite()) {
    fail(ErrorCode::Numerical, "the fold-free start map could not be solved (Tutte)");
  }
  for (int i = 0; i < num_nodes; ++i) {
    if (!fixed[i]) position.row(i) = free_values.row(free_index[i]);
  }
}

// Squared L2 stretch of triangle t's map from the plane back to its chart
// (the mean of the squared inverse singular values of J: chart -> plane);
// infinite for a triangle the map folds or flattens to nothing.
double squared_stretch(const Triangles& F, const TriangleCharts& charts, const Eigen::MatrixX2d& uv, int t) {
  Eigen::Matrix2d chart_edges, map_edges;
  chart_edges << charts.corners(t, 2) - charts.corners(t, 0), charts.corners(t, 4) - charts.corners(t, 0),
      charts.corners(t, 3) - charts.corners(t, 1), charts.corners(t, 5) - charts.corners(t, 1);
  const Eigen::RowVector2d e1 = uv.row(F(t, 1)) - uv.row(F(t, 0)), e2 = uv.row(F(t, 2)) - uv.row(F(t, 0));
  map_edges << e1.x(), e2.x(), e1.y(), e2.y();
  if (!(map_edges.determinant() > 0.0)) return std::numeric_limits<double>::infinity();
  // J^-1 = chart_edges * map_edges^-1.
  return 0.5 * (chart_edges * map_edges.inverse()).squaredNorm();
}

// Per triangle: its squared L2 stretch (0 for a degenerate one, which has no
// chart and is left out of every mean).
Eigen::VectorXd squared_stretches(const FlattenPatch& patch, const TriangleCharts& charts, const Eigen::MatrixX2d& uv) {
  Eigen::VectorXd squared = Eigen::VectorXd::Zero(patch.mesh.num_triangles());
  for (int t = 0; t < patch.mesh.num_triangles(); ++t) {
    if (charts.area[t] > 0.0) squared[t] = squared_stretch(patch.mesh.F, charts, uv, t);
  }
  return squared;
}

// The patch's area-weighted RMS L2 stretch.
double total_stretch(const TriangleCharts& charts, const Eigen::VectorXd& squared) {
  double sum = 0.0, area = 0.0;
  for (int t = 0; t < squared.size(); ++t) {
    if (!(charts.area[t] > 0.0)) continue;
    sum += charts.area[t] * squared[t];
    area += charts.area[t];
  }
  return area > 0.0 ? std::sqrt(sum / area) : 0.0;
}

// Per vertex: the area-weighted RMS of its triangles' L2 stretch (1 for a
// vertex without a non-degenerate triangle).
Eigen::VectorXd vertex_stretch(const FlattenPatch& patch, const TriangleCharts& charts,
                               const Eigen::VectorXd& squared) {
  const Triangles& F = patch.mesh.F;
  const int n = patch.mesh.num_vertices();
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(n), area = Eigen::VectorXd::Zero(n);
  for (int t = 0; t < F.rows(); ++t) {
    if (!(charts.area[t] > 0.0)) continue;
    const double s2 = std::min(squared[t], std::numeric_limits<double>::max());
    for (int k = 0; k < 3; ++k) {
      sum[F(t, k)] += charts.area[t] * s2;
      area[F(t, k)] += charts.area[t];
    }
  }
  Eigen::VectorXd stretch = Eigen::VectorXd::Ones(n);
  for (int i = 0; i < n; ++i) {
    if (area[i] > 0.0) stretch[i] = std::sqrt(sum[i] / area[i]);
  }
  return stretch;
}

}  // namespace

void tutte_embedding(const FlattenPatch& patch, const TriangleCharts& charts, Eigen::MatrixX2d& uv,
                     int stretch_rounds) {
  const Positions& V = patch.mesh.V;
  std::vector<int> outer(patch.num_components, -1);
  std::vector<double> outer_length(patch.num_components, -1.0);
  for (std::size_t l = 0; l < patch.boundary_loops.size(); ++l) {
    const int c = patch.loop_component[l];
    const double length = loop_length(V, patch.boundary_loops[l]);
    if (length > outer_length[c]) {
      outer_length[c] = length;
      outer[c] = static_cast<int>(l);
    }
  }
  int num_nodes = 0;
  const std::vector<std::pair<int, int>> edges = fan_filled_edges(patch, outer, num_nodes);

  // The outer loops on circles of their own length, by arc length.
  Eigen::MatrixX2d position = Eigen::MatrixX2d::Zero(num_nodes, 2);
  std::vector<char> fixed(num_nodes, 0);
  for (int c = 0; c < patch.num_components; ++c) {
    const std::vector<int>& loop = patch.boundary_loops[outer[c]];
    const double length = outer_length[c] > 0.0 ? outer_length[c] : 1.0;
    const double radius = length / (2.0 * kPi);
    double arc = 0.0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int vertex = loop[k];
      if (!fixed[vertex]) {  // a loop through a non-manifold vertex visits it twice
        const double angle = 2.0 * kPi * arc / length;
        position.row(vertex) = Eigen::RowVector2d(radius * std::cos(angle), radius * std::sin(angle));
        fixed[vertex] = 1;
      }
      arc += (V.row(loop[(k + 1) % loop.size()]) - V.row(vertex)).norm();
    }
  }

  // Rounds of convex-combination maps: uniform weights first, then reweighted.
  std::vector<double> weights(edges.size(), 1.0);
  Eigen::MatrixX2d best;
  double best_stretch = std::numeric_limits<double>::infinity();
  for (int round = 0; round <= stretch_rounds; ++round) {
    solve_convex_combination(edges, weights, fixed, position);
    Eigen::MatrixX2d map = position.topRows(patch.mesh.num_vertices());
    scale_to_area(patch, charts.area, map);
    const Eigen::VectorXd squared = squared_stretches(patch, charts, map);
    const double total = total_stretch(charts, squared);
    const bool improved = total < kStretchGain * best_stretch;
    if (total < best_stretch || best.rows() == 0) {
      best_stretch = total;
      best = std::move(map);
    }
    if (!improved || round == stretch_rounds) break;
    const Eigen::VectorXd stretch = vertex_stretch(patch, charts, squared);
    std::vector<double> next = weights;
    double largest = 0.0;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto [a, b] = edges[e];
      // The virtual fan vertices of the holes have no triangles: they take
      // their partner's stretch.
      const double sa = a < stretch.size() ? stretch[a] : stretch[b];
      const double sb = b < stretch.size() ? stretch[b] : stretch[a];
      next[e] /= 0.5 * (sa + sb);
      largest = std::max(largest, next[e]);
    }
    // A map that squeezed triangles beyond what double precision measures
    // (an infinite stretch) gives no usable weights: keep the best so far.
    if (!(largest > 0.0 && std::isfinite(largest))) break;
    for (double& w : next) w = std::isfinite(w) ? std::max(w / largest, kMinWeightShare) : kMinWeightShare;
    weights = std::move(next);
  }
  uv = std::move(best);
}

}  // namespace aniso
