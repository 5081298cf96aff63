// Direction constraints (the user's arrows) and their propagation to a smooth
// tangent line field with harmonically interpolated amounts (see
// direction_field.h).
//
// Line field: values u_i = exp(2 i theta_i) in per-vertex tangent bases
// (direction_field_transport.h); the free values minimise
//   sum over edges of w_ij |u_i - r_ij u_j|^2
// (w_ij cotangent weights, r_ij the transport from j's basis into i's), with
// the constrained values held: Knöppel et al.'s smoothest field with hard
// constraints. The direction is the halved angle of u_i. Where constraints
// disagree strongly, |u_i| drops towards 0 and the angle is least certain; two
// constraints at exactly 90° have opposite doubled values and the field then
// has a singular line between them (either turning sense is equally smooth).
// Signs: a constrained vertex keeps the sign it was given; the others are
// oriented outwards from the constraints (orient_line_field).
//
// Amounts su, sv: harmonic interpolation (the same weights, r = 1) with the
// constraints that carry amounts as Dirichlet values.
//
// Scope: both problems live on the region: the vertices with region_mask != 0
// and the triangles whose three vertices all are in it. A connected part of the
// region without any direction constraint has no direction to take: its
// vertices get the zero vector, which callers treat as degenerate (frames.h
// fills them). A part without amounts gets amount 1, as do vertices outside
// the region, whose direction is zero too.
#include "anisoform/direction_field.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>
#include <sstream>

#include "anisoform/error.h"
#include "geometry/frames.h"
#include "anisoform/laplacian.h"
#include "mesh/topology.h"
#include "anisoform/transforms.h"
#include "directions/direction_field_dirichlet.h"
#include "directions/direction_field_transport.h"
#include "directions/line_orientation.h"
#include "io/selection_text.h"

namespace aniso {
namespace {

// A direction whose tangential part is shorter than this fraction of its
// length is (nearly) parallel to the normal: its projection is noise.
constexpr double kParallelFraction = 1e-3;

[[noreturn]] void bad_field_parameter(const std::string& message) {
  fail(ErrorCode::BadParameter, message);
}

std::string vector_text(const Eigen::Vector3d& v) {
  std::ostringstream text;
  text << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return text.str();
}

// Connected parts of the region, through edges with both ends inside.
class RegionParts {
 public:
  explicit RegionParts(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  void join(int a, int b) { parent_[root(a)] = root(b); }
  int root(int a) {
    while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];
    return a;
  }

 private:
  std::vector<int> parent_;
};

std::string constraint_name(const std::vector<DirectionConstraint>& constraints, std::size_t k) {
  return "direction constraint " + std::to_string(k + 1) + " (vertex " +
         std::to_string(constraints[k].vertex) + ")";
}

// One constraint per vertex; -1 where there is none. Checks every constraint
// against the mesh and the region, naming it and its vertex.
std::vector<int> constraint_per_vertex(const std::vector<DirectionConstraint>& constraints,
                                       const std::vector<char>& in_region, const Positions& normals) {
  const int n = static_cast<int>(in_region.size());
  validate_direction_constraints(constraints, n);
  std::vector<int> constraint_at(n, -1);
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    const DirectionConstraint& c = constraints[k];
    const std::string name = constraint_name(constraints, k);
    if (!in_region[c.vertex]) bad_field_parameter(name + ": the vertex is outside the selected region");
    if (constraint_at[c.vertex] >= 0) {
      bad_field_parameter(name + ": the vertex is already constrained by constraint " +
                    std::to_string(constraint_at[c.vertex] + 1));
    }
    const Eigen::Vector3d normal = normals.row(c.vertex).transpose();
    const Eigen::Vector3d tangential = c.direction - c.direction.dot(normal) * normal;
    if (!(tangential.norm() > kParallelFraction * c.direction.norm())) {
      bad_field_parameter(name + ": the direction " + vector_text(c.direction) +
                          " is (nearly) parallel to the surface normal " + vector_text(normal) + " there");
    }
    constraint_at[c.vertex] = static_cast<int>(k);
  }
  return constraint_at;
}

// The undirected edges of the region's triangles (those with all three
// vertices in the region), each with the sum of those triangles' cotangent
// weights. Whole triangles, not edges with both ends inside: a triangle's
// weights may include a negative cotangent, and only whole triangles add up
// to a positive semidefinite energy.
std::vector<field::WeightedEdge> region_edges(const Mesh& mesh, const VertexAdjacency& adjacency,
                                             const std::vector<char>& in_region, RegionParts& parts) {
  const CotanWeights weights = cotangent_weights(mesh);
  // Summed weight per adjacency slot (i, j), kept on the slot with i < j.
  std::vector<double> slot_weight(adjacency.neighbors.size(), 0.0);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    if (!in_region[mesh.F(t, 0)] || !in_region[mesh.F(t, 1)] || !in_region[mesh.F(t, 2)]) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(t, (k + 1) % 3);
      const int b = mesh.F(t, (k + 2) % 3);
      if (a == b) continue;  // a collapsed side is no edge (vertex_adjacency skips it too)
      const int i = std::min(a, b);
      const int j = std::max(a, b);
      const auto begin = adjacency.neighbors.begin() + adjacency.offsets[i];
      const auto end = adjacency.neighbors.begin() + adjacency.offsets[i + 1];
      slot_weight[std::lower_bound(begin, end, j) - adjacency.neighbors.begin()] += weights.weight(t, k);
    }
  }
  std::vector<field::WeightedEdge> edges;
  edges.reserve(adjacency.neighbors.size() / 2);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    for (int slot = adjacency.offsets[i]; slot < adjacency.offsets[i + 1]; ++slot) {
      const int j = adjacency.neighbors[slot];
      if (j < i || slot_weight[slot] == 0.0) continue;
      parts.join(i, j);
      edges.push_back({i, j, slot_weight[slot]});
    }
  }
  return edges;
}

// The smoothest line field holding the constraints: unit tangents at the
// constrained vertices (their directions projected) and the free vertices,
// zero elsewhere.
Positions line_field(const std::vector<DirectionConstraint>& constraints, const std::vector<int>& constraint_at,
                     const std::vector<field::TangentBasis>& bases, const std::vector<field::WeightedEdge>& edges,
                     const std::vector<char>& line_free) {
  const int n = static_cast<int>(bases.size());
  field::ValueMatrix<std::complex<double>> values = field::ValueMatrix<std::complex<double>>::Zero(n, 1);
  for (int i = 0; i < n; ++i) {
    if (constraint_at[i] >= 0) values(i, 0) = field::line_to_complex(constraints[constraint_at[i]].direction, bases[i]);
  }
  std::vector<std::complex<double>> transport(edges.size());
  for (std::size_t k = 0; k < edges.size(); ++k) {
    transport[k] = field::line_transport(bases[edges[k].j], bases[edges[k].i]);
  }
  field::solve_with_fixed_values<std::complex<double>>(
      edges, [&](std::size_t k) { return transport[k]; }, line_free, "direction field", values);

  Positions direction = Positions::Zero(n, 3);
  for (int i = 0; i < n; ++i) {
    if (constraint_at[i] >= 0) {
      const Eigen::Vector3d& d = constraints[constraint_at[i]].direction;
      direction.row(i) = (d - d.dot(bases[i].n) * bases[i].n).normalized().transpose();
    } else if (line_free[i]) {
      direction.row(i) = field::complex_to_line(values(i, 0), bases[i]).transpose();
    }
  }
  return direction;
}

// su and sv (#V by 2): harmonic between the constraints with amounts, 1 where
// no amount reaches.
field::ValueMatrix<double> interpolated_amounts(const std::vector<DirectionConstraint>& constraints,
                                                const std::vector<int>& constraint_at,
                                                const std::vector<field::WeightedEdge>& edges,
                                                const std::vector<char>& amount_free) {
  field::ValueMatrix<double> amounts = field::ValueMatrix<double>::Ones(constraint_at.size(), 2);
  for (std::size_t i = 0; i < constraint_at.size(); ++i) {
    const int k = constraint_at[i];
    if (k >= 0 && constraints[k].has_amounts) {
      amounts(i, 0) = constraints[k].su;
      amounts(i, 1) = constraints[k].sv;
    }
  }
  field::solve_with_fixed_values<double>(
      edges, [](std::size_t) { return 1.0; }, amount_free, "direction amounts", amounts);
  return amounts;
}

}  // namespace

bool any_amounts(const std::vector<DirectionConstraint>& constraints) {
  for (const DirectionConstraint& c : constraints) {
    if (c.has_amounts) return true;
  }
  return false;
}

void validate_direction_constraints(const std::vector<DirectionConstraint>& constraints, int n,
                                    const std::string& source) {
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    const DirectionConstraint& c = constraints[k];
    const std::string name = source.empty() || c.line <= 0 ? constraint_name(constraints, k)
                                                           : source + " line " + std::to_string(c.line) +
                                                                 " (vertex " + std::to_string(c.vertex) + ")";
    if (c.vertex < 0 || c.vertex >= n) {
      bad_field_parameter(name + ": vertex index out of range, the mesh has " + std::to_string(n) + " vertices");
    }
    if (!c.direction.allFinite()) bad_field_parameter(name + ": the direction is not finite");
    if (c.direction.squaredNorm() == 0.0) bad_field_parameter(name + ": the direction is zero");
    if (c.has_amounts) {
      validate_scale(c.su, name + ": su");
      validate_scale(c.sv, name + ": sv");
    }
  }
}

std::vector<DirectionConstraint> parse_direction_constraints(const std::string& text,
                                                             const std::string& source) {
  std::vector<DirectionConstraint> constraints;
  const std::vector<std::string> lines = text::lines_of(text);
  static const char* const kFieldNames[] = {"INDEX", "DX", "DY", "DZ", "SU", "SV"};
  for (std::size_t line = 0; line < lines.size(); ++line) {
    const std::string where = source + " line " + std::to_string(line + 1) + ": ";
    const std::vector<std::string> tokens = text::tokens_of_line(lines[line]);
    if (tokens.empty()) continue;
    if (tokens.size() < 4 || tokens.size() > 6) {
      bad_field_parameter(where + "expected INDEX DX DY DZ [SU [SV]], got " + std::to_string(tokens.size()) +
                    " values");
    }
    const auto index = text::parse_index(tokens[0]);
    if (!index) bad_field_parameter(where + "INDEX must be a non-negative integer, got '" + tokens[0] + "'");
    double numbers[6] = {0.0, 0.0, 0.0, 0.0, 1.0, 1.0};
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      const std::string problem = text::number_field_problem(kFieldNames[k], tokens[k], numbers[k]);
      if (!problem.empty()) bad_field_parameter(where + problem);
    }
    DirectionConstraint constraint;
    constraint.vertex = *index;
    constraint.direction = Eigen::Vector3d(numbers[1], numbers[2], numbers[3]);
    if (constraint.direction.squaredNorm() == 0.0) bad_field_parameter(where + "the direction is zero");
    constraint.has_amounts = tokens.size() >= 5;
    constraint.line = static_cast<int>(line) + 1;
    constraint.su = numbers[4];
    constraint.sv = numbers[5];
    // Checked here too, so that a file's mistake is named by its line.
    if (constraint.has_amounts) {
      validate_scale(constraint.su, where + "SU");
      validate_scale(constraint.sv, where + "SV");
    }
    constraints.push_back(constraint);
  }
  return constraints;
}

void check_direction_constraints(const Mesh& mesh, const std::vector<DirectionConstraint>& constraints) {
  const std::vector<char> whole_mesh(static_cast<std::size_t>(mesh.num_vertices()), 1);
  constraint_per_vertex(constraints, whole_mesh, vertex_normals(mesh));
}

DirectionField propagate_direction_field(const Mesh& mesh,
                                         const std::vector<DirectionConstraint>& constraints,
                                         const std::vector<char>* region_mask) {
  const int n = mesh.num_vertices();
  if (region_mask && static_cast<int>(region_mask->size()) != n) {
    bad_field_parameter("region mask has " + std::to_string(region_mask->size()) + " entries, the mesh has " +
                  std::to_string(n) + " vertices");
  }
  std::vector<char> in_region(n, 1);
  if (region_mask) {
    for (int i = 0; i < n; ++i) in_region[i] = (*region_mask)[i] != 0;
  }
  const Positions normals = vertex_normals(mesh);
  const std::vector<int> constraint_at = constraint_per_vertex(constraints, in_region, normals);
  std::vector<field::TangentBasis> bases(n);
  for (int i = 0; i < n; ++i) bases[i] = field::tangent_basis(normals.row(i).transpose());

  const VertexAdjacency adjacency = vertex_adjacency(mesh.F, n);
  RegionParts parts(n);
  const std::vector<field::WeightedEdge> edges = region_edges(mesh, adjacency, in_region, parts);
  std::vector<char> part_has_direction(n, 0);
  std::vector<char> part_has_amounts(n, 0);
  for (const DirectionConstraint& c : constraints) {
    part_has_direction[parts.root(c.vertex)] = 1;
    if (c.has_amounts) part_has_amounts[parts.root(c.vertex)] = 1;
  }
  // Free: in the region, not held, and in a part that has something to hold.
  std::vector<char> line_free(n, 0);
  std::vector<char> amount_free(n, 0);
  for (int i = 0; i < n; ++i) {
    if (!in_region[i]) continue;
    const int k = constraint_at[i];
    line_free[i] = k < 0 && part_has_direction[parts.root(i)];
    amount_free[i] = (k < 0 || !constraints[k].has_amounts) && part_has_amounts[parts.root(i)];
  }

  DirectionField result;
  result.direction = line_field(constraints, constraint_at, bases, edges, line_free);
  // The arrows the user drew have signs (a rotation about cu turns the other
  // way for -cu): the free vertices take theirs outwards from the constraints.
  std::vector<char> constrained(n, 0);
  for (int i = 0; i < n; ++i) constrained[i] = constraint_at[i] >= 0;
  orient_line_field(adjacency, constrained, line_free, result.direction);
  const field::ValueMatrix<double> amounts = interpolated_amounts(constraints, constraint_at, edges, amount_free);
  result.su = amounts.col(0);
  result.sv = amounts.col(1);
  return result;
}

}  // namespace aniso
