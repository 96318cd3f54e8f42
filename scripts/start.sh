#!/usr/bin/env bash
# Installs what is missing, builds, and serves the page.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --locked

# ---- web: build the npm package and serve the page ----
bash scripts/build-wasm.sh
npm run build:web
PORT="${PORT:-5173}"
echo
echo "  logic-lfd demo: http://localhost:$PORT/"
echo
exec npm run preview -w web -- --port "$PORT" --strictPort --host 127.0.0.1
