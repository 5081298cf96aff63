// The one set of rules for turning text into a number, for every number a
// person or a file gives us: command-line options, selection and direction
// files, and the text mesh formats.
//
// A number is decimal and is the whole text: [+-]digits[.digits][e[+-]digits],
// ".5" and "2." included. Refused: the empty text, leading or trailing blanks,
// "1.5x", hexadecimal ("0x1p3", which strtod would take), and by default
// nan/inf and values too large for a double ("1e999"). Values too small
// for a double ("1e-999") are read as the nearest double (zero or denormal).
// The parsers return why a text is refused in words, so that each caller can
// put the field's name and place (option, file line) in front.
#pragma once

#include <string>
#include <string_view>

namespace aniso {

// Whether the words nan, inf, infinity (and overflowing values, as inf) are
// read. Only the mesh readers keep them: a non-finite coordinate is reported
// per vertex by check_mesh, which says more than a refused line would.
enum class NonFiniteText { Refuse, Keep };

// Parses `text` into `value`. Returns nullptr when it is a number, else the
// reason: "is empty", "is not a number", "is a hexadecimal number (write it in
// decimal)", "is not a finite number" or "is out of range".
const char* parse_strict_number(std::string_view text, double& value,
                                NonFiniteText non_finite = NonFiniteText::Refuse);

// [+-]digits within the range of long long; nullptr or the reason ("is empty",
// "is not an integer", "is out of range"). Callers check their own range.
const char* parse_strict_integer(std::string_view text, long long& value);

// "'TEXT' REASON", the text shown printable and short, for messages such as
// "--scale: '1.5x' is not a number".
std::string number_problem(std::string_view text, const char* reason);

}  // namespace aniso
