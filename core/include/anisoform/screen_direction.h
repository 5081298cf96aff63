// Turning a pointer drag on the screen into a world-space direction
// (METHOD §4.2): the drag in pixels is unprojected onto the camera's image
// plane at the depth of the picked surface point, or, given the surface normal
// there, onto the surface's tangent plane along the view rays, so that the
// direction is the one the user sees the drag go on that surface.
#pragma once

#include <Eigen/Core>

namespace aniso {

struct ScreenDrag {
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();        // world -> camera (OpenGL)
  Eigen::Matrix4d projection = Eigen::Matrix4d::Identity();  // camera -> clip (OpenGL)
  Eigen::Vector4d viewport{0, 0, 1, 1};                      // x, y, width, height in pixels
  Eigen::Vector2d from_px = Eigen::Vector2d::Zero();         // pixels, y down (DOM)
  Eigen::Vector2d to_px = Eigen::Vector2d::Zero();
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();          // picked world point
  // The surface normal at the anchor (any length); zero when not known.
  Eigen::Vector3d anchor_normal = Eigen::Vector3d::Zero();
};

// A tangent plane seen more nearly edge-on than this (the ratio of its
// shortest to its longest on-screen stretch, about the sine of the angle
// between the view ray and the plane) has no usable on-screen image: a drag
// across it would mean a tangent vector of almost unbounded length.
constexpr double kEdgeOnTangentPlane = 0.05;  // about 3 degrees

// World-space vector from the unprojected `from_px` to `to_px` at the anchor's
// depth: its direction is the drag seen in 3D, its length the drag's length in
// world units at that depth. Throws Error(BadParameter) for a singular matrix,
// an empty viewport, non-finite input or an anchor behind the camera.
//
// With an anchor normal the vector lies in the tangent plane at the anchor:
// the tangent vector whose on-screen image runs along the drag (the view
// ray through the displaced pointer met with that plane, to first order), its
// length the world length the drag covers on the plane there. Projecting the
// image-plane vector along the normal instead turned a 45 degree drag on a
// plane seen at an angle into a stretch seen at 60 degrees. A plane seen
// (nearly) edge-on (kEdgeOnTangentPlane) gives the image-plane vector, which
// the per-element projection then takes into each tangent plane.
Eigen::Vector3d screen_drag_to_world(const ScreenDrag& drag);

}  // namespace aniso
