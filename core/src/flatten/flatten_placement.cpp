// Where each pattern piece sits, how it is turned and how big it is: a start
// map scaled to the area it should have, each piece turned so that its
// grainline is horizontal, and the pieces laid out side by side.
#include <algorithm>
#include <cmath>
#include <vector>

#include "flatten/flatten_pipeline.h"

namespace aniso {

std::vector<Eigen::RowVector2d> component_centroids(const FlattenPatch& patch,
                                                    const Eigen::MatrixX2d& uv) {
  std::vector<Eigen::RowVector2d> centroid(patch.num_components, Eigen::RowVector2d::Zero());
  std::vector<int> count(patch.num_components, 0);
  for (int i = 0; i < uv.rows(); ++i) {
    centroid[patch.component[i]] += uv.row(i);
    ++count[patch.component[i]];
  }
  for (int c = 0; c < patch.num_components; ++c) centroid[c] /= std::max(count[c], 1);
  return centroid;
}

void scale_to_area(const FlattenPatch& patch, const Eigen::VectorXd& triangle_area,
                   Eigen::MatrixX2d& uv) {
  const Triangles& F = patch.mesh.F;
  const int components = patch.num_components;
  std::vector<double> wanted(components, 0.0), achieved(components, 0.0);
  for (int t = 0; t < F.rows(); ++t) {
    const int c = patch.component[F(t, 0)];
    wanted[c] += triangle_area[t];
    achieved[c] += uv_signed_area(F, uv, t);
  }
  const std::vector<Eigen::RowVector2d> centroid = component_centroids(patch, uv);
  std::vector<Eigen::RowVector2d> scale(components);
  for (int c = 0; c < components; ++c) {
    const double factor =
        std::abs(achieved[c]) > 0.0 ? std::sqrt(wanted[c] / std::abs(achieved[c])) : 1.0;
    // A map seen from the back is mirrored: every piece is shown from the
    // side its faces' normals point to (kPatternSide, pattern_export.h).
    scale[c] = Eigen::RowVector2d(factor, achieved[c] < 0.0 ? -factor : factor);
  }
  for (int i = 0; i < uv.rows(); ++i) {
    const int c = patch.component[i];
    uv.row(i) = ((uv.row(i) - centroid[c]).cwiseProduct(scale[c])).eval();
  }
}

void align_grainlines(const FlattenPatch& patch, std::vector<Eigen::Vector2d>& grainlines,
                      Eigen::MatrixX2d& uv) {
  const int components = patch.num_components;
  const std::vector<Eigen::RowVector2d> centroid = component_centroids(patch, uv);
  std::vector<Eigen::Matrix2d> turn(components);
  for (int c = 0; c < components; ++c) {
    const Eigen::Vector2d g = grainlines[c].normalized();
    turn[c] << g.x(), g.y(), -g.y(), g.x();  // rotation taking g to +u
    grainlines[c] = Eigen::Vector2d::UnitX();
  }
  for (int i = 0; i < uv.rows(); ++i) {
    const int c = patch.component[i];
    uv.row(i) = centroid[c] + (uv.row(i) - centroid[c]) * turn[c].transpose();
  }
}

void layout_components(const FlattenPatch& patch, Eigen::MatrixX2d& uv, double gap_fraction) {
  const int components = patch.num_components;
  Eigen::MatrixX2d lo = Eigen::MatrixX2d::Constant(components, 2, HUGE_VAL);
  Eigen::MatrixX2d hi = Eigen::MatrixX2d::Constant(components, 2, -HUGE_VAL);
  for (int i = 0; i < uv.rows(); ++i) {
    const int c = patch.component[i];
    lo.row(c) = lo.row(c).cwiseMin(uv.row(i));
    hi.row(c) = hi.row(c).cwiseMax(uv.row(i));
  }
  double largest = 0.0;
  for (int c = 0; c < components; ++c) largest = std::max(largest, (hi.row(c) - lo.row(c)).maxCoeff());
  const double gap = gap_fraction * largest;
  std::vector<Eigen::RowVector2d> shift(components);
  double cursor = 0.0;
  for (int c = 0; c < components; ++c) {
    shift[c] = Eigen::RowVector2d(cursor - lo(c, 0), -lo(c, 1));
    cursor += hi(c, 0) - lo(c, 0) + gap;
  }
  for (int i = 0; i < uv.rows(); ++i) uv.row(i) += shift[patch.component[i]];
}

}  // namespace aniso
