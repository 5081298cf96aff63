// Helpers for the solver tests: procedural oracles where no real mesh has the
// exact shape a property needs (an open cylinder), and common measurements.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "anisoform/deformer.h"
#include "anisoform/mesh.h"

namespace aniso::test {

// Open cylinder around z: `rings` rings of `segments` vertices, z in [0, height].
// Rings are aligned, so every triangle has a vertical edge and contains the axis direction.
inline Mesh open_cylinder(int segments, int rings, double radius, double height) {
  Mesh mesh;
  mesh.V.resize(segments * rings, 3);
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const double angle = 2.0 * M_PI * s / segments;
      mesh.V.row(r * segments + s) << radius * std::cos(angle), radius * std::sin(angle),
          height * r / (rings - 1);
    }
  }
  mesh.F.resize(2 * segments * (rings - 1), 3);
  int f = 0;
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      const int c = (r + 1) * segments + s, d = (r + 1) * segments + (s + 1) % segments;
      if (r % 2 == 0) {
        mesh.F.row(f++) << a, b, c;
        mesh.F.row(f++) << b, d, c;
      } else {
        mesh.F.row(f++) << a, d, c;
        mesh.F.row(f++) << a, b, d;
      }
    }
  }
  return mesh;
}

// Largest distance between V and A*rest + t for the best translation t.
inline double linear_map_error(const Positions& V, const Positions& rest, const Eigen::Matrix3d& A) {
  const Positions mapped = (rest * A.transpose()).eval();
  const Eigen::RowVector3d shift = (V - mapped).colwise().mean();
  return ((V - mapped).rowwise() - shift).rowwise().norm().maxCoeff();
}

inline double diagonal(const Positions& V) {
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

inline DeformRequest stretch_request(Method method, const Eigen::Vector3d& direction, double su,
                                     double sv = 1.0) {
  DeformRequest request;
  request.method = method;
  request.direction.kind = DirectionSource::Kind::Global;
  request.direction.vector = direction;
  request.transform.su = su;
  request.transform.sv = sv;
  return request;
}

// Area of each triangle.
inline Eigen::VectorXd triangle_areas(const Positions& V, const Triangles& F) {
  Eigen::VectorXd a(F.rows());
  for (int t = 0; t < F.rows(); ++t) {
    const Eigen::Vector3d p = V.row(F(t, 0)), q = V.row(F(t, 1)), r = V.row(F(t, 2));
    a[t] = 0.5 * (q - p).cross(r - p).norm();
  }
  return a;
}

}  // namespace aniso::test
