// Tangent line fields as complex numbers (private to the core; used by
// direction_field.cpp and curvature.cpp).
//
// Each vertex gets an orthonormal tangent basis (e1, e2) built from its normal
// alone, so equal normals give equal bases. A tangent line at angle theta to e1
// is stored as exp(2 i theta): doubling the angle makes d and -d the same
// number, which is what a line field (sign does not matter) needs, and lets
// lines be averaged and interpolated linearly (Knöppel et al. 2013).
// Comparing values at two vertices needs a transport between their bases: the
// smallest rotation taking one normal onto the other (a discrete Levi-Civita
// connection).
#pragma once

#include <cmath>
#include <complex>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace aniso::field {

struct TangentBasis {
  Eigen::Vector3d e1;
  Eigen::Vector3d e2;
  Eigen::Vector3d n;
};

// Orthonormal basis with e1 x e2 = n for a unit normal (Duff et al. 2017,
// "Building an orthonormal basis, revisited"). It jumps where n_z changes
// sign; that is harmless because values at different vertices are only ever
// compared through line_transport.
inline TangentBasis tangent_basis(const Eigen::Vector3d& n) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  TangentBasis basis;
  basis.n = n;
  basis.e1 = Eigen::Vector3d(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  basis.e2 = Eigen::Vector3d(b, sign + n.y() * n.y() * a, -n.y());
  return basis;
}

// v rotated by the smallest rotation taking unit `from` onto unit `to`
// (Rodrigues). For opposite normals that rotation is undefined; v is then
// projected onto the plane of `to`, which is as good a guess as any.
inline Eigen::Vector3d rotate_between_normals(const Eigen::Vector3d& v, const Eigen::Vector3d& from,
                                              const Eigen::Vector3d& to) {
  const double c = from.dot(to);
  if (c < -1.0 + 1e-12) return v - v.dot(to) * to;
  const Eigen::Vector3d axis = from.cross(to);  // |axis| = sin(angle)
  return v * c + axis.cross(v) + axis * (axis.dot(v) / (1.0 + c));
}

// The line through tangent vector d as exp(2 i theta) in `basis`, unit length;
// 0 when d has no tangential part (a line of no direction).
inline std::complex<double> line_to_complex(const Eigen::Vector3d& d, const TangentBasis& basis) {
  const std::complex<double> z(d.dot(basis.e1), d.dot(basis.e2));
  const double length_squared = std::norm(z);
  if (!(length_squared > 0.0)) return 0.0;
  return z * z / length_squared;
}

// The unit tangent vector of the line stored as u (the angle halved).
// u = 0 carries no direction; e1 is returned so the result is still a unit tangent.
inline Eigen::Vector3d complex_to_line(const std::complex<double>& u, const TangentBasis& basis) {
  const double theta = 0.5 * std::arg(u);
  return std::cos(theta) * basis.e1 + std::sin(theta) * basis.e2;
}

// Factor r with which a line value u_from in `from`'s basis becomes r * u_from
// in `to`'s basis (unit complex; the doubled angle between the bases after
// rotating `from` onto `to`'s tangent plane).
inline std::complex<double> line_transport(const TangentBasis& from, const TangentBasis& to) {
  const Eigen::Vector3d e1 = rotate_between_normals(from.e1, from.n, to.n);
  const std::complex<double> z(e1.dot(to.e1), e1.dot(to.e2));
  const double length_squared = std::norm(z);
  if (!(length_squared > 0.0)) return 1.0;  // only for exactly opposite normals
  return z * z / length_squared;
}

}  // namespace aniso::field
