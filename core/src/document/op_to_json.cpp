// to_json(DeformOp) and to_json(DirectionSource) (op.h): the inverse of
// deform_op_from_json, so that the edit document stores exactly what was
// solved. test_document.cpp checks parse(to_json(x)) == x.
#include "anisoform/op.h"

namespace aniso {
namespace {

Json xyz_json(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

// Column-major, as matrix4_from_json reads it (three.js Matrix4.elements).
Json matrix4_json(const Eigen::Matrix4d& m) {
  Json out = Json::array();
  for (int k = 0; k < 16; ++k) out.push_back(m.data()[k]);
  return out;
}

Json transform_json(const TransformSpec& t, bool origin_given) {
  Json out = Json::object();
  if (t.su != 1.0 || t.sv != 1.0) out["scale"] = Json::array({t.su, t.sv});
  if (t.sn != 1.0) out["thickness"] = t.sn;
  if (t.shear != 0.0) out["shear"] = t.shear;
  if (t.rotate_axis != RotateAxis::None) {
    const char* axis = t.rotate_axis == RotateAxis::Normal ? "n" : t.rotate_axis == RotateAxis::U ? "u" : "v";
    out["rotate"] = {{"axis", axis}, {"degrees", t.rotate_degrees}};
  }
  if (t.twist) {
    Json twist = {{"axis", xyz_json(t.twist_axis)}, {"degreesPerUnit", t.twist_degrees_per_unit}};
    if (origin_given) twist["origin"] = xyz_json(t.twist_origin);
    out["twist"] = twist;
  }
  return out;
}

Json constraint_json(const DirectionConstraint& c) {
  Json out = {{"vertex", c.vertex}, {"direction", xyz_json(c.direction)}};
  if (c.has_amounts) {
    out["su"] = c.su;
    out["sv"] = c.sv;
  }
  return out;
}

}  // namespace

Json to_json(const DirectionSource& d) {
  switch (d.kind) {
    case DirectionSource::Kind::Global:
      return {{"type", "global"}, {"vector", xyz_json(d.vector)}};
    case DirectionSource::Kind::CurvatureMin:
    case DirectionSource::Kind::CurvatureMax:
      return {{"type", "curvature"},
              {"which", d.kind == DirectionSource::Kind::CurvatureMin ? "min" : "max"},
              {"smoothing", d.curvature_smoothing}};
    case DirectionSource::Kind::Screen: {
      const ScreenDrag& s = d.screen;
      Json camera = {{"view", matrix4_json(s.view)},
                     {"projection", matrix4_json(s.projection)},
                     {"viewport", Json::array({s.viewport[0], s.viewport[1], s.viewport[2], s.viewport[3]})},
                     {"anchor", xyz_json(s.anchor)}};
      if (!s.anchor_normal.isZero(0.0)) camera["normal"] = xyz_json(s.anchor_normal);
      return {{"type", "screen"},
              {"from", Json::array({s.from_px.x(), s.from_px.y()})},
              {"to", Json::array({s.to_px.x(), s.to_px.y()})},
              {"camera", camera}};
    }
    case DirectionSource::Kind::Constraints: {
      Json list = Json::array();
      for (const DirectionConstraint& c : d.constraints) list.push_back(constraint_json(c));
      return {{"type", "constraints"}, {"constraints", list}};
    }
    case DirectionSource::Kind::Dense: {
      Json xyz = Json::array();
      for (Eigen::Index i = 0; i < d.dense.rows(); ++i)
        for (int k = 0; k < 3; ++k) xyz.push_back(d.dense(i, k));
      return {{"type", "dense"}, {"directions", xyz}};
    }
  }
  return Json::object();
}

Json to_json(const DeformOp& edit) {
  const DeformRequest& r = edit.request;
  Json op = {{"method", method_name(r.method)}};
  if (edit.direction_given) op["direction"] = to_json(r.direction);
  op["transform"] = transform_json(r.transform, edit.twist_origin_given);
  // Empty lists are "not given": ARAP then takes its handles and pins from
  // the selection (resolve_edit), and a resolved op lists them.
  if (!r.pins.empty()) op["pins"] = r.pins;
  if (!r.handles.empty()) op["handles"] = r.handles;
  op["move"] = xyz_json(r.handle_offset);
  op["elements"] = r.elements == ArapElements::Spokes ? "spokes" : "spokes-rims";
  op["maxIterations"] = r.max_iterations;
  op["rotations"] = r.rotations == RotationScheme::Coupled ? "coupled" : "steps";
  op["rotationCoupling"] = r.rotation_coupling;
  op["rotationSteps"] = r.rotation_steps;
  op["tolerance"] = r.tolerance;
  op["acceleration"] = r.acceleration == Acceleration::Lbfgs      ? "lbfgs"
                       : r.acceleration == Acceleration::Anderson ? "anderson"
                                                                  : "none";
  op["preview"] = edit.preview;
  op["warmStart"] = r.warm_start;
  return op;
}

}  // namespace aniso
