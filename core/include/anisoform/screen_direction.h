// Turning a pointer drag on the screen into a world-space direction
// (METHOD §4.2): the drag in pixels is unprojected onto the camera's image
// plane at the depth of the picked surface point.
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
};

// World-space vector from the unprojected `from_px` to `to_px` at the anchor's
// depth: its direction is the drag seen in 3D, its length the drag's length in
// world units at that depth. Throws Error(BadParameter) for a singular matrix,
// an empty viewport, non-finite input or an anchor behind the camera.
Eigen::Vector3d screen_drag_to_world(const ScreenDrag& drag);

}  // namespace aniso
