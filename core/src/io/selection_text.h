// Strict parsing of the small text inputs users write by hand: selection files
// ("file:PATH") and direction-constraint files. Private to the core; shared by
// selection.cpp and direction_field.cpp so both accept exactly the same numbers
// (the strict grammar of strict_number.h, as everywhere) and comments.
#pragma once

#include <climits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "anisoform/strict_number.h"

namespace aniso::text {

// The whitespace-separated tokens of one line; everything from '#' on is a
// comment. A blank or comment-only line gives no tokens.
inline std::vector<std::string> tokens_of_line(const std::string& line) {
  std::istringstream stream(line.substr(0, line.find('#')));
  std::vector<std::string> tokens;
  std::string token;
  while (stream >> token) tokens.push_back(token);
  return tokens;
}

// The lines of a text, without their line terminators ("\n" or "\r\n").
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  std::string line;
  while (std::getline(stream, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

// A vertex index: a whole-token integer (strict_number.h) that is >= 0 and
// fits an int; nullopt otherwise ("12" is one, "-1", "1.0" and "1e2" are not).
inline std::optional<int> parse_index(const std::string& token) {
  long long value = 0;
  if (parse_strict_integer(token, value) != nullptr || value < 0 || value > INT_MAX) return std::nullopt;
  return static_cast<int>(value);
}

// "NAME: 'TOKEN' REASON" when the token is not a finite decimal number
// (strict_number.h), empty when it is one (then stored in `value`).
inline std::string number_field_problem(const std::string& name, const std::string& token, double& value) {
  const char* problem = parse_strict_number(token, value);
  return problem ? name + ": " + number_problem(token, problem) : std::string();
}

}  // namespace aniso::text
