#!/usr/bin/env bash
# Runs the app: installs what is missing, builds the WASM module and the site,
# and serves web/dist (a self-contained static site with the default mesh
# bundled) on http://127.0.0.1:${PORT:-8080}/. Idempotent; Ctrl+C stops it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
npm run build --prefix web
PORT=${PORT:-8080}
echo "Anisoform: open http://127.0.0.1:${PORT}/"
exec python3 -m http.server "$PORT" --bind 127.0.0.1 --directory web/dist
