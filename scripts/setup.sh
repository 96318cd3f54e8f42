#!/usr/bin/env bash
# Installs what is missing on a fresh machine, idempotently: Rust components and targets,
# pinned cargo tools, Debian packages (when root), npm packages.
set -euo pipefail
cd "$(dirname "$0")/.."

say() { printf '\n== %s\n' "$*"; }

if ! command -v cargo >/dev/null 2>&1; then
  echo "cargo not found: install Rust with rustup (https://rustup.rs) first" >&2
  exit 1
fi

say "rust components"
for c in rustfmt clippy; do
  rustup component list --installed 2>/dev/null | grep -q "^$c" || rustup component add "$c"
done

# ---- web: wasm target, pinned wasm-bindgen and wasm-pack, Chromium, npm packages ----
say "wasm32 target"
rustup target list --installed 2>/dev/null | grep -q '^wasm32-unknown-unknown$' \
  || rustup target add wasm32-unknown-unknown

say "wasm-bindgen (pinned to Cargo.lock)"
wb_want="$(grep -A1 '^name = "wasm-bindgen"$' Cargo.lock | sed -n 's/^version = "\(.*\)"/\1/p' | head -1)"
wb_have="$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)"
if [ "$wb_want" != "$wb_have" ]; then
  cargo install wasm-bindgen-cli --version "$wb_want"
fi

# wasm-pack builds the npm package (scripts/build-wasm.sh, which reads this pin); pinned so that
# its cargo and wasm-bindgen command lines, and so the package's bytes, do not change under it.
WASM_PACK_VERSION=0.15.1
say "wasm-pack $WASM_PACK_VERSION"
wp_have="$(wasm-pack --version 2>/dev/null | awk '{print $2}' || true)"
if [ "$WASM_PACK_VERSION" != "$wp_have" ]; then
  cargo install wasm-pack --locked --version "$WASM_PACK_VERSION"
fi

if [ ! -x /usr/bin/chromium ]; then
  if [ "$(id -u)" = 0 ]; then
    say "chromium (Debian) for the browser tests"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
  else
    echo "note: /usr/bin/chromium is missing (apt-get install chromium); browser tests will fail" >&2
  fi
fi

say "npm packages"
if [ ! -d node_modules ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  if [ -n "${CI:-}" ]; then npm ci --no-audit --no-fund; else npm install --no-audit --no-fund; fi
fi

# ---- Python: a virtual environment of the project's own for the wheel's tests ----
say "python test environment (target/python-env)"
if ! command -v python3 >/dev/null 2>&1; then
  echo "python3 not found: install CPython >= 3.9 (the Python package's tests need it)" >&2
  exit 1
fi
PY_ENV=target/python-env
if [ ! -x "$PY_ENV/bin/python" ]; then
  python3 -m venv "$PY_ENV"
fi
# Reinstalled only when the requirements change.
if ! cmp -s python/requirements-test.txt "$PY_ENV/requirements-test.txt"; then
  "$PY_ENV/bin/pip" install -q --upgrade pip
  "$PY_ENV/bin/pip" install -q -r python/requirements-test.txt
  cp python/requirements-test.txt "$PY_ENV/requirements-test.txt"
fi
