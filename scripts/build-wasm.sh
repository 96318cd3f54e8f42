#!/usr/bin/env bash
# Builds the npm package `logic-lfd` into pkg/: the crate for wasm32 (speed-optimised profile
# wasm-speed, wasm-opt -O3), wasm-bindgen for the web (`init()` then use) and for node (CommonJS,
# ready on require), wasm-opt from the npm `binaryen` package (Debian's binaryen 108 emits broken
# modules).
# Also builds pkg/page/ (not part of the npm package) for the page: logic_lfd.js, its first-load
# module (feature `wasm-core` alone: the Session on B1's template task, `benchmark` and `blockRange`, without
# Teach mode, Session.replay, Session.fromScene, B2, B3, N-block tasks, JSON paths in load errors,
# the PDDL tab's plan, check, logicLfd and logicLfdPerturb, and the npm-only lqt, validate and
# runEpisode; size-optimised profile wasm-release, then wasm-opt -O3, for the first-load target),
# and logic_lfd_teach.js, the full module under its own name (the npm package's build), which the
# page's worker fetches after the first frame and moves its session onto (web/src/speed-up.ts).
set -euo pipefail
cd "$(dirname "$0")/.."

TARGET_DIR="${CARGO_TARGET_DIR:-target}"
wasm_of() { echo "$TARGET_DIR/wasm32-unknown-unknown/$1/logic_lfd.wasm"; }
OUT=pkg

want="$(grep -A1 '^name = "wasm-bindgen"$' Cargo.lock | sed -n 's/^version = "\(.*\)"/\1/p' | head -1)"
have="$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')"
if [ "$want" != "$have" ]; then
  echo "wasm-bindgen $want is needed (found '${have:-none}'): run scripts/setup.sh" >&2
  exit 1
fi
if [ ! -x node_modules/.bin/wasm-opt ]; then
  echo "node_modules/.bin/wasm-opt missing: run npm ci (scripts/setup.sh does)" >&2
  exit 1
fi

# Keep the target_features section for wasm-bindgen; wasm-opt strips names afterwards.
build() {
  echo "== cargo build (wasm32, profile $1, features $2)"
  CARGO_PROFILE_WASM_RELEASE_STRIP=false CARGO_PROFILE_WASM_SPEED_STRIP=false \
    cargo build --target wasm32-unknown-unknown --profile "$1" --features "$2" -p logic-lfd --lib --locked
}
FEATURES=(--enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext
  --enable-mutable-globals --enable-reference-types --enable-multivalue)
wasm_opt() {
  local file="$1"
  shift
  echo "== wasm-opt $* $file"
  node_modules/.bin/wasm-opt "$@" --strip-debug --strip-producers "${FEATURES[@]}" "$file" -o "$file"
}

rm -rf "$OUT"
mkdir -p "$OUT/web" "$OUT/node" "$OUT/page"

build wasm-release wasm-core
echo "== wasm-bindgen $have (page)"
wasm-bindgen "$(wasm_of wasm-release)" --target web --out-dir "$OUT/page" --out-name logic_lfd
# -O3 on the size-built module: 1.3–1.5× faster than -Oz on the hot paths for ~3 KB gzipped more
# (docs/performance.md).
wasm_opt "$OUT/page/logic_lfd_bg.wasm" -O3

build wasm-speed wasm
WASM="$(wasm_of wasm-speed)"
echo "== wasm-bindgen $have"
wasm-bindgen "$WASM" --target web --out-dir "$OUT/web" --out-name logic_lfd
wasm-bindgen "$WASM" --target nodejs --out-dir "$OUT/node" --out-name logic_lfd
wasm-bindgen "$WASM" --target web --out-dir "$OUT/page" --out-name logic_lfd_teach
wasm_opt "$OUT/web/logic_lfd_bg.wasm" -O3
cp "$OUT/web/logic_lfd_bg.wasm" "$OUT/node/logic_lfd_bg.wasm"
wasm_opt "$OUT/page/logic_lfd_teach_bg.wasm" -O3

# The node build is CommonJS (ready as soon as it is required); index.mjs gives ESM importers the
# same shape as the web build (a default `init()` that resolves at once), so code runs unchanged.
echo '{ "type": "commonjs" }' > "$OUT/node/package.json"
cat > "$OUT/node/index.mjs" <<'JS'
export * from './logic_lfd.js';
/** The node build is instantiated on import; `init()` exists so browser code runs unchanged. */
export default async function init() {}
JS
cat > "$OUT/node/index.d.mts" <<'TS'
export * from './logic_lfd.js';
/** The node build is instantiated on import; `init()` exists so browser code runs unchanged. */
export default function init(_module_or_path?: unknown): Promise<void>;
TS
cp npm/package.json npm/README.md "$OUT/"
ver="$(sed -n 's/^version = "\(.*\)"/\1/p' crate/Cargo.toml | head -1)"
node -e '
  const fs = require("fs"); const p = JSON.parse(fs.readFileSync(process.argv[1], "utf8"));
  p.version = process.argv[2]; fs.writeFileSync(process.argv[1], JSON.stringify(p, null, 2) + "\n");
' "$OUT/package.json" "$ver"

for f in web/logic_lfd_bg.wasm page/logic_lfd_bg.wasm; do
  raw=$(wc -c < "$OUT/$f")
  gz=$(gzip -9 -c "$OUT/$f" | wc -c)
  echo "== pkg/$f ready: $raw bytes ($gz gzipped)"
done
