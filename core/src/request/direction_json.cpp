// direction_from_json (op.h): the op's `direction` into a DirectionSource.
#include "anisoform/op.h"
#include "json_fields.h"
#include "op_keys.h"

namespace aniso {
namespace {

DirectionConstraint constraint_from_json(const Json& value, const std::string& where) {
  using namespace json_fields;
  object(value, where);
  reject_unknown_keys(value, op_keys::kConstraint, where);
  DirectionConstraint out;
  out.vertex = integer_at_least(member(value, "vertex", where + ".vertex"), 0, where + ".vertex");
  out.direction = non_zero_vector3(member(value, "direction", where + ".direction"), where + ".direction");
  out.has_amounts = has(value, "su") || has(value, "sv");
  if (has(value, "su")) out.su = finite_number(value["su"], where + ".su");
  if (has(value, "sv")) out.sv = finite_number(value["sv"], where + ".sv");
  return out;
}

// Column-major, as three.js Matrix4.elements.
Eigen::Matrix4d matrix4_from_json(const Json& value, const std::string& field) {
  using namespace json_fields;
  const std::vector<double> m = finite_numbers(value, 16, field);
  return Eigen::Map<const Eigen::Matrix4d>(m.data());
}

ScreenDrag screen_from_json(const Json& direction, const std::string& name) {
  using namespace json_fields;
  const std::string camera_name = name + ".camera";
  const Json& camera = object(member(direction, "camera", camera_name), camera_name);
  reject_unknown_keys(camera, op_keys::kCamera, camera_name);
  ScreenDrag drag;
  const std::vector<double> from = finite_numbers(member(direction, "from", name + ".from"), 2, name + ".from");
  const std::vector<double> to = finite_numbers(member(direction, "to", name + ".to"), 2, name + ".to");
  drag.from_px = {from[0], from[1]};
  drag.to_px = {to[0], to[1]};
  drag.view = matrix4_from_json(member(camera, "view", camera_name + ".view"), camera_name + ".view");
  drag.projection =
      matrix4_from_json(member(camera, "projection", camera_name + ".projection"), camera_name + ".projection");
  const std::vector<double> viewport =
      finite_numbers(member(camera, "viewport", camera_name + ".viewport"), 4, camera_name + ".viewport");
  drag.viewport = {viewport[0], viewport[1], viewport[2], viewport[3]};
  drag.anchor = vector3(member(camera, "anchor", camera_name + ".anchor"), camera_name + ".anchor");
  // Optional: the surface normal at the anchor puts the drag into its tangent plane.
  if (has(camera, "normal")) drag.anchor_normal = vector3(camera["normal"], camera_name + ".normal");
  return drag;
}

}  // namespace

DirectionSource direction_from_json(const Json& direction, const std::string& name) {
  using namespace json_fields;
  object(direction, name);
  const std::string type =
      one_of(member(direction, "type", name + ".type"), op_keys::kDirectionTypes, name + ".type");
  DirectionSource source;
  if (type == "global") {
    reject_unknown_keys(direction, op_keys::kGlobal, name);
    source.kind = DirectionSource::Kind::Global;
    source.vector = non_zero_vector3(member(direction, "vector", name + ".vector"), name + ".vector");
  } else if (type == "curvature") {
    reject_unknown_keys(direction, op_keys::kCurvature, name);
    const std::string which = one_of(member(direction, "which", name + ".which"), {"min", "max"}, name + ".which");
    source.kind = which == "min" ? DirectionSource::Kind::CurvatureMin : DirectionSource::Kind::CurvatureMax;
    // Its range is curvature.h's validate_curvature_smoothing, checked with the mesh.
    if (has(direction, "smoothing")) {
      source.curvature_smoothing = integer_at_least(direction["smoothing"], 0, name + ".smoothing");
    }
  } else if (type == "screen") {
    reject_unknown_keys(direction, op_keys::kScreen, name);
    source.kind = DirectionSource::Kind::Screen;
    source.screen = screen_from_json(direction, name);
  } else if (type == "constraints") {
    reject_unknown_keys(direction, op_keys::kConstraints, name);
    source.kind = DirectionSource::Kind::Constraints;
    const Json& list = member(direction, "constraints", name + ".constraints");
    if (!list.is_array() || list.empty()) refuse(name + ".constraints", "must be a non-empty array");
    for (std::size_t i = 0; i < list.size(); ++i) {
      source.constraints.push_back(
          constraint_from_json(list[i], name + ".constraints[" + std::to_string(i) + "]"));
    }
  } else {
    reject_unknown_keys(direction, op_keys::kDense, name);
    source.kind = DirectionSource::Kind::Dense;
    const std::string field = name + ".directions";
    const Json& xyz = member(direction, "directions", field);
    if (!xyz.is_array() || xyz.size() % 3 != 0) {
      refuse(field, "must be 3 numbers per vertex, got " + describe(xyz));
    }
    source.dense.resize(static_cast<Eigen::Index>(xyz.size() / 3), 3);
    for (std::size_t k = 0; k < xyz.size(); ++k) {
      source.dense(static_cast<Eigen::Index>(k / 3), static_cast<Eigen::Index>(k % 3)) =
          finite_number(xyz[k], field + "[" + std::to_string(k) + "]");
    }
  }
  return source;
}

}  // namespace aniso
