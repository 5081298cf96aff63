#!/usr/bin/env bash
# Runs the app: installs what is missing, builds the WASM module and the site,
# and serves web/dist (a self-contained static site with the default mesh
# bundled) on http://127.0.0.1:${PORT:-8080}/, with the strict
# Content-Security-Policy the tests use (scripts/serve-static.mjs; violations
# are printed). Idempotent; Ctrl+C stops it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
npm run build --prefix web
PORT=${PORT:-8080}
echo "Anisoform: open http://127.0.0.1:${PORT}/"
exec node scripts/serve-static.mjs web/dist --port "$PORT"
