// Garment flattening inside a Session (session.h): the request as a host
// gives it and the result laid out per INPUT vertex / patch triangle as
// flat float32 / uint32 arrays, so that a host can colour the 3D mesh and draw
// the 2D pattern without knowing the patch's own (compact) numbering.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "anisoform/flatten.h"

namespace aniso {

struct SessionFlatten {
  // true: the patch is the vertices with selection weight > 0 (the faces
  // whose three corners are selected); false: the whole mesh.
  bool use_selection = false;
  double su = 1.0;  // wanted stretch along the direction (unless constraints carry amounts)
  double sv = 1.0;  // wanted stretch across it
  FlattenDirections directions;  // constraints use input-mesh vertex indices
  // false: along the longest axis of the positions flattened (resolve_flatten, op.h).
  bool direction_given = true;
  FlattenMethod method = FlattenMethod::Anisotropic;
  int max_iterations = ArapFlattenSettings().max_iterations;
  double tolerance = ArapFlattenSettings().tolerance;
  bool refine = ArapFlattenSettings().refine;  // false: the paper's local/global result as it is
};

// The flatten() options a request means (its direction resolved first,
// resolve_flatten in op.h): the one place they are built, for the Session and
// the CLI's one-shot flatten alike.
FlattenOptions flatten_options(const SessionFlatten& request);

// The amounts a request wants: its su and sv, or, when the field's
// constraints carry amounts (which then replace them), their range over
// those constraints (the propagated amounts lie within it).
struct WantedAmounts {
  double su_min = 1.0, su_max = 1.0, sv_min = 1.0, sv_max = 1.0;
  bool from_field = false;
};
WantedAmounts wanted_amounts(const SessionFlatten& request);

// The pattern file's scale note for a request: the method, su and sv, where
// the direction came from (`direction`, e.g. "global:0,0,1" or "field
// (3 constraints)") and how the grainline is chosen. One wording for the
// Session's patterns and the CLI's.
std::string pattern_note(const SessionFlatten& request, const std::string& direction);
// A request's directions as the note names them: "global:X,Y,Z" or
// "field (N constraints)".
std::string describe_directions(const FlattenDirections& directions);

struct SessionFlattenResult {
  FlattenMetrics metrics;
  std::vector<float> uv;                  // #V * 2; NaN for vertices outside the patch
  std::vector<std::uint32_t> triangles;   // #T * 3 input-vertex indices of the patch triangles
  std::vector<float> compression_error;   // #T: |along / su_t - 1|; NaN for a degenerate triangle
  std::vector<float> cross_error;         // #T: |across / sv_t - 1|; NaN for a degenerate triangle
  std::vector<float> vertex_error;        // #V: area-weighted mean compression error of the
                                          // vertex's patch triangles; NaN outside the patch
  std::vector<Eigen::Vector2d> grainlines;             // per component, unit, in uv
  std::vector<std::vector<std::uint32_t>> outlines;    // boundary loops, input-vertex indices
  std::vector<int> outline_pieces;                     // per outline: its component (grainline index)
  int factorizations = 0;  // Session::factorizations() after the call
};

}  // namespace aniso
