#!/usr/bin/env bash
# The reproduction gallery: runs the paper's figure scenes (the Catch2 tests
# tagged [figures] and the Fig. 11 flattening) with ANISO_FIGURES_DIR set, so
# that they record their meshes and measured values (tests/figure_record.h),
# then renders every picture headless in Chromium with the app's viewer code
# and writes docs/FIGURES.md and docs/figures/*.png (scripts/figures/).
# A doc generator, not a test: the test command does not run it.
# Deterministic: a re-run on the same machine writes the same bytes.
#   bash scripts/figures.sh            (build dir: build-dev, a Release build)
#   ANISO_FIGURES_BUILD_DIR=DIR bash scripts/figures.sh
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${ANISO_FIGURES_BUILD_DIR:-build-dev}
if [ ! -f "$BUILD/build.ninja" ]; then
  # Optimised, without sanitizers: the scenes run in seconds.
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DANISO_UNITY_BUILD=OFF -DANISO_BENCH=OFF
fi
cmake --build "$BUILD" --target anisoform_tests
if [ ! -f web/node_modules/playwright-core/index.mjs ] || [ ! -d web/node_modules/three ]; then
  echo "figures.sh: web/node_modules is missing: run bash scripts/setup.sh (or npm ci --prefix web)" >&2
  exit 1
fi

DATA=$(mktemp -d)
trap 'rm -rf "$DATA"' EXIT
# The figure scenes only (the [anarap] convergence checks share the tag but show nothing).
# A failed check does not stop the gallery (it shows what was measured), but
# the script then exits non-zero.
status=0
ANISO_FIGURES_DIR="$DATA" "$BUILD/tests/anisoform_tests" "[figures]~[anarap],flatten (fig. 11)*" || status=$?
node scripts/figures/render.mjs "$DATA" docs
if [ "$status" -ne 0 ]; then
  echo "figures.sh: some figure checks failed (above); docs/FIGURES.md shows what they measured" >&2
  exit "$status"
fi
