// Where this build's files are: the shared meshes, the checkout, the CLI and
// a scratch folder. Compiled into build_paths.cpp alone, not into the test
// files: they then hold no path of the checkout, and a clone in another
// folder compiles the same text, which a compiler cache can serve
// (scripts/compiler-cache.sh).
#pragma once

namespace aniso::test {

extern const char kMeshesDir[];  // ../shared/meshes
extern const char kSourceDir[];  // the repository's root
extern const char kCliPath[];    // the anisoform executable of this build
extern const char kScratchDir[];  // files the tests write

}  // namespace aniso::test
