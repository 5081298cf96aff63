// What a flattening achieved per triangle (stretch along and across the
// wanted direction, singular values, folds) and its errors against the wanted
// amounts: the numbers the paper's Fig. 11 claim is measured by.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "anisoform/limits.h"
#include "base/math_constants.h"
#include "flatten/flatten_pipeline.h"

namespace aniso {

double uv_signed_area(const Triangles& F, const Eigen::MatrixX2d& uv, int t) {
  const Eigen::Vector2d ab = (uv.row(F(t, 1)) - uv.row(F(t, 0))).transpose();
  const Eigen::Vector2d ac = (uv.row(F(t, 2)) - uv.row(F(t, 0))).transpose();
  return 0.5 * (ab.x() * ac.y() - ab.y() * ac.x());
}

namespace {

// The map from the triangle's chart to the plane: J = D_uv D_chart^-1.
Eigen::Matrix2d chart_to_plane(const Triangles& F, const TriangleCharts& charts,
                               const Eigen::MatrixX2d& uv, int t) {
  Eigen::Matrix2d chart_edges, plane_edges;
  chart_edges << charts.corners(t, 2), charts.corners(t, 4),  //
      charts.corners(t, 3), charts.corners(t, 5);
  plane_edges.col(0) = (uv.row(F(t, 1)) - uv.row(F(t, 0))).transpose();
  plane_edges.col(1) = (uv.row(F(t, 2)) - uv.row(F(t, 0))).transpose();
  return plane_edges * chart_edges.inverse();
}

}  // namespace

int count_folded(const Triangles& F, const TriangleCharts& charts, const Eigen::MatrixX2d& uv) {
  int folded = 0;
  for (int t = 0; t < F.rows(); ++t) {
    if (charts.area[t] > 0.0 && !(uv_signed_area(F, uv, t) > 0.0)) ++folded;
  }
  return folded;
}

TriangleStretch measure_stretch(const Triangles& F, const TriangleCharts& charts,
                                const FlattenTargets& targets, const Eigen::MatrixX2d& uv) {
  const int m = static_cast<int>(F.rows());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  TriangleStretch stretch;
  stretch.along.setConstant(m, nan);
  stretch.across.setConstant(m, nan);
  stretch.sigma_max.setConstant(m, nan);
  stretch.sigma_min.setConstant(m, nan);
  stretch.area_ratio.setConstant(m, nan);
  stretch.shear_degrees.setConstant(m, nan);
  stretch.pattern_direction.setZero(m, 2);
  stretch.degenerate.assign(m, 0);
  for (int t = 0; t < m; ++t) {
    if (!(charts.area[t] > 0.0)) {
      stretch.degenerate[t] = 1;
      continue;
    }
    const Eigen::Matrix2d J = chart_to_plane(F, charts, uv, t);
    const Eigen::Vector2d cu = targets.direction.row(t);
    const Eigen::Vector2d cv(-cu.y(), cu.x());
    const Eigen::Vector2d mapped_u = J * cu;
    const Eigen::Vector2d mapped_v = J * cv;
    stretch.along[t] = mapped_u.norm();
    stretch.across[t] = mapped_v.norm();
    // The angle between the images of cu and cv, off square (atan2 of the
    // cross and dot products: exact near 90°, where acos is not).
    const double cross = mapped_u.x() * mapped_v.y() - mapped_u.y() * mapped_v.x();
    stretch.shear_degrees[t] = std::abs(std::atan2(cross, mapped_u.dot(mapped_v)) * 180.0 / kPi - 90.0);
    if (stretch.along[t] > 0.0) stretch.pattern_direction.row(t) = mapped_u.normalized().transpose();
    // Closed-form signed singular values of a 2x2 matrix.
    const double e = 0.5 * (J(0, 0) + J(1, 1)), f = 0.5 * (J(0, 0) - J(1, 1));
    const double g = 0.5 * (J(1, 0) + J(0, 1)), h = 0.5 * (J(1, 0) - J(0, 1));
    const double conformal = std::hypot(e, h), anticonformal = std::hypot(f, g);
    stretch.sigma_max[t] = conformal + anticonformal;
    stretch.sigma_min[t] = conformal - anticonformal;
    stretch.area_ratio[t] = J.determinant();
  }
  return stretch;
}

std::string flatten_problem(const FlattenMetrics& metrics) {
  // Folds first: they make the pattern unusable, converged or not (a
  // non-manifold edge cannot be laid flat without one, and its solver then
  // also stops unconverged).
  std::string reason;
  if (metrics.flipped > 0) reason = std::to_string(metrics.flipped) + " triangle(s) folded over";
  // Overlapping without a fold: no piece of cloth can be cut so either.
  if (metrics.outline_crossings > 0) {
    reason += (reason.empty() ? "" : " and ") + std::string("it overlaps itself (its outline crosses itself ") +
              std::to_string(metrics.outline_crossings) + " time(s))";
  }
  if (!metrics.converged) {
    reason += (reason.empty() ? "" : " and ") + std::string("the solver did not converge in ") +
              std::to_string(metrics.iterations) + " iterations";
  }
  // Why, when the patch itself cannot lie flat: the folds are its symptom,
  // and the advice to cut along a seam would not say where.
  if (metrics.non_manifold_edges > 0) {
    reason += (reason.empty() ? "" : "; ") + std::to_string(metrics.non_manifold_edges) +
              " edge(s) shared by three or more faces, which no flat piece can hold";
  }
  if (reason.empty() && !(metrics.area_distortion_mean <= kMaxUsableAreaDistortion)) {
    reason = "its area is off by " + std::to_string(static_cast<int>(std::lround(100.0 * metrics.area_distortion_mean))) +
             " % on average";
  }
  if (reason.empty()) return "";
  // The cap alone: the pattern is not finished, which says nothing of the patch.
  if (metrics.capped && metrics.flipped == 0 && metrics.non_manifold_edges == 0) {
    // At the most the iterations may be, raising them is no advice.
    if (metrics.iterations >= limits::kMaxIterations) {
      return "the flattening stopped at the iteration cap (" + std::to_string(metrics.iterations) +
             ", the most allowed) before it settled: a larger tolerance ends it where the energy changes less";
    }
    return "the flattening stopped at the iteration cap (" + std::to_string(metrics.iterations) +
           ") before it settled: raise the iterations for the finished pattern";
  }
  const std::string advice =
      metrics.non_manifold_edges > 0
          ? "select the faces on one side of each such edge (the mesh check names them) and flatten the "
            "Selection, then the rest"
          : "cut it along a seam or add darts where it curves most (select part of it and flatten the "
            "Selection), then flatten each piece";
  return "the patch does not flatten as one piece (" + reason + "): " + advice;
}

void summarize_stretch(const TriangleCharts& charts, const FlattenTargets& targets,
                       const TriangleStretch& stretch, FlattenMetrics& metrics) {
  double total_area = 0.0, along_sum = 0.0, across_sum = 0.0, area_sum = 0.0;
  double along_max = 0.0, across_max = 0.0, shear_sum = 0.0, shear_max = 0.0;
  for (int t = 0; t < charts.area.size(); ++t) {
    if (stretch.degenerate[t]) continue;
    const double area = charts.area[t];
    const double along_error = std::abs(stretch.along[t] / targets.su[t] - 1.0);
    const double across_error = std::abs(stretch.across[t] / targets.sv[t] - 1.0);
    const double area_error =
        std::abs(stretch.area_ratio[t] / (targets.su[t] * targets.sv[t]) - 1.0);
    total_area += area;
    along_sum += area * along_error;
    across_sum += area * across_error;
    area_sum += area * area_error;
    if (std::isfinite(stretch.shear_degrees[t])) {
      shear_sum += area * stretch.shear_degrees[t];
      shear_max = std::max(shear_max, stretch.shear_degrees[t]);
    }
    along_max = std::max(along_max, along_error);
    across_max = std::max(across_max, across_error);
  }
  const double inverse = total_area > 0.0 ? 1.0 / total_area : 0.0;
  metrics.compression_error_mean = along_sum * inverse;
  metrics.compression_error_max = along_max;
  metrics.cross_error_mean = across_sum * inverse;
  metrics.cross_error_max = across_max;
  metrics.area_distortion_mean = area_sum * inverse;
  metrics.shear_degrees_mean = shear_sum * inverse;
  metrics.shear_degrees_max = shear_max;
}

namespace {

// "faces 4, 9, 12 and 30 more": the first few input faces of a list, by number.
std::string face_list(const std::vector<int>& faces) {
  constexpr std::size_t kNamed = 5;
  std::string text = faces.size() == 1 ? "face " : "faces ";
  for (std::size_t k = 0; k < faces.size() && k < kNamed; ++k) text += (k > 0 ? ", " : "") + std::to_string(faces[k]);
  if (faces.size() > kNamed) text += " and " + std::to_string(faces.size() - kNamed) + " more";
  return text;
}

}  // namespace

std::vector<std::string> flatten_warnings(const FlattenMetrics& metrics) {
  std::vector<std::string> warnings;
  if (!metrics.dropped_faces.empty()) {
    warnings.push_back(std::to_string(metrics.dropped_faces.size()) +
                       " face(s) hanging off edges shared by three or more faces (a fin: " +
                       face_list(metrics.dropped_faces) +
                       ") were left out of the pattern: no flat piece can hold such an edge; if they belong to "
                       "the garment, select them and flatten them apart");
  }
  if (!metrics.reoriented_faces.empty()) {
    warnings.push_back(std::to_string(metrics.reoriented_faces.size()) +
                       " face(s) were wound against their neighbours (" + face_list(metrics.reoriented_faces) +
                       "): turned over to the winding most of the piece has, since the pattern is the piece seen "
                       "from the side its faces' normals point to; check the mesh's winding there");
  }
  const auto degrees = [](double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f°", value);
    return std::string(text);
  };
  if (metrics.shear_degrees_mean > kShearWarningDegrees) {
    warnings.push_back("the pattern shears the fabric: the wanted direction and its cross direction meet " +
                       degrees(metrics.shear_degrees_mean) + " off square on average (" +
                       degrees(metrics.shear_degrees_max) +
                       " at most), which the compression and cross errors do not show" +
                       // Offered only where the refinement ran: without it, it is no way out.
                       std::string(metrics.refined ? " (without the refinement, --no-refine or refine: false, it "
                                                     "shears less and misses the lengths more)"
                                                   : "") +
                       "; a cut or a dart where it curves most lowers both");
  }
  const int triangles = std::max(metrics.triangles, 1);
  const bool many_near_normal = metrics.near_normal_directions > kNearNormalDirectionShare * triangles;
  if (metrics.filled_directions > 0 || many_near_normal) {
    const int percent = static_cast<int>(std::lround(100.0 * metrics.near_normal_directions / triangles));
    std::string text = "the direction runs (nearly) along the surface's normal on " +
                       std::to_string(metrics.near_normal_directions) + " of " + std::to_string(metrics.triangles) +
                       " triangles (" + std::to_string(percent) + " %, within " +
                       std::to_string(static_cast<int>(kNearNormalDirectionDegrees)) + "°)";
    if (metrics.filled_directions > 0) {
      text += ", " + std::to_string(metrics.filled_directions) + " of them taken from their neighbours";
    }
    warnings.push_back(text + ": there it says little about where the fabric runs; choose a direction "
                              "along the patch");
  }
  return warnings;
}

std::vector<Eigen::Vector2d> mean_pattern_directions(const FlattenPatch& patch,
                                                     const TriangleCharts& charts,
                                                     const TriangleStretch& stretch) {
  std::vector<Eigen::Vector2d> doubled(patch.num_components, Eigen::Vector2d::Zero());
  const Triangles& F = patch.mesh.F;
  for (int t = 0; t < F.rows(); ++t) {
    if (stretch.degenerate[t]) continue;
    const double x = stretch.pattern_direction(t, 0), y = stretch.pattern_direction(t, 1);
    doubled[patch.component[F(t, 0)]] += charts.area[t] * Eigen::Vector2d(x * x - y * y, 2.0 * x * y);
  }
  std::vector<Eigen::Vector2d> directions(patch.num_components, Eigen::Vector2d::UnitX());
  for (int c = 0; c < patch.num_components; ++c) {
    if (doubled[c].norm() > 0.0) {
      const double angle = 0.5 * std::atan2(doubled[c].y(), doubled[c].x());
      directions[c] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    }
  }
  return directions;
}

}  // namespace aniso
