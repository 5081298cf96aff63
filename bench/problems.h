// The benchmark's standard problems (issue 2, item 9), built identically for
// every implementation so that all rows of one run time the same input.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "anisoform/mesh.h"

namespace aniso_bench {

struct Problem {
  std::string name;          // as given on the command line (cyl50k or a path)
  aniso::Mesh mesh;
  int long_axis = 2;         // longest bounding-box axis (0 x, 1 y, 2 z)
  int move_axis = 0;         // x, or y when the long axis is x
  double height = 0.0;       // extent along the long axis
  std::vector<int> fixed;    // the 5 % lowest vertices along the long axis
  std::vector<int> moved;    // the 5 % highest
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // 0.25 * height along move_axis
  Eigen::VectorXd top_half;  // 1 above the middle of the long axis, else 0
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // the long axis
};

// NAME: cyl1k | cyl10k | cyl50k | cyl200k (aniso::capped_cylinder(N, 1, 4)),
// anything else is read as a mesh file. Throws aniso::Error on a bad file.
Problem make_problem(const std::string& name);

}  // namespace aniso_bench
