// The accelerations of AnARAP / ARAP (anarap.h): L-BFGS (anarap_lbfgs.cpp)
// and Anderson acceleration (anderson.h). To the same tolerance each must stop
// in a fraction of plain local/global's iterations, at an energy no higher,
// with the energy history still never increasing; and where there is nothing
// to do it must stop at once.
#include <string>

#include <catch2/catch.hpp>

#include "anisoform/deformer.h"
#include "anisoform/selection.h"
#include "solver_test_support.h"
#include "test_support.h"

using namespace aniso;

namespace {

struct Compared {
  DeformResult plain, anderson, lbfgs;
};

Compared solve_all(const Mesh& mesh, DeformRequest request) {
  request.max_iterations = 3000;
  request.tolerance = 1e-6;
  request.warm_start = false;
  Deformer deformer(mesh);
  Compared out;
  request.acceleration = Acceleration::None;
  out.plain = deformer.deform(request);
  request.acceleration = Acceleration::Anderson;
  out.anderson = deformer.deform(request);
  request.acceleration = Acceleration::Lbfgs;
  out.lbfgs = deformer.deform(request);
  return out;
}

void check_accelerated(const DeformResult& plain, const DeformResult& accelerated, const char* what) {
  INFO(what << ": plain " << plain.iterations << " iterations, E " << plain.energy << "; accelerated "
            << accelerated.iterations << " iterations, E " << accelerated.energy);
  WARN(what << ": plain " << plain.iterations << " iterations, accelerated " << accelerated.iterations);
  REQUIRE(plain.converged);
  REQUIRE(accelerated.converged);
  CHECK(3 * accelerated.iterations <= plain.iterations);
  CHECK(accelerated.energy <= plain.energy * (1.0 + 1e-9));
  const std::vector<double>& history = accelerated.energy_history;
  for (std::size_t k = 1; k < history.size(); ++k) CHECK(history[k] <= history[k - 1]);
}

void check_both(const Compared& c, const std::string& what) {
  check_accelerated(c.plain, c.anderson, (what + ", Anderson").c_str());
  check_accelerated(c.plain, c.lbfgs, (what + ", L-BFGS").c_str());
}

}  // namespace

TEST_CASE("acceleration: an AnARAP stretch of the bunny's head converges in a third of the iterations, no higher energy",
          "[anarap][acceleration]") {
  const Mesh mesh = test::load("closed/bunny_npm.obj");
  DeformRequest request = test::stretch_request(Method::AnArap, Eigen::Vector3d::UnitY(), 1.4);
  request.selection = selection_weights(mesh, parse_region("box:-1e9,5.8,-1e9,1e9,1e9,1e9"), 1.0);
  check_both(solve_all(mesh, request), "AnARAP stretch");
}

TEST_CASE("acceleration: an edit with nothing to do stops at once, as plain iterations do", "[anarap][acceleration]") {
  // At an exact solution accelerated steps only stir rounding noise: without
  // the floor rule Anderson's ran 384-831 iterations where plain ones stop at 20.
  const Mesh mesh = test::load("closed/bunny_npm.obj");
  Deformer deformer(mesh);
  DeformRequest request = test::stretch_request(Method::AnArap, Eigen::Vector3d::UnitY(), 1.0);
  request.max_iterations = 3000;
  request.warm_start = false;
  for (const Acceleration acceleration : {Acceleration::Anderson, Acceleration::Lbfgs}) {
    request.acceleration = acceleration;
    const DeformResult identity = deformer.deform(request);
    CHECK(identity.iterations <= 5);
    CHECK((identity.V - mesh.V).rowwise().norm().maxCoeff() <= 1e-9 * test::diagonal(mesh.V));
  }
}

TEST_CASE("acceleration: ARAP with handles on spot converges in a third of the iterations, no higher energy",
          "[anarap][acceleration]") {
  const Mesh mesh = test::load("closed/spot_triangulated.obj");
  DeformRequest request;
  request.method = Method::Arap;
  const double top = mesh.V.col(1).maxCoeff(), bottom = mesh.V.col(1).minCoeff();
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.V(i, 1) > top - 0.15 * (top - bottom)) request.handles.push_back(i);
    if (mesh.V(i, 1) < bottom + 0.15 * (top - bottom)) request.pins.push_back(i);
  }
  request.handle_offset = Eigen::Vector3d(0.0, 0.1, 0.05) * (top - bottom);
  check_both(solve_all(mesh, request), "ARAP handles");
}

// With a rotational part (a shear, a rotation, a twist) AnARAP's rotations
// are coupled, fitted by a Gauss-Seidel sweep from the last ones: they, not
// the positions (L^-1 b(R)), are the iteration's state, and Anderson mixes
// them (L-BFGS falls back to it, anarap.cpp says why). Mixing the positions
// instead gained nothing here: spot's shear took 279 iterations against
// plain's 269.
TEST_CASE("acceleration: AnARAP's coupled rotations (spot's shear, rotation and twist) converge in a fifth of the "
          "iterations, no higher energy",
          "[anarap][acceleration]") {
  const Mesh mesh = test::load("closed/spot_triangulated.obj");
  DeformRequest request = test::stretch_request(Method::AnArap, Eigen::Vector3d::UnitX(), 1.0);
  request.selection = selection_weights(mesh, parse_region("box:-1e9,0.2,-1e9,1e9,1e9,1e9"), 1.0);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double selected = 0.0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    centroid += request.selection[i] * mesh.V.row(i).transpose();
    selected += request.selection[i];
  }
  centroid /= selected;
  TransformSpec shear, rotate, twist;
  shear.shear = 0.3;
  rotate.rotate_axis = RotateAxis::U;
  rotate.rotate_degrees = 25.0;
  twist.twist = true;
  twist.twist_axis = Eigen::Vector3d::UnitY();
  twist.twist_origin = centroid;
  twist.twist_degrees_per_unit = 60.0;
  for (const auto& [name, transform] : {std::pair<const char*, TransformSpec>{"shear", shear}, {"rotation", rotate},
                                        {"twist", twist}}) {
    request.transform = transform;
    const Compared c = solve_all(mesh, request);
    INFO(name);
    CHECK(5 * c.anderson.iterations <= c.plain.iterations);
    check_both(c, std::string("AnARAP coupled ") + name);
  }
}

TEST_CASE("acceleration: a solve that meets the tolerance on its last allowed iteration is converged",
          "[anarap][acceleration]") {
  // Convergence is the tolerance test's, not "fewer iterations than the cap":
  // with the cap at the count a solve takes by itself, it used to say
  // converged: false (and the CLI warned of the cap) for the same positions.
  // Spot at low resolution (829 vertices): the rule is the same, the plain
  // solve to 1e-6 three times cheaper than on the full Spot.
  const Mesh mesh = test::load("formats/spot_lowres.obj");
  DeformRequest request = test::stretch_request(Method::AnArap, Eigen::Vector3d::UnitX(), 1.5);
  request.selection = selection_weights(mesh, parse_region("box:-9,-9,0.2,9,9,9"), 1.0);
  request.tolerance = 1e-6;
  request.warm_start = false;
  Deformer deformer(mesh);
  for (const Acceleration acceleration : {Acceleration::None, Acceleration::Anderson, Acceleration::Lbfgs}) {
    request.acceleration = acceleration;
    request.max_iterations = 3000;
    const DeformResult free = deformer.deform(request);
    REQUIRE(free.converged);
    request.max_iterations = free.iterations;
    const DeformResult capped = deformer.deform(request);
    INFO("acceleration " << static_cast<int>(acceleration) << ", " << free.iterations << " iterations");
    CHECK(capped.iterations == free.iterations);
    CHECK(capped.converged);
    CHECK(capped.V == free.V);
    request.max_iterations = free.iterations - 1;
    CHECK_FALSE(deformer.deform(request).converged);
  }
}
