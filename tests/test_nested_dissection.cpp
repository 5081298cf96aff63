// The nested dissection ordering and the multilevel separators under it
// (geometry/nested_dissection.h, geometry/graph_bisection.h), on the graphs
// of real meshes and of the flattening refinement's systems.
#include <algorithm>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>

#include "anisoform/mesh.h"
#include "geometry/graph_bisection.h"
#include "geometry/nested_dissection.h"
#include "geometry/supernodal_ldlt.h"
#include "mesh/topology.h"
#include "test_support.h"

using namespace aniso;

namespace {

// The mesh's vertex graph (mesh/topology.h's adjacency), `copies` disjoint
// copies of it, unit weights.
WeightedGraph mesh_graph(const Mesh& mesh, int copies = 1) {
  const VertexAdjacency adjacency = vertex_adjacency(mesh.F, mesh.num_vertices());
  const int n = mesh.num_vertices();
  WeightedGraph g;
  for (int copy = 0; copy < copies; ++copy) {
    for (int v = 0; v < n; ++v) {
      for (int k = adjacency.offsets[v]; k < adjacency.offsets[v + 1]; ++k) {
        g.neighbour.push_back(copy * n + adjacency.neighbors[k]);
      }
      g.start.push_back(static_cast<int>(g.neighbour.size()));
    }
  }
  g.edge_weight.assign(g.neighbour.size(), 1);
  g.vertex_weight.assign(static_cast<std::size_t>(n) * copies, 1);
  return g;
}

// The pattern of the flattening refinement's Newton system on the mesh (u
// and v of each vertex interleaved, every pair of a triangle's corners
// coupled), lower triangle, with values that make it positive definite: per
// triangle G^T G for a fixed full-rank 4 by 6 G, plus the identity.
Eigen::SparseMatrix<double> flattening_system(const Mesh& mesh) {
  const int n = 2 * mesh.num_vertices();
  Eigen::Matrix<double, 4, 6> G;
  G << 1, 0, -1, 0.5, 0, 0.2,  //
      0, 1, 0.3, -1, 0, 0,     //
      -1, 0, 0, 0.4, 1, 0,     //
      0.1, -1, 0, 0, 0, 1;
  const Eigen::Matrix<double, 6, 6> block = G.transpose() * G;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 1.0);
  for (int t = 0; t < mesh.F.rows(); ++t) {
    for (int a = 0; a < 6; ++a) {
      for (int b = 0; b < 6; ++b) {
        const int row = 2 * mesh.F(t, a / 2) + a % 2, col = 2 * mesh.F(t, b / 2) + b % 2;
        if (row >= col) entries.emplace_back(row, col, block(a, b));
      }
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// Operations of A's factorization in `order` (order[k]: the row eliminated
// k-th), from the column counts of Eigen's own factor: sum of c^2.
double factor_work(const Eigen::SparseMatrix<double>& A, const std::vector<int>& order) {
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse(static_cast<int>(order.size()));
  std::copy(order.begin(), order.end(), inverse.indices().data());
  Eigen::SparseMatrix<double> permuted;
  permuted = A.selfadjointView<Eigen::Lower>().twistedBy(inverse.inverse());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(permuted);
  REQUIRE(ldlt.info() == Eigen::Success);
  const Eigen::SparseMatrix<double> L = ldlt.matrixL();
  double work = 0.0;
  for (int j = 0; j < L.outerSize(); ++j) {
    const double below = static_cast<double>(L.outerIndexPtr()[j + 1] - L.outerIndexPtr()[j]) - 1.0;
    work += below * below;
  }
  return work;
}

std::vector<int> amd_order(const Eigen::SparseMatrix<double>& A) {
  const Eigen::SparseMatrix<double> full = A.selfadjointView<Eigen::Lower>();
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(full, order);
  return std::vector<int>(order.indices().data(), order.indices().data() + order.size());
}

}  // namespace

TEST_CASE("vertex separator: separates, balances and stays short on a real patch", "[ordering]") {
  const WeightedGraph g = mesh_graph(test::load("open/demosthenes-low-res.obj"));
  const int n = g.size();
  const std::vector<std::int8_t> part = vertex_separator(g, 1);
  REQUIRE(static_cast<int>(part.size()) == n);
  int count[3] = {0, 0, 0};
  for (int v = 0; v < n; ++v) {
    ++count[part[v]];
    if (part[v] == kSeparator) continue;
    for (int e = g.start[v]; e < g.start[v + 1]; ++e) {
      const int u = g.neighbour[e];
      INFO("edge " << v << "-" << u);
      CHECK((part[u] == part[v] || part[u] == kSeparator));
    }
  }
  INFO("sides " << count[0] << ", " << count[1] << ", separator " << count[2] << " of " << n);
  // Each side within the balance (at most 65 % of the vertices), the
  // separator of the order of sqrt(n) as on a planar graph.
  CHECK(count[kSideA] <= 0.65 * n + 1);
  CHECK(count[kSideB] <= 0.65 * n + 1);
  CHECK(count[kSideA] >= 0.3 * n);
  CHECK(count[kSideB] >= 0.3 * n);
  CHECK(count[kSeparator] <= 2.0 * std::sqrt(static_cast<double>(n)));
  // The same seed, the same parts.
  CHECK(vertex_separator(g, 1) == part);
}

TEST_CASE("vertex separator: two components need no separator", "[ordering]") {
  const Mesh mesh = test::load("open/hand_lowres.obj");
  const WeightedGraph g = mesh_graph(mesh, 2);
  const std::vector<std::int8_t> part = vertex_separator(g, 7);
  const int n = mesh.num_vertices();
  CHECK(std::count(part.begin(), part.end(), kSeparator) == 0);
  for (int v = 0; v < n; ++v) CHECK(part[v] == part[0]);
  for (int v = n; v < 2 * n; ++v) CHECK(part[v] == 1 - part[0]);
}

TEST_CASE("nested dissection: a permutation with far fewer operations than AMD on a flattening system",
          "[ordering]") {
  const Mesh mesh = test::load("open/demosthenes-low-res.obj");
  const Eigen::SparseMatrix<double> A = flattening_system(mesh);
  const int n = static_cast<int>(A.rows());
  const std::vector<int> order = nested_dissection_order(A);
  REQUIRE(static_cast<int>(order.size()) == n);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (int k = 0; k < n; ++k) REQUIRE(sorted[k] == k);
  // u and v of a vertex have the same neighbours: eliminated one after the other.
  std::vector<int> position(n);
  for (int k = 0; k < n; ++k) position[order[k]] = k;
  int apart = 0;
  for (int v = 0; v < n / 2; ++v) apart += std::abs(position[2 * v] - position[2 * v + 1]) != 1;
  CHECK(apart == 0);
  // Measured when written: AMD 2.35e8, nested dissection 1.36e8.
  const double amd = factor_work(A, amd_order(A)), dissection = factor_work(A, order);
  INFO("AMD " << amd << ", nested dissection " << dissection);
  CHECK(dissection < 0.7 * amd);
}

TEST_CASE("supernodal analysis: kept, it orders by nested dissection where that is cheaper and solves as Eigen",
          "[ordering]") {
  for (const char* name : {"open/demosthenes-low-res.obj", "open/hand_lowres.obj"}) {
    INFO(name);
    const Eigen::SparseMatrix<double> A = flattening_system(test::load(name));
    const SupernodalAnalysis analysis(A);
    const double amd = factor_work(A, amd_order(A)), dissection = factor_work(A, nested_dissection_order(A));
    INFO("AMD " << amd << ", nested dissection " << dissection);
    // The hand's system (1,618 rows) is below the size where dissection is tried.
    CHECK(analysis.nested_dissection() == (A.rows() >= 1000 && dissection < amd));
    const SupernodalLdlt ours = analysis.factor(A, 0.0);
    REQUIRE(ours.bad_pivot == -1);
    const int n = static_cast<int>(A.rows());
    const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 1);
    Eigen::VectorXd y(n);
    for (int i = 0; i < n; ++i) y[ours.perm[i]] = b(i, 0);
    ours.L.solve(ours.d.cwiseInverse(), y.data(), 1);
    Eigen::VectorXd x(n);
    for (int i = 0; i < n; ++i) x[i] = y[ours.perm[i]];
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> eigen(A);
    const Eigen::VectorXd expected = eigen.solve(b.col(0));
    CHECK((x - expected).norm() <= 1e-9 * expected.norm());
  }
}

TEST_CASE("nested dissection: graphs no mesh makes stay ordered (isolated rows, a star, a clique, a path)",
          "[ordering]") {
  // Lower triangles, diagonally dominant where the degree is at most 2.
  const auto pattern = [](int n, const std::vector<std::pair<int, int>>& edges) {
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 3.0);
    for (const auto& [a, b] : edges) entries.emplace_back(std::max(a, b), std::min(a, b), 1.0);
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(entries.begin(), entries.end());
    return A;
  };
  std::vector<std::pair<const char*, Eigen::SparseMatrix<double>>> cases;
  cases.emplace_back("no edges", pattern(3000, {}));
  std::vector<std::pair<int, int>> star, clique, path, mixed;
  for (int i = 1; i < 3000; ++i) star.emplace_back(0, i);
  cases.emplace_back("a star", pattern(3000, star));
  for (int i = 0; i < 300; ++i) {
    for (int j = 0; j < i; ++j) clique.emplace_back(i, j);
  }
  cases.emplace_back("a clique", pattern(300, clique));
  for (int i = 1; i < 5000; ++i) path.emplace_back(i - 1, i);
  cases.emplace_back("a path", pattern(5000, path));
  // Half the rows isolated, the rest a path with a few long edges.
  for (int i = 2; i < 4000; i += 2) mixed.emplace_back(i - 2, i);
  for (int i = 0; i + 2000 < 4000; i += 398) mixed.emplace_back(i, i + 2000);
  cases.emplace_back("isolated rows and a path", pattern(4000, mixed));
  cases.emplace_back("empty", pattern(0, {}));
  for (const auto& [name, A] : cases) {
    INFO(name);
    std::vector<int> order = nested_dissection_order(A);
    REQUIRE(order.size() == static_cast<std::size_t>(A.rows()));
    std::sort(order.begin(), order.end());
    for (int k = 0; k < static_cast<int>(order.size()); ++k) REQUIRE(order[k] == k);
  }
  // A path's separators are single rows: eliminated, a stretch of it joins
  // the two around it, so no column has more than two entries below the
  // diagonal (an order with the separators first would fill whole columns).
  const std::vector<int> path_order = nested_dissection_order(cases[3].second);
  CHECK(factor_work(cases[3].second, path_order) <= 4.0 * 5000);
}
