// The public op's schema (op.h): defaults equal the C++ structs'
// initializers, every refusal names its field and quotes the value, JS's
// non-numbers ("NaN") are refused, and the mesh-dependent defaults are
// resolved in one place (resolve_edit / resolve_flatten).
#include <algorithm>
#include <string>

#include <catch2/catch.hpp>

#include "anisoform/op.h"
#include "anisoform/session.h"
#include "test_support.h"

namespace {

using namespace aniso;
using test::bad_parameter_message;

std::string refusal_of_op(const char* text) {
  return bad_parameter_message([&] { deform_op_from_json(Json::parse(text)); });
}

}  // namespace

TEST_CASE("op: an empty op has the structs' defaults and leaves the mesh's defaults open", "[op]") {
  const DeformOp edit = deform_op_from_json(Json::object());
  const DeformRequest defaults;
  const DeformOp edit_defaults;
  CHECK(edit.request.method == defaults.method);
  CHECK(edit.request.max_iterations == defaults.max_iterations);
  CHECK(edit.request.rotation_steps == defaults.rotation_steps);
  CHECK(edit.request.tolerance == defaults.tolerance);
  CHECK(edit.request.warm_start == defaults.warm_start);
  CHECK(edit.request.elements == defaults.elements);
  CHECK(edit.request.handle_offset == defaults.handle_offset);
  CHECK(edit.request.pins.empty());
  CHECK(edit.request.handles.empty());
  CHECK(edit.request.transform.is_identity());
  CHECK(edit.preview == edit_defaults.preview);
  CHECK_FALSE(edit.direction_given);
  CHECK_FALSE(edit.twist_origin_given);

  const SessionFlatten flatten = flatten_options_from_json(Json::object());
  const SessionFlatten flatten_defaults;
  CHECK(flatten.su == flatten_defaults.su);
  CHECK(flatten.sv == flatten_defaults.sv);
  CHECK(flatten.max_iterations == flatten_defaults.max_iterations);
  CHECK(flatten.tolerance == flatten_defaults.tolerance);
  CHECK(flatten.method == flatten_defaults.method);
  CHECK(flatten.use_selection == flatten_defaults.use_selection);
  CHECK_FALSE(flatten.direction_given);
}

TEST_CASE("op: every field is read into the request", "[op]") {
  const DeformOp edit = deform_op_from_json(Json::parse(R"({
    "method": "andefgrad", "direction": {"type": "curvature", "which": "max", "smoothing": 3},
    "transform": {"scale": [1.5, 0.5], "thickness": 2, "shear": 0.25, "rotate": {"axis": "u", "degrees": 30},
                  "twist": {"axis": [0, 0, 2], "degreesPerUnit": 45, "origin": [1, 2, 3]}},
    "pins": [4, 5], "move": [0, 0, 1], "elements": "spokes-rims", "maxIterations": 7,
    "rotations": "steps", "rotationCoupling": 2.5, "rotationSteps": 3, "tolerance": 0.001, "acceleration": "none",
    "preview": true, "warmStart": false})"));
  const DeformRequest& r = edit.request;
  CHECK(r.method == Method::AnDefGrad);
  CHECK(r.direction.kind == DirectionSource::Kind::CurvatureMax);
  CHECK(r.direction.curvature_smoothing == 3);
  CHECK(r.transform.su == 1.5);
  CHECK(r.transform.sv == 0.5);
  CHECK(r.transform.sn == 2);
  CHECK(r.transform.shear == 0.25);
  CHECK(r.transform.rotate_axis == RotateAxis::U);
  CHECK(r.transform.rotate_degrees == 30);
  CHECK(r.transform.twist);
  CHECK(r.transform.twist_axis == Eigen::Vector3d::UnitZ());  // normalised
  CHECK(r.transform.twist_degrees_per_unit == 45);
  CHECK(r.transform.twist_origin == Eigen::Vector3d(1, 2, 3));
  CHECK(edit.twist_origin_given);
  CHECK(r.pins == std::vector<int>{4, 5});
  CHECK(r.handle_offset == Eigen::Vector3d(0, 0, 1));
  CHECK(r.elements == ArapElements::SpokesAndRims);
  CHECK(r.max_iterations == 7);
  CHECK(r.rotations == RotationScheme::Steps);
  CHECK(r.rotation_coupling == 2.5);
  CHECK(r.rotation_steps == 3);
  CHECK(r.tolerance == 0.001);
  CHECK(r.acceleration == Acceleration::None);
  CHECK(edit.preview);
  CHECK_FALSE(r.warm_start);
  CHECK(edit.direction_given);
}

TEST_CASE("op: direction forms", "[op]") {
  const DirectionSource global = direction_from_json(Json::parse(R"({"type":"global","vector":[0,2,0]})"), "d");
  CHECK(global.kind == DirectionSource::Kind::Global);
  CHECK(global.vector == Eigen::Vector3d(0, 2, 0));
  CHECK(direction_from_json(Json::parse(R"({"type":"curvature","which":"min"})"), "d").curvature_smoothing ==
        DirectionSource().curvature_smoothing);

  const DirectionSource arrows = direction_from_json(
      Json::parse(R"({"type":"constraints","constraints":[{"vertex":3,"direction":[1,0,0]},
                                                          {"vertex":4,"direction":[0,1,0],"su":1.2}]})"),
      "d");
  REQUIRE(arrows.constraints.size() == 2);
  CHECK_FALSE(arrows.constraints[0].has_amounts);
  CHECK(arrows.constraints[1].has_amounts);
  CHECK(arrows.constraints[1].su == 1.2);
  CHECK(arrows.constraints[1].sv == DirectionConstraint().sv);

  const DirectionSource dense =
      direction_from_json(Json::parse(R"({"type":"dense","directions":[1,0,0, 0,1,0]})"), "d");
  REQUIRE(dense.dense.rows() == 2);
  CHECK(dense.dense.row(1) == Eigen::RowVector3d(0, 1, 0));

  Json screen = Json::parse(R"({"type":"screen","from":[10,20],"to":[30,20],
      "camera":{"viewport":[0,0,800,600],"anchor":[0,0,0]}})");
  screen["camera"]["view"] = Json::array();
  screen["camera"]["projection"] = Json::array();
  for (int i = 0; i < 16; ++i) {
    screen["camera"]["view"].push_back(i);  // column-major
    screen["camera"]["projection"].push_back(i % 5 == 0 ? 1 : 0);
  }
  const DirectionSource drag = direction_from_json(screen, "d");
  CHECK(drag.kind == DirectionSource::Kind::Screen);
  CHECK(drag.screen.view(1, 0) == 1);
  CHECK(drag.screen.view(0, 1) == 4);
  CHECK(drag.screen.projection == Eigen::Matrix4d::Identity());
  CHECK(drag.screen.from_px == Eigen::Vector2d(10, 20));
  CHECK(drag.screen.viewport == Eigen::Vector4d(0, 0, 800, 600));
}

TEST_CASE("op: refusals name the field and quote the value", "[op]") {
  CHECK(refusal_of_op(R"({"transform":{"scale":["NaN"]}})") ==
        "op.transform.scale[0] must be a finite number, got 'NaN'");
  CHECK(refusal_of_op(R"({"move":[0,"-Infinity",0]})") == "op.move[1] must be a finite number, got '-Infinity'");
  CHECK(refusal_of_op(R"({"method":"rigid"})") ==
        "op.method must be one of anarap, andefgrad, arap, linear, got 'rigid'");
  CHECK(refusal_of_op(R"({"speed":1})") ==
        "op has an unknown field 'speed' (allowed: method, direction, transform, pins, handles, move, elements, "
        "maxIterations, rotations, rotationCoupling, rotationSteps, tolerance, acceleration, preview, warmStart)");
  CHECK(refusal_of_op(R"({"direction":{"type":"global","vector":[0,0,0]}})") ==
        "op.direction.vector must not be the zero vector");
  CHECK(refusal_of_op(R"({"direction":{"type":"global","vector":[1,"NaN",0]}})") ==
        "op.direction.vector[1] must be a finite number, got 'NaN'");
  CHECK(refusal_of_op(R"({"direction":{"type":"global"}})") == "op.direction.vector is missing");
  CHECK(refusal_of_op(R"({"direction":{"type":"sideways"}})") ==
        "op.direction.type must be one of global, curvature, screen, constraints, dense, got 'sideways'");
  CHECK(refusal_of_op(R"({"direction":{"type":"constraints","constraints":[{"vertex":-1,"direction":[1,0,0]}]}})") ==
        "op.direction.constraints[0].vertex must be an integer >= 0, got -1");
  CHECK(refusal_of_op(R"({"maxIterations":0})") == "op.maxIterations must be an integer >= 1, got 0");
  CHECK(refusal_of_op(R"({"rotationSteps":1.5})") == "op.rotationSteps must be an integer >= 1, got 1.5");
  CHECK(refusal_of_op(R"({"rotations":"spin"})") == "op.rotations must be one of coupled, steps, got 'spin'");
  CHECK(refusal_of_op(R"({"rotationCoupling":0})") == "op.rotationCoupling = 0 is out of range (0.0001 .. 10000)");
  CHECK(refusal_of_op(R"({"rotationCoupling":1e308})") ==
        "op.rotationCoupling = 1e+308 is out of range (0.0001 .. 10000)");
  CHECK(refusal_of_op(R"({"acceleration":"fast"})") == "op.acceleration must be one of lbfgs, anderson, none, got 'fast'");
  CHECK(refusal_of_op(R"({"preview":"yes"})") == "op.preview must be true or false, got 'yes'");
  CHECK(refusal_of_op(R"({"pins":[1,"3"]})") == "op.pins element 1 must be a number, got '3'");
  CHECK(refusal_of_op(R"({"handles":[4294967297]})") ==
        "op.handles element 0 must be an integer from 0 to 2147483647, got 4294967297");
  CHECK(refusal_of_op(R"({"transform":{"rotate":{"axis":"w","degrees":3}}})") ==
        "op.transform.rotate.axis must be one of n, u, v, got 'w'");
  CHECK(refusal_of_op(R"({"transform":{"twist":{"axis":[0,0,1]}}})") ==
        "op.transform.twist.degreesPerUnit is missing");
  CHECK(refusal_of_op(R"([1,2])") == "op must be an object");
  CHECK(refusal_of_op(R"({"maxIterations":10001})") == "op.maxIterations must be an integer from 1 to 10000, got 10001");
  CHECK(refusal_of_op(R"({"rotationSteps":1e9})") ==
        "op.rotationSteps must be an integer from 1 to 10000, got 1000000000");
  // Ranges are the core's validators', named by where the value came from.
  CHECK(refusal_of_op(R"({"transform":{"scale":-1}})") == "op.transform: scale su must be positive, got -1");
  CHECK(refusal_of_op(R"({"transform":{"shear":1000}})").rfind("op.transform: shear", 0) == 0);

  const auto flatten_refusal = [](const char* text) {
    return bad_parameter_message([&] { flatten_options_from_json(Json::parse(text)); });
  };
  CHECK(flatten_refusal(R"({"compress":[0.8,"NaN"]})") ==
        "flatten: options.compress[1] must be a finite number, got 'NaN'");
  CHECK(flatten_refusal(R"({"compress":0})").rfind("flatten: options.compress must be positive", 0) == 0);
  CHECK(flatten_refusal(R"({"compress":[1,2,3]})") ==
        "flatten: options.compress must be su, [su] or [su, sv], got an array of length 3");
  CHECK(flatten_refusal(R"({"direction":{"type":"curvature","which":"min"}})") ==
        "flatten: options.direction.type must be one of global, constraints, got 'curvature'");
  CHECK(flatten_refusal(R"({"tolerance":-1})") == "flatten: options.tolerance must be >= 0, got -1");
  CHECK(flatten_refusal("null") == "flatten: options must be an object");
  CHECK(flatten_refusal(R"({"maxIterations":20000})") ==
        "flatten: options.maxIterations must be an integer from 1 to 10000, got 20000");
  CHECK(flatten_refusal(R"({"refine":1})") == "flatten: options.refine must be true or false, got 1");
  CHECK(flatten_options_from_json(Json::parse("{}")).refine);
  CHECK_FALSE(flatten_options_from_json(Json::parse(R"({"refine":false})")).refine);

  const auto region_refusal = [](const char* text) {
    return bad_parameter_message([&] { region_from_json(Json::parse(text)); });
  };
  CHECK(region_refusal(R"({})") == "region must have exactly one of all, sphere, box, vertices; got none");
  CHECK(region_refusal(R"({"all":true,"box":{}})") ==
        "region must have exactly one of all, sphere, box, vertices; got all, box");
  CHECK(region_refusal(R"({"sphere":{"center":[0,0,0],"radius":"Infinity"}})") ==
        "region.sphere.radius must be a finite number, got 'Infinity'");
  CHECK(region_refusal(R"({"vertices":[1,2],"weights":[1]})") ==
        "region.weights must be 2 finite numbers, got an array of length 1");
  CHECK(bad_parameter_message([] { selection_mode_from_json("union"); }) ==
        "select: options.mode must be one of replace, add, subtract, got 'union'");
}

TEST_CASE("op: regions and modes", "[op]") {
  const Region sphere = region_from_json(Json::parse(R"({"sphere":{"center":[1,2,3],"radius":0.5}})"));
  CHECK(sphere.kind == Region::Kind::Sphere);
  CHECK(sphere.center == Eigen::Vector3d(1, 2, 3));
  CHECK(sphere.radius == 0.5);
  const Region list = region_from_json(Json::parse(R"({"vertices":[3,1],"weights":[0.5,1]})"));
  CHECK(list.vertices == std::vector<int>{3, 1});
  CHECK(list.weights == std::vector<double>{0.5, 1});
  CHECK(region_from_json(Json::parse(R"({"all":true})")).kind == Region::Kind::All);
  CHECK(selection_mode_from_json("subtract") == SelectionMode::Subtract);
}

TEST_CASE("op: the mesh's defaults are resolved by the session's rule", "[op]") {
  const Mesh mesh = test::load("closed/torus.obj");
  const BoundingBox box = bounding_box(mesh.V);
  const Eigen::Vector3d extent = box.max - box.min;
  Eigen::Index longest = 0;
  extent.maxCoeff(&longest);
  CHECK(longest_axis(box) == Eigen::Vector3d::Unit(longest));
  CHECK(longest_axis(BoundingBox{}) == Eigen::Vector3d::UnitX());  // ties: x

  const int n = mesh.num_vertices();
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(n);
  weights[0] = 1.0;
  weights[1] = 0.9995;
  weights[2] = 0.5;
  const DeformOp arap = deform_op_from_json(Json::parse(R"({"method":"arap","move":[0,0,1]})"));
  const DeformRequest resolved = resolve_edit(arap, mesh.V, box, weights);
  CHECK(resolved.handles == std::vector<int>{0, 1});
  CHECK(static_cast<int>(resolved.pins.size()) == n - 3);
  CHECK(resolved.pins.front() == 3);
  CHECK(resolved.direction.vector == longest_axis(box));

  // Nothing selected: no handle, so nothing moves (it used to be the whole
  // mesh, which the CLI reported as unchanged); given pins and handles are kept.
  const DeformOp pinned = deform_op_from_json(Json::parse(R"({"method":"arap","pins":[7]})"));
  const DeformRequest none = resolve_edit(pinned, mesh.V, box, Eigen::VectorXd::Zero(n));
  CHECK(none.handles.empty());
  CHECK(none.pins == std::vector<int>{7});
  const DeformOp handled = deform_op_from_json(Json::parse(R"({"method":"arap","handles":[5, 6]})"));
  const DeformRequest kept = resolve_edit(handled, mesh.V, box, weights);
  CHECK(kept.handles == std::vector<int>{5, 6});
  // Without pins, the unselected vertices hold the mesh, handles or not (test_arap_pins.cpp).
  CHECK(static_cast<int>(kept.pins.size()) == n - 5);
  CHECK(std::find(kept.pins.begin(), kept.pins.end(), 5) == kept.pins.end());

  // Preview caps the iterations; a twist without origin turns about the selection's centroid line.
  const DeformOp twist = deform_op_from_json(
      Json::parse(R"({"preview":true,"transform":{"twist":{"axis":[0,0,1],"degreesPerUnit":10}}})"));
  const DeformRequest turned = resolve_edit(twist, mesh.V, box, weights);
  CHECK(turned.max_iterations == kPreviewIterations);
  CHECK_FALSE(turned.final_energy);
  CHECK(resolve_edit(arap, mesh.V, box, weights).final_energy);
  CHECK(turned.transform.twist_origin == default_twist_origin(mesh.V, weights, Eigen::Vector3d::UnitZ()));

  const SessionFlatten flatten = resolve_flatten(flatten_options_from_json(Json::object()), mesh.V, mesh.F);
  CHECK(flatten.directions.kind == FlattenDirections::Kind::Global);
  CHECK(flatten.directions.global == longest_axis(box));
}

TEST_CASE("op: the model unit is guessed from the largest side of the box", "[op]") {
  // The SMPL torso panel is in metres (about 0.3 x 0.4 m).
  const BoundingBox torso = bounding_box(test::load("open/human_woman_torso_front_patch.obj").V);
  CHECK(guess_model_unit(torso).name == "m");
  CHECK(guess_model_unit(torso).mm_per_unit == 1000.0);
  const auto box_of_side = [](double side) { return BoundingBox{Eigen::Vector3d::Zero(), Eigen::Vector3d(side, 0.5 * side, 0.0)}; };
  CHECK(guess_model_unit(box_of_side(4.99)).name == "m");
  CHECK(guess_model_unit(box_of_side(5.0)).name == "cm");
  CHECK(guess_model_unit(box_of_side(499.0)).mm_per_unit == 10.0);
  CHECK(guess_model_unit(box_of_side(500.0)).name == "mm");
  CHECK(guess_model_unit(box_of_side(1800.0)).mm_per_unit == 1.0);
  CHECK(guess_model_unit(BoundingBox{}).name == "m");  // an empty mesh
}

TEST_CASE("op: results as JSON and the schema", "[op]") {
  DeformOpResult result;
  result.selected = 12;
  result.energy_history = {3.0, 2.0};
  result.total_ms = 1.5;
  const Json json = to_json(result);
  CHECK(json["selected"] == 12);
  CHECK(json["energyHistory"] == Json::array({3.0, 2.0}));
  CHECK(json["ms"] == 1.5);
  FlattenMetrics metrics;
  metrics.boundary_loops = 2;
  metrics.method = "anisotropic";
  CHECK(to_json(metrics)["boundaryLoops"] == 2);
  CHECK(to_json(metrics)["method"] == "anisotropic");

  const Json schema = op_schema();
  CHECK(schema["op"].size() == 15);
  CHECK(schema["op.transform"] == Json::array({"scale", "thickness", "shear", "rotate", "twist"}));
  CHECK(schema["flatten"].size() == 7);
}
