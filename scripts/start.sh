#!/usr/bin/env bash
# Installs what is missing, builds, and serves the page.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --locked
