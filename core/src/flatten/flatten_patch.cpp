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

std::vector<int> selected_faces(const Mesh& mesh, const std::vector<char>& vertex_mask) {
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
  return faces;
}

double triangle_area(const Mesh& mesh, int t) {
  const Eigen::Vector3d a = mesh.V.row(mesh.F(t, 0));
  const Eigen::Vector3d b = mesh.V.row(mesh.F(t, 1));
  const Eigen::Vector3d c = mesh.V.row(mesh.F(t, 2));
  const double twice = (b - a).cross(c - a).norm();
  return std::isfinite(twice) ? 0.5 * twice : 0.0;
}

std::string edge_and_faces(const NonManifoldEdgeFaces& edge, const std::vector<int>& input_face) {
  std::string faces;
  for (std::size_t k = 0; k < edge.faces.size(); ++k) {
    faces += (k > 0 ? ", " : "") + std::to_string(input_face[edge.faces[k]]);
  }
  return "edge (" + std::to_string(edge.lo) + ", " + std::to_string(edge.hi) + ") is shared by " +
         std::to_string(edge.faces.size()) + " faces (" + faces + ")";
}

// No piece of fabric holds an edge shared by three or more faces. Where the
// faces off such an edge are a fin (a sheet of faces joined to the rest only
// across such edges, kMaxFinAreaShare of the patch or less: a modelling
// slip, not a part of the garment), they are left out and named
// (FlattenPatch::dropped_faces): flattened with the rest, a fin triangle came
// out as a second closed outline inside the piece, a cut line no one asked
// for. Any other such edge is refused, naming it and its faces.
void drop_fins(const Mesh& mesh, std::vector<int>& faces, std::vector<int>& dropped) {
  Mesh selected;
  selected.V = mesh.V;
  selected.F.resize(static_cast<int>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) selected.F.row(static_cast<int>(f)) = mesh.F.row(faces[f]);
  const std::vector<NonManifoldEdgeFaces> edges = non_manifold_edge_faces(selected);
  if (edges.empty()) return;
  int sheets = 0;
  const std::vector<int> sheet = face_sheets(selected, &sheets);
  std::vector<double> sheet_area(static_cast<std::size_t>(sheets), 0.0);
  double total_area = 0.0;
  for (int f = 0; f < selected.num_triangles(); ++f) {
    const double area = triangle_area(selected, f);
    sheet_area[sheet[f]] += area;
    total_area += area;
  }
  // At each edge the largest sheet stays; the others go if they are small.
  std::vector<char> drop_sheet(static_cast<std::size_t>(sheets), 0);
  for (const NonManifoldEdgeFaces& edge : edges) {
    int kept = sheet[edge.faces.front()];
    for (const int f : edge.faces) {
      if (sheet_area[sheet[f]] > sheet_area[kept]) kept = sheet[f];
    }
    for (const int f : edge.faces) {
      if (sheet[f] != kept && sheet_area[sheet[f]] <= kMaxFinAreaShare * total_area) drop_sheet[sheet[f]] = 1;
    }
  }
  std::vector<int> kept_faces;
  for (int f = 0; f < selected.num_triangles(); ++f) {
    (drop_sheet[sheet[f]] ? dropped : kept_faces).push_back(faces[f]);
  }
  Mesh rest;
  rest.V = std::move(selected.V);
  rest.F.resize(static_cast<int>(kept_faces.size()), 3);
  for (std::size_t f = 0; f < kept_faces.size(); ++f) rest.F.row(static_cast<int>(f)) = mesh.F.row(kept_faces[f]);
  const std::vector<NonManifoldEdgeFaces> left = non_manifold_edge_faces(rest);
  if (!left.empty()) {
    fail(ErrorCode::BadMesh,
         "the patch cannot be laid flat as one piece: " + edge_and_faces(left.front(), kept_faces) +
             (left.size() > 1 ? " (and " + std::to_string(left.size() - 1) + " more such edge(s))" : "") +
             ", and no flat piece can hold an edge shared by three or more faces; the faces off it are more than "
             "a fin: select the faces on one side of it and flatten them apart");
  }
  faces = std::move(kept_faces);
}

// Compacts the faces: only vertices some face uses are kept, so unreferenced
// vertices of the input (scans have them) never reach a solve.
void compact_faces(const Mesh& mesh, std::vector<int> faces, FlattenPatch& patch) {
  std::vector<int> input_to_patch(mesh.num_vertices(), -1);
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
  std::vector<int> faces = selected_faces(mesh, vertex_mask);
  drop_fins(mesh, faces, patch.dropped_faces);
  compact_faces(mesh, std::move(faces), patch);
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
    // Left out, a fin's edges are no boundary: say so, or its faces' (the
    // only ones `info` counts as a boundary) would make the refusal a riddle.
    std::string fins;
    if (!patch.dropped_faces.empty()) {
      fins = " (" + std::to_string(patch.dropped_faces.size()) +
             " face(s) hanging off edges shared by three or more faces were left out: face " +
             std::to_string(patch.dropped_faces.front()) + (patch.dropped_faces.size() > 1 ? " ..." : "") + ")";
    }
    fail(ErrorCode::BadMesh,
         "the patch is closed: flattening needs a boundary; select a part of the mesh" + where + fins);
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
