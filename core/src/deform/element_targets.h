// From a selection, a direction source and a transform to the per-element
// target matrices T the solvers consume (METHOD §3–4): per vertex (the linear
// baseline), per triangle (AnDefGrad) or per triangle side (AnARAP's spokes).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "anisoform/deform_request.h"
#include "anisoform/mesh.h"
#include "geometry/frames.h"

namespace aniso {

// Per-rest-mesh data the targets need, computed once and reused across edits.
class TargetContext {
 public:
  explicit TargetContext(const Mesh& rest);
  ~TargetContext();

  // Unit wanted direction per vertex (#V by 3), before projection; may be
  // zero where the source gives none (filled later as degenerate). Amounts
  // per vertex when the source carries them (constraint amounts), else empty.
  // `source` must have passed validate_direction_source (deformer.h).
  void vertex_directions(const DirectionSource& source, Positions& directions,
                         Eigen::VectorXd& su, Eigen::VectorXd& sv);

  const Mesh& rest() const { return rest_; }
  const Positions& vertex_normals() const { return vertex_normals_; }
  const Positions& triangle_normals() const { return triangle_normals_; }
  // Built on first use: only directions to fill (build_frames) need them,
  // and at 200k vertices they took a tenth of an edit's set-up.
  const VertexAdjacency& vertex_adjacency();
  const VertexAdjacency& triangle_adjacency();
  // Per vertex, 1 where the rest mesh has no reliable principal curvature
  // direction (curvature.h lacks_principal_direction); built on first use.
  const std::vector<char>& lacks_principal_direction();

 private:
  const Mesh& rest_;
  Positions vertex_normals_;
  Positions triangle_normals_;
  std::optional<VertexAdjacency> vertex_adjacency_, triangle_adjacency_;
  // Fields that cost a solve and depend on the rest mesh and the source
  // only: the curvature fields per (direction, smoothing), and the last
  // propagated field with its constraints.
  struct FieldCache;
  std::unique_ptr<FieldCache> fields_;
};

struct ElementTargets {
  std::vector<Eigen::Matrix3d> T;  // per element
  int filled = 0;                  // degenerate directions filled (METHOD §3)
};

// Per-vertex targets: vertex normals, the source's per-vertex directions (the
// linear baseline, which moves each vertex by its own map).
ElementTargets vertex_targets(TargetContext& context, const DirectionSource& source,
                              const TransformSpec& spec, const Eigen::VectorXd& weights);

// Per-triangle targets: triangle normals, directions averaged from the
// triangle's vertices as a line field (signs aligned), weight = mean of the
// vertices' weights, position = centroid.
ElementTargets triangle_targets(TargetContext& context, const DirectionSource& source,
                                const TransformSpec& spec, const Eigen::VectorXd& weights);

// What per-side targets need besides the transform and the weights: the
// triangles' frames (METHOD §3) and the per-vertex amounts, when the source
// carries them (else empty).
struct SideFrames {
  Frames frames;
  Eigen::VectorXd su, sv;
};
SideFrames side_frames(TargetContext& context, const DirectionSource& source);

// A shear moves points along cu in proportion to their cv coordinate, and
// cv = n x cu flips between opposite sides of a part (front and back of a
// box), which would shear them against each other. cv is oriented to point
// away from the unselected part (from its centroid towards the selection's:
// this unit vector), so a shear displaces the whole selection one way. Zero
// when there is nothing to orient by (no shear, or no unselected vertex).
Eigen::Vector3d shear_orientation(const Mesh& mesh, const TransformSpec& spec, const Eigen::VectorXd& w);

// The share of the shear an element with cross axis cv takes: |cv . o| for
// the unit orientation o (1 where cv points away from the unselected part,
// the sides of a post; 0 where cv is square to it, the top of a box), 1 when
// there is no orientation. A face square to o has no "away" for its cv: its
// sign came from rounding (v . o ~ 1e-17 either way), so a box's top was
// sheared in its own plane one way or the other, face by face, and a
// symmetric box came out asymmetric. Scaled by |cv . o| instead, the shear is
// the part of the one shear of the selection (along the direction, growing
// away from the unselected part) that lies across the face's direction: it
// fades to 0 on such faces, continuously, whichever sign their cv has.
double shear_share(const Eigen::Vector3d& cv, const Eigen::Vector3d& orientation);

// Per-side targets (3 per triangle, T[3t + k] for the side opposite corner k):
// the triangle's frame, with the side's own weight (the mean of its two
// vertices'), midpoint and amounts. AnARAP transforms each rest edge by the
// mean of its sides' maps: an edge inside a flat part takes that part's map,
// and the spokes of a vertex on a crease are each transformed by the faces
// they lie on, not by one map of the vertex's averaged normal.
// Made triangle by triangle for a caller that uses each map once
// (AnArapSolver::set_targets): all 3 #F maps at once were 86 MB at 200k
// vertices, written and read back on every edit.
class SideTargets {
 public:
  SideTargets(const Mesh& rest, const SideFrames& frames, const TransformSpec& spec, const Eigen::VectorXd& weights);
  // Triangle t's three maps: T[k] for its side opposite corner k.
  void operator()(int t, Eigen::Matrix3d T[3]) const;

 private:
  const Mesh& rest_;
  const SideFrames& frames_;
  const TransformSpec& spec_;
  const Eigen::VectorXd& weights_;
  Eigen::Vector3d orientation_;
};

// A side's weight (SideTargets): the mean of its two vertices' weights.
// Side 3t + k is opposite corner k of triangle t.
inline double side_weight(const Mesh& mesh, const Eigen::VectorXd& weights, int t, int k) {
  return 0.5 * (weights[mesh.F(t, (k + 1) % 3)] + weights[mesh.F(t, (k + 2) % 3)]);
}
// Every side's weight (3 #F).
Eigen::VectorXd side_weights(const Mesh& mesh, const Eigen::VectorXd& weights);

}  // namespace aniso
