// The patch to flatten (selected faces, compact, per component, each open) and
// every triangle's isometric chart.
#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "anisoform/error.h"
#include "flatten/flatten_pipeline.h"
#include "anisoform/mesh_check.h"
#include "geometry/frames.h"
#include "mesh/topology.h"

namespace aniso {

namespace {

bool selected(const std::vector<char>& vertex_mask, int vertex) {
  return vertex_mask.empty() || vertex_mask[vertex] != 0;
}

// Compacts the selected faces: only vertices some selected face uses are kept,
// so unreferenced vertices of the input (scans have them) never reach a solve.
void compact_selected_faces(const Mesh& mesh, const std::vector<char>& vertex_mask,
                            FlattenPatch& patch) {
  std::vector<int> input_to_patch(mesh.num_vertices(), -1);
  std::vector<int> faces;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    bool whole = true;
    for (int k = 0; k < 3; ++k) whole = whole && selected(vertex_mask, mesh.F(t, k));
    if (whole) faces.push_back(t);
  }
  if (faces.empty()) {
    fail(ErrorCode::BadParameter,
         vertex_mask.empty() ? "the mesh has no triangle to flatten"
                             : "the selection holds no whole triangle: nothing to flatten");
  }
  patch.mesh.F.resize(static_cast<int>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const int t = faces[f];
    for (int k = 0; k < 3; ++k) {
      const int input_vertex = mesh.F(t, k);
      if (input_to_patch[input_vertex] < 0) {
        input_to_patch[input_vertex] = static_cast<int>(patch.input_vertex.size());
        patch.input_vertex.push_back(input_vertex);
      }
      patch.mesh.F(static_cast<int>(f), k) = input_to_patch[input_vertex];
    }
  }
  patch.input_face = std::move(faces);
  patch.mesh.V.resize(static_cast<int>(patch.input_vertex.size()), 3);
  for (std::size_t i = 0; i < patch.input_vertex.size(); ++i) {
    const int input_vertex = patch.input_vertex[i];
    const std::string problem = coordinate_problem(mesh.V.row(input_vertex));
    if (!problem.empty()) {
      fail(ErrorCode::BadMesh, "vertex " + std::to_string(input_vertex) + " " + problem + ": cannot flatten");
    }
    patch.mesh.V.row(static_cast<int>(i)) = mesh.V.row(input_vertex);
  }
}

// The pattern is the patch seen from the side its faces' normals point to
// (pattern_export.h, kPatternSide): a face wound against its neighbours would
// be laid flat seen from the other side, folded over the rest (one such face
// on the torso panel folded and stopped the solver; half the faces turned
// gave an outline crossing itself 22 times). Such faces are turned over to
// the winding most of their piece has, and named (metrics.reoriented_faces).
void wind_faces_one_way(FlattenPatch& patch) {
  const WindingRepair repair = majority_winding(patch.mesh);
  if (repair.non_orientable_face >= 0) {
    fail(ErrorCode::BadMesh,
         "the patch cannot be wound one way: it is non-orientable (like a Moebius strip: at face " +
             std::to_string(patch.input_face[repair.non_orientable_face]) +
             " the winding disagrees with a neighbour's whichever way the faces are turned), and a piece of "
             "fabric has a right and a wrong side: cut the patch there, or flatten a selection that is not");
  }
  for (const int t : repair.faces_to_turn) {
    std::swap(patch.mesh.F(t, 1), patch.mesh.F(t, 2));
    patch.reoriented_faces.push_back(patch.input_face[t]);
  }
  std::sort(patch.reoriented_faces.begin(), patch.reoriented_faces.end());
}

}  // namespace

FlattenPatch extract_flatten_patch(const Mesh& mesh, const std::vector<char>& vertex_mask) {
  if (!vertex_mask.empty() && static_cast<int>(vertex_mask.size()) != mesh.num_vertices()) {
    fail(ErrorCode::BadParameter, "the vertex mask has " + std::to_string(vertex_mask.size()) +
                                      " entries, the mesh " + std::to_string(mesh.num_vertices()) +
                                      " vertices");
  }
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (mesh.F(t, k) < 0 || mesh.F(t, k) >= mesh.num_vertices()) {
        fail(ErrorCode::BadMesh, "face " + std::to_string(t) + " references vertex " +
                                     std::to_string(mesh.F(t, k)) + ", which does not exist");
      }
    }
  }
  FlattenPatch patch;
  compact_selected_faces(mesh, vertex_mask, patch);
  wind_faces_one_way(patch);
  const int n = patch.mesh.num_vertices();
  patch.component = vertex_components(patch.mesh.F, n, &patch.num_components);
  patch.boundary_loops = boundary_loops(patch.mesh.F, n);
  std::vector<char> open(patch.num_components, 0);
  for (const std::vector<int>& loop : patch.boundary_loops) {
    const int c = patch.component[loop.front()];
    patch.loop_component.push_back(c);
    open[c] = 1;
  }
  for (int c = 0; c < patch.num_components; ++c) {
    if (open[c]) continue;
    const auto first = std::find(patch.component.begin(), patch.component.end(), c);
    const int vertex = patch.input_vertex[first - patch.component.begin()];
    std::string where;
    if (patch.num_components > 1) {
      where = " (the component with vertex " + std::to_string(vertex) + " has no boundary)";
    }
    fail(ErrorCode::BadMesh,
         "the patch is closed: flattening needs a boundary; select a part of the mesh" + where);
  }
  return patch;
}

TriangleCharts triangle_charts(const Mesh& mesh) {
  const int m = mesh.num_triangles();
  TriangleCharts charts;
  charts.axis_u.setZero(m, 3);
  charts.axis_v.setZero(m, 3);
  charts.corners.setZero(m, 6);
  charts.area.setZero(m);
  for (int t = 0; t < m; ++t) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(t, 0));
    const Eigen::Vector3d b = mesh.V.row(mesh.F(t, 1));
    const Eigen::Vector3d c = mesh.V.row(mesh.F(t, 2));
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    const double longest2 =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const double twice_area = normal.norm();
    if (!(twice_area > kDegenerateAreaFraction * longest2)) continue;  // no chart
    const Eigen::Vector3d u = (b - a).normalized();
    const Eigen::Vector3d v = (normal / twice_area).cross(u);
    charts.axis_u.row(t) = u.transpose();
    charts.axis_v.row(t) = v.transpose();
    charts.corners(t, 2) = (b - a).norm();
    charts.corners(t, 4) = (c - a).dot(u);
    charts.corners(t, 5) = (c - a).dot(v);
    charts.area[t] = 0.5 * twice_area;
  }
  return charts;
}

const VertexAdjacency& TriangleNeighbours::get() const {
  if (!adjacency_) {
    adjacency_.emplace();
    triangle_adjacency(patch_->mesh.F, patch_->mesh.num_vertices(), adjacency_->offsets, adjacency_->neighbors);
  }
  return *adjacency_;
}

}  // namespace aniso
