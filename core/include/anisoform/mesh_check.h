// Checking a mesh before it is solved on, and the repairs we offer.
//
// check_mesh names every problem with its element (vertex or face index,
// 0-based in messages as "vertex 5" / "face 20"), and counts what `info` reports.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "anisoform/mesh.h"

namespace aniso {

enum class ProblemKind {
  EmptyMesh,                // no vertices or no triangles
  NonFiniteCoordinate,      // element = vertex
  CoordinateOutOfRange,     // element = vertex: |coordinate| > limits.h kMaxCoordinate
  IndexOutOfRange,          // element = face (only for meshes built in memory)
  RepeatedCorner,           // element = face: a face uses one vertex twice
  ZeroAreaTriangle,         // element = face
  DuplicateFace,            // element = face (the later of the two)
  NonManifoldEdge,          // element = one face on the edge; message names the edge
  NonManifoldVertex,        // element = vertex (its faces form more than one fan)
  InconsistentOrientation,  // element = face whose winding disagrees with a neighbour
  UnreferencedVertex,       // element = vertex used by no face (a warning)
};
const char* problem_kind_name(ProblemKind kind);
constexpr int kProblemKinds = static_cast<int>(ProblemKind::UnreferencedVertex) + 1;
// Of each kind, the problems with the lowest elements kept with their
// message; all are counted (MeshReport::problem_counts).
constexpr std::size_t kMaxProblemsKept = 1000;

struct Problem {
  ProblemKind kind;
  int element;          // vertex or face index as documented per kind
  std::string message;  // plain words, names the element
};

struct MeshReport {
  int vertices = 0;
  int triangles = 0;
  int components = 0;      // face-connected components
  int boundary_loops = 0;
  bool edge_manifold = true;
  bool vertex_manifold = true;
  bool consistently_oriented = true;
  int degenerate_triangles = 0;   // zero-area (collinear or repeated corners)
  int duplicate_faces = 0;
  int non_manifold_edges = 0;
  int inconsistent_edges = 0;     // interior edges its two faces use in the same direction
  int non_manifold_vertices = 0;
  int non_finite_vertices = 0;
  int unreferenced_vertices = 0;
  BoundingBox bbox;               // shape_bounding_box: finite vertices a face references
  // In element order per kind: the first kMaxProblemsKept of each kind (the
  // counts above and problem_counts say how many there are).
  std::vector<Problem> problems;
  std::array<int, kProblemKinds> problem_counts{};  // every problem, by kind (index: ProblemKind)
  int problem_count() const;
  int count_of(ProblemKind kind) const { return problem_counts[static_cast<int>(kind)]; }

  // No problem that makes solving impossible: not empty, all coordinates finite
  // and within limits.h kMaxCoordinate, all indices in range. (Zero-area triangles, non-manifold elements and flipped
  // faces are solved through, with the clamped weights of laplacian.h.)
  bool solvable() const;
  // The blocking problems in plain words on one line, joined by "; " (at
  // most `max_lines` of them, then "... and N more"): it goes into error
  // messages, which the CLI prints and the browser shows as one line each.
  std::string blocking_summary(int max_lines = 5) const;
};

MeshReport check_mesh(const Mesh& mesh);

// Why a vertex at p cannot be solved on, to follow "vertex 5 ": "has a
// non-finite coordinate (...)" or "has a coordinate out of range (...): ..."
// (limits.h kMaxCoordinate); empty when it can.
std::string coordinate_problem(const Eigen::RowVector3d& p);

// Throws Error(BadMesh) with blocking_summary() unless the mesh is solvable.
void require_solvable(const Mesh& mesh);

// The faces to turn over (two corners swapped) so that every group of faces
// joined across edges with two faces is wound one way: the way most of its
// faces are wound (the others are the faces check_mesh reports as
// InconsistentOrientation; a tie keeps the winding of the group's lowest
// face). When a group cannot be wound one way at all (it is non-orientable,
// a Moebius strip), non_orientable_face names a face where it fails and
// faces_to_turn is empty.
struct WindingRepair {
  std::vector<int> faces_to_turn;  // ascending
  int non_orientable_face = -1;
};
WindingRepair majority_winding(const Mesh& mesh);

// Every edge shared by three or more faces (check_mesh's NonManifoldEdge),
// with all its faces, ascending; edges ordered by (lo, hi).
struct NonManifoldEdgeFaces {
  int lo = 0, hi = 0;  // the edge's vertices, lo < hi
  std::vector<int> faces;
};
std::vector<NonManifoldEdgeFaces> non_manifold_edge_faces(const Mesh& mesh);

// Per face, its sheet (0 .. *count - 1): the faces joined to it across
// edges with exactly two faces, as one piece of fabric could hold them; an
// edge shared by three or more faces (or one) joins none.
std::vector<int> face_sheets(const Mesh& mesh, int* count = nullptr);

// Merges vertices whose positions are equal (tolerance 0: exactly equal;
// otherwise within `tolerance` in every coordinate). Faces that collapse
// (a corner repeated) are dropped. `old_to_new` (#V of the input) if not null.
Mesh weld_vertices(const Mesh& mesh, double tolerance = 0.0,
                   std::vector<int>* old_to_new = nullptr);

// true when no two faces share a vertex and there is more than one face:
// an STL-style soup that welding should repair.
bool is_triangle_soup(const Mesh& mesh);

// A triangle soup (is_triangle_soup) welded by exact position, with a note
// saying so ("the file is a triangle soup (no shared vertices): welded by
// exact position, 4962 -> 829 vertices"); any other mesh is left as it is.
// Returns whether it welded. The one rule: the Session welds every mesh it
// adopts so (the CLI's deform and replay, the browser), and `anisoform info`
// reports the mesh so welded (it reported the soup's 4962 vertices and 1654
// components while deform edited 829 vertices in one piece).
bool weld_if_triangle_soup(Mesh& mesh, std::vector<std::string>& notes);

// Triangulates one polygon (corner indices into V, in order) by ear clipping in
// its best-fit plane (Newell normal); works for concave polygons and for
// polygons with a doubled bridge edge. Returns #corners-2 triangles keeping the
// polygon's winding. Throws Error(BadFile) if the polygon has < 3 corners.
std::vector<std::array<int, 3>> triangulate_polygon(const Positions& V,
                                                    const std::vector<int>& polygon);

}  // namespace aniso
