// The strict number grammar (strict_number.h), shared by the CLI, the
// selection and direction files and the text mesh readers.
#include "anisoform/strict_number.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "io/io_common.h"

namespace aniso {

namespace {

bool same_word_ignoring_case(std::string_view text, std::string_view lower_word) {
  if (text.size() != lower_word.size()) return false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(text[i])) != lower_word[i]) return false;
  }
  return true;
}

// [digits][.digits][e[+-]digits] with at least one digit before the exponent:
// the grammar from_chars reads, checked by hand so that strtod (which also
// takes hex, blanks and words) can be used where from_chars cannot.
bool is_unsigned_decimal(std::string_view text) {
  std::size_t i = 0;
  const auto is_digit = [&](std::size_t k) { return k < text.size() && text[k] >= '0' && text[k] <= '9'; };
  std::size_t digits = 0;
  while (is_digit(i)) ++i, ++digits;
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (is_digit(i)) ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (!is_digit(i)) return false;
    while (is_digit(i)) ++i;
  }
  return i == text.size();
}

// The value of a text that passed is_unsigned_decimal (sign included). A
// value beyond the double range comes back as +-inf, one below it as the
// nearest double.
double decimal_value(std::string_view text) {
#if defined(__cpp_lib_to_chars)
  double value = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec == std::errc()) return value;
#endif
  // No floating-point from_chars (Emscripten's libc++), or out of range:
  // strtod gives inf or the nearest denormal/zero. The grammar was checked.
  const std::string copy(text);  // strtod needs a terminating NUL
  return std::strtod(copy.c_str(), nullptr);
}

}  // namespace

const char* parse_strict_number(std::string_view text, double& value, NonFiniteText non_finite) {
  if (text.empty()) return "is empty";
  std::string_view body = text;
  bool negative = false;
  if (body[0] == '+' || body[0] == '-') {
    negative = body[0] == '-';
    body.remove_prefix(1);
  }
  if (body.size() >= 2 && body[0] == '0' && (body[1] == 'x' || body[1] == 'X')) {
    return "is a hexadecimal number (write it in decimal)";
  }
  const bool infinite_word = same_word_ignoring_case(body, "inf") || same_word_ignoring_case(body, "infinity");
  if (infinite_word || same_word_ignoring_case(body, "nan")) {
    if (non_finite == NonFiniteText::Refuse) return "is not a finite number";
    value = infinite_word ? std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
    if (negative) value = -value;
    return nullptr;
  }
  if (!is_unsigned_decimal(body)) return "is not a number";
  // from_chars takes a leading '-' but not a '+'.
  const double parsed = decimal_value(text[0] == '+' ? body : text);
  if (!std::isfinite(parsed) && non_finite == NonFiniteText::Refuse) return "is out of range";
  value = parsed;
  return nullptr;
}

const char* parse_strict_integer(std::string_view text, long long& value) {
  if (text.empty()) return "is empty";
  std::string_view digits = text;
  if (digits[0] == '+') {  // from_chars refuses the '+' people write too
    digits.remove_prefix(1);
    if (!digits.empty() && digits[0] == '-') return "is not an integer";  // "+-5"
  }
  const char* end = digits.data() + digits.size();
  long long parsed = 0;
  const auto result = std::from_chars(digits.data(), end, parsed);
  if (digits.empty() || result.ptr != end) return "is not an integer";
  if (result.ec == std::errc::result_out_of_range) return "is out of range";
  if (result.ec != std::errc()) return "is not an integer";
  value = parsed;
  return nullptr;
}

std::string number_problem(std::string_view text, const char* reason) {
  return io::quoted(text) + " " + reason;
}

}  // namespace aniso
