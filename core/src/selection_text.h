// Strict parsing of the small text inputs users write by hand: selection files
// ("file:PATH") and direction-constraint files. Private to the core; shared by
// selection.cpp and direction_field.cpp so both accept exactly the same numbers
// and comments.
#pragma once

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

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

// A finite decimal number that is the whole token; nullopt otherwise
// ("1e3" and "-0.5" are numbers, "1.2.3", "nan", "inf" and "" are not).
inline std::optional<double> parse_finite(const std::string& token) {
  if (token.empty()) return std::nullopt;
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (end != begin + token.size() || errno == ERANGE || !std::isfinite(value)) return std::nullopt;
  return value;
}

// A non-negative integer that is the whole token and fits an int; nullopt
// otherwise ("12" is one, "-1", "1.0" and "1e2" are not).
inline std::optional<int> parse_index(const std::string& token) {
  if (token.empty() || token[0] == '-' || token[0] == '+') return std::nullopt;
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(begin, &end, 10);
  if (end != begin + token.size() || errno == ERANGE || value > INT_MAX) return std::nullopt;
  return static_cast<int>(value);
}

}  // namespace aniso::text
