// What every `anisoform` subcommand shares: the exit-status contract, strict
// parsing of option values, reading the input mesh and writing the output one
// with the right error codes, and printing the one-line JSON result.
//
// Option values are taken from CLI11 as plain strings and parsed here, so that
// every number on the command line goes through the same strict rules, the
// core's (strict_number.h): the whole text must be a finite decimal number
// ("1.5x", "0x1p3", "nan", "inf", "" are refused), and a refusal is an
// Error(BadParameter) that names the option (exit status 2).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "anisoform/deformer.h"
#include "anisoform/direction_field.h"
#include "anisoform/error.h"
#include "anisoform/file_io.h"
#include "anisoform/mesh.h"
#include "anisoform/mesh_check.h"
#include "anisoform/mesh_io.h"
#include "anisoform/selection.h"
#include "anisoform/session.h"
#include "anisoform/strict_number.h"
#include "anisoform/transforms.h"

namespace aniso::cli {

// Keys in the order they are written: the contract's keys first, for people
// reading the output (scripts do not care).
using Json = nlohmann::ordered_json;

// ---- exit statuses -------------------------------------------------------

constexpr int kExitSuccess = 0;
constexpr int kExitBadUsage = 2;  // bad command line or parameter
constexpr int kExitBadMesh = 3;   // bad input mesh, or a numerical failure it causes

int exit_status_for(ErrorCode code);

// One error line on stderr: "anisoform COMMAND: error: MESSAGE" (COMMAND may
// be empty), for every error, CLI11's parse errors included.
void report_error(const std::string& command, const std::string& message);

// Runs a subcommand's body and turns every exception into one line on stderr
// ("anisoform COMMAND: error: ...", COMMAND may be empty) and the contract's
// exit status:
// Error -> by code, std::bad_alloc and any other std::exception -> 3.
// Nothing escapes, so no input can end the process with a signal.
int run_reporting_errors(const std::string& command, const std::function<int()>& body);

// ---- strict values -------------------------------------------------------

// Every option given on the command line has a value: `--scale ""` is
// refused naming the option (an empty value would read as "not given").
void refuse_empty_values(const CLI::App& command);

// The whole text as a finite number (a leading '+' is allowed).
double parse_number(const std::string& text, const std::string& option);
// The whole text as an integer that fits in an int.
int parse_integer(const std::string& text, const std::string& option);
// Comma-separated finite numbers; `expected` > 0 demands exactly that many.
// A number that is not one is named by `names` (the option's own words: SU,
// SV), or by its place when the list has several: "--scale: SV: '' is
// empty", as a field file's "line 2: DX: '0x1p0' is a hexadecimal number".
std::vector<double> parse_number_list(const std::string& text, const std::string& option,
                                      int expected = 0, const std::vector<std::string>& names = {});
Eigen::Vector3d parse_vector3(const std::string& text, const std::string& option);
// A non-zero vector, normalised.
Eigen::Vector3d parse_unit_vector3(const std::string& text, const std::string& option);

// Splits "KIND:REST" at the first ':' (REST may hold more ':'); throws naming
// the option and `expected_form` when there is no ':'.
struct Prefixed {
  std::string kind;
  std::string rest;
};
Prefixed split_prefixed(const std::string& text, const std::string& option,
                        const std::string& expected_form);

// Runs `parse` and puts "OPTION: " before the message of a BadParameter or
// BadFile (a file the option names that cannot be read) error it throws: the core's parsers cannot know which option the text came
// from, and --select, --pin and --handle take the same forms.
template <typename Parse>
auto naming_option(const std::string& option, Parse&& parse) -> decltype(parse()) {
  try {
    return parse();
  } catch (const Error& e) {
    if (e.code() != ErrorCode::BadParameter && e.code() != ErrorCode::BadFile) throw;
    throw Error(e.code(), option + ": " + e.what());
  }
}

// ---- transforms and directions ------------------------------------------

// "SU" or "SU,SV" into spec.su / spec.sv (sv stays 1 when omitted).
void parse_scale(const std::string& text, TransformSpec& spec);
// "n|u|v:DEGREES".
void parse_rotation(const std::string& text, TransformSpec& spec);
// "X,Y,Z:DEGREES_PER_UNIT": the axis is normalised (a zero axis is refused);
// the origin is left for the caller, who knows the selection.
void parse_twist(const std::string& text, TransformSpec& spec);

// Where the direction field comes from, as given by --direction (the mesh is
// needed to finish it: curvature and constraint fields are built by the core).
struct DirectionFlag {
  DirectionSource::Kind kind = DirectionSource::Kind::Global;
  Eigen::Vector3d vector = Eigen::Vector3d::UnitX();  // Global: unit
  std::string field_path;                             // Constraints: the file
  std::string description;                            // echoed in the JSON
};
// "global:X,Y,Z" | "curvature:min" | "curvature:max" | "field:PATH".
DirectionFlag parse_direction(const std::string& text);
// How the default direction (op.h longest_axis of `box`, the rule the core
// applies) is echoed: "global:0,0,1 (longest axis)".
std::string longest_axis_description(const BoundingBox& box);

// ---- regions -------------------------------------------------------------

// The vertices a region gives a positive weight: the index lists of --pin and
// --handle. A region that holds no vertex is refused naming `option`, since
// pinning or moving nothing is surely not what was meant.
std::vector<int> region_vertices(const Mesh& mesh, const Region& region,
                                 const std::string& option);

// ---- files ---------------------------------------------------------------

// A whole text file (read_regular_file); Error(BadParameter) "OPTION: cannot
// open PATH ..." or "OPTION: PATH is a directory, not a regular file" when it
// cannot be read (files named by options are parameters).
std::string read_text_file(const std::string& path, const std::string& option);

// The direction constraints of `--direction field:PATH` (the format of
// parse_direction_constraints), every problem named "--direction: ..." once,
// for deform and flatten alike.
std::vector<DirectionConstraint> read_direction_field(const std::string& path);

// Reads the input mesh: an unknown extension is Error(BadParameter); a missing,
// unreadable or non-regular file Error(BadFile) ("cannot open PATH: ...",
// "PATH is not a regular file (a FIFO)"); parse errors keep the reader's code
// with the path in front of the message.
ReadResult read_input_mesh(const std::string& path);

// Reads IN (read_input_mesh) into the session, through the session's own
// preparation as the browser's meshes (Session::adopt_mesh: a soup is welded
// and noted in info().notes, a mesh that cannot be solved on is refused with
// Error(BadMesh) "PATH: cannot edit this mesh: ..."). Returns what the reader did.
ReadReport load_into_session(Session& session, const std::string& path);

// Checks OUT before any work is done: a known extension and an existing
// directory, else Error(BadParameter). Returns the format.
MeshFormat check_output_path(const std::string& path);
// Checks OUT's location before any work is done: not a directory, in a
// directory that exists and takes a new file (temporary_file_error_next_to);
// else Error(BadParameter) (exit 2). OUT itself is
// written with write_file_atomically (write_mesh does too): a write that
// fails later is Error(BadFile) (exit 3) and leaves an existing OUT as it was.
void check_output_location(const std::string& path);

// ---- JSON ----------------------------------------------------------------

Json to_json(const Eigen::Vector3d& v);
Json to_json(const BoundingBox& box);
Json to_json(const ReadReport& report);
// The result object as one line plus a newline on stdout.
void print_json(const Json& result);
// Each warning of the result's `warnings` as a line on stderr too
// ("anisoform COMMAND: warning: ..."), where a person running the command
// sees it without reading the JSON.
void print_warnings(const std::string& command, const std::vector<std::string>& warnings);

// The warning for an option's amounts (deform's --scale, flatten's
// --compress) beside a field file that carries its own (SU SV columns):
// the file's replace the option's everywhere (the core's rule, any_amounts).
std::string field_amounts_replace(const std::string& option, const std::string& value, const std::string& path);

}  // namespace aniso::cli
