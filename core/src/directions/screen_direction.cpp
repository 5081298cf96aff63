// A pointer drag turned into a world-space vector (METHOD §4.2), in the
// image plane or, given the surface normal, in the tangent plane at the anchor.
//
// Conventions are OpenGL's, as in three.js: `view` is camera.matrixWorldInverse
// and `projection` camera.projectionMatrix, both as mathematical matrices
// (three.js stores them column-major; Eigen's operator() is (row, col)). Clip
// space has y up and depth in [-1, 1]. Pixels are DOM pixels with y down, and
// the viewport's (x, y) is its top-left corner in those same pixels, so a
// pointer at (x, y) is the viewport's top-left corner and one at
// (x + width, y + height) its bottom-right.
#include "anisoform/screen_direction.h"

#include <cmath>
#include <optional>
#include <sstream>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "anisoform/error.h"

namespace aniso {
namespace {

[[noreturn]] void bad_screen_drag(const std::string& message) {
  fail(ErrorCode::BadParameter, "screen drag: " + message);
}

// Normalised device coordinates (x right, y up, both in [-1, 1] over the viewport).
Eigen::Vector2d pixel_to_ndc(const Eigen::Vector2d& px, const Eigen::Vector4d& viewport) {
  return {2.0 * (px.x() - viewport[0]) / viewport[2] - 1.0, 1.0 - 2.0 * (px.y() - viewport[1]) / viewport[3]};
}

Eigen::Vector3d unproject(const Eigen::Matrix4d& clip_to_world, const Eigen::Vector2d& ndc, double ndc_depth) {
  const Eigen::Vector4d world = clip_to_world * Eigen::Vector4d(ndc.x(), ndc.y(), ndc_depth, 1.0);
  if (!(std::abs(world.w()) > 0.0)) bad_screen_drag("the drag cannot be unprojected (w = 0)");
  return world.head<3>() / world.w();
}

// Pixels moved per unit world displacement at `point` (2 by 3; y down, as
// the pointer): the derivative of the perspective division of clip = M p.
Eigen::Matrix<double, 2, 3> pixels_per_world(const Eigen::Matrix4d& world_to_clip, const Eigen::Vector3d& point,
                                             const Eigen::Vector4d& viewport) {
  const Eigen::Vector4d clip = world_to_clip * point.homogeneous();
  const double w = clip.w();
  Eigen::Matrix<double, 2, 3> ndc;
  ndc.row(0) = (world_to_clip.block<1, 3>(0, 0) - (clip.x() / w) * world_to_clip.block<1, 3>(3, 0)) / w;
  ndc.row(1) = (world_to_clip.block<1, 3>(1, 0) - (clip.y() / w) * world_to_clip.block<1, 3>(3, 0)) / w;
  ndc.row(0) *= 0.5 * viewport[2];
  ndc.row(1) *= -0.5 * viewport[3];
  return ndc;
}

// The tangent vector at the anchor whose on-screen image is the drag, or
// nothing when the tangent plane is seen (nearly) edge-on.
std::optional<Eigen::Vector3d> tangent_drag(const ScreenDrag& drag, const Eigen::Matrix4d& world_to_clip) {
  const Eigen::Vector3d n = drag.anchor_normal.stableNormalized();
  // Any two orthonormal tangents t1, t2; the result does not depend on them.
  const Eigen::Vector3d t1 = n.unitOrthogonal();
  const Eigen::Vector3d t2 = n.cross(t1);
  Eigen::Matrix<double, 3, 2> tangents;
  tangents << t1, t2;
  const Eigen::Matrix2d on_screen = pixels_per_world(world_to_clip, drag.anchor, drag.viewport) * tangents;
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(on_screen);
  const Eigen::Vector2d stretch = svd.singularValues();
  if (!(stretch[1] > kEdgeOnTangentPlane * stretch[0])) return std::nullopt;
  return tangents * on_screen.inverse() * (drag.to_px - drag.from_px);
}

void check_input(const ScreenDrag& drag) {
  if (!drag.view.allFinite()) bad_screen_drag("the view matrix is not finite");
  if (!drag.projection.allFinite()) bad_screen_drag("the projection matrix is not finite");
  if (!drag.viewport.allFinite()) bad_screen_drag("the viewport is not finite");
  if (!drag.from_px.allFinite() || !drag.to_px.allFinite()) bad_screen_drag("the pointer positions are not finite");
  if (!drag.anchor.allFinite()) bad_screen_drag("the anchor point is not finite");
  if (!drag.anchor_normal.allFinite()) bad_screen_drag("the anchor normal is not finite");
  if (!(drag.viewport[2] > 0.0 && drag.viewport[3] > 0.0)) {
    std::ostringstream message;
    message << "the viewport is empty (" << drag.viewport[2] << " x " << drag.viewport[3] << " pixels)";
    bad_screen_drag(message.str());
  }
}

}  // namespace

Eigen::Vector3d screen_drag_to_world(const ScreenDrag& drag) {
  check_input(drag);
  const Eigen::FullPivLU<Eigen::Matrix4d> view_lu(drag.view);
  if (!view_lu.isInvertible()) bad_screen_drag("the view matrix is singular");
  const Eigen::FullPivLU<Eigen::Matrix4d> projection_lu(drag.projection);
  if (!projection_lu.isInvertible()) bad_screen_drag("the projection matrix is singular");

  const Eigen::Vector4d anchor_clip = drag.projection * drag.view *
                                      Eigen::Vector4d(drag.anchor.x(), drag.anchor.y(), drag.anchor.z(), 1.0);
  // w_clip is the distance in front of the camera (perspective) or 1 (orthographic).
  if (!(anchor_clip.w() > 0.0)) bad_screen_drag("the anchor point is behind the camera");
  const double ndc_depth = anchor_clip.z() / anchor_clip.w();

  if (!drag.anchor_normal.isZero(0.0)) {
    if (const auto tangent = tangent_drag(drag, drag.projection * drag.view)) return *tangent;
  }
  const Eigen::Matrix4d clip_to_world = view_lu.inverse() * projection_lu.inverse();
  const Eigen::Vector3d from = unproject(clip_to_world, pixel_to_ndc(drag.from_px, drag.viewport), ndc_depth);
  const Eigen::Vector3d to = unproject(clip_to_world, pixel_to_ndc(drag.to_px, drag.viewport), ndc_depth);
  return to - from;
}

}  // namespace aniso
