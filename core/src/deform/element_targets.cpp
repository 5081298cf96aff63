#include "deform/element_targets.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <new>
#include <optional>
#include <utility>

#include <Eigen/Eigenvalues>

#include "directions/curvature.h"
#include "anisoform/direction_field.h"
#include "anisoform/error.h"
#include "geometry/frames.h"
#include "anisoform/screen_direction.h"
#include "mesh/topology.h"

namespace aniso {

struct TargetContext::FieldCache {
  std::map<std::pair<int, int>, Positions> curvature;  // (min/max, smoothing) -> field
  std::optional<std::vector<char>> lacks_principal_direction;
  // The last propagated field and its constraints: a drag or a slider asks
  // for the same one at every value, and propagating it is a solve.
  std::vector<DirectionConstraint> constraints;
  std::optional<DirectionField> propagated;
};

TargetContext::TargetContext(const Mesh& rest)
    : rest_(rest), fields_(std::make_unique<FieldCache>()) {
  vertex_normals_ = aniso::vertex_normals(rest);
  triangle_normals_ = aniso::triangle_normals(rest);
  // A zero-area triangle has no normal of its own: its frame borrows the mean
  // of its corners' vertex normals so that T stays a proper 3D map there.
  for (int t = 0; t < rest.num_triangles(); ++t) {
    if (triangle_normals_.row(t).squaredNorm() > 0.0) continue;
    Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 3; ++k) sum += vertex_normals_.row(rest.F(t, k));
    triangle_normals_.row(t) = sum.norm() > 0.0 ? Eigen::RowVector3d(sum.normalized())
                                                : Eigen::RowVector3d(0, 0, 1);
  }
}

const VertexAdjacency& TargetContext::vertex_adjacency() {
  if (!vertex_adjacency_) vertex_adjacency_ = aniso::vertex_adjacency(rest_.F, rest_.num_vertices());
  return *vertex_adjacency_;
}

const VertexAdjacency& TargetContext::triangle_adjacency() {
  if (!triangle_adjacency_) {
    triangle_adjacency_.emplace();
    aniso::triangle_adjacency(rest_.F, rest_.num_vertices(), triangle_adjacency_->offsets,
                              triangle_adjacency_->neighbors);
  }
  return *triangle_adjacency_;
}

const std::vector<char>& TargetContext::lacks_principal_direction() {
  if (!fields_->lacks_principal_direction) fields_->lacks_principal_direction = aniso::lacks_principal_direction(rest_);
  return *fields_->lacks_principal_direction;
}

TargetContext::~TargetContext() = default;

void TargetContext::vertex_directions(const DirectionSource& source, Positions& directions,
                                      Eigen::VectorXd& su, Eigen::VectorXd& sv) {
  const int n = rest_.num_vertices();
  su.resize(0);
  sv.resize(0);
  switch (source.kind) {
    case DirectionSource::Kind::Global:
    case DirectionSource::Kind::Screen: {
      const Eigen::Vector3d d = source.kind == DirectionSource::Kind::Global
                                    ? source.vector
                                    : screen_drag_to_world(source.screen);
      if (!d.allFinite() || d.isZero(0.0)) {
        fail(ErrorCode::BadParameter, "the direction must be a non-zero finite vector");
      }
      // Any non-zero finite vector means its unit vector: stableNormalized,
      // as the plain norm overflows past 1e154 and underflows below 1e-154.
      directions = d.stableNormalized().transpose().replicate(n, 1);
      return;
    }
    case DirectionSource::Kind::CurvatureMin:
    case DirectionSource::Kind::CurvatureMax: {
      const int which = source.kind == DirectionSource::Kind::CurvatureMin ? 0 : 1;
      const auto key = std::make_pair(which, source.curvature_smoothing);
      auto it = fields_->curvature.find(key);
      if (it == fields_->curvature.end()) {
        it = fields_->curvature
                 .emplace(key, curvature_direction_field(
                                   rest_, which == 0 ? CurvatureDirection::Min : CurvatureDirection::Max,
                                   source.curvature_smoothing))
                 .first;
      }
      directions = it->second;
      return;
    }
    case DirectionSource::Kind::Constraints: {
      if (!fields_->propagated || fields_->constraints != source.constraints) {
        DirectionField propagated = propagate_direction_field(rest_, source.constraints);
        fields_->propagated.reset();  // until both are set (an allocation may fail)
        fields_->constraints = source.constraints;
        fields_->propagated = std::move(propagated);
      }
      const DirectionField& field = *fields_->propagated;
      directions = field.direction;
      if (any_amounts(source.constraints)) {
        su = field.su;
        sv = field.sv;
      }
      return;
    }
    case DirectionSource::Kind::Dense: {
      directions = source.dense;
      return;
    }
  }
}

Eigen::Vector3d shear_orientation(const Mesh& mesh, const TransformSpec& spec, const Eigen::VectorXd& w) {
  if (spec.shear == 0.0) return Eigen::Vector3d::Zero();
  Eigen::Vector3d selected = Eigen::Vector3d::Zero(), unselected = Eigen::Vector3d::Zero();
  double ws = 0.0;
  int wu = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (w[i] > 0.0) {
      selected += w[i] * mesh.V.row(i).transpose();
      ws += w[i];
    } else {
      unselected += mesh.V.row(i).transpose();
      ++wu;
    }
  }
  if (ws == 0.0 || wu == 0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d away = selected / ws - unselected / wu;
  const double length = away.norm();
  return length > 0.0 && std::isfinite(length) ? Eigen::Vector3d(away / length) : Eigen::Vector3d::Zero();
}

double shear_share(const Eigen::Vector3d& cv, const Eigen::Vector3d& orientation) {
  if (orientation.isZero(0.0)) return 1.0;
  return std::min(1.0, std::abs(cv.dot(orientation)));
}

namespace {

Amounts amounts_at(const TransformSpec& spec, const Eigen::VectorXd& su, const Eigen::VectorXd& sv,
                   int i) {
  if (su.size() == 0) return {spec.su, spec.sv};
  return {su[i], sv[i]};
}

// An element square to the direction is scaled across it only
// (Frames::along_normal): sv along its u as well as its v.
Amounts element_amounts(const Frames& frames, int e, Amounts amounts) {
  if (frames.along_normal[static_cast<std::size_t>(e)]) amounts.su = amounts.sv;
  return amounts;
}

// Element frame columns with cv oriented along `orientation` (shear_orientation):
// flipping cv and n together keeps the frame right-handed. Returns the
// element's share of the shear (shear_share): none where the direction is
// its normal (Frames::along_normal), as the one shear of the selection moves
// such a face along its normal, not in its plane (its filled u, square to
// the direction, picked by the order of the fill, sheared the x = +-1 sides
// of a box sheared along x along y or z, unevenly).
double oriented_frame(const Frames& frames, int e, const Eigen::Vector3d& orientation, Eigen::Vector3d& u,
                      Eigen::Vector3d& v, Eigen::Vector3d& n) {
  u = frames.u.row(e).transpose();
  v = frames.v.row(e).transpose();
  n = frames.n.row(e).transpose();
  if (v.dot(orientation) < 0.0) {
    v = -v;
    n = -n;
  }
  return frames.along_normal[static_cast<std::size_t>(e)] ? 0.0 : shear_share(v, orientation);
}

}  // namespace

ElementTargets vertex_targets(TargetContext& context, const DirectionSource& source,
                              const TransformSpec& spec, const Eigen::VectorXd& weights) {
  const Mesh& mesh = context.rest();
  const int n = mesh.num_vertices();
  Positions directions;
  Eigen::VectorXd su, sv;
  context.vertex_directions(source, directions, su, sv);
  const Frames frames = build_frames(context.vertex_normals(), directions,
                                     [&]() -> const VertexAdjacency& { return context.vertex_adjacency(); });
  ElementTargets out;
  out.filled = frames.filled;
  out.T.resize(n);
  const Eigen::Vector3d orientation = shear_orientation(mesh, spec, weights);
  Eigen::Vector3d u, v, normal;
  for (int i = 0; i < n; ++i) {
    Amounts amounts = element_amounts(frames, i, amounts_at(spec, su, sv, i));
    amounts.shear = oriented_frame(frames, i, orientation, u, v, normal);
    out.T[i] = element_transform(spec, u, v, normal, weights[i], mesh.V.row(i).transpose(), amounts);
  }
  return out;
}

namespace {

// The line-field mean of triangle t's corner directions: the principal axis
// of the sum of d d^T, which neither a corner's sign nor the corner a face
// lists first changes. (Signs aligned to the first corner, then summed, gave
// an edit that moved by 1 % of the diagonal when the file listed each face
// from its next corner.) Its sign is the lowest-numbered corner's; zero when
// no corner has a direction.
Eigen::Vector3d corner_line_mean(const Mesh& mesh, const Positions& vdir, int t) {
  Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();
  int lowest = -1;
  for (int k = 0; k < 3; ++k) {
    const int corner = mesh.F(t, k);
    const Eigen::Vector3d d = vdir.row(corner).transpose();
    if (d.squaredNorm() == 0.0) continue;
    tensor += d * d.transpose();
    if (lowest < 0 || corner < lowest) lowest = corner;
  }
  if (lowest < 0) return Eigen::Vector3d::Zero();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(tensor, Eigen::ComputeEigenvectors);
  Eigen::Vector3d axis = eigen.eigenvectors().col(2);  // eigenvalues ascend
  if (axis.dot(vdir.row(lowest).transpose()) < 0.0) axis = -axis;
  return axis;
}

// Per-triangle frames (METHOD §3): triangle normals, directions averaged from
// the triangle's vertices as a line field (corner_line_mean), degenerate ones
// filled from the neighbouring triangles.
Frames triangle_frames(TargetContext& context, const DirectionSource& source, const Positions& vdir) {
  const Mesh& mesh = context.rest();
  const int m = mesh.num_triangles();
  const bool constant_direction = source.kind == DirectionSource::Kind::Global ||
                                  source.kind == DirectionSource::Kind::Screen;
  Positions directions(m, 3);
  for (int t = 0; t < m; ++t) {
    if (constant_direction) {
      directions.row(t) = vdir.row(mesh.F(t, 0));
      continue;
    }
    directions.row(t) = corner_line_mean(mesh, vdir, t).transpose();
  }
  return build_frames(context.triangle_normals(), directions,
                      [&]() -> const VertexAdjacency& { return context.triangle_adjacency(); });
}

}  // namespace

ElementTargets triangle_targets(TargetContext& context, const DirectionSource& source,
                                const TransformSpec& spec, const Eigen::VectorXd& weights) {
  const Mesh& mesh = context.rest();
  const int m = mesh.num_triangles();
  Positions vdir;
  Eigen::VectorXd su, sv;
  context.vertex_directions(source, vdir, su, sv);
  const Frames frames = triangle_frames(context, source, vdir);
  ElementTargets out;
  out.filled = frames.filled;
  out.T.resize(m);
  const Eigen::Vector3d orientation = shear_orientation(mesh, spec, weights);
  Eigen::Vector3d u, v, normal;
  for (int t = 0; t < m; ++t) {
    const int a = mesh.F(t, 0), b = mesh.F(t, 1), c = mesh.F(t, 2);
    const double w = (weights[a] + weights[b] + weights[c]) / 3.0;
    const Eigen::Vector3d centroid = (mesh.V.row(a) + mesh.V.row(b) + mesh.V.row(c)).transpose() / 3.0;
    Amounts amounts{spec.su, spec.sv};
    if (su.size() > 0) amounts = {(su[a] + su[b] + su[c]) / 3.0, (sv[a] + sv[b] + sv[c]) / 3.0};
    amounts = element_amounts(frames, t, amounts);
    amounts.shear = oriented_frame(frames, t, orientation, u, v, normal);
    out.T[t] = element_transform(spec, u, v, normal, w, centroid, amounts);
  }
  return out;
}

SideFrames side_frames(TargetContext& context, const DirectionSource& source) {
  SideFrames out;
  Positions vdir;
  context.vertex_directions(source, vdir, out.su, out.sv);
  out.frames = triangle_frames(context, source, vdir);
  return out;
}

SideTargets::SideTargets(const Mesh& rest, const SideFrames& frames, const TransformSpec& spec,
                         const Eigen::VectorXd& weights)
    : rest_(rest), frames_(frames), spec_(spec), weights_(weights),
      orientation_(shear_orientation(rest, spec, weights)) {}

void SideTargets::operator()(int t, Eigen::Matrix3d T[3]) const {
  Eigen::Vector3d u, v, normal;
  const double shear = oriented_frame(frames_.frames, t, orientation_, u, v, normal);
  // Without a twist a side's map depends on its position only through its
  // weight and amounts, the same on the three sides of most triangles (all
  // of a selection's inside): made once for them (element_transform was a
  // quarter of a rotation's live preview at 50k vertices in WASM).
  const bool by_position = spec_.twist && spec_.twist_degrees_per_unit != 0.0;
  double last_w = 0.0;
  Amounts last_amounts{0.0, 0.0};
  for (int k = 0; k < 3; ++k) {
    const int a = rest_.F(t, (k + 1) % 3), b = rest_.F(t, (k + 2) % 3);
    const double w = side_weight(rest_, weights_, t, k);
    Amounts amounts{spec_.su, spec_.sv};
    if (frames_.su.size() > 0) amounts = {0.5 * (frames_.su[a] + frames_.su[b]), 0.5 * (frames_.sv[a] + frames_.sv[b])};
    amounts = element_amounts(frames_.frames, t, amounts);
    amounts.shear = shear;
    if (k > 0 && !by_position && w == last_w && amounts.su == last_amounts.su && amounts.sv == last_amounts.sv) {
      T[k] = T[k - 1];
      continue;
    }
    last_w = w;
    last_amounts = amounts;
    const Eigen::Vector3d midpoint = 0.5 * (rest_.V.row(a) + rest_.V.row(b)).transpose();
    // Made in place (the prvalue initializes the element): assigned, the
    // result went through a temporary whose 72 bytes were then copied, and
    // in WASM that copy is a call to memcpy, once per side.
    ::new (static_cast<void*>(&T[k])) Eigen::Matrix3d(element_transform(spec_, u, v, normal, w, midpoint, amounts));
  }
}

Eigen::VectorXd side_weights(const Mesh& mesh, const Eigen::VectorXd& weights) {
  Eigen::VectorXd out(3 * mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) out[3 * t + k] = side_weight(mesh, weights, t, k);
  return out;
}

}  // namespace aniso
