// The local transformations of METHOD §3 and their per-element matrices.
//
// In the element frame C = [cu, cv, n] the local matrix is
//   M = Rot * Shear * Scale,  Scale = diag(su, sv, sn),
//   Shear = [[1, h, 0], [0, 1, 0], [0, 0, 1]],
//   Rot   = rotation by theta about n, cu or cv,
// and T = J * C M C^T, where J is the Jacobian of the twist map
//   phi(p) = o + Rot(a, k (p - o).a) (p - o)
// (rotation about the axis line through o, angle growing with height; paper
// Fig. 6) at the element's rest position p. We use the Jacobian, not the bare
// rotation the paper names: a per-element rotation about the axis keeps edges
// along the axis parallel to it, so a least-squares solve reaches only about a
// quarter of the wanted twist (measured 5.3 instead of 20 deg/unit on the
// spool), while the Jacobian reproduces the twist map.
// Strength: an element of weight s gets su -> 1 + s(su - 1) (same for sv, sn),
// h -> s h, theta -> s theta, twist angle -> s * angle, so soft selections give
// soft borders.
#pragma once

#include <string>

#include <Eigen/Core>

#include "anisoform/mesh.h"

namespace aniso {

enum class RotateAxis { None, Normal, U, V };

struct TransformSpec {
  double su = 1.0;  // scale along the direction
  double sv = 1.0;  // scale across it, in the tangent plane
  double sn = 1.0;  // scale along the normal (thickness)
  double shear = 0.0;
  RotateAxis rotate_axis = RotateAxis::None;
  double rotate_degrees = 0.0;
  bool twist = false;
  Eigen::Vector3d twist_axis = Eigen::Vector3d::UnitZ();  // unit
  Eigen::Vector3d twist_origin = Eigen::Vector3d::Zero();  // angle 0 here
  double twist_degrees_per_unit = 0.0;

  // true when T has a rotational part: a rotation, a twist or a shear (a shear's
  // polar decomposition has a rotation in it). AnARAP then runs a fixed number
  // of steps instead of converging (METHOD §5).
  bool has_rotational_part() const;
  // Only the scales su, sv, sn: the element maps are then
  // I + w ((su - 1) cu cu^T + (sv - 1) cv cv^T + (sn - 1) n n^T), affine in them.
  bool scales_only() const { return !has_rotational_part(); }
  // Only a shear, no scale: the element maps are then I + w h cu cv^T, linear in h.
  bool shears_only() const;
  // Only a rotation about cu, cv or n, no scale: the element maps are then
  // rotations about that axis by w times the angle.
  bool rotates_only() const;
  // Only a twist, no scale: the element maps are then the twist's Jacobian.
  bool twists_only() const;
  bool is_identity() const;
};

// Throws Error(BadParameter) naming the field for non-finite values,
// non-positive scales and amounts outside the ranges of limits.h.
void validate(const TransformSpec& spec);

// The one rule for a scale amount, wherever it comes from: su, sv and sn of a
// TransformSpec, the su / sv a direction constraint carries (CLI field files,
// WASM constraints) and the stretches of a flattening: finite, positive and
// within limits.h [kMinScale, kMaxScale]; Error(BadParameter) naming `name`
// otherwise.
void validate_scale(double value, const std::string& name);

// The rotation coupling (limits.h [kMinRotationCoupling, kMaxRotationCoupling]),
// wherever it comes from (the deformer's request, an op, the CLI):
// Error(BadParameter) "NAME = 1e+308 is out of range (0.0001 .. 10000)".
void validate_rotation_coupling(double value, const std::string& name);

// The twist's range depends on the mesh's size (limits.h kMaxTwistDegrees):
// Error(BadParameter) when |rate| * mesh_diagonal exceeds it.
void validate_twist(const TransformSpec& spec, double mesh_diagonal);

// ARAP's move depends on the mesh's size too (limits.h kMaxMoveDiagonals):
// Error(BadParameter) when the offset is not finite or longer than that many
// diagonals.
void validate_move(const Eigen::Vector3d& offset, double mesh_diagonal);

// Per-element amounts overriding su / sv (from a direction field with amounts),
// and the share of the shear the element takes (shear_share,
// element_targets.h: 1 where its cv points along the shear's orientation, 0
// where it is square to it).
struct Amounts {
  double su;
  double sv;
  double shear = 1.0;
};

// T for one element: frame columns (cu, cv, n), selection weight s in [0, 1],
// rest position p, and the amounts to use for su / sv. noexcept (fixed-size
// arithmetic only): called once per triangle side, and in WASM a call that
// may throw from a function with cleanups goes through a JS trampoline
// (emscripten's exception handling), 1.2 million round trips at 200k vertices.
Eigen::Matrix3d element_transform(const TransformSpec& spec, const Eigen::Vector3d& cu,
                                  const Eigen::Vector3d& cv, const Eigen::Vector3d& n,
                                  double weight, const Eigen::Vector3d& position,
                                  const Amounts& amounts) noexcept;

// Where a twist starts when the user gives no origin: the axis line passes
// through the selection's weighted centroid (weights = selection weights), so
// a part turns about its own middle instead of about a line on its surface
// (with the lowest selected vertex as origin the spool's far rim swung ~0.24
// units sideways); the angle is 0 at the lowest selected height along `axis`,
// so the selection's base stays put and its far end turns most. The CLI and
// the session both use it. Zero when nothing is selected.
Eigen::Vector3d default_twist_origin(const Positions& V, const Eigen::VectorXd& weights,
                                     const Eigen::Vector3d& axis);

// The twist's rotation Rot(a, s k (p - o).a) and the Jacobian of the twist map
// at p (identity without a twist).
Eigen::Matrix3d twist_rotation(const TransformSpec& spec, double weight, const Eigen::Vector3d& position) noexcept;
Eigen::Matrix3d twist_jacobian(const TransformSpec& spec, double weight, const Eigen::Vector3d& position) noexcept;

// The symmetric positive part P of the polar decomposition T = Q P
// (METHOD §5: the AnARAP local step fits rotations against P, not T).
Eigen::Matrix3d polar_positive_part(const Eigen::Matrix3d& T);

}  // namespace aniso
