#include "js_values.h"

#include <cmath>
#include <limits>
#include <type_traits>

#include "anisoform/error.h"

namespace aniso::wasm {

using emscripten::val;

namespace {

[[noreturn]] void fail_field(const char* name, const std::string& problem) {
  fail(ErrorCode::BadParameter, std::string("request field '") + name + "' " + problem);
}

val field(const val& object, const char* name) {
  val value = object[name];
  if (value.isUndefined() || value.isNull()) fail_field(name, "is missing");
  return value;
}

double number(const val& object, const char* name) {
  const val value = field(object, name);
  if (!value.isNumber()) fail_field(name, "must be a number");
  return value.as<double>();
}

// A JS value as JS itself would print it (1e10 as 10000000000, 2**32 + 1 in
// full), so that a message shows what the caller passed, not what C++ made of it.
std::string js_text(const val& value) {
  if (value.isString()) return "'" + value.as<std::string>() + "'";
  if (!value.isNumber()) return "a value of type " + value.typeOf().as<std::string>();
  return val::global("String")(value).as<std::string>();
}

std::string js_text(double value) { return js_text(val(value)); }

int integer(const val& object, const char* name) {
  const double value = number(object, name);
  if (!(std::floor(value) == value && std::abs(value) <= 2147483647.0)) {
    fail_field(name, "must be an integer from -2147483648 to 2147483647, got " + js_text(value));
  }
  return static_cast<int>(value);
}

bool flag(const val& object, const char* name) {
  const val value = field(object, name);
  if (!value.isTrue() && !value.isFalse()) fail_field(name, "must be true or false");
  return value.isTrue();
}

std::string text(const val& object, const char* name) {
  const val value = field(object, name);
  if (!value.isString()) fail_field(name, "must be a string");
  return value.as<std::string>();
}

template <int N>
Eigen::Matrix<double, N, 1> fixed_vector(const val& object, const char* name) {
  const val value = field(object, name);
  if (value["length"].as<int>() != N) fail_field(name, "must hold " + std::to_string(N) + " numbers");
  Eigen::Matrix<double, N, 1> out;
  for (int i = 0; i < N; ++i) {
    const val element = value[i];
    if (!element.isNumber()) fail_field(name, "must hold " + std::to_string(N) + " numbers");
    out[i] = element.as<double>();
  }
  return out;
}

std::vector<int> index_list(const val& object, const char* name) {
  return checked_indices<int>(field(object, name), std::string("request field '") + name + "'");
}

RotateAxis rotate_axis(const std::string& name) {
  if (name == "none") return RotateAxis::None;
  if (name == "n") return RotateAxis::Normal;
  if (name == "u") return RotateAxis::U;
  if (name == "v") return RotateAxis::V;
  fail_field("rotateAxis", "must be one of none, n, u, v, got '" + name + "'");
}

ArapElements arap_elements(const std::string& name) {
  if (name == "spokes") return ArapElements::Spokes;
  if (name == "spokes-rims") return ArapElements::SpokesAndRims;
  fail_field("elements", "must be spokes or spokes-rims, got '" + name + "'");
}

TransformSpec transform_from_js(const val& transform) {
  TransformSpec spec;
  spec.su = number(transform, "su");
  spec.sv = number(transform, "sv");
  spec.sn = number(transform, "sn");
  spec.shear = number(transform, "shear");
  spec.rotate_axis = rotate_axis(text(transform, "rotateAxis"));
  spec.rotate_degrees = number(transform, "rotateDegrees");
  spec.twist = flag(transform, "twist");
  if (spec.twist) {
    spec.twist_axis = fixed_vector<3>(transform, "twistAxis");
    spec.twist_degrees_per_unit = number(transform, "twistDegreesPerUnit");
  }
  return spec;
}

DirectionConstraint constraint_from_js(const val& constraint) {
  DirectionConstraint out;
  out.vertex = integer(constraint, "vertex");
  out.direction = fixed_vector<3>(constraint, "direction");
  out.has_amounts = flag(constraint, "hasAmounts");
  if (out.has_amounts) {
    out.su = number(constraint, "su");
    out.sv = number(constraint, "sv");
  }
  return out;
}

ScreenDrag screen_from_js(const val& screen) {
  ScreenDrag drag;
  const Eigen::Matrix<double, 16, 1> view = fixed_vector<16>(screen, "view");
  const Eigen::Matrix<double, 16, 1> projection = fixed_vector<16>(screen, "projection");
  // Column-major, as three.js Matrix4.elements.
  drag.view = Eigen::Map<const Eigen::Matrix4d>(view.data());
  drag.projection = Eigen::Map<const Eigen::Matrix4d>(projection.data());
  drag.viewport = fixed_vector<4>(screen, "viewport");
  drag.from_px = fixed_vector<2>(screen, "from");
  drag.to_px = fixed_vector<2>(screen, "to");
  drag.anchor = fixed_vector<3>(screen, "anchor");
  return drag;
}

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

DirectionSource direction_from_js(const val& direction) {
  DirectionSource source;
  const std::string kind = text(direction, "kind");
  if (kind == "global") {
    source.kind = DirectionSource::Kind::Global;
    source.vector = fixed_vector<3>(direction, "vector");
  } else if (kind == "curvature-min" || kind == "curvature-max") {
    source.kind = kind == "curvature-min" ? DirectionSource::Kind::CurvatureMin
                                          : DirectionSource::Kind::CurvatureMax;
    source.curvature_smoothing = integer(direction, "smoothing");
  } else if (kind == "constraints") {
    source.kind = DirectionSource::Kind::Constraints;
    const val constraints = field(direction, "constraints");
    const int count = constraints["length"].as<int>();
    for (int i = 0; i < count; ++i) source.constraints.push_back(constraint_from_js(constraints[i]));
  } else if (kind == "screen") {
    source.kind = DirectionSource::Kind::Screen;
    source.screen = screen_from_js(field(direction, "screen"));
  } else if (kind == "dense") {
    source.kind = DirectionSource::Kind::Dense;
    const std::vector<float> xyz = float_vector(field(direction, "dense"));
    if (xyz.size() % 3 != 0) fail_field("dense", "needs 3 numbers per vertex");
    source.dense.resize(static_cast<Eigen::Index>(xyz.size() / 3), 3);
    for (std::size_t i = 0; i < xyz.size(); ++i) source.dense.data()[i] = xyz[i];  // row-major
  } else {
    fail_field("kind", "must be one of global, curvature-min, curvature-max, constraints, "
                       "screen, dense, got '" + kind + "'");
  }
  return source;
}

SessionEdit edit_from_js(const val& request) {
  SessionEdit edit;
  DeformRequest& out = edit.request;
  out.method = parse_method(text(request, "method"));
  out.direction = direction_from_js(field(request, "direction"));
  const val transform = field(request, "transform");
  out.transform = transform_from_js(transform);
  const val twist_origin = transform["twistOrigin"];
  edit.twist_origin_given = !(twist_origin.isUndefined() || twist_origin.isNull());
  if (edit.twist_origin_given) out.transform.twist_origin = fixed_vector<3>(transform, "twistOrigin");
  out.pins = index_list(request, "pins");
  out.handles = index_list(request, "handles");
  out.handle_offset = fixed_vector<3>(request, "move");
  out.elements = arap_elements(text(request, "elements"));
  out.max_iterations = integer(request, "maxIterations");
  out.rotation_steps = integer(request, "rotationSteps");
  out.tolerance = number(request, "tolerance");
  out.warm_start = flag(request, "warmStart");
  edit.preview = flag(request, "preview");
  return edit;
}

SessionFlatten flatten_from_js(const val& request) {
  SessionFlatten out;
  out.use_selection = flag(request, "useSelection");
  out.su = number(request, "su");
  out.sv = number(request, "sv");
  const val direction = field(request, "direction");
  const std::string kind = text(direction, "kind");
  if (kind == "global") {
    out.directions.kind = FlattenDirections::Kind::Global;
    out.directions.global = fixed_vector<3>(direction, "vector");
  } else if (kind == "constraints") {
    out.directions.kind = FlattenDirections::Kind::Constraints;
    const val constraints = field(direction, "constraints");
    const int count = constraints["length"].as<int>();
    for (int i = 0; i < count; ++i) out.directions.constraints.push_back(constraint_from_js(constraints[i]));
  } else {
    fail_field("kind", "must be global or constraints for flatten, got '" + kind + "'");
  }
  const std::string method = text(request, "method");
  if (method == "anisotropic") {
    out.method = FlattenMethod::Anisotropic;
  } else if (method == "uniform-baseline") {
    out.method = FlattenMethod::UniformBaseline;
  } else {
    fail_field("method", "must be anisotropic or uniform-baseline, got '" + method + "'");
  }
  out.max_iterations = integer(request, "maxIterations");
  out.tolerance = number(request, "tolerance");
  return out;
}

Region region_from_js(const val& region) {
  Region out;
  const std::string kind = text(region, "kind");
  if (kind == "all") {
    out.kind = Region::Kind::All;
  } else if (kind == "box") {
    out.kind = Region::Kind::Box;
    out.min = fixed_vector<3>(region, "min");
    out.max = fixed_vector<3>(region, "max");
  } else if (kind == "sphere") {
    out.kind = Region::Kind::Sphere;
    out.center = fixed_vector<3>(region, "center");
    out.radius = number(region, "radius");
  } else if (kind == "vertices") {
    out.kind = Region::Kind::Vertices;
    out.vertices = index_list(region, "vertices");
    const val weights = region["weights"];
    if (!weights.isUndefined() && !weights.isNull()) {
      out.weights = emscripten::convertJSArrayToNumberVector<double>(weights);
    }
  } else {
    fail_field("kind", "must be one of all, box, sphere, vertices, got '" + kind + "'");
  }
  return out;
}

SelectionMode selection_mode_from_js(const std::string& mode) {
  if (mode == "replace") return SelectionMode::Replace;
  if (mode == "add") return SelectionMode::Add;
  if (mode == "subtract") return SelectionMode::Subtract;
  fail(ErrorCode::BadParameter, "selection mode must be replace, add or subtract, got '" + mode + "'");
}

DistortionKind distortion_kind_from_js(const std::string& kind) {
  if (kind == "area") return DistortionKind::AreaRatio;
  if (kind == "stretch") return DistortionKind::MaxStretch;
  fail(ErrorCode::BadParameter, "distortion kind must be area or stretch, got '" + kind + "'");
}

DistortionReference distortion_reference_from_js(const std::string& reference) {
  if (reference == "rest") return DistortionReference::Rest;
  if (reference == "loaded") return DistortionReference::Loaded;
  fail(ErrorCode::BadParameter,
       "distortion reference must be rest or loaded, got '" + reference + "'");
}

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
