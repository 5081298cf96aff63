#include "anisoform/mesh.h"

namespace aniso {

BoundingBox bounding_box(const Positions& V) {
  BoundingBox box;
  if (V.rows() == 0) return box;
  box.min = V.colwise().minCoeff().transpose();
  box.max = V.colwise().maxCoeff().transpose();
  return box;
}

}  // namespace aniso
