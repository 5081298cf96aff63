// The indexed triangle mesh every module works on.
//
// Positions are double precision, one row per vertex (#V by 3); triangles are
// one row per face (#F by 3) of 0-based vertex indices, counter-clockwise seen
// from outside. Row-major storage so that a flat xyz buffer maps onto it.
#pragma once

#include <Eigen/Core>

namespace aniso {

using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct Mesh {
  Positions V;  // #V by 3 vertex positions
  Triangles F;  // #F by 3 vertex indices per triangle

  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_triangles() const { return static_cast<int>(F.rows()); }
};

struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  // stableNorm: the plain norm's square underflows to 0 below ~1e-154 (a
  // mesh in units of 1e-200 had no extent, and no unit-size copy) and
  // overflows above ~1e154.
  double diagonal() const { return (max - min).stableNorm(); }
};

// Axis-aligned bounding box of the vertices (zero box for an empty mesh).
BoundingBox bounding_box(const Positions& V);

// The box of the shape: of the finite vertices that a face references (an
// index out of range is skipped); of every finite vertex when no face
// references one. An unreferenced vertex is not part of the surface and is
// never moved: it does not count toward the mesh's size, and so neither
// toward the unit guess (guess_model_unit), the deformer's unit-size copy,
// the twist and move limits (limits.h) or the default direction
// (longest_axis). spothead plus one unused `v 10 10 10` was guessed in
// centimetres, its pattern 100 times too small. MeshReport::bbox is this box.
BoundingBox shape_bounding_box(const Positions& V, const Triangles& F);
inline BoundingBox shape_bounding_box(const Mesh& mesh) { return shape_bounding_box(mesh.V, mesh.F); }

}  // namespace aniso
