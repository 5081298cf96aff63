// The one number grammar (strict_number.h): what it reads, what it refuses and
// why, for the CLI, the selection and direction files and the mesh readers.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "anisoform/strict_number.h"

namespace {

// The reason the text is refused, or "" when it is read (value in `value`).
std::string number_refusal(const std::string& text, double& value,
                           aniso::NonFiniteText non_finite = aniso::NonFiniteText::Refuse) {
  const char* problem = aniso::parse_strict_number(text, value, non_finite);
  return problem ? problem : "";
}

}  // namespace

TEST_CASE("strict number: decimal forms are read exactly as from_chars reads them", "[number]") {
  const std::pair<const char*, double> accepted[] = {
      {"1", 1.0},       {"-0.5", -0.5}, {"+1.25", 1.25}, {".5", 0.5},  {"2.", 2.0},
      {"1e3", 1000.0},  {"1E-2", 0.01}, {"-2.5e+1", -25.0}, {"0", 0.0}, {"1e-999", 0.0},
  };
  for (const auto& [text, expected] : accepted) {
    INFO(text);
    double value = -7.0;
    CHECK(number_refusal(text, value).empty());
    CHECK(value == expected);
  }
}

TEST_CASE("strict number: refusals say why", "[number]") {
  const std::pair<const char*, const char*> refused[] = {
      {"", "is empty"},
      {"1.5x", "is not a number"},
      {" 1", "is not a number"},
      {"1 ", "is not a number"},
      {"+-1", "is not a number"},
      {"1..2", "is not a number"},
      {"e5", "is not a number"},
      {"1e", "is not a number"},
      {"0x1p3", "is a hexadecimal number (write it in decimal)"},
      {"-0X10", "is a hexadecimal number (write it in decimal)"},
      {"nan", "is not a finite number"},
      {"-inf", "is not a finite number"},
      {"Infinity", "is not a finite number"},
      {"1e999", "is out of range"},
      {"-1e400", "is out of range"},
  };
  for (const auto& [text, reason] : refused) {
    INFO("'" << text << "'");
    double value = 42.0;
    CHECK(number_refusal(text, value) == reason);
    CHECK(value == 42.0);  // untouched
  }
}

TEST_CASE("strict number: the mesh readers' mode keeps nan and inf, nothing else", "[number]") {
  const auto keep = aniso::NonFiniteText::Keep;
  double value = 0.0;
  CHECK(number_refusal("nan", value, keep).empty());
  CHECK(std::isnan(value));
  CHECK(number_refusal("-inf", value, keep).empty());
  CHECK(value == -HUGE_VAL);
  CHECK(number_refusal("1e999", value, keep).empty());
  CHECK(value == HUGE_VAL);
  CHECK(number_refusal("0x1p3", value, keep) == "is a hexadecimal number (write it in decimal)");
  CHECK(number_refusal("nanx", value, keep) == "is not a number");
}

TEST_CASE("strict integer: whole decimal integers within long long", "[number]") {
  long long value = 0;
  CHECK(aniso::parse_strict_integer("+12", value) == nullptr);
  CHECK(value == 12);
  CHECK(aniso::parse_strict_integer("-3", value) == nullptr);
  CHECK(value == -3);
  CHECK(std::string(aniso::parse_strict_integer("", value)) == "is empty");
  CHECK(std::string(aniso::parse_strict_integer("1.0", value)) == "is not an integer");
  CHECK(std::string(aniso::parse_strict_integer("0x10", value)) == "is not an integer");
  CHECK(std::string(aniso::parse_strict_integer("+-5", value)) == "is not an integer");
  CHECK(std::string(aniso::parse_strict_integer("99999999999999999999", value)) == "is out of range");
  CHECK(aniso::number_problem("1.5x", "is not a number") == "'1.5x' is not a number");
}
