#!/usr/bin/env bash
# Runs every test: installs what is missing, builds natively and as WASM, runs
# the Catch2 suite through ctest under ASan+UBSan, the Node tests of the WASM
# module, the Playwright end-to-end tests of the web app, and a short libFuzzer
# run over the mesh readers and solvers.
#
# One native build serves the Catch2 suite, the CLI the Node tests compare
# against, and the fuzzer: clang with AddressSanitizer + UndefinedBehavior-
# Sanitizer (UBSan not inside Eigen: cmake/sanitizer-ignorelist.txt), the
# core at -O2 (the test files at -O0), line tables only. Its machine code is
# selected by LLVM's fast instruction selector (-mllvm -fast-isel, what -O0
# uses), after the same -O2 optimisation of the same instrumented IR: the
# core's two batches compiled in 59 + 61 s against 75 + 69 s; the tests ran
# at most 5 % slower (summed 118 against 113 s; ctest 60.7 and 59.9 s against
# 61.0 and 53.9, alternated), the fuzzer no slower.
# Every test therefore runs with the sanitizers' checks; the optimised release configuration is what the WASM
# module ships (tested in Node and Playwright) and what the benchmark builds
# (bench/README.md).
# Order: fail fast on the cheap stages; the fuzzer last.
# Idempotent; build trees live in build-*/ (git-ignored).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
JOBS=${JOBS:-2}
export ANISO_SHARED_DIR=${ANISO_SHARED_DIR:-$ROOT/../shared}
if [ ! -d "$ANISO_SHARED_DIR/meshes" ]; then
  echo "test: the shared meshes are missing: expected $ANISO_SHARED_DIR/meshes" >&2
  exit 1
fi
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

stage() { printf '\n=== %s (%ss)\n' "$1" "$SECONDS"; }

stage "set-up"
bash scripts/setup.sh

# Both builds compile through ccache where it is installed
# (scripts/compiler-cache.sh).
source scripts/compiler-cache.sh

stage "native build (clang, ASan + UBSan, libFuzzer targets)"
CC=clang CXX=clang++ cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG="-O2 -gline-tables-only -mllvm -fast-isel" -DANISO_SANITIZE=ON -DANISO_FUZZ=ON \
  -DANISO_BENCH=OFF -DANISO_UNITY_BATCHES="$JOBS" -DANISO_SHARED_DIR="$ANISO_SHARED_DIR" \
  "${ANISO_COMPILER_LAUNCHER[@]}" >/dev/null
cmake --build build-asan -j"$JOBS"

stage "native tests (ctest)"
ctest --test-dir build-asan -j"$JOBS" --output-on-failure --timeout 600

stage "WASM build (emcmake)"
bash scripts/build-wasm.sh

stage "WASM tests (node --test)"
# Two files at a time (node's default is one fewer than the cores: one here).
ANISO_CLI="$ROOT/build-asan/cli/anisoform" node --test --test-concurrency="$JOBS" wasm/test/

stage "web build (the site and the anisoform package)"
npm run build:site --prefix web

stage "type declarations (tsc: the package and the page API, built on the module's one contract)"
npm run check:types --prefix web

stage "end-to-end tests (Playwright, Debian's chromium-headless-shell)"
CI=${CI:-} npx --prefix web playwright test -c e2e/playwright.config.mjs

stage "fuzzing (libFuzzer, short run; long: bash scripts/fuzz.sh --seconds 3600)"
bash scripts/fuzz.sh

stage "all tests passed"
