#include "anisoform/transforms.h"

#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "anisoform/error.h"
#include "anisoform/limits.h"
#include "base/math_constants.h"

namespace aniso {
namespace {

void require_finite(double value, const char* name) {
  if (!std::isfinite(value)) {
    fail(ErrorCode::BadParameter, std::string(name) + " must be a finite number");
  }
}

// Six significant digits, or as many more as it takes to read back as the
// value itself: 3600.0001 printed as "3600" said "rotation angle = 3600 is out
// of range (-3600 .. 3600)".
std::string range_number_text(double value) {
  for (int digits = 6;; ++digits) {
    std::ostringstream text;
    text.precision(digits);
    text << value;
    if (digits >= 17 || std::stod(text.str()) == value) return text.str();
  }
}

// "scale su = 1e+300 is out of range (0.01 .. 100)".
void require_in_range(double value, double lowest, double highest, const char* name) {
  require_finite(value, name);
  if (value >= lowest && value <= highest) return;
  fail(ErrorCode::BadParameter, std::string(name) + " = " + range_number_text(value) + " is out of range (" +
                                    range_number_text(lowest) + " .. " + range_number_text(highest) + ")");
}

}  // namespace

bool TransformSpec::has_rotational_part() const {
  return (rotate_axis != RotateAxis::None && rotate_degrees != 0.0) ||
         (twist && twist_degrees_per_unit != 0.0) || shear != 0.0;
}

bool TransformSpec::rotates_only() const {
  TransformSpec unturned = *this;
  unturned.rotate_degrees = 0.0;
  return rotate_axis != RotateAxis::None && rotate_degrees != 0.0 && unturned.is_identity();
}

bool TransformSpec::twists_only() const {
  TransformSpec untwisted = *this;
  untwisted.twist = false;
  return twist && twist_degrees_per_unit != 0.0 && untwisted.is_identity();
}

bool TransformSpec::shears_only() const {
  TransformSpec unsheared = *this;
  unsheared.shear = 0.0;
  return shear != 0.0 && unsheared.is_identity();
}

bool TransformSpec::is_identity() const {
  return su == 1.0 && sv == 1.0 && sn == 1.0 && !has_rotational_part();
}

void validate_scale(double value, const std::string& name) {
  require_finite(value, name.c_str());
  if (value <= 0.0) fail(ErrorCode::BadParameter, name + " must be positive, got " + range_number_text(value));
  require_in_range(value, limits::kMinScale, limits::kMaxScale, name.c_str());
}

void validate_rotation_coupling(double value, const std::string& name) {
  require_in_range(value, limits::kMinRotationCoupling, limits::kMaxRotationCoupling, name.c_str());
}

void validate(const TransformSpec& spec) {
  validate_scale(spec.su, "scale su");
  validate_scale(spec.sv, "scale sv");
  validate_scale(spec.sn, "thickness scale sn");
  require_in_range(spec.shear, -limits::kMaxShear, limits::kMaxShear, "shear");
  require_in_range(spec.rotate_degrees, -limits::kMaxRotateDegrees, limits::kMaxRotateDegrees,
                   "rotation angle (degrees)");
  require_finite(spec.twist_degrees_per_unit, "twist rate");  // its range depends on the mesh (validate_twist)
  if (spec.twist) {
    if (!spec.twist_axis.allFinite() || spec.twist_axis.isZero(0.0)) {
      fail(ErrorCode::BadParameter, "twist axis must be a non-zero finite vector");
    }
    if (!spec.twist_origin.allFinite()) fail(ErrorCode::BadParameter, "twist origin must be finite");
  }
}

void validate_twist(const TransformSpec& spec, double mesh_diagonal) {
  if (!spec.twist) return;
  const double total = std::abs(spec.twist_degrees_per_unit) * mesh_diagonal;
  if (total <= limits::kMaxTwistDegrees) return;
  fail(ErrorCode::BadParameter,
       "twist rate = " + range_number_text(spec.twist_degrees_per_unit) + " degrees per unit turns the mesh by " +
           range_number_text(total) + " degrees over its bounding-box diagonal of " +
           range_number_text(mesh_diagonal) + "; at most " + range_number_text(limits::kMaxTwistDegrees) +
           " degrees are allowed");
}

void validate_move(const Eigen::Vector3d& offset, double mesh_diagonal) {
  const std::string given = "move = (" + range_number_text(offset.x()) + ", " + range_number_text(offset.y()) +
                            ", " + range_number_text(offset.z()) + ")";
  if (!offset.allFinite()) fail(ErrorCode::BadParameter, given + " must be finite");
  const double limit = limits::kMaxMoveDiagonals * mesh_diagonal;
  // stableNorm: |(1e300, 0, 0)| is 1e300, where the plain norm's square overflows.
  const double length = offset.stableNorm();
  if (length <= limit) return;
  fail(ErrorCode::BadParameter,
       given + " is " + range_number_text(length) + " long; at most " +
           range_number_text(limits::kMaxMoveDiagonals) + " times the mesh's bounding-box diagonal of " +
           range_number_text(mesh_diagonal) + " (" + range_number_text(limit) + ") is allowed");
}

Eigen::Matrix3d element_transform(const TransformSpec& spec, const Eigen::Vector3d& cu,
                                  const Eigen::Vector3d& cv, const Eigen::Vector3d& n,
                                  double weight, const Eigen::Vector3d& position,
                                  const Amounts& amounts) noexcept {
  const double s = weight;
  if (s <= 0.0) return Eigen::Matrix3d::Identity();
  Eigen::Matrix3d local = Eigen::Matrix3d::Zero();
  local(0, 0) = 1.0 + s * (amounts.su - 1.0);
  local(1, 1) = 1.0 + s * (amounts.sv - 1.0);
  local(2, 2) = 1.0 + s * (spec.sn - 1.0);
  const bool rotates = spec.rotate_axis != RotateAxis::None && spec.rotate_degrees != 0.0;
  const bool twists = spec.twist && spec.twist_degrees_per_unit != 0.0;
  if (spec.shear == 0.0 && !rotates && !twists) {
    // Scales only: C diag(a, b, c) C^T as three outer products, each entry
    // once and mirrored (exactly symmetric). The two 3x3 products cost
    // twice the arithmetic, and this runs for every triangle side of every
    // edit (1.2 million at 200k vertices).
    const double a = local(0, 0), b = local(1, 1), c = local(2, 2);
    Eigen::Matrix3d T;
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i <= j; ++i) T(i, j) = T(j, i) = a * cu[i] * cu[j] + b * cv[i] * cv[j] + c * n[i] * n[j];
    }
    return T;
  }
  if (spec.shear != 0.0) {
    Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
    shear(0, 1) = s * spec.shear * amounts.shear;
    local = shear * local;
  }
  if (rotates) {
    const int axis = spec.rotate_axis == RotateAxis::Normal ? 2 : spec.rotate_axis == RotateAxis::U ? 0 : 1;
    const Eigen::Vector3d unit = Eigen::Vector3d::Unit(axis);
    local = Eigen::AngleAxisd(s * spec.rotate_degrees * kDegToRad, unit).toRotationMatrix() * local;
  }
  Eigen::Matrix3d C;
  C.col(0) = cu;
  C.col(1) = cv;
  C.col(2) = n;
  Eigen::Matrix3d T = C * local * C.transpose();
  if (twists) {
    T = twist_jacobian(spec, weight, position) * T;
  }
  return T;
}

Eigen::Matrix3d twist_rotation(const TransformSpec& spec, double weight, const Eigen::Vector3d& position) noexcept {
  if (!spec.twist || weight <= 0.0) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d axis = spec.twist_axis.stableNormalized();
  const double rate = weight * spec.twist_degrees_per_unit * kDegToRad;
  return Eigen::AngleAxisd(rate * (position - spec.twist_origin).dot(axis), axis).toRotationMatrix();
}

Eigen::Matrix3d twist_jacobian(const TransformSpec& spec, double weight, const Eigen::Vector3d& position) noexcept {
  if (!spec.twist || weight <= 0.0) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d axis = spec.twist_axis.stableNormalized();
  const double rate = weight * spec.twist_degrees_per_unit * kDegToRad;
  const Eigen::Vector3d r = position - spec.twist_origin;
  // d/dp [Rot(rate * r.a) r] = Rot (I + rate (a x r) a^T).
  return twist_rotation(spec, weight, position) *
         (Eigen::Matrix3d::Identity() + rate * axis.cross(r) * axis.transpose());
}

Eigen::Matrix3d polar_positive_part(const Eigen::Matrix3d& T) {
  if ((T - T.transpose()).cwiseAbs().maxCoeff() <= 1e-14 * T.cwiseAbs().maxCoeff()) {
    // Symmetric: our scale transforms are C diag C^T with positive factors.
    // Positive definite by Sylvester's criterion (leading minors positive):
    // the AnARAP solver runs this for every vertex of every edit and live
    // preview, and it costs a fraction of an eigendecomposition.
    const double minor2 = T(0, 0) * T(1, 1) - T(0, 1) * T(1, 0);
    if (T(0, 0) > 0.0 && minor2 > 0.0 && T.determinant() > 0.0) return T;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(T.transpose() * T);
  const Eigen::Vector3d root = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return eig.eigenvectors() * root.asDiagonal() * eig.eigenvectors().transpose();
}

Eigen::Vector3d default_twist_origin(const Positions& V, const Eigen::VectorXd& weights,
                                     const Eigen::Vector3d& axis) {
  const Eigen::Vector3d a = axis.stableNormalized();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double total = 0.0;
  double lowest = 0.0;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    if (!(weights[i] > 0.0)) continue;
    const Eigen::Vector3d p = V.row(i).transpose();
    if (total == 0.0 || p.dot(a) < lowest) lowest = p.dot(a);
    centroid += weights[i] * p;
    total += weights[i];
  }
  if (!(total > 0.0)) return Eigen::Vector3d::Zero();
  centroid /= total;
  // Slide along the axis line (which stays through the centroid) down to the
  // lowest selected height, where the angle is 0.
  return centroid + (lowest - centroid.dot(a)) * a;
}

}  // namespace aniso
