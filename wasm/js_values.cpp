#include "js_values.h"

#include <cmath>
#include <limits>
#include <type_traits>

#include "anisoform/error.h"

namespace aniso::wasm {

using emscripten::val;

namespace {

// A JS value as JS itself would print it (1e10 as 10000000000, 2**32 + 1 in
// full), so that a message shows what the caller passed, not what C++ made of it.
std::string js_text(const val& value) {
  if (value.isString()) return "'" + value.as<std::string>() + "'";
  if (!value.isNumber()) return "a value of type " + value.typeOf().as<std::string>();
  return val::global("String")(value).as<std::string>();
}

std::string js_text(double value) { return js_text(val(value)); }

}  // namespace

template <typename Index>
std::vector<Index> checked_indices(const val& array, const std::string& name) {
  constexpr double kLargest = static_cast<double>(std::numeric_limits<Index>::max());
  const bool typed = val::global("ArrayBuffer").call<bool>("isView", array);
  if (!typed && !val::global("Array").call<bool>("isArray", array)) {
    fail(ErrorCode::BadParameter, name + " must be an array or typed array of indices, got " + js_text(array));
  }
  // A Uint32Array holds exactly what it says (a mesh's triangles): one bulk copy.
  if (std::is_same_v<Index, std::uint32_t> && array.instanceof(val::global("Uint32Array"))) {
    return emscripten::convertJSArrayToNumberVector<Index>(array);
  }
  // Anything else goes through doubles, which hold every JS number exactly,
  // and is checked before it is narrowed. A plain array is read element by
  // element, as a bulk copy would turn null or '3' into numbers.
  const std::size_t count = array["length"].as<std::size_t>();
  std::vector<double> values;
  if (typed) {
    values = emscripten::convertJSArrayToNumberVector<double>(array);
  } else {
    values.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      const val element = array[k];
      if (!element.isNumber()) {
        fail(ErrorCode::BadParameter, name + " element " + std::to_string(k) + " must be a number, got " +
                                          js_text(element));
      }
      values[k] = element.as<double>();
    }
  }
  std::vector<Index> out(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double value = values[k];
    if (!(value >= 0.0 && value <= kLargest && std::floor(value) == value)) {
      fail(ErrorCode::BadParameter, name + " element " + std::to_string(k) + " must be an integer from 0 to " +
                                        js_text(kLargest) + ", got " + js_text(value));
    }
    out[k] = static_cast<Index>(value);
  }
  return out;
}

template std::vector<int> checked_indices<int>(const val&, const std::string&);
template std::vector<std::uint32_t> checked_indices<std::uint32_t>(const val&, const std::string&);

std::vector<float> float_vector(const val& array) {
  return emscripten::convertJSArrayToNumberVector<float>(array);
}

std::vector<double> double_vector(const val& array) {
  return emscripten::convertJSArrayToNumberVector<double>(array);
}

std::vector<std::uint8_t> byte_vector(const val& array) {
  return emscripten::convertJSArrayToNumberVector<std::uint8_t>(array);
}

}  // namespace aniso::wasm
