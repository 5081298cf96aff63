// The public op: one edit, one flattening, one region, as JSON. This is the
// one place its schema lives: the WASM module, the edit document and
// `anisoform deform --op FILE` all hand their JSON here; the CLI's flags build
// the same DeformOp, and every host deforms through Session::deform.
//
// An op (every key optional):
//   {method: 'anarap'|'andefgrad'|'arap'|'linear',
//    direction: {type:'global', vector:[x,y,z]}
//             | {type:'curvature', which:'min'|'max', smoothing?}
//             | {type:'screen', from:[x,y], to:[x,y], camera:{view[16], projection[16], viewport[4], anchor[3], normal[3]?}}
//             | {type:'constraints', constraints:[{vertex, direction:[x,y,z], su?, sv?}]}
//             | {type:'dense', directions:[#V*3]},
//    transform: {scale?: su|[su]|[su,sv], thickness?, shear?, rotate?: {axis:'n'|'u'|'v', degrees},
//                twist?: {axis:[x,y,z], degreesPerUnit, origin?:[x,y,z]}},
//    pins?, handles?: [vertex...], move?: [x,y,z], elements?: 'spokes'|'spokes-rims',
//    maxIterations?, rotationSteps?, tolerance?, preview?, warmStart?}
//
// Defaults are the C++ structs' initializers (DeformRequest, TransformSpec,
// DeformOp, SessionFlatten). Defaults that depend on the mesh are left
// "not given" in the parsed struct (DeformOp::direction_given, ...) and
// resolved by resolve_edit / resolve_flatten, which the Session calls.
//
// JSON cannot hold NaN or infinities: JS callers send them as the strings
// "NaN", "Infinity", "-Infinity", which are refused like any other
// non-number, quoting the value. Every refusal is Error(BadParameter) naming
// the field path: "op.transform.scale[0] must be a finite number, got 'NaN'".
#pragma once

#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "anisoform/deformer.h"
#include "anisoform/flatten.h"
#include "anisoform/mesh.h"
#include "anisoform/selection.h"
#include "anisoform/session.h"

namespace aniso {

// Ordered: results keep their keys in the order they are written, for people
// reading them (the CLI prints them as they are).
using Json = nlohmann::ordered_json;

// ---- JSON -> request ------------------------------------------------------

// A JSON text (an edit document, the CLI's --op file) as JSON, every failure
// Error(BadParameter) starting with `what` ("the document", "--op: op.json"):
// "WHAT is not valid JSON: ..." for a syntax error, "WHAT holds a number out
// of range: 1e400 ..." for a number no double holds (nlohmann reports it as
// out_of_range, which the CLI took for an internal error, exit 3).
Json json_from_text(const std::string& text, const std::string& what);

DeformOp deform_op_from_json(const Json& op);
// {compress?: su|[su]|[su,sv], direction?: global or constraints (as an op's),
//  baseline?: 'uniform', patch?: 'mesh'|'selection', maxIterations?, tolerance?, refine?}
SessionFlatten flatten_options_from_json(const Json& options);
// {all:true} | {sphere:{center, radius}} | {box:{min, max}} | {vertices:[...], weights?:[...]}
Region region_from_json(const Json& region);
// A direction source as an op's `direction`; `field` names it in messages
// ("op.direction", "direction").
DirectionSource direction_from_json(const Json& direction, const std::string& field);
SelectionMode selection_mode_from_json(const Json& mode);  // "replace" | "add" | "subtract"

// ---- the hosts' small option objects (the JS API's; op_schema lists them) --

// select(region, options): {falloff?, mode?}. The falloff's range is
// apply_falloff's rule (selection.h).
struct SelectOptions {
  double falloff = 0.0;
  SelectionMode mode = SelectionMode::Replace;
};
SelectOptions select_options_from_json(const Json& options);

// setMesh(positions, triangles, options): {weld?}.
struct MeshOptions {
  bool weld = false;  // merge vertices at equal positions (an unindexed three.js geometry)
};
MeshOptions mesh_options_from_json(const Json& options);

// exportPattern(format, options): {mmPerUnit?}. Its range is the pattern
// writer's rule (pattern_export.h).
struct PatternOptions {
  double mm_per_unit = 1.0;
};
PatternOptions pattern_options_from_json(const Json& options);

// The names the hosts use for the core's enums; Error(BadParameter) naming
// the choices otherwise.
DistortionKind distortion_kind_from_name(const std::string& name);            // "area" | "stretch"
DistortionReference distortion_reference_from_name(const std::string& name);  // "rest" | "loaded"
MeshFormat mesh_format_from_name(const std::string& name);                    // "obj" | "off" | "ply" | "stl"
// "coupled" | "steps" (op.rotations); `field` names the option in the message.
RotationScheme rotation_scheme_from_name(const std::string& name, const std::string& field);
// "lbfgs" | "anderson" | "none" (op.acceleration); `field` names the option in the message.
Acceleration acceleration_from_name(const std::string& name, const std::string& field);

// ---- defaults that depend on the mesh --------------------------------------

// The unit axis along the longest side of the box (x on ties, so a cube or an
// empty box gives x): the default direction wherever none is given.
Eigen::Vector3d longest_axis(const BoundingBox& box);

// The unit the mesh's coordinates are most likely in, for pattern files in
// millimetres. Garments and the bodies they fit are 5 cm .. 5 m, so the
// box's largest side L says: L < 5 -> metres (1000 mm per unit), L < 500 ->
// centimetres (10), else millimetres (1); between 50 and 500 both cm and mm
// fit, and cm (body-sized) wins. A guess: hosts say so and let the user
// change it (mesh info "unitGuess"; the CLI's --mm-per-unit is explicit).
struct ModelUnitGuess {
  std::string name;  // "m" | "cm" | "mm"
  double mm_per_unit = 1.0;
  double largest_side = 0.0;  // the size it was guessed from, in model units
};
ModelUnitGuess guess_model_unit(const BoundingBox& box);

// The DeformRequest an edit means on this mesh: `edit.request` with its
// "not given" parts filled in and `weights` as the selection:
//   direction not given: global along longest_axis(loaded_box), the mesh as loaded;
//   twist origin not given: default_twist_origin (transforms.h) of the rest pose;
//   Arap with no handles (none would move: the edit would do nothing): handles
//     are the vertices with selection weight >= 0.999 (the soft border in
//     between deforms as rigidly as possible); nothing selected: no handle
//     (nothing moves);
//   Arap without pins (handles given or not): pins are the vertices with
//     weight 0 that are not handles; given handles and a move with nothing
//     unselected to hold the mesh (a rigid translation of all of it) are
//     refused, Error(BadParameter);
//   preview: max_iterations capped at kPreviewIterations.
DeformRequest resolve_edit(const DeformOp& edit, const Positions& rest, const BoundingBox& loaded_box,
                           const Eigen::VectorXd& weights);

// Why a resolved edit leaves the mesh unchanged, in words for a warning
// ("the selection holds no vertex: the mesh is left unchanged", with
// `selection` naming what selected), or "" when it can move something: no
// selected vertex; ARAP with no handle (none selected with weight 1); every
// selected vertex pinned.
std::string unchanged_reason(const DeformRequest& resolved, const std::string& selection = "the selection");

// A flattening's default direction: longest_axis of the positions it flattens
// (their shape_bounding_box, mesh.h).
SessionFlatten resolve_flatten(const SessionFlatten& request, const Positions& positions, const Triangles& faces);

// ---- results -> JSON (the keys the JS API returns) -------------------------

// {vertices, triangles, components, boundaryLoops, edgeManifold, vertexManifold,
//  consistentlyOriented, degenerateTriangles, duplicateFaces, unreferencedVertices,
//  bbox: {min, max}, unitGuess: {name, mmPerUnit} (guess_model_unit),
//  problems: [{kind, element, message}] (the first kMaxProblemsKept of each kind),
//  problemCounts: {kind: how many, for each kind found}, notes}
Json to_json(const SessionMeshInfo& info);
// {selected, iterations, energy, energyHistory, converged, directionsFilled,
//  inverted, factorizations, precomputeMs, solveMs, ms, warnings}
Json to_json(const DeformOpResult& result);
// {triangles, vertices, components, boundaryLoops, flipped, compressionErrorMean,
//  compressionErrorMax, crossErrorMean, crossErrorMax, areaDistortionMean,
//  shearDegreesMean, shearDegreesMax, nearNormalDirections,
//  iterations, energy, converged, seconds, filledDirections, initialization, method,
//  problem, warnings, suggestedCuts} (problem: flatten_problem, "" when usable as one piece;
//  warnings: flatten_warnings, what a usable pattern still should say;
//  suggestedCuts: [{vertices, vertex, centroid, errorMean, triangles}], FlattenRegion)
Json to_json(const FlattenMetrics& metrics);

// ---- request -> JSON (the document stores what was solved) ----------------

// The op that deform_op_from_json reads back as `edit` (round trip: every
// value and every "given" flag). Keys left out are the ones not given; a
// screen direction stays a screen drag (resolve_for_document, document.h,
// turns it into the global vector first).
Json to_json(const DeformOp& edit);
// A direction source as an op's `direction`.
Json to_json(const DirectionSource& direction);

// The allowed keys of each object of the schema, by path, each an array of
// names: "op", "op.transform", "op.transform.rotate", "op.transform.twist",
// "direction.type" (the direction types), "direction.global",
// "direction.curvature", "direction.screen", "direction.screen.camera",
// "direction.constraints", "direction.constraint", "direction.dense",
// "region" (the region kinds), "region.sphere", "region.box",
// "region.vertices", "flatten", and the edit document's (document.h)
// "document", "document.mesh", "document.region", "document.step",
// "document.op". For tests that check the TypeScript
// declarations against the parsers.
Json op_schema();

}  // namespace aniso
