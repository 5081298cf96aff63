// The bulk arguments of the bindings, read from JS arrays and typed arrays:
// mesh bytes, positions, weights and triangle corners. Requests (ops, regions,
// directions, options) do not come this way: they arrive as JSON text and are
// parsed by the core (anisoform/op.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <emscripten/val.h>

namespace aniso::wasm {

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
