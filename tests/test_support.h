// Shared helpers for the Catch2 suite: paths to the real meshes in ../shared.
#pragma once

#include <string>

#include "anisoform/mesh.h"

namespace aniso::test {

inline std::string mesh_path(const std::string& relative) {
  return std::string(ANISO_MESHES_DIR) + "/" + relative;
}

// Reads a mesh from ../shared/meshes; fails the test on error.
Mesh load(const std::string& relative);

}  // namespace aniso::test
