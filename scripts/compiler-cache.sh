# Sourced by test.sh and build-wasm.sh: compile through ccache (a Debian
# package, installed by setup.sh) when it is there.
#
# A fresh clone of the repository compiles the same text with the same flags
# as the last checkout built here did, and ccache hands back those objects:
# the compiler's own output, keyed on the preprocessed text, the flags and
# the compiler. Paths inside the checkout count relative to it
# (CCACHE_BASEDIR), so a clone in another folder is served too; for that the
# unity batches include their sources by relative path (CMakeLists.txt) and
# the tests' absolute paths sit in one small file (tests/build_paths.h).
# The sanitizer ignorelist, which the compiler reads without an #include, is
# hashed by its content with every compile (CCACHE_EXTRAFILES), so that a
# change to it is never served stale objects, and not by its absolute path in
# the option that names it (CCACHE_IGNOREOPTIONS).
# Sets ANISO_COMPILER_LAUNCHER to the CMake arguments that turn the cache on,
# or off (an empty launcher) without ccache or with ANISO_CCACHE=0.
# Needs ROOT, the checkout's root.
ANISO_COMPILER_LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER= -DCMAKE_C_COMPILER_LAUNCHER=)
if [ "${ANISO_CCACHE:-1}" != 0 ] && command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="$ROOT"
  # Debug line tables name the compiler's working folder; it is left out of
  # the key (the objects are the same code), or no other folder would hit.
  export CCACHE_NOHASHDIR=1
  # A miss costs no more than the compile: the key is read from the
  # compiler's own dependency list (-MD, which CMake's Ninja builds pass)
  # instead of a second, preprocessing run.
  export CCACHE_DEPEND=1
  export CCACHE_EXTRAFILES="$ROOT/cmake/sanitizer-ignorelist.txt"
  export CCACHE_IGNOREOPTIONS='-fsanitize-ignorelist=*'
  if [ -z "${CCACHE_DIR:-}" ] && [ -z "${HOME:-}" ]; then
    export CCACHE_DIR=/var/cache/anisoform-ccache
  fi
  ANISO_COMPILER_LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
