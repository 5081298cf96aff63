#include "json_fields.h"

#include <cmath>
#include <limits>

#include "anisoform/error.h"
#include "anisoform/limits.h"

namespace aniso::json_fields {

std::string describe(const Json& value) {
  if (value.is_string()) return "'" + value.get<std::string>() + "'";
  if (value.is_array()) return "an array of length " + std::to_string(value.size());
  if (value.is_object()) return "an object";
  return value.dump();  // numbers, true, false, null
}

void refuse(const std::string& field, const std::string& problem) {
  fail(ErrorCode::BadParameter, field + " " + problem);
}

const Json& object(const Json& value, const std::string& field) {
  if (!value.is_object()) refuse(field, "must be an object");
  return value;
}

void reject_unknown_keys(const Json& object, const Keys& allowed, const std::string& field) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    bool known = false;
    for (const std::string& key : allowed) known = known || it.key() == key;
    if (known) continue;
    std::string list;
    for (const std::string& key : allowed) list += (list.empty() ? "" : ", ") + key;
    refuse(field, "has an unknown field '" + it.key() + "' (allowed: " + list + ")");
  }
}

bool has(const Json& object, const char* key) { return object.contains(key); }

const Json& member(const Json& object, const char* key, const std::string& field) {
  if (!object.contains(key)) refuse(field, "is missing");
  return object[key];
}

double finite_number(const Json& value, const std::string& field) {
  if (!value.is_number() || !std::isfinite(value.get<double>())) {
    refuse(field, "must be a finite number, got " + describe(value));
  }
  return value.get<double>();
}

int integer_at_least(const Json& value, int minimum, const std::string& field) {
  const bool whole = value.is_number() && std::isfinite(value.get<double>()) &&
                     std::floor(value.get<double>()) == value.get<double>();
  if (!whole || value.get<double>() < minimum ||
      value.get<double>() > static_cast<double>(std::numeric_limits<int>::max())) {
    refuse(field, "must be an integer >= " + std::to_string(minimum) + ", got " + describe(value));
  }
  return static_cast<int>(value.get<double>());
}

int iteration_count(const Json& value, const std::string& field) {
  const int count = integer_at_least(value, 1, field);
  check_iteration_count(count, field);
  return count;
}

bool flag(const Json& value, const std::string& field) {
  if (!value.is_boolean()) refuse(field, "must be true or false, got " + describe(value));
  return value.get<bool>();
}

std::string one_of(const Json& value, const Keys& choices, const std::string& field) {
  if (value.is_string()) {
    for (const std::string& choice : choices) {
      if (value.get<std::string>() == choice) return choice;
    }
  }
  std::string list;
  for (const std::string& choice : choices) list += (list.empty() ? "" : ", ") + choice;
  refuse(field, "must be one of " + list + ", got " + describe(value));
}

std::vector<double> finite_numbers(const Json& value, std::size_t length, const std::string& field) {
  if (!value.is_array() || value.size() != length) {
    refuse(field, "must be " + std::to_string(length) + " finite numbers, got " + describe(value));
  }
  std::vector<double> out(length);
  for (std::size_t i = 0; i < length; ++i) {
    out[i] = finite_number(value[i], field + "[" + std::to_string(i) + "]");
  }
  return out;
}

Eigen::Vector3d vector3(const Json& value, const std::string& field) {
  const std::vector<double> xyz = finite_numbers(value, 3, field);
  return {xyz[0], xyz[1], xyz[2]};
}

Eigen::Vector3d non_zero_vector3(const Json& value, const std::string& field) {
  const Eigen::Vector3d v = vector3(value, field);
  if (v.isZero(0.0)) refuse(field, "must not be the zero vector");
  return v;
}

std::vector<int> indices(const Json& value, const std::string& field) {
  if (!value.is_array()) refuse(field, "must be an array of vertex indices, got " + describe(value));
  constexpr double kLargest = std::numeric_limits<int>::max();
  std::vector<int> out;
  out.reserve(value.size());
  for (std::size_t k = 0; k < value.size(); ++k) {
    const Json& element = value[k];
    const std::string where = field + " element " + std::to_string(k);
    if (!element.is_number()) refuse(where, "must be a number, got " + describe(element));
    const double index = element.get<double>();
    if (!(index >= 0.0 && index <= kLargest && std::floor(index) == index)) {
      refuse(where, "must be an integer from 0 to 2147483647, got " + describe(element));
    }
    out.push_back(static_cast<int>(index));
  }
  return out;
}

}  // namespace aniso::json_fields
