#!/usr/bin/env bash
# Checks that the npm package wasm-pack builds (pkg/, scripts/build-wasm.sh) is byte-identical to
# the one `cargo build` and the pinned wasm-bindgen build directly, every file of the tree: the
# build may change tools, never the package. Usage: scripts/check-wasm-pack.sh [--no-build]
# (--no-build: pkg/ was just built from these sources, as in scripts/test.sh).
# The second build reuses cargo's cache: it costs wasm-bindgen and wasm-opt (about 2 minutes).
set -euo pipefail
cd "$(dirname "$0")/.."

if [ "${1:-}" != --no-build ]; then
  bash scripts/build-wasm.sh
fi
if [ ! -f pkg/package.json ]; then
  echo "pkg/ is missing: run scripts/build-wasm.sh (or drop --no-build)" >&2
  exit 1
fi

ref="$(mktemp -d "${TMPDIR:-/tmp}/logic-lfd-pkg.XXXXXX")"
trap 'rm -rf "$ref"' EXIT
WASM_BUILDER=wasm-bindgen PKG_DIR="$ref/pkg" bash scripts/build-wasm.sh

echo "== comparing pkg/ (wasm-pack) with the wasm-bindgen build"
if ! diff -r pkg "$ref/pkg"; then
  echo "pkg/ from wasm-pack differs from the wasm-bindgen build (above)" >&2
  exit 1
fi
echo "== identical: $(find pkg -type f | wc -l) files"
