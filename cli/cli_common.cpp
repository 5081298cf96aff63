#include "cli_common.h"

#include "anisoform/op.h"

#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>
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

void report_error(const std::string& command, const std::string& message) {
  std::cerr << (command.empty() ? "anisoform" : "anisoform " + command) << ": error: " << message << std::endl;
}

int run_reporting_errors(const std::string& command, const std::function<int()>& body) {
  const auto report = [&command](const std::string& message) { report_error(command, message); };
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

}  // namespace

void refuse_empty_values(const CLI::App& command) {
  for (const CLI::Option* option : command.get_options()) {
    // Flags take no value, and positionals are paths checked where they are used.
    if (option->get_positional() || option->get_expected_min() == 0) continue;
    for (const std::string& value : option->results()) {
      if (value.empty()) fail_value(option->get_name(), "needs a value, got an empty one");
    }
  }
}

double parse_number(const std::string& text, const std::string& option) {
  double value = 0.0;
  if (const char* problem = parse_strict_number(text, value)) fail_value(option, number_problem(text, problem));
  return value;
}

int parse_integer(const std::string& text, const std::string& option) {
  long long value = 0;
  const char* problem = parse_strict_integer(text, value);
  if (!problem && (value < INT_MIN || value > INT_MAX)) problem = "is out of range";
  if (problem) fail_value(option, number_problem(text, problem));
  return static_cast<int>(value);
}

std::vector<double> parse_number_list(const std::string& text, const std::string& option,
                                      int expected, const std::vector<std::string>& names) {
  const std::vector<std::string> parts = split_commas(text);
  if (expected > 0 && static_cast<int>(parts.size()) != expected) {
    fail_value(option, "needs " + std::to_string(expected) + " comma-separated numbers, got " +
                           std::to_string(parts.size()) + " in '" + text + "'");
  }
  std::vector<double> values;
  values.reserve(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    double value = 0.0;
    if (const char* problem = parse_strict_number(parts[i], value)) {
      if (parts.size() == 1) fail_value(option, number_problem(parts[i], problem));
      const std::string name = i < names.size() ? names[i] : "number " + std::to_string(i + 1);
      fail_value(option, name + ": " + number_problem(parts[i], problem));
    }
    values.push_back(value);
  }
  return values;
}

Eigen::Vector3d parse_vector3(const std::string& text, const std::string& option) {
  const std::vector<double> xyz = parse_number_list(text, option, 3, {"X", "Y", "Z"});
  return {xyz[0], xyz[1], xyz[2]};
}

Eigen::Vector3d parse_unit_vector3(const std::string& text, const std::string& option) {
  const Eigen::Vector3d vector = parse_vector3(text, option);
  // Any non-zero vector names a direction, however large or small
  // (stableNormalized: the plain norm overflows past 1e154).
  if (vector.isZero(0.0)) fail_value(option, "the vector '" + text + "' has no direction");
  return vector.stableNormalized();
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
  const std::vector<double> scales = parse_number_list(text, "--scale", 0, {"SU", "SV"});
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

DirectionFlag parse_direction(const std::string& text) {
  const std::string form = "global:X,Y,Z | curvature:min | curvature:max | field:PATH";
  const Prefixed parts = split_prefixed(text, "--direction", form);
  DirectionFlag choice;
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

std::string longest_axis_description(const BoundingBox& box) {
  const Eigen::Vector3d axis = longest_axis(box);
  const char* names[] = {"global:1,0,0", "global:0,1,0", "global:0,0,1"};
  const int k = axis.x() == 1.0 ? 0 : axis.y() == 1.0 ? 1 : 2;
  return std::string(names[k]) + " (longest axis)";
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
  return naming_option(option, [&] { return read_regular_file(path, ErrorCode::BadFile); });
}

std::vector<DirectionConstraint> read_direction_field(const std::string& path) {
  const std::string text = read_text_file(path, "--direction");
  return naming_option("--direction", [&] { return parse_direction_constraints(text, path); });
}

ReadReport load_into_session(Session& session, const std::string& path) {
  ReadResult read = read_input_mesh(path);
  const int read_vertices = read.mesh.num_vertices();
  try {
    session.adopt_mesh(std::move(read.mesh), {}, std::move(read.attributes), element_numbering_note(format_from_path(path)));
  } catch (const Error& e) {
    throw Error(e.code(), path + ": " + e.what());
  }
  // The session welds a triangle soup: the report counts those vertices too.
  read.report.vertices_welded += read_vertices - session.info().report.vertices;
  return std::move(read.report);
}

ReadResult read_input_mesh(const std::string& path) {
  format_from_path(path);  // an unknown extension is a bad parameter, checked first
  try {
    return read_mesh(path);  // a missing or non-regular file is refused before reading
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.find(path) != std::string::npos) throw;
    throw Error(e.code(), path + ": " + message);
  }
}

MeshFormat check_output_path(const std::string& path) {
  const MeshFormat format = format_from_path(path);
  check_output_location(path);
  return format;
}

void check_output_location(const std::string& path) {
  std::error_code ignored;
  if (fs::is_directory(path, ignored)) fail_value("OUT", "cannot write " + path + ": it is a directory");
  const fs::path directory = fs::path(path).parent_path();
  if (!directory.empty() && !fs::is_directory(directory, ignored)) {
    fail_value("OUT", "cannot write " + path + ": directory " + directory.string() + " does not exist");
  }
  // A directory that takes no new file (no write permission, a read-only
  // file system) was found only by the write, after the whole solve: 4.6 s
  // of deforming the koala, a minute of flattening the bunny.
  if (const int error = temporary_file_error_next_to(path)) {
    fail_value("OUT", "cannot write " + path + ": no file can be created in directory " +
                          (directory.empty() ? std::string(".") : directory.string()) + " (" + std::strerror(error) +
                          ")");
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

void print_warnings(const std::string& command, const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) std::cerr << "anisoform " << command << ": warning: " << warning << '\n';
  std::cerr << std::flush;
}

std::string field_amounts_replace(const std::string& option, const std::string& value, const std::string& path) {
  return option + " " + value + " is not used: the field file " + path +
         " gives amounts (its SU SV columns), which replace it everywhere; give the amounts in one place only";
}

}  // namespace aniso::cli
