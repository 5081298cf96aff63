// aniso::test::load (the shared meshes, read through the real reader) and slurp.
#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>

#include "anisoform/mesh_io.h"
#include "test_support.h"

namespace aniso::test {

Mesh load(const std::string& relative) {
  try {
    return read_mesh(mesh_path(relative)).mesh;
  } catch (const std::exception& error) {
    FAIL("cannot load " << relative << ": " << error.what());
  }
  return {};
}

std::string slurp(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

CliRun run_cli_expecting(const std::vector<std::string>& args, int expected_exit) {
  const CliRun run = run_cli(args, 60);
  std::string command = "anisoform";
  for (const std::string& arg : args) command += " " + arg;
  INFO(command << "\n  exit " << run.exit_status << "\n  stdout: " << run.out << "\n  stderr: " << run.err);
  REQUIRE_FALSE(run.timed_out);
  REQUIRE_FALSE(run.signaled);
  REQUIRE(run.exit_status == expected_exit);
  return run;
}

}  // namespace aniso::test
