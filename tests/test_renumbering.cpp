// The Deformer solves on a breadth-first renumbering of the rest mesh
// (deformer.h): what it brings (neighbours numbered close together on a
// subdivided scan) and that callers never see it (requests and results in
// the input's numbering, errors naming the input's vertices).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <random>
#include <vector>

#include "anisoform/deformer.h"
#include "anisoform/mesh.h"
#include "mesh/topology.h"
#include "test_support.h"

using aniso::DeformRequest;
using aniso::Deformer;
using aniso::DirectionSource;
using aniso::Mesh;
using aniso::Method;
using aniso::Positions;
using aniso::test::load;

namespace {

// Mean |a - b| over the face sides a-b: how far apart neighbours are numbered.
double mean_edge_span(const aniso::Triangles& F, const std::vector<int>& number) {
  double sum = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) sum += std::abs(number[F(f, k)] - number[F(f, (k + 1) % 3)]);
  }
  return sum / (3.0 * static_cast<double>(F.rows()));
}

// `mesh` with vertex i renamed to shuffled[i].
Mesh renamed(const Mesh& mesh, const std::vector<int>& shuffled) {
  Mesh out;
  out.V.resize(mesh.V.rows(), 3);
  for (int i = 0; i < mesh.num_vertices(); ++i) out.V.row(shuffled[i]) = mesh.V.row(i);
  out.F = mesh.F.unaryExpr([&shuffled](int v) { return shuffled[v]; });
  return out;
}

// The request for the renamed mesh: the same vertices under their new names.
DeformRequest renamed(const DeformRequest& request, const std::vector<int>& shuffled) {
  DeformRequest out = request;
  for (int i = 0; i < static_cast<int>(shuffled.size()); ++i) {
    if (request.selection.size() > 0) out.selection[shuffled[i]] = request.selection[i];
    if (request.direction.dense.rows() > 0) out.direction.dense.row(shuffled[i]) = request.direction.dense.row(i);
  }
  for (int& p : out.pins) p = shuffled[p];
  for (int& h : out.handles) h = shuffled[h];
  for (auto& c : out.direction.constraints) c.vertex = shuffled[c.vertex];
  return out;
}

// Largest distance between the result on `mesh` and the one on its renamed
// copy (read back under the old names), over the mesh's diagonal.
double renaming_difference(const Mesh& mesh, const DeformRequest& request, const std::vector<int>& shuffled) {
  Deformer original(mesh);
  Deformer other(renamed(mesh, shuffled));
  const Positions a = original.deform(request).V;
  const Positions b = other.deform(renamed(request, shuffled)).V;
  double largest = 0.0;
  for (int i = 0; i < mesh.num_vertices(); ++i) largest = std::max(largest, (a.row(i) - b.row(shuffled[i])).norm());
  return largest / (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
}

}  // namespace

TEST_CASE("topology: the breadth-first order numbers the subdivided koala's neighbours 100 times closer",
          "[topology][renumbering]") {
  const Mesh koala = load("large/koala_loop1_200k.ply");
  const int n = koala.num_vertices();
  const std::vector<int> order = aniso::breadth_first_order(koala.F, n);
  REQUIRE(static_cast<int>(order.size()) == n);
  std::vector<int> rank(n, -1);
  for (int k = 0; k < n; ++k) {
    REQUIRE(rank[order[k]] == -1);  // every vertex once
    rank[order[k]] = k;
  }
  std::vector<int> identity(n);
  std::iota(identity.begin(), identity.end(), 0);
  const double as_given = mean_edge_span(koala.F, identity), renumbered = mean_edge_span(koala.F, rank);
  INFO("mean edge span: as given " << as_given << ", breadth-first " << renumbered);
  // Loop subdivision numbers the edge vertices after the old ones.
  CHECK(as_given > 10000.0);
  CHECK(renumbered * 100.0 < as_given);
}

TEST_CASE("deformer: renaming the input's vertices renames the result, for every per-vertex input",
          "[deformer][renumbering]") {
  const Mesh spot = load("closed/spot_triangulated.obj");
  const int n = spot.num_vertices();
  std::vector<int> shuffled(n);
  std::iota(shuffled.begin(), shuffled.end(), 0);
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(7));

  // A soft selection (weights graded along z), so that a
  // selection read under the wrong names would select other vertices.
  Eigen::VectorXd weights(n);
  for (int i = 0; i < n; ++i) weights[i] = std::clamp(0.5 + 2.0 * spot.V(i, 2), 0.0, 1.0);

  // Iterated methods: the same 60 iterations in either numbering, which
  // round differently (4e-8 of the diagonal after 400 ARAP iterations); an
  // input read under the wrong names moves vertices by a share of the edit
  // (a selection left unrenamed: 0.056 of the diagonal).
  const auto iterated = [](Method method) {
    DeformRequest request;
    request.method = method;
    request.tolerance = 1e-12;
    request.max_iterations = 60;
    return request;
  };
  SECTION("AnARAP stretch along a propagated field, soft selection, pins") {
    DeformRequest request = iterated(Method::AnArap);
    request.selection = weights;
    request.direction.kind = DirectionSource::Kind::Constraints;
    request.direction.constraints = {{10, Eigen::Vector3d(1, 0, 0)}, {2000, Eigen::Vector3d(0, 1, 0)}};
    request.transform.su = 1.4;
    request.pins = {5, 17, 2900};
    CHECK(renaming_difference(spot, request, shuffled) < 1e-6);
  }
  SECTION("ARAP with handles and pins") {
    DeformRequest request = iterated(Method::Arap);
    request.handles = {100, 101, 102};
    request.handle_offset = Eigen::Vector3d(0.0, 0.1, 0.05);
    request.pins = {2500, 2501};
    CHECK(renaming_difference(spot, request, shuffled) < 1e-6);
  }
  SECTION("AnDefGrad along a dense field") {
    DeformRequest request;
    request.method = Method::AnDefGrad;
    request.selection = weights;
    request.direction.kind = DirectionSource::Kind::Dense;
    request.direction.dense.resize(n, 3);
    for (int i = 0; i < n; ++i) request.direction.dense.row(i) = Eigen::RowVector3d(1.0, spot.V(i, 1), 0.3);
    request.transform.sv = 1.3;
    CHECK(renaming_difference(spot, request, shuffled) < 1e-9);
  }
}

TEST_CASE("deformer: a direction constraint's error names the input's vertex", "[deformer][renumbering]") {
  Deformer deformer(load("closed/spot_triangulated.obj"));
  DeformRequest request;
  request.direction.kind = DirectionSource::Kind::Constraints;
  request.direction.constraints = {{1234, Eigen::Vector3d(1, 0, 0)}, {1234, Eigen::Vector3d(0, 1, 0)}};
  const std::string message = aniso::test::bad_parameter_message([&] { deformer.deform(request); });
  CHECK(message.find("direction constraint 2 (vertex 1234)") != std::string::npos);
  CHECK(message.find("already constrained by constraint 1") != std::string::npos);
}
