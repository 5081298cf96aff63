// Local transformations in element frames (METHOD §3).
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "anisoform/error.h"
#include "anisoform/transforms.h"

using namespace aniso;

namespace {
const Eigen::Vector3d cu = Eigen::Vector3d(1, 1, 0).normalized();
const Eigen::Vector3d n = Eigen::Vector3d(0, 0, 1);
const Eigen::Vector3d cv = n.cross(cu);
const Eigen::Vector3d p0 = Eigen::Vector3d::Zero();
}  // namespace

TEST_CASE("transforms: anisotropic scale acts along cu, cv and n by su, sv, sn", "[transforms]") {
  TransformSpec spec;
  spec.su = 1.7;
  spec.sv = 0.6;
  spec.sn = 1.2;
  const Eigen::Matrix3d T = element_transform(spec, cu, cv, n, 1.0, p0, {spec.su, spec.sv});
  CHECK((T * cu - 1.7 * cu).norm() < 1e-14);
  CHECK((T * cv - 0.6 * cv).norm() < 1e-14);
  CHECK((T * n - 1.2 * n).norm() < 1e-14);
  CHECK((T - T.transpose()).norm() < 1e-14);
}

TEST_CASE("transforms: the selection weight blends each amount from the identity", "[transforms]") {
  TransformSpec spec;
  spec.su = 2.0;
  spec.shear = 0.4;
  CHECK(element_transform(spec, cu, cv, n, 0.0, p0, {2.0, 1.0}).isIdentity(0.0));
  const Eigen::Matrix3d half = element_transform(spec, cu, cv, n, 0.5, p0, {2.0, 1.0});
  // su -> 1 + s(su - 1) = 1.5 along cu; h -> s h = 0.2: cv gains 0.2 cu.
  CHECK((half * cu - 1.5 * cu).norm() < 1e-14);
  CHECK((half * cv - (cv + 0.2 * cu)).norm() < 1e-14);
}

TEST_CASE("transforms: shear moves cv along cu by h (paper eq. 7)", "[transforms]") {
  TransformSpec spec;
  spec.shear = 0.3;
  const Eigen::Matrix3d T = element_transform(spec, cu, cv, n, 1.0, p0, {1.0, 1.0});
  CHECK((T * cu - cu).norm() < 1e-14);
  CHECK((T * cv - (cv + 0.3 * cu)).norm() < 1e-14);
  CHECK((T * n - n).norm() < 1e-14);
  CHECK(spec.has_rotational_part());  // a shear has a rotational polar part
}

TEST_CASE("transforms: rotation about n, cu or cv turns the frame by the angle (paper eq. 8)", "[transforms]") {
  TransformSpec spec;
  spec.rotate_degrees = 90.0;
  spec.rotate_axis = RotateAxis::Normal;
  Eigen::Matrix3d T = element_transform(spec, cu, cv, n, 1.0, p0, {1.0, 1.0});
  CHECK((T * cu - cv).norm() < 1e-12);
  spec.rotate_axis = RotateAxis::U;
  T = element_transform(spec, cu, cv, n, 1.0, p0, {1.0, 1.0});
  CHECK((T * cu - cu).norm() < 1e-12);
  CHECK((T * cv - n).norm() < 1e-12);
  spec.rotate_axis = RotateAxis::V;
  T = element_transform(spec, cu, cv, n, 1.0, p0, {1.0, 1.0});
  CHECK((T * n - cu).norm() < 1e-12);
  CHECK(std::abs(T.determinant() - 1.0) < 1e-12);
}

TEST_CASE("transforms: the twist Jacobian is the derivative of the twist map", "[transforms]") {
  TransformSpec spec;
  spec.twist = true;
  spec.twist_axis = Eigen::Vector3d(0, 0, 2);  // normalised inside
  spec.twist_origin = Eigen::Vector3d(0.5, -0.2, -1.0);
  spec.twist_degrees_per_unit = 35.0;
  auto twist_map = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(spec.twist_origin + twist_rotation(spec, 1.0, p) * (p - spec.twist_origin));
  };
  const Eigen::Vector3d p(1.2, 0.7, 0.9);
  const Eigen::Matrix3d J = twist_jacobian(spec, 1.0, p);
  Eigen::Matrix3d numeric;
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    numeric.col(k) = (twist_map(p + h * Eigen::Vector3d::Unit(k)) - twist_map(p - h * Eigen::Vector3d::Unit(k))) / (2 * h);
  }
  CHECK((J - numeric).norm() < 1e-7);
  // The rotation angle grows linearly with height along the axis.
  const double angle = Eigen::AngleAxisd(twist_rotation(spec, 1.0, p)).angle() * 180.0 / M_PI;
  CHECK(angle == Approx(35.0 * (p.z() - spec.twist_origin.z())).epsilon(1e-12));
}

TEST_CASE("transforms: the polar positive part removes exactly the rotation", "[transforms]") {
  TransformSpec spec;
  spec.su = 1.5;
  spec.shear = 0.4;
  spec.rotate_axis = RotateAxis::Normal;
  spec.rotate_degrees = 25.0;
  const Eigen::Matrix3d T = element_transform(spec, cu, cv, n, 1.0, p0, {1.5, 1.0});
  const Eigen::Matrix3d P = polar_positive_part(T);
  CHECK((P - P.transpose()).norm() < 1e-12);
  const Eigen::Matrix3d Q = T * P.inverse();
  CHECK((Q.transpose() * Q - Eigen::Matrix3d::Identity()).norm() < 1e-12);
  CHECK(Q.determinant() == Approx(1.0));
  // A pure scale is its own positive part.
  TransformSpec scale;
  scale.su = 0.7;
  const Eigen::Matrix3d S = element_transform(scale, cu, cv, n, 1.0, p0, {0.7, 1.0});
  CHECK(polar_positive_part(S) == S);
  // A symmetric map that is not positive definite is not: its positive part is |T|.
  const Eigen::Matrix3d flip = Eigen::Vector3d(2.0, -1.0, 0.5).asDiagonal();
  const Eigen::Matrix3d unflipped = Eigen::Vector3d(2.0, 1.0, 0.5).asDiagonal();
  CHECK((polar_positive_part(flip) - unflipped).norm() < 1e-14);
}

TEST_CASE("transforms: invalid amounts are refused with the field named", "[transforms]") {
  TransformSpec spec;
  spec.su = 0.0;
  CHECK_THROWS_WITH(validate(spec), Catch::Contains("su") && Catch::Contains("positive"));
  spec.su = 1.0;
  spec.shear = std::nan("");
  CHECK_THROWS_WITH(validate(spec), Catch::Contains("shear"));
  spec.shear = 0.0;
  spec.twist = true;
  spec.twist_axis.setZero();
  CHECK_THROWS_WITH(validate(spec), Catch::Contains("twist axis"));
  try {
    spec.twist_axis = Eigen::Vector3d::UnitZ();
    spec.sv = -1.0;
    validate(spec);
    FAIL("negative sv accepted");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::BadParameter);
  }
}
