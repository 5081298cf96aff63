#include "anisoform/mesh.h"

#include <algorithm>
#include <vector>

namespace aniso {

BoundingBox bounding_box(const Positions& V) {
  BoundingBox box;
  if (V.rows() == 0) return box;
  box.min = V.colwise().minCoeff().transpose();
  box.max = V.colwise().maxCoeff().transpose();
  return box;
}

BoundingBox shape_bounding_box(const Positions& V, const Triangles& F) {
  const Eigen::Index n = V.rows();
  std::vector<char> counted(static_cast<std::size_t>(n), 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = F(f, k);
      if (v >= 0 && v < n) counted[static_cast<std::size_t>(v)] = 1;
    }
  }
  const bool any_referenced = std::find(counted.begin(), counted.end(), 1) != counted.end();
  BoundingBox box;
  bool any = false;
  for (Eigen::Index v = 0; v < n; ++v) {
    if (any_referenced && !counted[static_cast<std::size_t>(v)]) continue;
    const Eigen::Vector3d p = V.row(v).transpose();
    if (!p.allFinite()) continue;
    box.min = any ? Eigen::Vector3d(box.min.cwiseMin(p)) : p;
    box.max = any ? Eigen::Vector3d(box.max.cwiseMax(p)) : p;
    any = true;
  }
  return box;
}

}  // namespace aniso
