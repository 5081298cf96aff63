// Cotangent weights, the Laplacian and the shared factorization.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>

#include "anisoform/laplacian.h"
#include "geometry/laplacian_solver.h"
#include "geometry/supernodal_factor.h"
#include "geometry/supernodal_ldlt.h"
#include "mesh/topology.h"
#include "test_support.h"

using namespace aniso;

TEST_CASE("laplacian: constants are in the null space and L is symmetric", "[laplacian]") {
  for (const char* name : {"closed/torus.obj", "closed/spool.off", "open/hemisphere.obj", "closed/fandisk.off"}) {
    const Mesh mesh = test::load(name);
    const CotanWeights w = cotangent_weights(mesh);
    const Eigen::SparseMatrix<double> L = cotangent_laplacian(mesh, w);
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(mesh.num_vertices());
    INFO(name);
    CHECK((L * ones).cwiseAbs().maxCoeff() < 1e-9 * L.coeffs().cwiseAbs().maxCoeff());
    const Eigen::SparseMatrix<double> Lt = L.transpose();
    CHECK((L - Lt).norm() < 1e-12 * L.norm());
    for (int i = 0; i < mesh.num_vertices(); ++i) REQUIRE(L.coeff(i, i) > 0.0);
  }
}

TEST_CASE("laplacian: linear functions are harmonic on a flat mesh, up to the raised edges", "[laplacian]") {
  // With the raw cotangents a linear function is exactly harmonic at interior
  // vertices of a flat mesh; our L differs only by the floor raise of edges
  // with weights below it (this plane's 6-digit coordinates make some right
  // angles slightly obtuse), so |(L f)_i| is bounded by those raises.
  const Mesh mesh = test::load("open/plane.off");
  const CotanWeights w = cotangent_weights(mesh);
  const Eigen::SparseMatrix<double> L = cotangent_laplacian(mesh, w);
  Eigen::SparseMatrix<double> raw(mesh.num_vertices(), mesh.num_vertices());
  std::vector<Eigen::Triplet<double>> triplets;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = mesh.V.row(mesh.F(t, k)), q = mesh.V.row(mesh.F(t, (k + 1) % 3)),
                            r = mesh.V.row(mesh.F(t, (k + 2) % 3));
      const double cot = (q - p).dot(r - p) / (q - p).cross(r - p).norm();
      triplets.emplace_back(mesh.F(t, (k + 1) % 3), mesh.F(t, (k + 2) % 3), -0.5 * cot);
      triplets.emplace_back(mesh.F(t, (k + 2) % 3), mesh.F(t, (k + 1) % 3), -0.5 * cot);
    }
  }
  raw.setFromTriplets(triplets.begin(), triplets.end());
  const std::vector<char> boundary = boundary_vertex_mask(mesh.F, mesh.num_vertices());
  const Eigen::VectorXd f = 2.0 * mesh.V.col(0) - 3.0 * mesh.V.col(2) + Eigen::VectorXd::Constant(mesh.num_vertices(), 0.5);
  const Eigen::VectorXd Lf = L * f;
  const Eigen::SparseMatrix<double> Lraw = raw;  // off-diagonal raw entries
  int interior = 0, exact = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (boundary[i]) continue;
    ++interior;
    double bound = 1e-12;
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, i); it; ++it) {
      if (it.row() == i) continue;
      bound += std::abs(it.value() - Lraw.coeff(it.row(), i)) * std::abs(f[it.row()] - f[i]);
    }
    REQUIRE(std::abs(Lf[i]) <= bound);
    if (bound <= 1e-11) ++exact;
  }
  CHECK(interior > 600);
  CHECK(w.raised_edges > 0);
  CHECK(exact > 0);
}

TEST_CASE("laplacian: zero-area triangles are left out and the system stays definite", "[laplacian]") {
  const Mesh mesh = test::load("malformed/bad_degenerate_faces.obj");
  const CotanWeights w = cotangent_weights(mesh);
  CHECK(w.degenerate_triangles == 6);
  CHECK(w.weight.allFinite());
  const Eigen::SparseMatrix<double> L = cotangent_laplacian(mesh, w);
  // One pin makes the connected mesh's system definite: the factorization succeeds.
  LaplacianSolver solver(L, {0});
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(mesh.num_vertices(), 1);
  Eigen::MatrixXd b = Eigen::MatrixXd::Ones(mesh.num_vertices(), 1);
  solver.solve(b, x);
  CHECK(x.allFinite());
}

TEST_CASE("laplacian: weights stay bounded and the system definite on a real messy scan", "[laplacian]") {
  const Mesh mesh = test::load("malformed/Spider_binary.stl");
  const CotanWeights w = cotangent_weights(mesh);
  CHECK(w.weight.allFinite());
  CHECK(w.weight.cwiseAbs().maxCoeff() <= 1.5 * kMaxCot);
  CHECK(w.degenerate_triangles > 0);
  CHECK(w.raised_edges > 0);
  // PSD: x^T L x >= 0 for random x.
  const Eigen::SparseMatrix<double> L = cotangent_laplacian(mesh, w);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd x = Eigen::VectorXd::Random(mesh.num_vertices());
    CHECK(x.dot(L * x) >= -1e-12 * x.squaredNorm() * L.diagonal().maxCoeff());
  }
}

TEST_CASE("laplacian solver: one-sweep multi-column solve matches Eigen's LDLT", "[laplacian]") {
  // The torus, and the armadillo, whose factor (AMD) has supernodes over 64
  // columns wide: every column count takes its own path (1, 2, 3 fused, more
  // one by one).
  for (const char* name : {"closed/torus.obj", "closed/armadillo.off"}) {
    const Mesh mesh = test::load(name);
    const Eigen::SparseMatrix<double> L = cotangent_laplacian(mesh, cotangent_weights(mesh));
    const std::vector<int> pins = {0, 100, 2000};
    LaplacianSolver solver(L, pins);
    const int n = mesh.num_vertices();
    std::vector<int> free;
    for (int i = 0; i < n; ++i)
      if (std::find(pins.begin(), pins.end(), i) == pins.end()) free.push_back(i);
    for (const int k : {1, 2, 3, 5}) {
      INFO(name << ", " << k << " columns");
      Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, k);
      Eigen::MatrixXd x = Eigen::MatrixXd::Zero(n, k);
      for (int p : pins) x.row(p) = Eigen::RowVectorXd::LinSpaced(k, 1.0 + p, -2.0);
      const Eigen::MatrixXd pinned_values = x;
      solver.solve(b, x);
      const Eigen::MatrixXd residual = L * x - b;
      double worst = 0.0;
      for (int i : free) worst = std::max(worst, residual.row(i).norm() / (1.0 + b.row(i).norm()));
      CHECK(worst < 1e-8);
      for (int p : pins) CHECK(x.row(p) == pinned_values.row(p));
    }
  }
}

TEST_CASE("supernodal LDL^T: the ordering, pivots and solutions of Eigen's SimplicialLDLT", "[laplacian]") {
  // A closed scan and an open patch, one vertex held (the free-free block).
  for (const char* name : {"closed/armadillo.off", "open/human_woman_torso_front_patch.obj"}) {
    INFO(name);
    const Mesh mesh = test::load(name);
    const Eigen::SparseMatrix<double> L = cotangent_laplacian(mesh, cotangent_weights(mesh));
    const int n = mesh.num_vertices() - 1;
    const Eigen::SparseMatrix<double> free_block = L.bottomRightCorner(n, n);
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> eigen(free_block);
    REQUIRE(eigen.info() == Eigen::Success);
    const SupernodalLdlt ours = supernodal_ldlt(free_block, 0.0);
    REQUIRE(ours.bad_pivot == -1);
    CHECK(std::equal(ours.perm.begin(), ours.perm.end(), eigen.permutationP().indices().data()));
    CHECK((ours.d - eigen.vectorD()).norm() <= 1e-10 * eigen.vectorD().norm());
    CHECK(ours.L.supernodes() < n);
    // x = P^T L^-T D^-1 L^-1 P b against Eigen's solve.
    const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 3);
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> y(n, 3);
    for (int i = 0; i < n; ++i) y.row(ours.perm[i]) = b.row(i);
    ours.L.solve(ours.d.cwiseInverse(), y.data(), 3);
    Eigen::MatrixXd x(n, 3);
    for (int i = 0; i < n; ++i) x.row(i) = y.row(ours.perm[i]);
    const Eigen::MatrixXd expected = eigen.solve(b);
    CHECK((x - expected).norm() <= 1e-9 * expected.norm());
    CHECK_THROWS_WITH(ours.L.solve(ours.d.cwiseInverse(), y.data(), 4), Catch::Contains("1, 2 or 3 columns"));
  }
}

TEST_CASE("supernodal LDL^T: a singular matrix stops at the pivot that vanishes", "[laplacian]") {
  // The whole Laplacian of a closed mesh (no vertex held): constants are in
  // its null space, so the last pivot vanishes to round-off.
  const Mesh mesh = test::load("closed/torus.obj");
  const Eigen::SparseMatrix<double> L = cotangent_laplacian(mesh, cotangent_weights(mesh));
  const double floor = 1e-13 * L.diagonal().cwiseAbs().maxCoeff();
  const SupernodalLdlt result = supernodal_ldlt(L, floor);
  CHECK(result.bad_pivot == mesh.num_vertices() - 1);
  // Held at one vertex, the same matrix factors.
  const int n = mesh.num_vertices() - 1;
  CHECK(supernodal_ldlt(L.bottomRightCorner(n, n), floor).bad_pivot == -1);
}

TEST_CASE("supernodal solve: a complex Hermitian system as Eigen's SimplicialLDLT solves it", "[laplacian]") {
  // A connection Laplacian as the direction fields build (complex transport
  // of unit modulus along each edge), one vertex held: Hermitian, definite.
  const Mesh mesh = test::load("open/hemisphere.obj");
  const Eigen::SparseMatrix<double> L = cotangent_laplacian(mesh, cotangent_weights(mesh));
  const int n = mesh.num_vertices() - 1;
  std::vector<Eigen::Triplet<std::complex<double>>> lower;
  for (int col = 0; col < L.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) {
      const int r = static_cast<int>(it.row()) - 1, c = col - 1;
      if (r < 0 || c < 0 || r < c) continue;
      const std::complex<double> value =
          r == c ? std::complex<double>(it.value()) : it.value() * std::polar(1.0, 0.37 * r - 0.11 * c);
      lower.emplace_back(r, c, value);
    }
  }
  Eigen::SparseMatrix<std::complex<double>> A(n, n);
  A.setFromTriplets(lower.begin(), lower.end());
  const Eigen::MatrixXcd b = Eigen::MatrixXcd::Random(n, 2);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<std::complex<double>>, Eigen::Lower> eigen(A);
  REQUIRE(eigen.info() == Eigen::Success);
  const Eigen::MatrixXcd expected = eigen.solve(b);
  Eigen::MatrixXcd x = b;
  CHECK(supernodal_solve(A, 0.0, x) == -1);
  CHECK((x - expected).norm() <= 1e-9 * expected.norm());
  // The real path is the same arithmetic as supernodal_ldlt's.
  const Eigen::SparseMatrix<double> real_block = L.bottomRightCorner(n, n);
  Eigen::MatrixXd y = b.real();
  CHECK(supernodal_solve(real_block, 0.0, y) == -1);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> real_eigen(real_block);
  CHECK((y - real_eigen.solve(Eigen::MatrixXd(b.real()))).norm() <= 1e-9 * y.norm());
  // A zero pivot (an empty row and column) is reported, the right side kept.
  Eigen::SparseMatrix<std::complex<double>> singular = A;
  singular.prune([](int row, int col, const std::complex<double>&) { return row != 5 && col != 5; });
  Eigen::MatrixXcd z = b;
  CHECK(supernodal_solve(singular, 0.0, z) >= 0);
  CHECK(z == b);
}

TEST_CASE("laplacian solver: a component without a pin is reported, not solved", "[laplacian]") {
  const Mesh mesh = test::load("malformed/multi_component.obj");
  const Eigen::SparseMatrix<double> L = cotangent_laplacian(mesh, cotangent_weights(mesh));
  CHECK_THROWS_WITH(LaplacianSolver(L, {0}), Catch::Contains("vertex") && Catch::Contains("pinned"));
}
