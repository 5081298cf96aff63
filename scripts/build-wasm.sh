#!/usr/bin/env bash
# Builds the WASM module (core + wasm/ bindings) with emcmake and checks that
# the CMake build copied it into web/src/wasm/, where the site imports it.
# Called by `npm run build --prefix web` (script build:wasm).
#   ANISO_WASM_BUILD_DIR  build folder (default: build-wasm/ in the repo, git-ignored)
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${ANISO_WASM_BUILD_DIR:-${repo_root}/build-wasm}"

for tool in emcmake cmake node; do
  if ! command -v "$tool" >/dev/null; then
    echo "build-wasm: '$tool' is not installed (Debian: apt-get install emscripten cmake nodejs libeigen3-dev)" >&2
    exit 1
  fi
done

# emcmake's default emulator passes a flag Node 20 rejects (TOOLCHAIN.md §1).
# Unity batches: one per core (CMakeLists.txt, ANISO_UNITY_BATCHES); 0 for
# batches of 8 sources, quicker to rebuild after a change.
ROOT="$repo_root"
source "${repo_root}/scripts/compiler-cache.sh"
emcmake cmake -S "$repo_root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CROSSCOMPILING_EMULATOR=/usr/bin/node -DANISO_UNITY_BATCHES="${ANISO_UNITY_BATCHES:-2}" \
  "${ANISO_COMPILER_LAUNCHER[@]}"
cmake --build "$build_dir" -j2

for file in anisoform.mjs anisoform.wasm anisoform-wasm.mjs; do
  if [[ ! -f "${repo_root}/web/src/wasm/${file}" ]]; then
    echo "build-wasm: web/src/wasm/${file} is missing after the build" >&2
    exit 1
  fi
done
echo "build-wasm: web/src/wasm/ is up to date ($(wc -c < "${repo_root}/web/src/wasm/anisoform.wasm") bytes of WASM)"
