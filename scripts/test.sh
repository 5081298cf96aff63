#!/usr/bin/env bash
# Runs every test: installs what is missing, builds natively and as WASM, runs
# the Catch2 suite through ctest (plain and under ASan+UBSan), the Node tests of
# the WASM module, and the Playwright end-to-end tests of the web app.
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

stage() { printf '\n=== %s (%ss)\n' "$1" "$SECONDS"; }

stage "set-up"
bash scripts/setup.sh

stage "native build"
cmake -S . -B build-native -DCMAKE_BUILD_TYPE=Release -DANISO_SHARED_DIR="$ANISO_SHARED_DIR" >/dev/null
cmake --build build-native -j"$JOBS"

stage "native tests (ctest)"
ctest --test-dir build-native -j"$JOBS" --output-on-failure --timeout 300

stage "sanitizer build (ASan + UBSan)"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DANISO_SANITIZE=ON -DANISO_BENCH=OFF -DANISO_SHARED_DIR="$ANISO_SHARED_DIR" >/dev/null
cmake --build build-asan -j"$JOBS"

stage "sanitizer tests (ctest)"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan -j"$JOBS" --output-on-failure --timeout 900

stage "WASM build (emcmake)"
bash scripts/build-wasm.sh

stage "WASM tests (node --test)"
ANISO_CLI="$ROOT/build-native/cli/anisoform" node --test wasm/test/

stage "web build"
npm run build --prefix web

stage "end-to-end tests (Playwright, Debian chromium)"
CI=${CI:-} npx --prefix web playwright test -c e2e/playwright.config.mjs

stage "all tests passed"
