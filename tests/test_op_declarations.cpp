// The TypeScript declarations of the public op (wasm/js/anisoform-wasm.d.ts)
// name exactly the keys the core's parsers accept (op_schema, op.h): the
// .d.ts is written by hand, the schema lives in C++, and this keeps them one.
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "anisoform/op.h"
#include "test_support.h"

namespace {

using aniso::Json;

const char* const kDeclarations = ANISO_SOURCE_DIR "/wasm/js/anisoform-wasm.d.ts";

// The property names at the top level of `export interface NAME { ... }`
// (one property per line; inline object types stay on their property's line).
std::set<std::string> declared_keys(const std::string& text, const std::string& name) {
  const std::string opening = "export interface " + name + " {";
  const std::size_t start = text.find(opening);
  REQUIRE(start != std::string::npos);
  const std::size_t end = text.find("\n}", start);
  REQUIRE(end != std::string::npos);
  const std::string body = text.substr(start + opening.size(), end - start - opening.size());
  std::set<std::string> keys;
  static const std::regex property(R"(^  (\w+)\??:)");
  std::istringstream lines(body);
  std::smatch match;
  for (std::string line; std::getline(lines, line);) {
    if (std::regex_search(line, match, property)) keys.insert(match[1]);
  }
  return keys;
}

std::set<std::string> schema_keys(const char* path) {
  const Json keys = aniso::op_schema().at(path);
  return {keys.begin(), keys.end()};
}

}  // namespace

TEST_CASE("op declarations: the .d.ts names the keys the core accepts", "[op]") {
  const std::string text = aniso::test::slurp(kDeclarations);
  REQUIRE_FALSE(text.empty());
  CHECK(declared_keys(text, "DeformOp") == schema_keys("op"));
  CHECK(declared_keys(text, "Transform") == schema_keys("op.transform"));
  CHECK(declared_keys(text, "FlattenOptions") == schema_keys("flatten"));
  for (const std::string type : schema_keys("direction.type")) {
    INFO(type);
    CHECK(text.find("type: '" + type + "'") != std::string::npos);
  }
}
