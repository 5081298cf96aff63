// Normals and element frames, including the degenerate-direction fill of METHOD §3.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "deform/element_targets.h"
#include "geometry/frames.h"
#include "mesh/topology.h"
#include "test_support.h"

using namespace aniso;

TEST_CASE("frames: vertex normals are unit and point outwards on a closed mesh", "[frames]") {
  const Mesh mesh = test::load("closed/spot_triangulated.obj");
  const Positions N = vertex_normals(mesh);
  const Eigen::RowVector3d centroid = mesh.V.colwise().mean();
  int outward = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    REQUIRE(N.row(i).norm() == Approx(1.0).epsilon(1e-12));
    if (N.row(i).dot(mesh.V.row(i) - centroid) > 0) ++outward;
  }
  CHECK(outward > 0.85 * mesh.num_vertices());
}

TEST_CASE("frames: frames are orthonormal and right-handed with cu along the projected direction", "[frames]") {
  const Mesh mesh = test::load("closed/torus.obj");
  const Positions N = vertex_normals(mesh);
  const VertexAdjacency adj = vertex_adjacency(mesh.F, mesh.num_vertices());
  const Eigen::Vector3d d(0.3, 1.0, 0.2);
  const Positions D = d.transpose().replicate(mesh.num_vertices(), 1);
  const Frames f = build_frames(N, D, [&]() -> const VertexAdjacency& { return adj; });
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d u = f.u.row(i), v = f.v.row(i), n = f.n.row(i);
    REQUIRE(u.norm() == Approx(1.0));
    REQUIRE(std::abs(u.dot(n)) < 1e-12);
    REQUIRE((u.cross(v) - n).norm() < 1e-12);
    if (f.filled == 0 || (d - d.dot(n) * n).norm() > 0.01 * d.norm()) {
      const Eigen::Vector3d projected = (d - d.dot(n) * n).normalized();
      REQUIRE((u - projected).norm() < 1e-9);
    }
  }
}

namespace {

// The hemisphere's pole: the element whose normal (of `normals`, per vertex or
// per triangle) runs most nearly along the mesh's shortest extent, its axis.
int pole_of(const Mesh& mesh, const Positions& normals) {
  const Eigen::RowVector3d extent = mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff();
  int axis = 0;
  extent.minCoeff(&axis);
  int pole = 0;
  normals.col(axis).cwiseAbs().maxCoeff(&pole);
  return pole;
}

}  // namespace

TEST_CASE("frames: directions parallel to the normal are filled from neighbours and counted", "[frames]") {
  // The hemisphere's pole has its normal along the axis: a global direction
  // along the axis is degenerate there.
  const Mesh mesh = test::load("open/hemisphere.obj");
  const Positions N = vertex_normals(mesh);
  const int pole = pole_of(mesh, N);
  const Eigen::Vector3d d = N.row(pole).transpose();  // exactly the pole's normal
  const VertexAdjacency adj = vertex_adjacency(mesh.F, mesh.num_vertices());
  const Frames f = build_frames(N, d.transpose().replicate(mesh.num_vertices(), 1),
                                [&]() -> const VertexAdjacency& { return adj; });
  CHECK(f.filled >= 1);
  CHECK(f.filled < mesh.num_vertices() / 10);
  CHECK(f.u.allFinite());
  CHECK(f.u.row(pole).norm() == Approx(1.0));
  CHECK(std::abs(f.u.row(pole).dot(N.row(pole))) < 1e-12);
}

TEST_CASE("frames: the edit's triangle frames fill a direction along the normal from neighbours, through the lazily built adjacency", "[frames]") {
  // TargetContext builds the triangle adjacency only when some triangle's
  // direction is degenerate: the hemisphere's pole triangles, for a global
  // direction along the axis.
  const Mesh mesh = test::load("open/hemisphere.obj");
  const Positions N = triangle_normals(mesh);
  const int pole = pole_of(mesh, N);
  TargetContext context(mesh);
  DirectionSource along_pole;
  along_pole.vector = N.row(pole).transpose();
  const SideFrames sides = side_frames(context, along_pole);
  CHECK(sides.frames.filled >= 1);
  CHECK(sides.frames.filled < mesh.num_triangles() / 10);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    REQUIRE(sides.frames.u.row(t).norm() == Approx(1.0));
    REQUIRE(std::abs(sides.frames.u.row(t).dot(N.row(t))) < 1e-9);
  }
}
