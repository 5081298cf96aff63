#!/usr/bin/env bash
# Installs what Anisoform needs on Debian bookworm, as root, from Debian's
# packages and the npm registry only (web/package-lock.json pins the npm side).
# Idempotent: packages already present are not reinstalled.
set -euo pipefail
cd "$(dirname "$0")/.."

APT_PACKAGES=(
  build-essential cmake ninja-build pkg-config   # native toolchain
  clang libclang-rt-14-dev                       # sanitizer + libFuzzer build (clang 14, as emscripten's)
  libeigen3-dev                                  # the core's only dependency
  catch2 libcli11-dev nlohmann-json3-dev         # tests and the CLI
  libcgal-dev                                    # benchmark peer only (GPL, never linked into the library)
  emscripten                                     # the WASM build (3.1.6, prebuilt frozen cache)
  chromium-headless-shell                        # Playwright drives Debian's Chromium (headless shell); no browser download
  libegl1 libegl-mesa0 libgl1-mesa-dri          # Mesa's llvmpipe: the e2e browser's WebGL (e2e/renderer.mjs)
  python3 gzip
  ccache                                         # compiler cache for rebuilds and fresh clones (compiler-cache.sh)
)
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  APT_PACKAGES+=(nodejs npm)
fi

missing=()
for pkg in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

node_major=$(node -p 'process.versions.node.split(".")[0]')
if [ "$node_major" -lt 20 ]; then
  echo "setup: Node.js >= 20 is needed for the web build (found $(node --version))" >&2
  exit 1
fi

# npm packages exactly as locked; skipped when node_modules already matches the lock.
if [ -f web/package-lock.json ]; then
  if [ ! -f web/node_modules/.package-lock.json ] || ! cmp -s web/package-lock.json web/.installed-lock 2>/dev/null; then
    echo "setup: npm ci (web)"
    npm ci --prefix web --no-audit --no-fund --loglevel=error
    cp web/package-lock.json web/.installed-lock
  fi
fi
