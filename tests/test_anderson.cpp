// Anderson acceleration of AnARAP / ARAP (anderson.h, anarap.h): to the same
// tolerance it must stop in a fraction of plain local/global's iterations, at
// an energy no higher, with the energy history still never increasing; and
// where there is nothing to do it must stop at once.
#include <catch2/catch.hpp>

#include "anisoform/deformer.h"
#include "anisoform/selection.h"
#include "solver_test_support.h"
#include "test_support.h"

using namespace aniso;

namespace {

struct Compared {
  DeformResult plain, accelerated;
};

Compared solve_both(const Mesh& mesh, DeformRequest request) {
  request.max_iterations = 3000;
  request.tolerance = 1e-6;
  request.warm_start = false;
  Deformer deformer(mesh);
  Compared out;
  request.acceleration = Acceleration::None;
  out.plain = deformer.deform(request);
  request.acceleration = Acceleration::Anderson;
  out.accelerated = deformer.deform(request);
  return out;
}

void check_accelerated(const Compared& c, const char* what) {
  INFO(what << ": plain " << c.plain.iterations << " iterations, E " << c.plain.energy << "; Anderson "
            << c.accelerated.iterations << " iterations, E " << c.accelerated.energy);
  WARN(what << ": plain " << c.plain.iterations << " iterations, Anderson " << c.accelerated.iterations);
  REQUIRE(c.plain.converged);
  REQUIRE(c.accelerated.converged);
  CHECK(3 * c.accelerated.iterations <= c.plain.iterations);
  CHECK(c.accelerated.energy <= c.plain.energy * (1.0 + 1e-9));
  const std::vector<double>& history = c.accelerated.energy_history;
  for (std::size_t k = 1; k < history.size(); ++k) CHECK(history[k] <= history[k - 1]);
}

}  // namespace

TEST_CASE("anderson: an AnARAP stretch of the bunny's head converges in a third of the iterations, no higher energy",
          "[anarap][anderson]") {
  const Mesh mesh = test::load("closed/bunny_npm.obj");
  DeformRequest request = test::stretch_request(Method::AnArap, Eigen::Vector3d::UnitY(), 1.4);
  request.selection = selection_weights(mesh, parse_region("box:-1e9,5.8,-1e9,1e9,1e9,1e9"), 1.0);
  check_accelerated(solve_both(mesh, request), "AnARAP stretch");
}

TEST_CASE("anderson: an edit with nothing to do stops at once, as plain iterations do", "[anarap][anderson]") {
  // At an exact solution the mixed steps only stir rounding noise: without
  // the floor rule they ran 384-831 iterations where plain ones stop at 20.
  const Mesh mesh = test::load("closed/bunny_npm.obj");
  Deformer deformer(mesh);
  DeformRequest request = test::stretch_request(Method::AnArap, Eigen::Vector3d::UnitY(), 1.0);
  request.max_iterations = 3000;
  const DeformResult identity = deformer.deform(request);
  CHECK(identity.iterations <= 5);
  CHECK((identity.V - mesh.V).rowwise().norm().maxCoeff() <= 1e-9 * test::diagonal(mesh.V));
}

TEST_CASE("anderson: ARAP with handles on spot converges in a third of the iterations, no higher energy",
          "[anarap][anderson]") {
  const Mesh mesh = test::load("closed/spot_triangulated.obj");
  DeformRequest request;
  request.method = Method::Arap;
  const double top = mesh.V.col(1).maxCoeff(), bottom = mesh.V.col(1).minCoeff();
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.V(i, 1) > top - 0.15 * (top - bottom)) request.handles.push_back(i);
    if (mesh.V(i, 1) < bottom + 0.15 * (top - bottom)) request.pins.push_back(i);
  }
  request.handle_offset = Eigen::Vector3d(0.0, 0.1, 0.05) * (top - bottom);
  check_accelerated(solve_both(mesh, request), "ARAP handles");
}
