// Connectivity queries: components, boundary loops, boundary masks and vertex
// adjacency, checked against the MANIFEST and against their definitions.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "mesh/topology.h"
#include "test_support.h"

using aniso::Mesh;
using aniso::Triangles;
using aniso::test::load;

namespace {

using Edge = std::pair<int, int>;

// Directed boundary half-edges by definition: sides of edges that exactly
// one face side uses.
std::set<Edge> boundary_half_edges(const Triangles& F) {
  std::map<Edge, int> uses;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a != b) ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::set<Edge> boundary;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a != b && uses[{std::min(a, b), std::max(a, b)}] == 1) boundary.insert({a, b});
    }
  }
  return boundary;
}

// The half-edges the loops walk. A loop closes back to its start through a
// boundary half-edge; an open chain (where the boundary runs into a
// non-manifold or inconsistently oriented edge) does not.
std::multiset<Edge> walked_half_edges(const std::vector<std::vector<int>>& loops, const std::set<Edge>& boundary) {
  std::multiset<Edge> walked;
  for (const auto& loop : loops) {
    for (std::size_t i = 0; i + 1 < loop.size(); ++i) walked.insert({loop[i], loop[i + 1]});
    if (boundary.count({loop.back(), loop.front()})) walked.insert({loop.back(), loop.front()});
  }
  return walked;
}

Triangles triangles(std::vector<Eigen::RowVector3i> rows) {
  Triangles F(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) F.row(i) = rows[i];
  return F;
}

}  // namespace

TEST_CASE("topology: boundary loops walk every boundary half-edge once, as many loops as the MANIFEST says", "[topology]") {
  const std::pair<const char*, int> meshes[] = {
      {"open/stanford-bunny.obj", 5},
      {"open/human_woman_torso_front_patch.obj", 1},
      {"open/hemisphere.obj", 1},
      {"open/cube_no_bottom.obj", 1},
      {"formats/concave_polygon.obj", 2},
      {"malformed/bad_nonmanifold_edge.obj", 1},  // an open chain along the fin
      {"closed/torus.obj", 0},
  };
  for (const auto& [file, expected] : meshes) {
    INFO(file);
    const Mesh mesh = load(file);
    const auto loops = aniso::boundary_loops(mesh.F, mesh.num_vertices());
    CHECK(loops.size() == static_cast<std::size_t>(expected));
    const std::set<Edge> boundary = boundary_half_edges(mesh.F);
    const std::multiset<Edge> walked = walked_half_edges(loops, boundary);
    CHECK(walked.size() == boundary.size());
    CHECK(std::set<Edge>(walked.begin(), walked.end()) == boundary);

    const std::vector<char> mask = aniso::boundary_vertex_mask(mesh.F, mesh.num_vertices());
    std::vector<char> on_loops(static_cast<std::size_t>(mesh.num_vertices()), 0);
    for (const auto& loop : loops) {
      for (int v : loop) on_loops[v] = 1;
    }
    CHECK(mask == on_loops);
  }
}

TEST_CASE("topology: the walk ends at pinched and inconsistently oriented boundaries", "[topology]") {
  SECTION("two triangles touching at one vertex: every boundary edge in exactly one loop") {
    const Triangles F = triangles({{0, 1, 2}, {0, 3, 4}});
    const auto loops = aniso::boundary_loops(F, 5);
    const std::set<Edge> boundary = boundary_half_edges(F);
    const std::multiset<Edge> walked = walked_half_edges(loops, boundary);
    CHECK(walked.size() == 6);
    CHECK(std::set<Edge>(walked.begin(), walked.end()) == boundary);
  }
  SECTION("a flipped neighbour: the loops are open chains, each edge still walked once") {
    const Triangles F = triangles({{0, 1, 2}, {1, 2, 3}});  // edge 1-2 used twice in the same direction
    const auto loops = aniso::boundary_loops(F, 4);
    std::size_t edges = 0;
    for (const auto& loop : loops) edges += loop.size() - 1;  // open chains: one edge fewer than vertices
    CHECK(edges <= 4);
    CHECK_FALSE(loops.empty());
  }
  SECTION("faces with an index out of range are left out, not crashed on") {
    const Triangles F = triangles({{0, 1, 2}, {0, 2, 9}, {-1, 0, 1}});
    CHECK(aniso::boundary_loops(F, 3).size() == 1);
    CHECK(aniso::count_face_components(F, 3) == 1);
    CHECK(aniso::vertex_adjacency(F, 3).neighbors.size() == 6);
  }
}

TEST_CASE("topology: components count faces joined through shared vertices, and unreferenced vertices stand alone", "[topology]") {
  const Mesh two = load("malformed/multi_component.obj");
  CHECK(aniso::count_face_components(two.F, two.num_vertices()) == 2);
  int count = 0;
  const std::vector<int> labels = aniso::vertex_components(two.F, two.num_vertices(), &count);
  CHECK(count == 2);
  CHECK(labels.front() == 0);
  CHECK(std::set<int>(labels.begin(), labels.end()) == std::set<int>{0, 1});
  for (Eigen::Index f = 0; f < two.F.rows(); ++f) {
    CHECK(labels[two.F(f, 0)] == labels[two.F(f, 1)]);
    CHECK(labels[two.F(f, 1)] == labels[two.F(f, 2)]);
  }
  // The scanned bunny has 1113 vertices no face uses.
  const Mesh bunny = load("open/stanford-bunny.obj");
  CHECK(aniso::count_face_components(bunny.F, bunny.num_vertices()) == 1);
  aniso::vertex_components(bunny.F, bunny.num_vertices(), &count);
  CHECK(count == 1 + 1113);
  // Faces touching at a single vertex are one component.
  CHECK(aniso::count_face_components(triangles({{0, 1, 2}, {0, 3, 4}}), 5) == 1);
  CHECK(aniso::count_face_components(triangles({{0, 1, 2}, {3, 4, 5}}), 6) == 2);
}

TEST_CASE("topology: vertex adjacency is sorted, symmetric and lists every edge twice", "[topology]") {
  const Mesh mesh = load("closed/spot_triangulated.obj");
  const aniso::VertexAdjacency adjacency = aniso::vertex_adjacency(mesh.F, mesh.num_vertices());
  REQUIRE(adjacency.offsets.size() == static_cast<std::size_t>(mesh.num_vertices()) + 1);
  // Closed genus 0: E = 3F/2 and V - E + F = 2.
  const long long edges = static_cast<long long>(adjacency.neighbors.size()) / 2;
  CHECK(edges == 3LL * mesh.num_triangles() / 2);
  CHECK(mesh.num_vertices() - edges + mesh.num_triangles() == 2);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const auto begin = adjacency.neighbors.begin() + adjacency.offsets[v];
    const auto end = adjacency.neighbors.begin() + adjacency.offsets[v + 1];
    CHECK(std::adjacent_find(begin, end, std::greater_equal<int>()) == end);  // strictly ascending
    for (auto it = begin; it != end; ++it) {
      const auto their_begin = adjacency.neighbors.begin() + adjacency.offsets[*it];
      const auto their_end = adjacency.neighbors.begin() + adjacency.offsets[*it + 1];
      CHECK(std::binary_search(their_begin, their_end, v));
    }
  }
}

TEST_CASE("topology: the armadillo is one closed component with 3 neighbours per face corner", "[topology]") {
  const Mesh mesh = load("closed/armadillo.off");
  const auto loops = aniso::boundary_loops(mesh.F, mesh.num_vertices());
  const int components = aniso::count_face_components(mesh.F, mesh.num_vertices());
  const auto adjacency = aniso::vertex_adjacency(mesh.F, mesh.num_vertices());
  CHECK(loops.empty());
  CHECK(components == 1);
  // Closed and edge-manifold: each of the 3F/2 edges is listed from both ends, 3F entries.
  CHECK(adjacency.neighbors.size() == 3 * static_cast<std::size_t>(mesh.num_triangles()));
}
