// check_mesh: every problem of a mesh named with its element, and the counts
// `info` reports; the repairs offered for what readers cannot fix (welding).
//
// Edge-based checks work on "edge uses": the sides of in-range faces between
// two distinct vertices, grouped by their unordered vertex pair. A face with a
// repeated corner (a, a, b) thus uses edge {a, b} twice, as the MANIFEST
// counts it; a zero-length side (a, a) is no edge.
#include "anisoform/mesh_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <type_traits>
#include <utility>

#include <Eigen/Geometry>

#include "anisoform/error.h"
#include "anisoform/limits.h"
#include "mesh/topology.h"

namespace aniso {

namespace {

// ---------------------------------------------------------------- elements

bool has_repeated_corner(const Triangles& F, Eigen::Index f) {
  return F(f, 0) == F(f, 1) || F(f, 1) == F(f, 2) || F(f, 2) == F(f, 0);
}

bool is_finite_vertex(const Positions& V, Eigen::Index v) { return V.row(v).allFinite(); }

std::string number_text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

std::string corners_text(const Triangles& F, Eigen::Index f) {
  return "(" + std::to_string(F(f, 0)) + ", " + std::to_string(F(f, 1)) + ", " +
         std::to_string(F(f, 2)) + ")";
}

// Problems collected per kind, reported kind by kind in element order: all
// counted, the first kMaxProblemsKept of each kind (by element) kept with
// their message. A message is built only for a problem that is kept (when
// `message` is callable, it is called then): 12.5M unused vertices built
// 12.5M strings, of which `info` printed 100 (78 s and 2.1 GB).
class ProblemList {
 public:
  template <typename Message>
  void add(ProblemKind kind, int element, Message&& message) {
    Kind& kept = by_kind_[static_cast<int>(kind)];
    ++kept.count;
    const long long order = added_++;
    if (kept.problems.size() == kMaxProblemsKept) {
      // The heap's top is the last of the kept; equal elements keep the order they came in.
      if (element >= kept.problems.front().problem.element) return;
      std::pop_heap(kept.problems.begin(), kept.problems.end(), earlier);
      kept.problems.pop_back();
    }
    std::string text;
    if constexpr (std::is_invocable_v<Message>) {
      text = message();
    } else {
      text = std::forward<Message>(message);
    }
    kept.problems.push_back({Problem{kind, element, std::move(text)}, order});
    std::push_heap(kept.problems.begin(), kept.problems.end(), earlier);
  }
  std::vector<Problem> in_order() {
    std::vector<Problem> all;
    for (Kind& kind : by_kind_) {
      std::sort(kind.problems.begin(), kind.problems.end(), earlier);
      for (Kept& kept : kind.problems) all.push_back(std::move(kept.problem));
    }
    return all;
  }
  std::array<int, kProblemKinds> counts() const {
    std::array<int, kProblemKinds> counts{};
    for (int k = 0; k < kProblemKinds; ++k) counts[k] = by_kind_[k].count;
    return counts;
  }

 private:
  struct Kept {
    Problem problem;
    long long order;
  };
  struct Kind {
    std::vector<Kept> problems;  // a max-heap on (element, order) while collecting
    int count = 0;
  };
  static bool earlier(const Kept& a, const Kept& b) {
    return a.problem.element != b.problem.element ? a.problem.element < b.problem.element : a.order < b.order;
  }
  Kind by_kind_[kProblemKinds];
  long long added_ = 0;
};

bool is_blocking(ProblemKind kind) {
  return kind == ProblemKind::EmptyMesh || kind == ProblemKind::NonFiniteCoordinate ||
         kind == ProblemKind::CoordinateOutOfRange ||
         kind == ProblemKind::IndexOutOfRange;
}

// The problems that make solving impossible; cheap enough for require_solvable.
void find_blocking_problems(const Mesh& mesh, ProblemList& problems) {
  const int num_vertices = mesh.num_vertices();
  if (num_vertices == 0) problems.add(ProblemKind::EmptyMesh, -1, "the mesh has no vertices");
  if (mesh.num_triangles() == 0) problems.add(ProblemKind::EmptyMesh, -1, "the mesh has no triangles");
  for (int v = 0; v < num_vertices; ++v) {
    const std::string problem = coordinate_problem(mesh.V.row(v));
    if (problem.empty()) continue;
    problems.add(is_finite_vertex(mesh.V, v) ? ProblemKind::CoordinateOutOfRange : ProblemKind::NonFiniteCoordinate,
                 v, [&] { return "vertex " + std::to_string(v) + " " + problem; });
  }
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    if (face_in_range(mesh.F, f, num_vertices)) continue;
    problems.add(ProblemKind::IndexOutOfRange, f,
                 "face " + std::to_string(f) + " " + corners_text(mesh.F, f) +
                     " references a vertex that does not exist (the mesh has " +
                     std::to_string(num_vertices) + " vertices)");
  }
}

// Repeated corners, zero areas, unreferenced vertices (faces in range only).
void check_faces(const Mesh& mesh, MeshReport& report, ProblemList& problems) {
  const int num_vertices = mesh.num_vertices();
  std::vector<char> referenced(static_cast<std::size_t>(num_vertices), 0);
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    if (!face_in_range(mesh.F, f, num_vertices)) continue;
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    referenced[a] = referenced[b] = referenced[c] = 1;
    if (has_repeated_corner(mesh.F, f)) {
      ++report.degenerate_triangles;
      problems.add(ProblemKind::RepeatedCorner, f, [&] {
        return "face " + std::to_string(f) + " " + corners_text(mesh.F, f) + " uses a vertex twice (it has no area)";
      });
      continue;
    }
    if (!is_finite_vertex(mesh.V, a) || !is_finite_vertex(mesh.V, b) || !is_finite_vertex(mesh.V, c)) {
      continue;  // no area to speak of; the vertex is reported
    }
    Eigen::RowVector3d ab = mesh.V.row(b) - mesh.V.row(a);
    Eigen::RowVector3d ac = mesh.V.row(c) - mesh.V.row(a);
    Eigen::RowVector3d bc = mesh.V.row(c) - mesh.V.row(b);
    // Relative to the face's own size, so the test does not depend on units:
    // the sides divided by their largest coordinate first (the squares and
    // the cross product of a face 1e-160 across underflowed to 0, and Spot
    // in units of 1e-200 had 9024 "zero-area" faces; above 1e154 they overflow).
    const double largest = std::max({ab.cwiseAbs().maxCoeff(), ac.cwiseAbs().maxCoeff(), bc.cwiseAbs().maxCoeff()});
    if (largest > 0.0) {
      ab /= largest;
      ac /= largest;
      bc /= largest;
    }
    const double longest_squared = std::max({ab.squaredNorm(), ac.squaredNorm(), bc.squaredNorm()});
    if (largest == 0.0 || ab.cross(ac).norm() <= 1e-12 * longest_squared) {
      ++report.degenerate_triangles;
      problems.add(ProblemKind::ZeroAreaTriangle, f, [&] {
        return "face " + std::to_string(f) + " " + corners_text(mesh.F, f) +
               " has zero area (its corners are collinear or coincide)";
      });
    }
  }
  for (int v = 0; v < num_vertices; ++v) {
    if (referenced[v]) continue;
    ++report.unreferenced_vertices;
    problems.add(ProblemKind::UnreferencedVertex, v,
                 [v] { return "vertex " + std::to_string(v) + " is used by no face (it is ignored)"; });
  }
}

// Faces in range, bucketed by a vertex: faces_at(v) lists v's faces once each.
class VertexFaces {
 public:
  explicit VertexFaces(const Mesh& mesh) : start_(static_cast<std::size_t>(mesh.num_vertices()) + 1, 0) {
    auto for_each_corner = [&](auto&& visit) {
      for (int f = 0; f < mesh.num_triangles(); ++f) {
        if (!face_in_range(mesh.F, f, mesh.num_vertices())) continue;
        const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
        visit(a, f);
        if (b != a) visit(b, f);
        if (c != a && c != b) visit(c, f);
      }
    };
    for_each_corner([&](int v, int) { ++start_[v + 1]; });
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    faces_.resize(static_cast<std::size_t>(start_.back()));
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for_each_corner([&](int v, int f) { faces_[fill[v]++] = f; });
  }
  const int* begin(int v) const { return faces_.data() + start_[v]; }
  const int* end(int v) const { return faces_.data() + start_[v + 1]; }

 private:
  std::vector<int> start_;
  std::vector<int> faces_;
};

// Duplicates share their smallest vertex: compare faces within its bucket.
void check_duplicate_faces(const Mesh& mesh, const VertexFaces& vertex_faces, MeshReport& report,
                           ProblemList& problems) {
  struct Key {
    int middle, largest, face;
  };
  std::vector<Key> keys;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    keys.clear();
    for (const int* f = vertex_faces.begin(v); f != vertex_faces.end(v); ++f) {
      std::array<int, 3> corners = {mesh.F(*f, 0), mesh.F(*f, 1), mesh.F(*f, 2)};
      std::sort(corners.begin(), corners.end());
      if (corners[0] == v) keys.push_back({corners[1], corners[2], *f});
    }
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
      return a.middle != b.middle ? a.middle < b.middle : a.largest != b.largest ? a.largest < b.largest : a.face < b.face;
    });
    for (std::size_t first = 0, i = 1; i < keys.size(); ++i) {
      if (keys[i].middle != keys[first].middle || keys[i].largest != keys[first].largest) {
        first = i;
        continue;
      }
      ++report.duplicate_faces;
      problems.add(ProblemKind::DuplicateFace, keys[i].face, [&] {
        return "face " + std::to_string(keys[i].face) + " uses the same vertices as face " +
               std::to_string(keys[first].face);
      });
    }
  }
}

// A vertex is manifold when its faces form one fan. Two faces of a vertex v
// that share another vertex w share the edge (v, w): so the fans are the
// groups of v's faces joined through their other vertices.
void check_vertex_fans(const Mesh& mesh, const VertexFaces& vertex_faces, MeshReport& report,
                       ProblemList& problems) {
  struct Spoke {
    int other;  // a vertex of the face other than the centre
    int face;   // local index of the face around the centre
  };
  std::vector<Spoke> spokes;
  std::vector<int> fan_of;  // union-find over the centre's faces
  auto find = [&](int i) {
    while (fan_of[i] != i) i = fan_of[i] = fan_of[fan_of[i]];
    return i;
  };
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const int count = static_cast<int>(vertex_faces.end(v) - vertex_faces.begin(v));
    if (count <= 1) continue;
    spokes.clear();
    for (int local = 0; local < count; ++local) {
      const int f = vertex_faces.begin(v)[local];
      for (int k = 0; k < 3; ++k) {
        if (mesh.F(f, k) != v) spokes.push_back({mesh.F(f, k), local});
      }
    }
    std::sort(spokes.begin(), spokes.end(), [](const Spoke& a, const Spoke& b) { return a.other < b.other; });
    fan_of.resize(static_cast<std::size_t>(count));
    std::iota(fan_of.begin(), fan_of.end(), 0);
    int fans = count;
    for (std::size_t i = 1; i < spokes.size(); ++i) {
      if (spokes[i].other != spokes[i - 1].other) continue;
      const int a = find(spokes[i].face), b = find(spokes[i - 1].face);
      if (a == b) continue;
      fan_of[a] = b;
      --fans;
    }
    if (fans <= 1) continue;
    ++report.non_manifold_vertices;
    problems.add(ProblemKind::NonManifoldVertex, v, [&] {
      return "vertex " + std::to_string(v) + " joins " + std::to_string(fans) +
             " separate fans of faces (the surface touches itself there)";
    });
  }
}

// ---------------------------------------------------------------- edges

struct EdgeUse {
  int lo, hi;    // the edge's vertices, lo < hi
  int face;
  bool forward;  // the face walks lo -> hi
};

// Every edge use, grouped by edge: sorted by (lo, hi, face). Counting sort by
// the smaller vertex, then a sort of each vertex's few uses.
std::vector<EdgeUse> edge_uses(const Mesh& mesh) {
  const int num_vertices = mesh.num_vertices();
  std::vector<int> start(static_cast<std::size_t>(num_vertices) + 1, 0);
  auto for_each_use = [&](auto&& visit) {
    for (int f = 0; f < mesh.num_triangles(); ++f) {
      if (!face_in_range(mesh.F, f, num_vertices)) continue;
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
        if (a != b) visit(EdgeUse{std::min(a, b), std::max(a, b), f, a < b});
      }
    }
  };
  for_each_use([&](const EdgeUse& use) { ++start[use.lo + 1]; });
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<EdgeUse> uses(static_cast<std::size_t>(start.back()));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for_each_use([&](const EdgeUse& use) { uses[fill[use.lo]++] = use; });
  for (int v = 0; v < num_vertices; ++v) {
    std::sort(uses.begin() + start[v], uses.begin() + start[v + 1], [](const EdgeUse& a, const EdgeUse& b) {
      return a.hi != b.hi ? a.hi < b.hi : a.face < b.face;
    });
  }
  return uses;
}

// Calls visit(begin, end) for each edge's run of uses.
template <class Visit>
void for_each_edge(const std::vector<EdgeUse>& uses, Visit&& visit) {
  for (std::size_t begin = 0; begin < uses.size();) {
    std::size_t end = begin + 1;
    while (end < uses.size() && uses[end].lo == uses[begin].lo && uses[end].hi == uses[begin].hi) ++end;
    visit(begin, end);
    begin = end;
  }
}

void check_non_manifold_edges(const std::vector<EdgeUse>& uses, MeshReport& report, ProblemList& problems) {
  for_each_edge(uses, [&](std::size_t begin, std::size_t end) {
    if (end - begin <= 2) return;
    ++report.non_manifold_edges;
    int last_face = 0;
    for (std::size_t u = begin; u < end; ++u) last_face = std::max(last_face, uses[u].face);
    problems.add(ProblemKind::NonManifoldEdge, last_face, [&] {
      std::string faces;
      for (std::size_t u = begin; u < end; ++u) faces += (u == begin ? "" : ", ") + std::to_string(uses[u].face);
      return "edge (" + std::to_string(uses[begin].lo) + ", " + std::to_string(uses[begin].hi) + ") is shared by " +
             std::to_string(end - begin) + " faces (" + faces + "); an edge may border at most 2";
    });
  });
}

// Faces joined across edges with exactly two uses, in groups (the faces a
// winding can be compared between). Within each group, every face's side (0:
// wound as the group's first face, 1: against it) and whether that side is
// the group's minority (the fewer faces; a tie: side 1). The one rule for
// which faces are "the flipped ones": check_mesh reports them, and
// majority_winding turns them over.
struct WindingGroups {
  std::vector<int> side;                      // per face
  std::vector<char> in_minority;              // per face
  std::vector<std::pair<int, int>> disagreeing_pairs;  // faces using their shared edge in the same direction
  std::vector<int> disagreeing_edges;         // per face: how many of its edges disagree
  int non_orientable_face = -1;  // the lowest face of a link no choice of sides satisfies (a Moebius strip)
};

WindingGroups winding_groups(int num_faces, const std::vector<EdgeUse>& uses) {
  WindingGroups groups;
  groups.side.assign(static_cast<std::size_t>(num_faces), 0);
  groups.in_minority.assign(static_cast<std::size_t>(num_faces), 0);
  groups.disagreeing_edges.assign(static_cast<std::size_t>(num_faces), 0);
  struct Link {
    int face, other;
    bool flips;  // the two faces use their shared edge in the same direction
  };
  std::vector<Link> links;  // both directions of every face pair across a 2-use edge
  for_each_edge(uses, [&](std::size_t begin, std::size_t end) {
    if (end - begin != 2 || uses[begin].face == uses[begin + 1].face) return;
    const EdgeUse& x = uses[begin];
    const EdgeUse& y = uses[begin + 1];
    const bool flips = x.forward == y.forward;
    if (flips) {
      ++groups.disagreeing_edges[x.face];
      ++groups.disagreeing_edges[y.face];
      groups.disagreeing_pairs.emplace_back(x.face, y.face);
    }
    links.push_back({x.face, y.face, flips});
    links.push_back({y.face, x.face, flips});
  });
  if (groups.disagreeing_pairs.empty()) return groups;  // the common case: no graph needed

  std::vector<int> start(static_cast<std::size_t>(num_faces) + 1, 0);
  for (const Link& link : links) ++start[link.face + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<Link> by_face(links.size());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const Link& link : links) by_face[fill[link.face]++] = link;

  std::vector<int>& side = groups.side;
  side.assign(static_cast<std::size_t>(num_faces), -1);
  std::vector<int> group;
  for (int seed = 0; seed < num_faces; ++seed) {
    if (side[seed] != -1) continue;
    group.assign(1, seed);
    side[seed] = 0;
    int flipped = 0;
    for (std::size_t i = 0; i < group.size(); ++i) {
      for (int l = start[group[i]]; l < start[group[i] + 1]; ++l) {
        const Link& link = by_face[l];
        if (side[link.other] != -1) continue;
        side[link.other] = side[group[i]] ^ static_cast<int>(link.flips);
        flipped += side[link.other];
        group.push_back(link.other);
      }
    }
    const int minority = 2 * flipped <= static_cast<int>(group.size()) ? 1 : 0;
    for (const int f : group) groups.in_minority[f] = side[f] == minority;
  }
  for (const Link& link : links) {
    if ((side[link.face] ^ side[link.other]) == static_cast<int>(link.flips)) continue;
    const int face = std::min(link.face, link.other);
    if (groups.non_orientable_face < 0 || face < groups.non_orientable_face) groups.non_orientable_face = face;
  }
  return groups;
}

// Within each group of faces so connected, the faces whose winding the fewer
// agree with are reported: for one flipped face that is the face, not its
// neighbours.
void check_orientation(const Mesh& mesh, const std::vector<EdgeUse>& uses, MeshReport& report,
                       ProblemList& problems) {
  const int num_faces = mesh.num_triangles();
  const WindingGroups groups = winding_groups(num_faces, uses);
  report.inconsistent_edges = static_cast<int>(groups.disagreeing_pairs.size());
  if (report.inconsistent_edges == 0) return;
  std::vector<char> reported = groups.in_minority;
  // A non-orientable group (a Moebius strip) can leave a disagreeing pair with
  // both faces on one side: report the later face.
  for (const auto& [f, g] : groups.disagreeing_pairs) {
    if (!reported[f] && !reported[g]) reported[std::max(f, g)] = 1;
  }
  for (int f = 0; f < num_faces; ++f) {
    if (!reported[f] || groups.disagreeing_edges[f] == 0) continue;
    problems.add(ProblemKind::InconsistentOrientation, f, [&] {
      return "face " + std::to_string(f) + " is wound opposite to its neighbours (across " +
             std::to_string(groups.disagreeing_edges[f]) + " of its edges)";
    });
  }
}

}  // namespace

// ---------------------------------------------------------------- public

std::string coordinate_problem(const Eigen::RowVector3d& p) {
  // Checked before anything is formatted: this runs for every vertex of
  // every mesh, and printing three numbers each time was a third of an
  // 800k-vertex load.
  const bool finite = p.allFinite();
  if (finite && p.cwiseAbs().maxCoeff() <= limits::kMaxCoordinate) return "";
  const std::string position =
      "(" + number_text(p[0]) + ", " + number_text(p[1]) + ", " + number_text(p[2]) + ")";
  if (!finite) return "has a non-finite coordinate " + position;
  return "has a coordinate out of range " + position + ": coordinates must be within +-" +
         number_text(limits::kMaxCoordinate) + " (rescale the mesh)";
}

const char* problem_kind_name(ProblemKind kind) {
  switch (kind) {
    case ProblemKind::EmptyMesh: return "empty-mesh";
    case ProblemKind::NonFiniteCoordinate: return "non-finite-coordinate";
    case ProblemKind::CoordinateOutOfRange: return "coordinate-out-of-range";
    case ProblemKind::IndexOutOfRange: return "index-out-of-range";
    case ProblemKind::RepeatedCorner: return "repeated-corner";
    case ProblemKind::ZeroAreaTriangle: return "zero-area-triangle";
    case ProblemKind::DuplicateFace: return "duplicate-face";
    case ProblemKind::NonManifoldEdge: return "non-manifold-edge";
    case ProblemKind::NonManifoldVertex: return "non-manifold-vertex";
    case ProblemKind::InconsistentOrientation: return "inconsistent-orientation";
    case ProblemKind::UnreferencedVertex: return "unreferenced-vertex";
  }
  return "unknown";
}

bool MeshReport::solvable() const {
  return std::none_of(problems.begin(), problems.end(),
                      [](const Problem& problem) { return is_blocking(problem.kind); });
}

std::string MeshReport::blocking_summary(int max_lines) const {
  std::string summary;
  int shown = 0;
  for (const Problem& problem : problems) {
    if (!is_blocking(problem.kind) || shown >= max_lines) continue;
    summary += (shown++ == 0 ? "" : "; ") + problem.message;
  }
  long long blocking = 0;
  for (int k = 0; k < kProblemKinds; ++k) {
    if (is_blocking(static_cast<ProblemKind>(k))) blocking += problem_counts[k];
  }
  const long long more = blocking - shown;
  if (more > 0) summary += "; ... and " + std::to_string(more) + " more";
  return summary;
}

int MeshReport::problem_count() const {
  int total = 0;
  for (const int count : problem_counts) total += count;
  return total;
}

MeshReport check_mesh(const Mesh& mesh) {
  MeshReport report;
  report.vertices = mesh.num_vertices();
  report.triangles = mesh.num_triangles();
  ProblemList problems;
  find_blocking_problems(mesh, problems);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (!is_finite_vertex(mesh.V, v)) ++report.non_finite_vertices;
  }
  report.bbox = shape_bounding_box(mesh);
  check_faces(mesh, report, problems);
  const VertexFaces vertex_faces(mesh);
  check_duplicate_faces(mesh, vertex_faces, report, problems);
  check_vertex_fans(mesh, vertex_faces, report, problems);

  const std::vector<EdgeUse> uses = edge_uses(mesh);
  check_non_manifold_edges(uses, report, problems);
  check_orientation(mesh, uses, report, problems);
  report.edge_manifold = report.non_manifold_edges == 0;
  report.vertex_manifold = report.non_manifold_vertices == 0;
  report.consistently_oriented = report.inconsistent_edges == 0;
  report.components = count_face_components(mesh.F, mesh.num_vertices());
  report.boundary_loops = static_cast<int>(boundary_loops(mesh.F, mesh.num_vertices()).size());
  report.problems = problems.in_order();
  report.problem_counts = problems.counts();
  return report;
}

void require_solvable(const Mesh& mesh) {
  ProblemList problems;
  find_blocking_problems(mesh, problems);
  MeshReport report;
  report.problems = problems.in_order();
  report.problem_counts = problems.counts();
  if (!report.solvable()) fail(ErrorCode::BadMesh, "the mesh cannot be solved on: " + report.blocking_summary());
}

WindingRepair majority_winding(const Mesh& mesh) {
  WindingRepair repair;
  const WindingGroups groups = winding_groups(mesh.num_triangles(), edge_uses(mesh));
  if (groups.disagreeing_pairs.empty()) return repair;
  if (groups.non_orientable_face >= 0) {
    repair.non_orientable_face = groups.non_orientable_face;
    return repair;
  }
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    if (groups.in_minority[f]) repair.faces_to_turn.push_back(f);
  }
  return repair;
}

std::vector<int> face_sheets(const Mesh& mesh, int* count) {
  const int num_faces = mesh.num_triangles();
  std::vector<int> parent(static_cast<std::size_t>(num_faces));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  const std::vector<EdgeUse> uses = edge_uses(mesh);
  for_each_edge(uses, [&](std::size_t begin, std::size_t end) {
    if (end - begin != 2) return;
    const int a = root(uses[begin].face), b = root(uses[begin + 1].face);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  });
  std::vector<int> sheet(static_cast<std::size_t>(num_faces), -1);
  int sheets = 0;
  for (int f = 0; f < num_faces; ++f) {
    const int r = root(f);
    if (sheet[r] < 0) sheet[r] = sheets++;
    sheet[f] = sheet[r];
  }
  if (count) *count = sheets;
  return sheet;
}

std::vector<NonManifoldEdgeFaces> non_manifold_edge_faces(const Mesh& mesh) {
  std::vector<NonManifoldEdgeFaces> edges;
  const std::vector<EdgeUse> uses = edge_uses(mesh);
  for_each_edge(uses, [&](std::size_t begin, std::size_t end) {
    if (end - begin <= 2) return;
    NonManifoldEdgeFaces edge{uses[begin].lo, uses[begin].hi, {}};
    for (std::size_t u = begin; u < end; ++u) edge.faces.push_back(uses[u].face);
    edges.push_back(std::move(edge));
  });
  return edges;
}

// ---------------------------------------------------------------- repairs

namespace {

// For each vertex, the lowest-index vertex at exactly its position.
std::vector<int> exact_representatives(const Positions& V) {
  const int n = static_cast<int>(V.rows());
  std::vector<int> representative(static_cast<std::size_t>(n));
  std::iota(representative.begin(), representative.end(), 0);
  std::vector<int> order;
  order.reserve(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) {
    if (is_finite_vertex(V, v)) order.push_back(v);  // NaN breaks sorting, and equals nothing
  }
  auto less = [&](int a, int b) {
    for (int k = 0; k < 3; ++k) {
      if (V(a, k) != V(b, k)) return V(a, k) < V(b, k);
    }
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t i = 1; i < order.size(); ++i) {
    const int previous = order[i - 1], current = order[i];
    if (V.row(previous) == V.row(current)) representative[current] = representative[previous];
  }
  return representative;
}

// For each vertex, the lowest-index earlier representative within `tolerance`
// in every coordinate, found through a grid of tolerance-sized cells.
std::vector<int> tolerance_representatives(const Positions& V, double tolerance) {
  const int n = static_cast<int>(V.rows());
  using Cell = std::array<long long, 3>;
  auto cell_of = [&](int v) {
    Cell cell;
    for (int k = 0; k < 3; ++k) {
      // Clamped: far-out coordinates share edge cells, which costs time, not correctness.
      const double scaled = std::floor(V(v, k) / tolerance);
      cell[k] = static_cast<long long>(std::clamp(scaled, -1e18, 1e18));
    }
    return cell;
  };
  std::vector<std::pair<Cell, int>> cells;
  cells.reserve(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) {
    if (is_finite_vertex(V, v)) cells.emplace_back(cell_of(v), v);
  }
  std::sort(cells.begin(), cells.end());

  std::vector<int> representative(static_cast<std::size_t>(n));
  std::iota(representative.begin(), representative.end(), 0);
  for (int v = 0; v < n; ++v) {
    if (!is_finite_vertex(V, v)) continue;
    const Cell home = cell_of(v);
    int best = v;
    for (long long dx = -1; dx <= 1; ++dx) {
      for (long long dy = -1; dy <= 1; ++dy) {
        for (long long dz = -1; dz <= 1; ++dz) {
          const Cell near = {home[0] + dx, home[1] + dy, home[2] + dz};
          auto it = std::lower_bound(cells.begin(), cells.end(), std::make_pair(near, 0));
          for (; it != cells.end() && it->first == near && it->second < best; ++it) {
            const int u = it->second;
            if (representative[u] == u && (V.row(u) - V.row(v)).cwiseAbs().maxCoeff() <= tolerance) best = u;
          }
        }
      }
    }
    representative[v] = best;
  }
  return representative;
}

}  // namespace

Mesh weld_vertices(const Mesh& mesh, double tolerance, std::vector<int>* old_to_new) {
  if (!(tolerance >= 0) || !std::isfinite(tolerance)) {
    fail(ErrorCode::BadParameter, "weld tolerance must be a finite number >= 0, got " + number_text(tolerance));
  }
  const int n = mesh.num_vertices();
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    if (!face_in_range(mesh.F, f, n)) {
      fail(ErrorCode::BadMesh, "cannot weld: face " + std::to_string(f) + " " + corners_text(mesh.F, f) +
                                   " references a vertex that does not exist (the mesh has " +
                                   std::to_string(n) + " vertices)");
    }
  }
  const std::vector<int> representative =
      tolerance == 0 ? exact_representatives(mesh.V) : tolerance_representatives(mesh.V, tolerance);

  // Kept vertices are numbered in their original order.
  std::vector<int> map(static_cast<std::size_t>(n));
  int kept = 0;
  for (int v = 0; v < n; ++v) map[v] = representative[v] == v ? kept++ : map[representative[v]];

  Mesh welded;
  welded.V.resize(kept, 3);
  for (int v = 0; v < n; ++v) {
    if (representative[v] == v) welded.V.row(map[v]) = mesh.V.row(v);
  }
  welded.F.resize(mesh.num_triangles(), 3);
  int faces = 0;
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const int a = map[mesh.F(f, 0)], b = map[mesh.F(f, 1)], c = map[mesh.F(f, 2)];
    if (a == b || b == c || c == a) continue;  // collapsed by welding
    welded.F.row(faces++) << a, b, c;
  }
  welded.F.conservativeResize(faces, 3);
  if (old_to_new) *old_to_new = std::move(map);
  return welded;
}

bool weld_if_triangle_soup(Mesh& mesh, std::vector<std::string>& notes) {
  if (!is_triangle_soup(mesh)) return false;
  const int before = mesh.num_vertices();
  mesh = weld_vertices(mesh);
  notes.push_back("the file is a triangle soup (no shared vertices): welded by exact position, " +
                  std::to_string(before) + " -> " + std::to_string(mesh.num_vertices()) + " vertices");
  return true;
}

bool is_triangle_soup(const Mesh& mesh) {
  if (mesh.num_triangles() <= 1) return false;
  std::vector<int> owner(static_cast<std::size_t>(mesh.num_vertices()), -1);
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(f, k);
      if (v < 0 || v >= mesh.num_vertices()) continue;
      if (owner[v] != -1 && owner[v] != f) return false;
      owner[v] = f;
    }
  }
  return true;
}

}  // namespace aniso
