// The paths tests/CMakeLists.txt passes for this build.
#include "build_paths.h"

namespace aniso::test {

const char kMeshesDir[] = ANISO_MESHES_DIR;
const char kSourceDir[] = ANISO_SOURCE_DIR;
const char kCliPath[] = ANISO_CLI_PATH;
const char kScratchDir[] = ANISO_TEST_TMP;

}  // namespace aniso::test
