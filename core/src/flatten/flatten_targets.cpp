// What every triangle should become in the plane: its wanted direction in its
// chart and the wanted stretch along and across it (METHOD §3, §8).
#include <cmath>
#include <string>

#include "anisoform/error.h"
#include "base/math_constants.h"
#include "flatten/flatten_pipeline.h"
#include "geometry/frames.h"
#include "anisoform/transforms.h"

namespace aniso {

namespace {

// Line-field mean of the corners' directions in the triangle's plane, as a 3D
// vector: doubled angles are averaged so that d and -d agree (a line field),
// each corner weighted by its squared projected length. When the corners
// cancel out (a singularity of the field runs through the triangle) the first
// corner's direction is returned and build_frames decides.
Eigen::Vector3d corner_line_mean(const Positions& vertex_directions, const Triangles& F,
                                 const TriangleCharts& charts, int t) {
  const Eigen::Vector3d axis_u = charts.axis_u.row(t);
  const Eigen::Vector3d axis_v = charts.axis_v.row(t);
  Eigen::Vector2d doubled = Eigen::Vector2d::Zero();
  double weight = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d d = vertex_directions.row(F(t, k));
    const double x = d.dot(axis_u), y = d.dot(axis_v);
    doubled += Eigen::Vector2d(x * x - y * y, 2.0 * x * y);
    weight += x * x + y * y;
  }
  const Eigen::Vector3d first = vertex_directions.row(F(t, 0));
  if (!(doubled.norm() > 1e-6 * weight)) return first;
  const double angle = 0.5 * std::atan2(doubled.y(), doubled.x());
  return std::cos(angle) * axis_u + std::sin(angle) * axis_v;
}

// 3D directions per triangle into unit chart vectors, the degenerate ones
// (direction along the normal, or none) filled from neighbouring triangles.
void directions_into_charts(const FlattenPatch& patch, const TriangleCharts& charts,
                            const TriangleNeighbours& neighbours, const Positions& triangle_directions,
                            FlattenTargets& targets) {
  const Frames frames = build_frames(triangle_normals(patch.mesh), triangle_directions,
                                     [&]() -> const VertexAdjacency& { return neighbours.get(); });
  const int m = patch.mesh.num_triangles();
  targets.direction.resize(m, 2);
  targets.filled_directions = frames.filled;
  const Positions& normals = frames.n;  // the triangle normals build_frames was given
  const double near = std::cos(kNearNormalDirectionDegrees * kPi / 180.0);
  targets.near_normal_directions = 0;
  for (int t = 0; t < m; ++t) {
    const Eigen::Vector3d d = triangle_directions.row(t);
    const Eigen::Vector3d n = normals.row(t);
    // Only a triangle that has a normal; one without a direction is filled (counted above).
    if (n.squaredNorm() > 0.0 && d.squaredNorm() > 0.0 && std::abs(d.dot(n)) >= near * d.norm() * n.norm()) {
      ++targets.near_normal_directions;
    }
  }
  for (int t = 0; t < m; ++t) {
    const Eigen::Vector3d cu = frames.u.row(t);
    Eigen::Vector2d chart(cu.dot(charts.axis_u.row(t)), cu.dot(charts.axis_v.row(t)));
    // A degenerate triangle has no chart; any unit vector serves it.
    targets.direction.row(t) = chart.norm() > 0.0 ? chart.normalized() : Eigen::Vector2d::UnitX();
  }
}

}  // namespace

FlattenTargets with_uniform_amounts(const FlattenTargets& targets, double su, double sv) {
  validate_scale(su, "the stretch along the direction su");
  validate_scale(sv, "the stretch across the direction sv");
  FlattenTargets uniform = targets;
  uniform.su.setConstant(targets.direction.rows(), su);
  uniform.sv.setConstant(targets.direction.rows(), sv);
  return uniform;
}

FlattenTargets flatten_targets(const Mesh& input, const FlattenPatch& patch,
                               const TriangleCharts& charts, const TriangleNeighbours& neighbours,
                               const FlattenDirections& directions, double su, double sv) {
  validate_scale(su, "the stretch along the direction su");
  validate_scale(sv, "the stretch across the direction sv");
  const int m = patch.mesh.num_triangles();
  FlattenTargets targets;
  targets.su.setConstant(m, su);
  targets.sv.setConstant(m, sv);
  Positions triangle_directions(m, 3);

  if (directions.kind == FlattenDirections::Kind::Global) {
    if (!directions.global.allFinite() || directions.global.isZero(0.0)) {
      fail(ErrorCode::BadParameter, "the global direction must be a finite non-zero vector");
    }
    triangle_directions.rowwise() = directions.global.stableNormalized().transpose();
    directions_into_charts(patch, charts, neighbours, triangle_directions, targets);
    return targets;
  }

  if (directions.constraints.empty()) {
    fail(ErrorCode::BadParameter, "the direction field has no constraint");
  }
  const bool field_amounts = any_amounts(directions.constraints);
  // The field lives on the patch only: constraints outside it (and bad
  // amounts) are refused by the propagation, naming the input vertex.
  std::vector<char> in_patch(input.num_vertices(), 0);
  for (int input_vertex : patch.input_vertex) in_patch[input_vertex] = 1;
  const DirectionField field = propagate_direction_field(input, directions.constraints, &in_patch);

  Positions vertex_directions(patch.mesh.num_vertices(), 3);
  for (int i = 0; i < patch.mesh.num_vertices(); ++i) {
    vertex_directions.row(i) = field.direction.row(patch.input_vertex[i]);
  }
  const Triangles& F = patch.mesh.F;
  for (int t = 0; t < m; ++t) {
    triangle_directions.row(t) = corner_line_mean(vertex_directions, F, charts, t).transpose();
    if (field_amounts) {
      double along = 0.0, across = 0.0;
      for (int k = 0; k < 3; ++k) {
        along += field.su[patch.input_vertex[F(t, k)]];
        across += field.sv[patch.input_vertex[F(t, k)]];
      }
      targets.su[t] = along / 3.0;
      targets.sv[t] = across / 3.0;
    }
  }
  directions_into_charts(patch, charts, neighbours, triangle_directions, targets);
  return targets;
}

}  // namespace aniso
