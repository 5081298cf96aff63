// Smooth tangent line fields from a few constraints (the user's arrows), and
// scalar amounts interpolated harmonically from the same constraints.
//
// The line field is found by a connection Laplacian on vertex tangent planes
// with angles doubled (a line field: d and -d are the same; Knöppel et al.
// 2013), constrained vertices fixed; the amounts by the cotangent Laplacian
// with the constrained values as Dirichlet conditions. Both are restricted to a
// region (the selection or patch) when a mask is given.
#pragma once

#include <string>
#include <vector>

#include "anisoform/mesh.h"

namespace aniso {

struct DirectionConstraint {
  int vertex = 0;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // projected to the tangent plane
  double su = 1.0;                                       // amount along (optional use)
  double sv = 1.0;                                       // amount across (optional use)
  bool has_amounts = false;                              // su/sv given for this vertex
  int line = 0;  // the text line it was read from (parse_direction_constraints), 0 if none: for messages
};

// Exactly the same constraint (every field bitwise, but where it was read):
// what caches key on.
inline bool operator==(const DirectionConstraint& a, const DirectionConstraint& b) {
  return a.vertex == b.vertex && a.direction == b.direction && a.su == b.su && a.sv == b.sv &&
         a.has_amounts == b.has_amounts;
}

// Whether any constraint carries amounts: then the field's interpolated
// amounts replace the edit's own (a deform's scale su, sv; a flatten's
// compression), everywhere on the mesh.
bool any_amounts(const std::vector<DirectionConstraint>& constraints);

struct DirectionField {
  Positions direction;  // #V by 3 unit tangent vectors (zero outside the region)
  Eigen::VectorXd su;   // #V amounts along (1 where no amounts were given)
  Eigen::VectorXd sv;   // #V amounts across
};

// Parses constraint lines "INDEX DX DY DZ [SU [SV]]" (blank lines and # comments
// ignored). Throws Error(BadParameter) naming the line. `source` names the file
// in messages.
std::vector<DirectionConstraint> parse_direction_constraints(const std::string& text,
                                                             const std::string& source);

// The checks every consumer of constraints makes before using them
// (propagate_direction_field, validate_direction_source in deformer.h): each
// vertex in [0, n), each direction finite and non-zero, and the amounts, when
// given, allowed by validate_scale (transforms.h), the rule of the
// global scale. Error(BadParameter) naming the constraint (1-based) and its
// vertex; with `source` (the file parse_direction_constraints read), by the
// file and line instead of the constraint's number: "FILE line 2 (vertex
// 5000): vertex index out of range, the mesh has 829 vertices".
void validate_direction_constraints(const std::vector<DirectionConstraint>& constraints, int n,
                                    const std::string& source = "");

// The checks propagate_direction_field makes of the constraints over the
// whole mesh before it solves (validate_direction_constraints, one constraint
// per vertex, no direction along its vertex's normal), without the solve: an
// edit that moves nothing refuses the same bad field as one that moves
// something (Deformer::deform).
void check_direction_constraints(const Mesh& mesh, const std::vector<DirectionConstraint>& constraints);

// Propagates the constraints over the mesh (or over the vertices with
// region_mask[i] != 0). A constraint whose direction is (nearly) parallel to
// the normal is refused with Error(BadParameter) naming the vertex; an index
// out of range too. With every vertex of the region constrained, the field is
// used as is (only projected to the tangent planes).
DirectionField propagate_direction_field(const Mesh& mesh,
                                         const std::vector<DirectionConstraint>& constraints,
                                         const std::vector<char>* region_mask = nullptr);

}  // namespace aniso
