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

}  // namespace aniso::test
