// Screen drags to world vectors, with camera matrices built exactly as
// three.js builds them (PerspectiveCamera / OrthographicCamera
// projectionMatrix, matrixWorldInverse).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "anisoform/error.h"
#include "anisoform/screen_direction.h"
#include "test_support.h"

namespace {

using aniso::test::kPi;

// three.js Matrix4.makePerspective for a PerspectiveCamera (vertical fov in degrees).
Eigen::Matrix4d perspective(double fov_degrees, double aspect, double near, double far) {
  const double top = near * std::tan(0.5 * fov_degrees * kPi / 180.0);
  const double right = top * aspect;
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = near / right;
  m(1, 1) = near / top;
  m(2, 2) = -(far + near) / (far - near);
  m(2, 3) = -2.0 * far * near / (far - near);
  m(3, 2) = -1.0;
  return m;
}

// three.js Matrix4.makeOrthographic.
Eigen::Matrix4d orthographic(double left, double right, double top, double bottom, double near, double far) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m(0, 0) = 2.0 / (right - left);
  m(1, 1) = 2.0 / (top - bottom);
  m(2, 2) = -2.0 / (far - near);
  m(0, 3) = -(right + left) / (right - left);
  m(1, 3) = -(top + bottom) / (top - bottom);
  m(2, 3) = -(far + near) / (far - near);
  return m;
}

// A camera at `eye` looking at `target` (Object3D.lookAt with up = +y): its
// world matrix has columns right, up, back (+z looks away from the target), eye.
struct Camera {
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();
  Eigen::Vector3d right() const { return world.block<3, 1>(0, 0); }
  Eigen::Vector3d up() const { return world.block<3, 1>(0, 1); }
  Eigen::Matrix4d view() const { return world.inverse(); }  // matrixWorldInverse
};

Camera look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d back = (eye - target).normalized();
  const Eigen::Vector3d right = Eigen::Vector3d::UnitY().cross(back).normalized();
  const Eigen::Vector3d up = back.cross(right);
  Camera camera;
  camera.world.block<3, 1>(0, 0) = right;
  camera.world.block<3, 1>(0, 1) = up;
  camera.world.block<3, 1>(0, 2) = back;
  camera.world.block<3, 1>(0, 3) = eye;
  return camera;
}

aniso::ScreenDrag drag_from_center(const Camera& camera, const Eigen::Matrix4d& projection, double dx, double dy) {
  aniso::ScreenDrag drag;
  drag.view = camera.view();
  drag.projection = projection;
  drag.viewport = Eigen::Vector4d(0, 0, 800, 600);
  drag.from_px = Eigen::Vector2d(400, 300);
  drag.to_px = Eigen::Vector2d(400 + dx, 300 + dy);
  return drag;
}

using aniso::test::bad_parameter_message;

}  // namespace

TEST_CASE("screen: perspective drags move along the image plane at the anchor's depth", "[screen]") {
  const Camera camera = look_at(Eigen::Vector3d(0, 0, 5), Eigen::Vector3d::Zero());
  const double fov = 50.0;
  const Eigen::Matrix4d projection = perspective(fov, 800.0 / 600.0, 0.1, 100.0);
  // At depth 5 one pixel covers 2 * 5 * tan(fov/2) / height world units.
  const double per_pixel = 2.0 * 5.0 * std::tan(0.5 * fov * kPi / 180.0) / 600.0;

  const Eigen::Vector3d right = aniso::screen_drag_to_world(drag_from_center(camera, projection, 40, 0));
  CHECK((right - Eigen::Vector3d(40 * per_pixel, 0, 0)).norm() < 1e-12);

  const Eigen::Vector3d down = aniso::screen_drag_to_world(drag_from_center(camera, projection, 0, 25));
  CHECK((down - Eigen::Vector3d(0, -25 * per_pixel, 0)).norm() < 1e-12);

  // Farther away the same drag covers more world: at depth 10, twice as much.
  aniso::ScreenDrag far_drag = drag_from_center(camera, projection, 40, 0);
  far_drag.anchor = Eigen::Vector3d(0, 0, -5);
  CHECK((aniso::screen_drag_to_world(far_drag) - 2.0 * right).norm() < 1e-12);
}

TEST_CASE("screen: the result is a difference of points, so off-centre drags scale the same", "[screen]") {
  const Camera camera = look_at(Eigen::Vector3d(0, 0, 5), Eigen::Vector3d::Zero());
  const Eigen::Matrix4d projection = perspective(60.0, 1.0, 0.01, 1000.0);
  aniso::ScreenDrag drag;
  drag.view = camera.view();
  drag.projection = projection;
  drag.viewport = Eigen::Vector4d(100, 50, 500, 500);  // the canvas is offset inside the page
  drag.from_px = Eigen::Vector2d(120, 70);
  drag.to_px = Eigen::Vector2d(170, 70);
  drag.anchor = Eigen::Vector3d(0.3, -0.2, 0.0);
  const double per_pixel = 2.0 * 5.0 * std::tan(30.0 * kPi / 180.0) / 500.0;
  CHECK((aniso::screen_drag_to_world(drag) - Eigen::Vector3d(50 * per_pixel, 0, 0)).norm() < 1e-10);
}

TEST_CASE("screen: orthographic drags have a fixed scale", "[screen]") {
  const Camera camera = look_at(Eigen::Vector3d(0, 0, 5), Eigen::Vector3d::Zero());
  // 8 x 6 world units shown on 800 x 600 pixels: 0.01 units per pixel at every depth.
  const Eigen::Matrix4d projection = orthographic(-4, 4, 3, -3, 0.1, 100);
  aniso::ScreenDrag drag = drag_from_center(camera, projection, 30, -20);
  CHECK((aniso::screen_drag_to_world(drag) - Eigen::Vector3d(0.3, 0.2, 0)).norm() < 1e-12);
  drag.anchor = Eigen::Vector3d(1, 1, -40);
  CHECK((aniso::screen_drag_to_world(drag) - Eigen::Vector3d(0.3, 0.2, 0)).norm() < 1e-12);
}

TEST_CASE("screen: a rotated camera maps right and down onto its own axes", "[screen]") {
  const Eigen::Vector3d target(0.5, -0.25, 1.0);
  const Eigen::Vector3d eye = target + Eigen::Vector3d(3, 2, -4);
  const Camera camera = look_at(eye, target);
  const Eigen::Matrix4d projection = perspective(45.0, 800.0 / 600.0, 0.1, 100.0);
  const double distance = (eye - target).norm();
  const double per_pixel = 2.0 * distance * std::tan(22.5 * kPi / 180.0) / 600.0;

  aniso::ScreenDrag drag = drag_from_center(camera, projection, 12, 0);
  drag.anchor = target;
  CHECK((aniso::screen_drag_to_world(drag) - 12 * per_pixel * camera.right()).norm() < 1e-12);
  drag.to_px = Eigen::Vector2d(400, 300 + 9);
  CHECK((aniso::screen_drag_to_world(drag) + 9 * per_pixel * camera.up()).norm() < 1e-12);
  // The drag always lies in the image plane: perpendicular to the view direction.
  drag.to_px = Eigen::Vector2d(431, 277);
  CHECK(std::abs(aniso::screen_drag_to_world(drag).dot((eye - target).normalized())) < 1e-12);
}

TEST_CASE("screen: bad cameras, viewports and inputs are refused", "[screen]") {
  const Camera camera = look_at(Eigen::Vector3d(0, 0, 5), Eigen::Vector3d::Zero());
  const aniso::ScreenDrag good = drag_from_center(camera, perspective(50, 4.0 / 3.0, 0.1, 100), 10, 0);
  REQUIRE_NOTHROW(aniso::screen_drag_to_world(good));

  aniso::ScreenDrag drag = good;
  drag.viewport = Eigen::Vector4d(0, 0, 0, 600);
  CHECK_THAT(bad_parameter_message([&] { aniso::screen_drag_to_world(drag); }),
             Catch::Contains("the viewport is empty (0 x 600 pixels)"));
  drag = good;
  drag.projection.row(3).setZero();
  CHECK_THAT(bad_parameter_message([&] { aniso::screen_drag_to_world(drag); }),
             Catch::Contains("the projection matrix is singular"));
  drag = good;
  drag.view.setZero();
  CHECK_THAT(bad_parameter_message([&] { aniso::screen_drag_to_world(drag); }),
             Catch::Contains("the view matrix is singular"));
  drag = good;
  drag.to_px.x() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(bad_parameter_message([&] { aniso::screen_drag_to_world(drag); }),
             Catch::Contains("the pointer positions are not finite"));
  drag = good;
  drag.view(0, 3) = std::numeric_limits<double>::infinity();
  CHECK_THAT(bad_parameter_message([&] { aniso::screen_drag_to_world(drag); }),
             Catch::Contains("the view matrix is not finite"));
  drag = good;
  drag.anchor = Eigen::Vector3d(0, 0, 10);  // behind a camera at z = 5 looking down -z
  CHECK_THAT(bad_parameter_message([&] { aniso::screen_drag_to_world(drag); }),
             Catch::Contains("the anchor point is behind the camera"));
}

namespace {

// Where a world point lands on screen, in pixels (y down), as three.js's
// Vector3.project followed by the viewport mapping.
Eigen::Vector2d to_pixels(const aniso::ScreenDrag& drag, const Eigen::Vector3d& p) {
  const Eigen::Vector4d clip = drag.projection * drag.view * p.homogeneous();
  const Eigen::Vector2d ndc = clip.head<2>() / clip.w();
  return {drag.viewport[0] + 0.5 * (ndc.x() + 1.0) * drag.viewport[2],
          drag.viewport[1] + 0.5 * (1.0 - ndc.y()) * drag.viewport[3]};
}

// |sin| of the angle between two 2D vectors.
double sine_between(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::abs(a.x() * b.y() - a.y() * b.x()) / (a.norm() * b.norm());
}

}  // namespace

TEST_CASE("screen: with the surface normal the drag becomes the tangent vector seen along it", "[screen]") {
  // A plane z = 0 seen from above at an angle (the app's default view is
  // similar): a 45 degree drag once stretched along a direction seen at 60
  // degrees, the image-plane vector having been projected along the normal.
  Camera camera = look_at(Eigen::Vector3d(3, 4, -3), Eigen::Vector3d::Zero());
  const Eigen::Matrix4d projection = perspective(45, 800.0 / 600.0, 0.1, 100);
  for (const double degrees : {0.0, 30.0, 45.0, 60.0, 90.0, 135.0}) {
    const double a = degrees * kPi / 180.0;
    aniso::ScreenDrag drag = drag_from_center(camera, projection, 100 * std::cos(a), -100 * std::sin(a));
    drag.anchor = Eigen::Vector3d::Zero();
    drag.anchor_normal = Eigen::Vector3d(0, 0, 2);  // any length
    const Eigen::Vector3d d = aniso::screen_drag_to_world(drag);
    INFO("drag at " << degrees << " degrees: " << d.transpose());
    CHECK(std::abs(d.z()) < 1e-12 * d.norm());  // in the tangent plane
    const Eigen::Vector2d seen = to_pixels(drag, 1e-4 * d.normalized()) - to_pixels(drag, Eigen::Vector3d::Zero());
    const Eigen::Vector2d dragged = drag.to_px - drag.from_px;
    CHECK(sine_between(seen, dragged) < 1e-9);
    CHECK(seen.dot(dragged) > 0.0);  // the same way, not the opposite one
    // The whole drag's far end, on the plane, lies on the ray through to_px.
    CHECK((to_pixels(drag, d) - drag.to_px).norm() < 0.5 * (drag.to_px - drag.from_px).norm());

    // Without the normal: the image-plane vector, as before.
    drag.anchor_normal.setZero();
    const Eigen::Vector3d image_plane = aniso::screen_drag_to_world(drag);
    CHECK(std::abs(image_plane.dot((camera.world.block<3, 1>(0, 2)))) < 1e-9 * image_plane.norm());
  }
}

TEST_CASE("screen: a tangent plane seen edge-on falls back to the image-plane vector", "[screen]") {
  const Camera camera = look_at(Eigen::Vector3d(0, 0, 5), Eigen::Vector3d::Zero());
  const Eigen::Matrix4d projection = perspective(45, 800.0 / 600.0, 0.1, 100);
  aniso::ScreenDrag drag = drag_from_center(camera, projection, 0, -50);
  drag.anchor_normal = Eigen::Vector3d(0, 1, 0);  // the plane y = 0, seen exactly edge-on
  const Eigen::Vector3d d = aniso::screen_drag_to_world(drag);
  CHECK(d.allFinite());
  drag.anchor_normal.setZero();
  CHECK((d - aniso::screen_drag_to_world(drag)).norm() < 1e-12);
  drag.anchor_normal = Eigen::Vector3d(0, std::numeric_limits<double>::quiet_NaN(), 1);
  CHECK_THAT(bad_parameter_message([&] { aniso::screen_drag_to_world(drag); }),
             Catch::Contains("the anchor normal is not finite"));
}
