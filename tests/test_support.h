// Shared helpers for the Catch2 suite: paths to the real meshes in ../shared,
// and what several test files need alike.
#pragma once

#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "anisoform/error.h"
#include "anisoform/mesh.h"
#include "build_paths.h"
#include "cli_runner.h"

namespace aniso::test {

constexpr double kPi = 3.14159265358979323846;

inline std::string mesh_path(const std::string& relative) {
  return std::string(aniso::test::kMeshesDir) + "/" + relative;
}

// Reads a mesh from ../shared/meshes; fails the test on error.
Mesh load(const std::string& relative);

// Runs the CLI (60 s deadline) and requires a normal exit with
// `expected_exit`; on failure the command, stdout and stderr are shown.
CliRun run_cli_expecting(const std::vector<std::string>& args, int expected_exit);

// A whole file as bytes ("" if it cannot be read).
std::string slurp(const std::string& path);

// How often `part` occurs in `text` (overlapping occurrences counted).
inline int count_of(const std::string& text, const std::string& part) {
  int count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

// Whether any of `texts` (warnings, lines) contains `part`.
inline bool any_contains(const std::vector<std::string>& texts, const std::string& part) {
  for (const std::string& text : texts) {
    if (text.find(part) != std::string::npos) return true;
  }
  return false;
}

// The message of the aniso::Error that `call` throws; fails the test if it
// throws nothing or an error with another code.
template <typename Call>
std::string error_message_of(Call call, ErrorCode code) {
  try {
    call();
  } catch (const Error& e) {
    CHECK(e.code() == code);
    return e.what();
  }
  FAIL("no aniso::Error was thrown");
  return "";
}

// The message of the aniso::Error(BadParameter) that `call` throws.
template <typename Call>
std::string bad_parameter_message(Call call) {
  return error_message_of(call, ErrorCode::BadParameter);
}

}  // namespace aniso::test
