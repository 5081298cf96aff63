#include "cli_common.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <sstream>
#include <string_view>
#include <system_error>

namespace aniso::cli {

namespace fs = std::filesystem;

int exit_status_for(ErrorCode code) {
  switch (code) {
    case ErrorCode::BadParameter: return kExitBadUsage;
    case ErrorCode::BadMesh:
    case ErrorCode::BadFile:
    case ErrorCode::Numerical: return kExitBadMesh;
  }
  return kExitBadMesh;
}

int run_reporting_errors(const std::string& command, const std::function<int()>& body) {
  const std::string prefix = command.empty() ? "anisoform" : "anisoform " + command;
  const auto report = [&prefix](const std::string& message) {
    std::cerr << prefix << ": error: " << message << std::endl;
  };
  try {
    return body();
  } catch (const Error& e) {
    report(e.what());
    return exit_status_for(e.code());
  } catch (const std::bad_alloc&) {
    report("out of memory (the mesh is too large for this machine)");
    return kExitBadMesh;
  } catch (const std::exception& e) {
    report(std::string("internal error: ") + e.what());
    return kExitBadMesh;
  } catch (...) {
    report("internal error of unknown type");
    return kExitBadMesh;
  }
}

namespace {

[[noreturn]] void fail_value(const std::string& option, const std::string& message) {
  fail(ErrorCode::BadParameter, option + ": " + message);
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma - start));
    if (comma == std::string::npos) return parts;
    start = comma + 1;
  }
}

// from_chars takes a leading '-' but not a '+', which people write too.
// "+-1" keeps its '+' and is refused.
std::string_view without_plus_sign(const std::string& text) {
  std::string_view digits = text;
  if (digits.size() >= 2 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
  return digits;
}

}  // namespace

double parse_number(const std::string& text, const std::string& option) {
  // from_chars is locale-independent and never skips whitespace, so the
  // whole-text rule is a plain end-pointer check.
  const std::string_view digits = without_plus_sign(text);
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool whole_text = !digits.empty() && end == digits.data() + digits.size();
  if (whole_text && error == std::errc::result_out_of_range) {
    fail_value(option, "'" + text + "' is out of range");
  }
  if (!whole_text || error != std::errc()) fail_value(option, "'" + text + "' is not a number");
  if (!std::isfinite(value)) fail_value(option, "'" + text + "' is not a finite number");
  return value;
}

int parse_integer(const std::string& text, const std::string& option) {
  const std::string_view digits = without_plus_sign(text);
  int value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error == std::errc::result_out_of_range) fail_value(option, "'" + text + "' is out of range");
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size()) {
    fail_value(option, "'" + text + "' is not an integer");
  }
  return value;
}

std::vector<double> parse_number_list(const std::string& text, const std::string& option,
                                      int expected) {
  const std::vector<std::string> parts = split_commas(text);
  if (expected > 0 && static_cast<int>(parts.size()) != expected) {
    fail_value(option, "needs " + std::to_string(expected) + " comma-separated numbers, got " +
                           std::to_string(parts.size()) + " in '" + text + "'");
  }
  std::vector<double> values;
  values.reserve(parts.size());
  for (const std::string& part : parts) values.push_back(parse_number(part, option));
  return values;
}

Eigen::Vector3d parse_vector3(const std::string& text, const std::string& option) {
  const std::vector<double> xyz = parse_number_list(text, option, 3);
  return {xyz[0], xyz[1], xyz[2]};
}

Eigen::Vector3d parse_unit_vector3(const std::string& text, const std::string& option) {
  const Eigen::Vector3d vector = parse_vector3(text, option);
  const double length = vector.norm();
  // A tiny but non-zero vector still names a direction; only zero (or an
  // overflow to infinity in the norm) does not.
  if (!(length > 0.0) || !std::isfinite(length)) {
    fail_value(option, "the vector '" + text + "' has no direction");
  }
  return vector / length;
}

Prefixed split_prefixed(const std::string& text, const std::string& option,
                        const std::string& expected_form) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) {
    fail_value(option, "'" + text + "' is not of the form " + expected_form);
  }
  return {text.substr(0, colon), text.substr(colon + 1)};
}

void parse_scale(const std::string& text, TransformSpec& spec) {
  const std::vector<double> scales = parse_number_list(text, "--scale");
  if (scales.size() > 2) {
    fail_value("--scale", "needs SU or SU,SV, got " + std::to_string(scales.size()) + " numbers");
  }
  spec.su = scales[0];
  if (scales.size() == 2) spec.sv = scales[1];
}

void parse_rotation(const std::string& text, TransformSpec& spec) {
  const std::string form = "n|u|v:DEGREES";
  const Prefixed parts = split_prefixed(text, "--rotate", form);
  if (parts.kind == "n") {
    spec.rotate_axis = RotateAxis::Normal;
  } else if (parts.kind == "u") {
    spec.rotate_axis = RotateAxis::U;
  } else if (parts.kind == "v") {
    spec.rotate_axis = RotateAxis::V;
  } else {
    fail_value("--rotate", "unknown axis '" + parts.kind + "' (expected " + form + ")");
  }
  spec.rotate_degrees = parse_number(parts.rest, "--rotate");
}

void parse_twist(const std::string& text, TransformSpec& spec) {
  const Prefixed parts = split_prefixed(text, "--twist", "X,Y,Z:DEGREES_PER_UNIT");
  spec.twist = true;
  spec.twist_axis = parse_unit_vector3(parts.kind, "--twist");
  spec.twist_degrees_per_unit = parse_number(parts.rest, "--twist");
}

DirectionChoice parse_direction(const std::string& text) {
  const std::string form = "global:X,Y,Z | curvature:min | curvature:max | field:PATH";
  const Prefixed parts = split_prefixed(text, "--direction", form);
  DirectionChoice choice;
  choice.description = text;
  if (parts.kind == "global") {
    choice.kind = DirectionSource::Kind::Global;
    choice.vector = parse_unit_vector3(parts.rest, "--direction");
  } else if (parts.kind == "curvature" && parts.rest == "min") {
    choice.kind = DirectionSource::Kind::CurvatureMin;
  } else if (parts.kind == "curvature" && parts.rest == "max") {
    choice.kind = DirectionSource::Kind::CurvatureMax;
  } else if (parts.kind == "field" && !parts.rest.empty()) {
    choice.kind = DirectionSource::Kind::Constraints;
    choice.field_path = parts.rest;
  } else {
    fail_value("--direction", "'" + text + "' is not one of " + form);
  }
  return choice;
}

DirectionChoice longest_axis_direction(const Mesh& mesh) {
  const BoundingBox box = bounding_box(mesh.V);
  const Eigen::Vector3d extent = box.max - box.min;
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (extent[k] > extent[axis]) axis = k;
  }
  DirectionChoice choice;
  choice.kind = DirectionSource::Kind::Global;
  choice.vector = Eigen::Vector3d::Unit(axis);
  const char* names[] = {"global:1,0,0", "global:0,1,0", "global:0,0,1"};
  choice.description = std::string(names[axis]) + " (longest axis)";
  return choice;
}

std::vector<int> region_vertices(const Mesh& mesh, const Region& region,
                                 const std::string& option) {
  const Eigen::VectorXd weights = naming_option(option, [&] { return region_weights(mesh, region); });
  std::vector<int> vertices;
  for (Eigen::Index i = 0; i < weights.size(); ++i) {
    if (weights[i] > 0.0) vertices.push_back(static_cast<int>(i));
  }
  if (vertices.empty()) fail_value(option, "the region holds no vertex of the mesh");
  return vertices;
}

std::string read_text_file(const std::string& path, const std::string& option) {
  std::error_code ignored;
  if (!fs::is_regular_file(path, ignored)) {
    fail_value(option, "cannot open " + path + ": no such file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) fail_value(option, "cannot open " + path + ": " + std::strerror(errno));
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) fail_value(option, "cannot read " + path);
  return text.str();
}

void weld_if_soup(Mesh& mesh, std::vector<std::string>& warnings) {
  if (!is_triangle_soup(mesh)) return;
  const int before = mesh.num_vertices();
  mesh = weld_vertices(mesh);
  warnings.push_back("the input is a triangle soup (no shared vertices): welded by exact position, " +
                     std::to_string(before) + " -> " + std::to_string(mesh.num_vertices()) + " vertices");
}

ReadResult read_input_mesh(const std::string& path) {
  format_from_path(path);  // an unknown extension is a bad parameter, checked first
  std::error_code ignored;
  if (!fs::exists(path, ignored)) fail(ErrorCode::BadFile, "cannot open " + path + ": no such file");
  if (fs::is_directory(path, ignored)) {
    fail(ErrorCode::BadFile, "cannot open " + path + ": it is a directory");
  }
  if (!std::ifstream(path, std::ios::binary)) {
    fail(ErrorCode::BadFile, "cannot open " + path + ": " + std::strerror(errno));
  }
  try {
    return read_mesh(path);
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.find(path) != std::string::npos) throw;
    throw Error(e.code(), path + ": " + message);
  }
}

MeshFormat check_output_path(const std::string& path) {
  const MeshFormat format = format_from_path(path);
  std::error_code ignored;
  if (fs::is_directory(path, ignored)) fail_value("OUT", "cannot write " + path + ": it is a directory");
  const fs::path directory = fs::path(path).parent_path();
  if (!directory.empty() && !fs::is_directory(directory, ignored)) {
    fail_value("OUT", "cannot write " + path + ": directory " + directory.string() + " does not exist");
  }
  return format;
}

void write_output_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
  try {
    write_mesh(path, mesh, options);
  } catch (const Error& e) {
    if (e.code() == ErrorCode::BadParameter) throw;
    fail_value("OUT", "cannot write " + path + ": " + e.what());
  } catch (const std::system_error& e) {  // std::ios_base::failure is one
    fail_value("OUT", "cannot write " + path + ": " + e.what());
  }
}

Json to_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

Json to_json(const BoundingBox& box) {
  return {{"min", to_json(box.min)}, {"max", to_json(box.max)}};
}

Json to_json(const ReadReport& report) {
  return {{"polygons_triangulated", report.polygons_triangulated},
          {"vertices_welded", report.vertices_welded},
          {"elements_skipped", report.elements_skipped},
          {"notes", report.notes}};
}

void print_json(const Json& result) {
  // Messages may quote bytes from a broken file: replace invalid UTF-8 rather
  // than let dump() throw after the work is done.
  std::cout << result.dump(-1, ' ', false, Json::error_handler_t::replace) << '\n'
            << std::flush;
}

}  // namespace aniso::cli
