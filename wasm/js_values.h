// Reading the core's request structs from the plain JS objects that the JS
// layer (js/anisoform-wasm.mjs) builds. The JS layer checks the user's input
// and fills in every field, so these readers only guard against a field that
// is missing or of the wrong type (Error(BadParameter) naming it) and never
// apply defaults of their own: there is one place for those.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <emscripten/val.h>

#include "anisoform/selection.h"
#include "anisoform/session.h"

namespace aniso::wasm {

// request: {method, direction, transform, pins, handles, move, elements,
//           maxIterations, rotationSteps, tolerance, warmStart, preview}, as documented in
// js/anisoform-wasm.mjs (normalizeOp).
SessionEdit edit_from_js(const emscripten::val& request);

// request: {useSelection, su, sv, direction: {kind: 'global'|'constraints', vector,
//           constraints}, method: 'anisotropic'|'uniform-baseline', maxIterations,
//           tolerance}, as built by js/anisoform-wasm.mjs (normalizeFlatten).
SessionFlatten flatten_from_js(const emscripten::val& request);

// direction: {kind, vector, constraints, screen, dense, smoothing}.
DirectionSource direction_from_js(const emscripten::val& direction);

// region: {kind: 'all'|'box'|'sphere'|'vertices', min, max, center, radius,
//          vertices, weights}.
Region region_from_js(const emscripten::val& region);

SelectionMode selection_mode_from_js(const std::string& mode);
DistortionKind distortion_kind_from_js(const std::string& kind);
DistortionReference distortion_reference_from_js(const std::string& reference);

// Indices (vertices, pins, handles, triangle corners) from a JS array or
// typed array, each checked to be an integer Number in [0, max of Index]
// BEFORE it is narrowed: 2**32 + 1 or 1e10 would otherwise wrap to another
// vertex. Error(BadParameter) "<name> element K must be ..., got <the value as
// JS prints it>". Whether an index exists in the mesh is the core's check.
template <typename Index>
std::vector<Index> checked_indices(const emscripten::val& array, const std::string& name);

// One bulk copy of a JS typed array (or array of numbers) into a vector.
std::vector<float> float_vector(const emscripten::val& array);
std::vector<double> double_vector(const emscripten::val& array);
std::vector<std::uint8_t> byte_vector(const emscripten::val& array);

}  // namespace aniso::wasm
