// Per-vertex distortion (distortion.h), the numbers the browser's heat map
// colours: known maps on real meshes give known values at every vertex.
#include <catch2/catch.hpp>

#include "anisoform/distortion.h"
#include "test_support.h"

namespace {

aniso::Positions scaled_positions(const aniso::Positions& V, double x, double y, double z) {
  aniso::Positions out = V;
  out.col(0) *= x;
  out.col(1) *= y;
  out.col(2) *= z;
  return out;
}

void check_distortion_everywhere(const Eigen::VectorXd& values, double expected) {
  REQUIRE(values.size() > 0);
  CHECK(values.minCoeff() == Approx(expected).epsilon(1e-12));
  CHECK(values.maxCoeff() == Approx(expected).epsilon(1e-12));
}

}  // namespace

TEST_CASE("distortion: a uniform scale by 2 doubles the stretch and quadruples the area everywhere",
          "[distortion]") {
  const aniso::Mesh bunny = aniso::test::load("closed/bunny_npm.obj");
  const aniso::Positions doubled = scaled_positions(bunny.V, 2, 2, 2);
  check_distortion_everywhere(aniso::vertex_distortion(bunny, doubled, aniso::DistortionKind::Stretch), 2.0);
  check_distortion_everywhere(aniso::vertex_distortion(bunny, doubled, aniso::DistortionKind::AreaRatio), 4.0);
  check_distortion_everywhere(aniso::vertex_distortion(bunny, bunny.V, aniso::DistortionKind::Stretch), 1.0);
}

TEST_CASE("distortion: stretch is the principal stretch farthest from 1 by ratio", "[distortion]") {
  // plane.off lies in y = 0: scaling x and z gives every triangle the
  // principal stretches (sx, sz) exactly.
  const aniso::Mesh plane = aniso::test::load("open/plane.off");
  REQUIRE(plane.V.col(1).cwiseAbs().maxCoeff() == 0.0);
  const auto stretch = [&](double sx, double sz) {
    return aniso::vertex_distortion(plane, scaled_positions(plane.V, sx, 1, sz), aniso::DistortionKind::Stretch);
  };
  // A squeeze along one direction shows, although no line element got longer.
  check_distortion_everywhere(stretch(0.5, 1.0), 0.5);
  check_distortion_everywhere(stretch(1.0, 0.5), 0.5);
  // Stretched by 2 and squeezed by 0.75: 2 deviates more (2 * 0.75 >= 1).
  check_distortion_everywhere(stretch(2.0, 0.75), 2.0);
  // Squeezed by 0.4 and stretched by 1.5: 0.4 deviates more (0.4 * 1.5 < 1).
  check_distortion_everywhere(stretch(0.4, 1.5), 0.4);
  check_distortion_everywhere(aniso::vertex_distortion(plane, scaled_positions(plane.V, 0.4, 1, 1.5), aniso::DistortionKind::AreaRatio),
                   0.6);
}
