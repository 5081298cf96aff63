// Selections: the region forms of the CLI, their per-vertex weights and the
// geodesic soft border around them (see selection.h).
#include "anisoform/selection.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <sstream>
#include <utility>

#include "anisoform/error.h"
#include "anisoform/file_io.h"
#include "anisoform/strict_number.h"
#include "mesh/topology.h"
#include "io/selection_text.h"

namespace aniso {
namespace {

[[noreturn]] void bad_region_parameter(const std::string& message) {
  fail(ErrorCode::BadParameter, message);
}

// "X0,Y0,Z0,..." after a "box:" or "sphere:" prefix: exactly `expected` finite numbers.
std::vector<double> parse_number_list(const std::string& list, std::size_t expected,
                                      const std::string& kind) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream stream(list);
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!list.empty() && list.back() == ',') fields.emplace_back();
  if (fields.size() != expected) {
    bad_region_parameter(kind + " needs " + std::to_string(expected) + " numbers, got " +
                  std::to_string(fields.size()) + " ('" + list + "')");
  }
  std::vector<double> numbers;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const std::vector<std::string> tokens = text::tokens_of_line(fields[k]);
    double value = 0.0;
    const std::string name = kind + " number " + std::to_string(k + 1);
    const char* not_one_token = tokens.empty() ? "is empty" : "is not a number";
    const std::string problem = tokens.size() == 1 ? text::number_field_problem(name, tokens[0], value)
                                                   : name + ": " + number_problem(fields[k], not_one_token);
    if (!problem.empty()) bad_region_parameter(problem);
    numbers.push_back(value);
  }
  return numbers;
}

Region parse_vertex_file(const std::string& path) {
  const std::string contents = read_regular_file(path, ErrorCode::BadFile);

  Region region;
  region.kind = Region::Kind::Vertices;
  bool any_weight = false;
  std::vector<double> weights;
  const std::vector<std::string> lines = text::lines_of(contents);
  for (std::size_t line = 0; line < lines.size(); ++line) {
    const std::string where = "file " + path + " line " + std::to_string(line + 1) + ": ";
    const std::vector<std::string> tokens = text::tokens_of_line(lines[line]);
    if (tokens.empty()) continue;
    if (tokens.size() > 2) {
      bad_region_parameter(where + "expected a vertex index and an optional weight, got " +
                    std::to_string(tokens.size()) + " values");
    }
    const auto index = text::parse_index(tokens[0]);
    if (!index) bad_region_parameter(where + "vertex index must be a non-negative integer, got '" + tokens[0] + "'");
    double weight = 1.0;
    if (tokens.size() == 2) {
      const std::string problem = text::number_field_problem("weight", tokens[1], weight);
      if (!problem.empty()) bad_region_parameter(where + problem);
      if (weight < 0.0 || weight > 1.0) bad_region_parameter(where + "weight " + tokens[1] + " is outside [0, 1]");
      any_weight = true;
    }
    region.vertices.push_back(*index);
    weights.push_back(weight);
  }
  if (region.vertices.empty()) bad_region_parameter("selection file '" + path + "' lists no vertices");
  if (any_weight) region.weights = std::move(weights);
  return region;
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

void check_finite(const Eigen::Vector3d& v, const std::string& what) {
  if (!v.allFinite()) bad_region_parameter(what + " has a non-finite coordinate");
}

Eigen::VectorXd box_weights(const Mesh& mesh, const Region& region) {
  check_finite(region.min, "box minimum");
  check_finite(region.max, "box maximum");
  for (int axis = 0; axis < 3; ++axis) {
    if (region.min[axis] > region.max[axis]) {
      bad_region_parameter("box minimum exceeds its maximum along " + std::string(1, "xyz"[axis]) + " (" +
                    std::to_string(region.min[axis]) + " > " + std::to_string(region.max[axis]) + ")");
    }
  }
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d p = mesh.V.row(i).transpose();
    const bool inside = (p.array() >= region.min.array()).all() && (p.array() <= region.max.array()).all();
    if (inside) weights[i] = 1.0;
  }
  return weights;
}

Eigen::VectorXd sphere_weights(const Mesh& mesh, const Region& region) {
  check_finite(region.center, "sphere centre");
  if (!std::isfinite(region.radius)) bad_region_parameter("sphere radius is not finite");
  if (region.radius < 0.0) bad_region_parameter("sphere radius is negative (" + std::to_string(region.radius) + ")");
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    // stableNorm: in units of 1e-200 every plain distance underflows to 0.
    if ((mesh.V.row(i).transpose() - region.center).stableNorm() <= region.radius) weights[i] = 1.0;
  }
  return weights;
}

// Listed vertices take their weight (1 without weights); a vertex listed twice
// keeps the larger weight, as two overlapping selections would.
Eigen::VectorXd vertex_list_weights(const Mesh& mesh, const Region& region) {
  if (!region.weights.empty() && region.weights.size() != region.vertices.size()) {
    bad_region_parameter("vertex selection has " + std::to_string(region.vertices.size()) + " vertices but " +
                  std::to_string(region.weights.size()) + " weights");
  }
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (std::size_t k = 0; k < region.vertices.size(); ++k) {
    const int vertex = region.vertices[k];
    if (vertex < 0 || vertex >= mesh.num_vertices()) {
      bad_region_parameter("selected vertex " + std::to_string(vertex) + " is out of range (the mesh has " +
                    std::to_string(mesh.num_vertices()) + " vertices)");
    }
    const double weight = region.weights.empty() ? 1.0 : region.weights[k];
    if (!(weight >= 0.0 && weight <= 1.0)) {
      bad_region_parameter("selected vertex " + std::to_string(vertex) + " has weight " + std::to_string(weight) +
                    ", outside [0, 1]");
    }
    weights[vertex] = std::max(weights[vertex], weight);
  }
  return weights;
}

double smoothstep(double x) {
  const double t = std::clamp(x, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

struct DistanceResult {
  Eigen::VectorXd distance;  // to the nearest seed
  std::vector<int> nearest;  // that seed (-1 where unreachable)
};

// Multi-source Dijkstra over mesh edges with Euclidean lengths, walking only
// paths shorter than `limit`: a vertex at `limit` or farther keeps infinity
// (and nearest -1). A small falloff on a large mesh then visits the vertices
// near the region, not the whole component; every distance below `limit` is
// the same as an unbounded walk gives, since its shortest path only passes
// nearer vertices. Edges with a non-finite length (a vertex with a NaN
// coordinate) are not walked, so bad coordinates cannot spread NaN into the
// weights.
DistanceResult edge_path_distances(const Mesh& mesh, const VertexAdjacency& adjacency,
                                   const Eigen::VectorXd& seed_weights, double limit) {
  const int n = mesh.num_vertices();
  if (seed_weights.size() != n) {
    bad_region_parameter("seed weights have " + std::to_string(seed_weights.size()) + " entries, the mesh has " +
                  std::to_string(n) + " vertices");
  }
  DistanceResult result{Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity()),
                        std::vector<int>(n, -1)};
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int i = 0; i < n; ++i) {
    if (seed_weights[i] > 0.0) {
      result.distance[i] = 0.0;
      result.nearest[i] = i;
      queue.emplace(0.0, i);
    }
  }
  while (!queue.empty()) {
    const auto [distance, i] = queue.top();
    queue.pop();
    if (distance > result.distance[i]) continue;  // a stale entry
    for (int k = adjacency.offsets[i]; k < adjacency.offsets[i + 1]; ++k) {
      const int j = adjacency.neighbors[k];
      const Eigen::RowVector3d edge = mesh.V.row(j) - mesh.V.row(i);
      double length = edge.norm();
      // Its square underflows for a mesh in units of 1e-200: stableNorm then.
      if (length < 1e-150) length = edge.stableNorm();
      if (!std::isfinite(length)) continue;
      const double candidate = distance + length;
      if (candidate < result.distance[j] && candidate < limit) {
        result.distance[j] = candidate;
        result.nearest[j] = result.nearest[i];
        queue.emplace(candidate, j);
      }
    }
  }
  return result;
}

}  // namespace

Region parse_region(const std::string& text) {
  Region region;
  if (text == "all") return region;
  if (starts_with(text, "box:")) {
    const std::vector<double> v = parse_number_list(text.substr(4), 6, "box");
    region.kind = Region::Kind::Box;
    region.min = Eigen::Vector3d(v[0], v[1], v[2]);
    region.max = Eigen::Vector3d(v[3], v[4], v[5]);
    return region;
  }
  if (starts_with(text, "sphere:")) {
    const std::vector<double> v = parse_number_list(text.substr(7), 4, "sphere");
    region.kind = Region::Kind::Sphere;
    region.center = Eigen::Vector3d(v[0], v[1], v[2]);
    region.radius = v[3];
    return region;
  }
  if (starts_with(text, "file:")) {
    const std::string path = text.substr(5);
    if (path.empty()) bad_region_parameter("region 'file:' needs a path");
    return parse_vertex_file(path);
  }
  bad_region_parameter("unknown region '" + text +
                "': expected all, box:X0,Y0,Z0,X1,Y1,Z1, sphere:X,Y,Z,R or file:PATH");
}

Eigen::VectorXd region_weights(const Mesh& mesh, const Region& region) {
  switch (region.kind) {
    case Region::Kind::All: return Eigen::VectorXd::Ones(mesh.num_vertices());
    case Region::Kind::Box: return box_weights(mesh, region);
    case Region::Kind::Sphere: return sphere_weights(mesh, region);
    case Region::Kind::Vertices: return vertex_list_weights(mesh, region);
  }
  bad_region_parameter("unknown region kind");
}

Eigen::VectorXd distance_from(const Mesh& mesh, const Eigen::VectorXd& seed_weights) {
  const VertexAdjacency adjacency = vertex_adjacency(mesh.F, mesh.num_vertices());
  return edge_path_distances(mesh, adjacency, seed_weights, std::numeric_limits<double>::infinity()).distance;
}

// The border fades from the weight of the nearest region vertex:
// w = max(w, w_nearest * smoothstep(1 - d / falloff)). For a plain region
// (weights 0 or 1) that is the documented max(w, smoothstep(1 - d/falloff));
// scaling by w_nearest keeps the soft weights of a weighted vertex list
// instead of lifting every listed vertex (at distance 0) to 1.
// Vertices at falloff or farther get smoothstep(<= 0) = 0, so the walk stops there.
Eigen::VectorXd apply_falloff(const Mesh& mesh, const VertexAdjacency& adjacency,
                              const Eigen::VectorXd& weights, double falloff) {
  if (!std::isfinite(falloff) || falloff < 0.0) {
    bad_region_parameter("falloff must be a finite distance >= 0, got " + std::to_string(falloff));
  }
  if (falloff == 0.0) return weights;
  const DistanceResult seeds = edge_path_distances(mesh, adjacency, weights, falloff);
  Eigen::VectorXd result = weights;
  for (int i = 0; i < result.size(); ++i) {
    if (seeds.nearest[i] < 0) continue;
    const double border = weights[seeds.nearest[i]] * smoothstep(1.0 - seeds.distance[i] / falloff);
    result[i] = std::max(result[i], border);
  }
  return result;
}

Eigen::VectorXd apply_falloff(const Mesh& mesh, const Eigen::VectorXd& weights, double falloff) {
  if (falloff == 0.0) return weights;
  return apply_falloff(mesh, vertex_adjacency(mesh.F, mesh.num_vertices()), weights, falloff);
}

Eigen::VectorXd selection_weights(const Mesh& mesh, const Region& region, double falloff) {
  return apply_falloff(mesh, region_weights(mesh, region), falloff);
}

Eigen::VectorXd selection_weights(const Mesh& mesh, const VertexAdjacency& adjacency,
                                  const Region& region, double falloff) {
  return apply_falloff(mesh, adjacency, region_weights(mesh, region), falloff);
}

}  // namespace aniso
