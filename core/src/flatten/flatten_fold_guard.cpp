// The fold guard's step bound, shared by the local/global iterations and the
// stretch refinement: how far a map may move towards another before a
// triangle's signed area in the plane reaches zero.
#include <algorithm>
#include <cmath>

#include "flatten/flatten_pipeline.h"

namespace aniso {

namespace {

// The guard takes this share of the largest fold-free step, so that no
// triangle is driven to exactly zero area.
constexpr double kStepSafety = 0.8;

// The smallest alpha in (0, 1] at which a triangle's signed area along
// from + alpha (to - from) reaches 0, or 1 when none does: the area is a
// quadratic in alpha, a(alpha) = a0 + a1 alpha + a2 alpha^2 (Smith & Schaefer
// 2015 compute the same bound for their line search).
double first_zero_area(double a0, double a1, double a2) {
  const double scale = std::abs(a0) + std::abs(a1) + std::abs(a2);
  double first = 1.0;
  const auto consider = [&first](double root) {
    if (root > 0.0 && root < first) first = root;
  };
  if (std::abs(a2) <= 1e-14 * scale) {
    if (a1 != 0.0) consider(-a0 / a1);
    return first;
  }
  const double discriminant = a1 * a1 - 4.0 * a2 * a0;
  if (discriminant < 0.0) return first;
  const double root = std::sqrt(discriminant);
  // The two roots without cancellation: q / a2 and a0 / q.
  const double q = -0.5 * (a1 + std::copysign(root, a1));
  if (q != 0.0) {
    consider(q / a2);
    consider(a0 / q);
  }
  return first;
}

}  // namespace

double fold_free_step_fraction(const Triangles& F, const TriangleCharts& charts,
                               const Eigen::Ref<const Eigen::MatrixXd>& from_map,
                               const Eigen::Ref<const Eigen::MatrixXd>& to_map) {
  const UvRows from = from_map, to = to_map;  // the same values, gathered faster
  double fraction = 1.0;
  bool shortened = false;
  for (int t = 0; t < F.rows(); ++t) {
    if (!(charts.area[t] > 0.0)) continue;
    const Eigen::Vector2d e1 = (from.row(F(t, 1)) - from.row(F(t, 0))).transpose();
    const Eigen::Vector2d e2 = (from.row(F(t, 2)) - from.row(F(t, 0))).transpose();
    const Eigen::Vector2d d1 = (to.row(F(t, 1)) - to.row(F(t, 0))).transpose() - e1;
    const Eigen::Vector2d d2 = (to.row(F(t, 2)) - to.row(F(t, 0))).transpose() - e2;
    const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      return a.x() * b.y() - a.y() * b.x();
    };
    const double a0 = cross(e1, e2);
    const double a1 = cross(e1, d2) + cross(d1, e2);
    const double a2 = cross(d1, d2);
    if (a0 + a1 + a2 > 0.0 && a1 >= 0.0 && a2 >= 0.0) continue;  // stays positive
    const double zero = first_zero_area(a0, a1, a2);
    if (zero < 1.0 || !(a0 + a1 + a2 > 0.0)) {
      fraction = std::min(fraction, zero);
      shortened = true;
    }
  }
  return shortened ? kStepSafety * fraction : 1.0;
}

}  // namespace aniso
