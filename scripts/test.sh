#!/usr/bin/env bash
# Every check of the project, in the order CI runs them (`.ci/run` calls this via `npm test`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh

step() { printf '\n== %s\n' "$*"; }

step "cargo fmt --check"
cargo fmt --all -- --check

step "cargo clippy -D warnings"
cargo clippy --workspace --all-targets --locked -- -D warnings

step "cargo test"
cargo test --workspace --locked

step "cargo build --all-targets (benches and examples build from a clone alone)"
cargo build --workspace --all-targets --locked

step "cargo doc -D warnings"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked

# ---- web: the npm package, the page, node and browser tests ----
step "wasm build (npm package into pkg/, with wasm-pack)"
bash scripts/build-wasm.sh

# wasm-pack must not change the package: the same bytes as cargo + wasm-bindgen (about 2 minutes).
step "pkg/ byte-identical to a direct wasm-bindgen build"
bash scripts/check-wasm-pack.sh --no-build

step "tsc --noEmit"
npm run typecheck

step "node tests of the built package"
npm run test:node

step "page build (vite)"
npm run build:web

step "browser tests (Playwright + Chromium)"
npm run test:e2e

# ---- Python: the wheel built from python/ and installed as a user installs it ----
step "python: pip install ./python, then pytest (stubs checked by mypy)"
bash scripts/test-python.sh
