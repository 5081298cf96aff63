// Selections: which vertices an edit affects, with soft weights in [0, 1].
//
// A region gives weight 1 inside (or the weights a vertex list brings); a
// falloff distance adds a soft border measured geodesically (shortest paths
// along mesh edges, within a component) from the region: weight =
// smoothstep(1 - d / falloff), so the edit fades out smoothly.
#pragma once

#include <string>
#include <vector>

#include "anisoform/mesh.h"

namespace aniso {

struct VertexAdjacency;  // topology.h

struct Region {
  enum class Kind { All, Box, Sphere, Vertices };
  Kind kind = Kind::All;
  Eigen::Vector3d min = Eigen::Vector3d::Zero();     // Box
  Eigen::Vector3d max = Eigen::Vector3d::Zero();     // Box
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // Sphere
  double radius = 0.0;                               // Sphere
  std::vector<int> vertices;                         // Vertices
  std::vector<double> weights;                       // Vertices: empty = all 1
};

// Parses the CLI forms "all", "box:X0,Y0,Z0,X1,Y1,Z1", "sphere:X,Y,Z,R" and
// "file:PATH" (one vertex index per line, optionally followed by a weight;
// blank lines and lines starting with # ignored). Throws Error(BadParameter)
// naming the problem ("box needs 6 numbers, got 4", "file sel.txt line 3: ...").
Region parse_region(const std::string& text);

// Weight per vertex (#V) of a region, before falloff. Throws Error(BadParameter)
// for a vertex index out of range, a weight outside [0, 1], a negative radius,
// or a box whose min exceeds its max.
Eigen::VectorXd region_weights(const Mesh& mesh, const Region& region);

// Geodesic (edge-path) distance from every vertex to the nearest vertex with
// seed weight > 0 (infinity where unreachable).
Eigen::VectorXd distance_from(const Mesh& mesh, const Eigen::VectorXd& seed_weights);

// Adds a soft border of width `falloff` (model units) around the region:
// w = max(w, smoothstep(1 - d/falloff)). falloff 0 returns the input.
// Throws Error(BadParameter) if falloff < 0 or not finite. Only vertices
// nearer than `falloff` to the region are visited, so the cost follows the
// border's size, not the mesh's.
Eigen::VectorXd apply_falloff(const Mesh& mesh, const Eigen::VectorXd& weights, double falloff);
// The same with the mesh's vertex_adjacency built once by the caller (a host
// that selects many times on one mesh, such as the browser's brush).
Eigen::VectorXd apply_falloff(const Mesh& mesh, const VertexAdjacency& adjacency,
                              const Eigen::VectorXd& weights, double falloff);

// Convenience: region_weights + apply_falloff.
Eigen::VectorXd selection_weights(const Mesh& mesh, const Region& region, double falloff);
Eigen::VectorXd selection_weights(const Mesh& mesh, const VertexAdjacency& adjacency,
                                  const Region& region, double falloff);

}  // namespace aniso
