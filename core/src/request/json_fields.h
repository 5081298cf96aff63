// Reading one field of the public op's JSON (op.h): each reader checks the
// value's form and throws Error(BadParameter) naming the field path and
// quoting what was given ("op.move[1] must be a finite number, got 'NaN'").
// Ranges are the core's validators' business (transforms.h, limits.h), not
// these readers'.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "anisoform/error.h"
#include "anisoform/op.h"

namespace aniso::json_fields {

using Keys = std::vector<std::string>;

// The value as a message quotes it: strings in quotes ('NaN'), numbers as
// written, "an array of length 3", "an object", true, false, null.
std::string describe(const Json& value);
[[noreturn]] void refuse(const std::string& field, const std::string& problem);

const Json& object(const Json& value, const std::string& field);   // "must be an object"
void reject_unknown_keys(const Json& object, const Keys& allowed, const std::string& field);
bool has(const Json& object, const char* key);  // given (JSON has no undefined)
// A key that must be given: "FIELD is missing" otherwise.
const Json& member(const Json& object, const char* key, const std::string& field);

double finite_number(const Json& value, const std::string& field);
int integer_at_least(const Json& value, int minimum, const std::string& field);
// An integer within limits.h's iteration bound ("FIELD must be an integer
// from 1 to 10000, got 20000").
int iteration_count(const Json& value, const std::string& field);
bool flag(const Json& value, const std::string& field);  // "must be true or false"
// The string, if it is one of `choices`.
std::string one_of(const Json& value, const Keys& choices, const std::string& field);
// Exactly `length` finite numbers.
std::vector<double> finite_numbers(const Json& value, std::size_t length, const std::string& field);
Eigen::Vector3d vector3(const Json& value, const std::string& field);
Eigen::Vector3d non_zero_vector3(const Json& value, const std::string& field);  // not normalised
// Vertex indices: integers in [0, 2^31 - 1] (the range check against the mesh
// is the core's: check_indices, region_weights).
std::vector<int> indices(const Json& value, const std::string& field);

// Runs `check` (a core validator) and puts "FIELD: " before its message, so
// that a range refusal still names where the value came from.
template <typename Check>
void naming_field(const std::string& field, Check&& check) {
  try {
    check();
  } catch (const Error& error) {
    if (error.code() != ErrorCode::BadParameter) throw;
    throw Error(error.code(), field + ": " + error.what());
  }
}

}  // namespace aniso::json_fields
