// A fold-free start map (Tutte 1963; Floater 2003): the outer boundary on a
// circle and every other vertex the mean of its neighbours. Used when the
// conformal start folds triangles over (nearly closed or very curved patches,
// where LSCM's free boundary can overlap itself), because the ARAP guard keeps
// a fold-free map fold-free but cannot unfold a folded one.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/SparseCholesky>

#include "anisoform/error.h"
#include "base/math_constants.h"
#include "flatten/flatten_pipeline.h"

namespace aniso {

namespace {

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

}  // namespace

void tutte_embedding(const FlattenPatch& patch, const TriangleCharts& charts,
                     Eigen::MatrixX2d& uv) {
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

  // Uniform weights: every free node is the mean of its neighbours.
  std::vector<int> free_index(num_nodes, -1);
  int free_count = 0;
  for (int i = 0; i < num_nodes; ++i) {
    if (!fixed[i]) free_index[i] = free_count++;
  }
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(free_count, 2);
  entries.reserve(edges.size() * 4);
  for (const auto& [a, b] : edges) {
    const int ends[2] = {a, b};
    for (int s = 0; s < 2; ++s) {
      const int i = ends[s], j = ends[1 - s];
      if (fixed[i]) continue;
      entries.emplace_back(free_index[i], free_index[i], 1.0);
      if (fixed[j]) {
        rhs.row(free_index[i]) += position.row(j);
      } else {
        entries.emplace_back(free_index[i], free_index[j], -1.0);
      }
    }
  }
  if (free_count > 0) {
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
  uv = position.topRows(patch.mesh.num_vertices());
  scale_to_area(patch, charts.area, uv);
}

}  // namespace aniso
