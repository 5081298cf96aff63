#include "problems.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "anisoform/mesh_io.h"
#include "bench/primitives.h"

namespace aniso_bench {
namespace {

// Vertex order "lowest first" along `axis`. Ties are common (a flat cap has
// 10 % of a capped cylinder's vertices on one plane), so they are broken by
// the distance from the bounding box's long axis line (nearest first, i.e. a
// central disc of a flat cap), then by index: the selection is deterministic
// and compact whatever the vertex numbering.
std::vector<int> order_along(const aniso::Mesh& mesh, int axis, const Eigen::Vector3d& centre, bool highest_first) {
  const int n = mesh.num_vertices();
  std::vector<double> key(n), radial(n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d p = mesh.V.row(i).transpose() - centre;
    key[i] = highest_first ? -p[axis] : p[axis];
    p[axis] = 0.0;
    radial[i] = p.squaredNorm();
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    if (key[a] != key[b]) return key[a] < key[b];
    if (radial[a] != radial[b]) return radial[a] < radial[b];
    return a < b;
  });
  return order;
}

}  // namespace

Problem make_problem(const std::string& name) {
  Problem problem;
  problem.name = name;
  if (name == "cyl1k") {
    problem.mesh = aniso::capped_cylinder(1000, 1.0, 4.0);
  } else if (name == "cyl10k") {
    problem.mesh = aniso::capped_cylinder(10000, 1.0, 4.0);
  } else if (name == "cyl50k") {
    problem.mesh = aniso::capped_cylinder(50000, 1.0, 4.0);
  } else if (name == "cyl200k") {
    problem.mesh = aniso::capped_cylinder(200000, 1.0, 4.0);
  } else {
    problem.mesh = aniso::read_mesh(name).mesh;
  }
  const aniso::Mesh& mesh = problem.mesh;
  const int n = mesh.num_vertices();
  const aniso::BoundingBox box = aniso::bounding_box(mesh.V);
  const Eigen::Vector3d extent = box.max - box.min;
  int axis = 0;
  for (int a = 1; a < 3; ++a) {
    if (extent[a] > extent[axis]) axis = a;
  }
  problem.long_axis = axis;
  problem.move_axis = axis == 0 ? 1 : 0;
  problem.height = extent[axis];
  problem.offset = Eigen::Vector3d::Zero();
  problem.offset[problem.move_axis] = 0.25 * problem.height;
  problem.direction = Eigen::Vector3d::Unit(axis);

  const Eigen::Vector3d centre = 0.5 * (box.min + box.max);
  const int count = std::max(1, static_cast<int>(std::lround(0.05 * n)));
  const std::vector<int> low = order_along(mesh, axis, centre, false);
  const std::vector<int> high = order_along(mesh, axis, centre, true);
  problem.fixed.assign(low.begin(), low.begin() + count);
  problem.moved.assign(high.begin(), high.begin() + count);
  std::sort(problem.fixed.begin(), problem.fixed.end());
  std::sort(problem.moved.begin(), problem.moved.end());

  problem.top_half = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    if (mesh.V(i, axis) > centre[axis]) problem.top_half[i] = 1.0;
  }
  return problem;
}

}  // namespace aniso_bench
