// The industry baseline (paper §4.2, "scaled" in Fig. 11): flatten without
// compression, then scale each flat piece non-uniformly along one single 2D
// direction. Exact where the wanted directions are parallel in the pattern;
// wrong where they curve, which is what the anisotropic flattening fixes.
#include <vector>

#include "flatten/flatten_pipeline.h"

namespace aniso {

void apply_uniform_scale(const FlattenPatch& patch, const TriangleCharts& charts,
                         const FlattenTargets& targets,
                         const std::vector<Eigen::Vector2d>& directions, Eigen::MatrixX2d& uv) {
  const int components = patch.num_components;
  const Triangles& F = patch.mesh.F;
  std::vector<double> area(components, 0.0), su(components, 0.0), sv(components, 0.0);
  for (int t = 0; t < F.rows(); ++t) {
    const int c = patch.component[F(t, 0)];
    area[c] += charts.area[t];
    su[c] += charts.area[t] * targets.su[t];
    sv[c] += charts.area[t] * targets.sv[t];
  }
  const std::vector<Eigen::RowVector2d> centroid = component_centroids(patch, uv);
  std::vector<Eigen::Matrix2d> scale(components);
  for (int c = 0; c < components; ++c) {
    const double along = area[c] > 0.0 ? su[c] / area[c] : 1.0;
    const double across = area[c] > 0.0 ? sv[c] / area[c] : 1.0;
    const Eigen::Vector2d d = directions[c].normalized();
    const Eigen::Vector2d n(-d.y(), d.x());
    scale[c] = along * d * d.transpose() + across * n * n.transpose();
  }
  for (int i = 0; i < uv.rows(); ++i) {
    const int c = patch.component[i];
    uv.row(i) = centroid[c] + (uv.row(i) - centroid[c]) * scale[c].transpose();
  }
}

}  // namespace aniso
