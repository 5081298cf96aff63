// deform_op_from_json (op.h): the public op into a DeformOp, its
// transform checked by the core's own rule (transforms.h validate).
#include <cmath>

#include "anisoform/op.h"
#include "anisoform/transforms.h"
#include "json_fields.h"
#include "op_keys.h"

namespace aniso {
namespace {

// {scale?: su | [su] | [su, sv], thickness?, shear?, rotate?: {axis, degrees},
//  twist?: {axis, degreesPerUnit, origin?}}; sets *origin_given.
TransformSpec transform_from_json(const Json& t, bool* origin_given) {
  using namespace json_fields;
  const std::string name = "op.transform";
  object(t, name);
  reject_unknown_keys(t, op_keys::kTransform, name);
  TransformSpec spec;
  if (has(t, "scale")) {
    const Json& scale = t["scale"];
    if (scale.is_number()) {
      spec.su = finite_number(scale, name + ".scale");
    } else {
      if (!scale.is_array() || scale.empty() || scale.size() > 2) {
        refuse(name + ".scale", "must be su or [su, sv], got " + describe(scale));
      }
      spec.su = finite_number(scale[0], name + ".scale[0]");
      if (scale.size() == 2) spec.sv = finite_number(scale[1], name + ".scale[1]");
    }
  }
  if (has(t, "thickness")) spec.sn = finite_number(t["thickness"], name + ".thickness");
  if (has(t, "shear")) spec.shear = finite_number(t["shear"], name + ".shear");
  if (has(t, "rotate")) {
    const std::string where = name + ".rotate";
    const Json& rotate = object(t["rotate"], where);
    reject_unknown_keys(rotate, op_keys::kRotate, where);
    const std::string axis = one_of(member(rotate, "axis", where + ".axis"), {"n", "u", "v"}, where + ".axis");
    spec.rotate_axis = axis == "n" ? RotateAxis::Normal : axis == "u" ? RotateAxis::U : RotateAxis::V;
    spec.rotate_degrees = finite_number(member(rotate, "degrees", where + ".degrees"), where + ".degrees");
  }
  if (has(t, "twist")) {
    const std::string where = name + ".twist";
    const Json& twist = object(t["twist"], where);
    reject_unknown_keys(twist, op_keys::kTwist, where);
    spec.twist = true;
    spec.twist_axis = non_zero_vector3(member(twist, "axis", where + ".axis"), where + ".axis").stableNormalized();
    spec.twist_degrees_per_unit =
        finite_number(member(twist, "degreesPerUnit", where + ".degreesPerUnit"), where + ".degreesPerUnit");
    *origin_given = has(twist, "origin");
    if (*origin_given) spec.twist_origin = vector3(twist["origin"], where + ".origin");
  }
  naming_field(name, [&] { validate(spec); });  // the ranges of limits.h
  return spec;
}

Method method_from_json(const Json& value) {
  using namespace json_fields;
  return parse_method(one_of(value, {"anarap", "andefgrad", "arap", "linear"}, "op.method"));
}

Acceleration acceleration_from_json(const Json& value, const std::string& field) {
  const std::string name = json_fields::one_of(value, op_keys::kAccelerations, field);
  return name == "lbfgs" ? Acceleration::Lbfgs : name == "anderson" ? Acceleration::Anderson : Acceleration::None;
}

RotationScheme rotation_scheme_from_json(const Json& value, const std::string& field) {
  return json_fields::one_of(value, op_keys::kRotationSchemes, field) == "coupled" ? RotationScheme::Coupled
                                                                                   : RotationScheme::Steps;
}

}  // namespace

RotationScheme rotation_scheme_from_name(const std::string& name, const std::string& field) {
  return rotation_scheme_from_json(Json(name), field);
}

Acceleration acceleration_from_name(const std::string& name, const std::string& field) {
  return acceleration_from_json(Json(name), field);
}

DeformOp deform_op_from_json(const Json& op) {
  using namespace json_fields;
  object(op, "op");
  reject_unknown_keys(op, op_keys::kOp, "op");
  DeformOp edit;
  DeformRequest& request = edit.request;
  if (has(op, "method")) request.method = method_from_json(op["method"]);
  edit.direction_given = has(op, "direction");
  if (edit.direction_given) request.direction = direction_from_json(op["direction"], "op.direction");
  if (has(op, "transform")) request.transform = transform_from_json(op["transform"], &edit.twist_origin_given);
  if (has(op, "pins")) request.pins = indices(op["pins"], "op.pins");
  if (has(op, "handles")) request.handles = indices(op["handles"], "op.handles");
  if (has(op, "move")) request.handle_offset = vector3(op["move"], "op.move");
  if (has(op, "elements")) {
    request.elements = one_of(op["elements"], {"spokes", "spokes-rims"}, "op.elements") == "spokes"
                           ? ArapElements::Spokes
                           : ArapElements::SpokesAndRims;
  }
  if (has(op, "maxIterations")) request.max_iterations = iteration_count(op["maxIterations"], "op.maxIterations");
  if (has(op, "rotations")) request.rotations = rotation_scheme_from_json(op["rotations"], "op.rotations");
  if (has(op, "rotationCoupling")) {
    request.rotation_coupling = finite_number(op["rotationCoupling"], "op.rotationCoupling");
    validate_rotation_coupling(request.rotation_coupling, "op.rotationCoupling");
  }
  if (has(op, "acceleration")) request.acceleration = acceleration_from_json(op["acceleration"], "op.acceleration");
  if (has(op, "rotationSteps")) request.rotation_steps = iteration_count(op["rotationSteps"], "op.rotationSteps");
  if (has(op, "tolerance")) {
    request.tolerance = finite_number(op["tolerance"], "op.tolerance");
    if (request.tolerance < 0.0) refuse("op.tolerance", "must be >= 0, got " + describe(op["tolerance"]));
  }
  if (has(op, "preview")) edit.preview = flag(op["preview"], "op.preview");
  if (has(op, "warmStart")) request.warm_start = flag(op["warmStart"], "op.warmStart");
  return edit;
}

}  // namespace aniso
