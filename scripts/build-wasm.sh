#!/usr/bin/env bash
# Builds the npm package `logic-lfd` into pkg/: the crate for wasm32 (speed-optimised profile
# wasm-speed, wasm-opt -O3), bindings for the web (`init()` then use) and for node (CommonJS,
# ready on require), wasm-opt from the npm `binaryen` package (Debian's binaryen 108 emits broken
# modules).
# Also builds pkg/page/ (not part of the npm package) for the page: logic_lfd.js, its first-load
# module (feature `wasm-core` alone: the Session on B1's template task, `benchmark` and `blockRange`, without
# Teach mode, Session.replay, Session.fromScene, B2, B3, N-block tasks, JSON paths in load errors,
# the PDDL tab's plan, check, logicLfd and logicLfdPerturb, and the npm-only lqt, validate and
# runEpisode; size-optimised profile wasm-release, then wasm-opt -Os, for the first-load target),
# and logic_lfd_teach.js, the full module under its own name (the npm package's build), which the
# page's worker fetches after the first frame and moves its session onto (web/src/speed-up.ts).
#
# wasm-pack (pinned in scripts/setup.sh) runs cargo and the pinned wasm-bindgen for each output.
# WASM_BUILDER=wasm-bindgen runs `cargo build` and `wasm-bindgen` directly instead, and PKG_DIR
# builds elsewhere than pkg/: scripts/check-wasm-pack.sh builds both ways and compares the trees.
set -euo pipefail
cd "$(dirname "$0")/.."

# wasm-pack runs cargo in crate/, so a relative target dir must not be read from there.
if [ -n "${CARGO_TARGET_DIR:-}" ]; then
  case "$CARGO_TARGET_DIR" in /*) ;; *) CARGO_TARGET_DIR="$PWD/$CARGO_TARGET_DIR" ;; esac
  export CARGO_TARGET_DIR
fi
TARGET_DIR="${CARGO_TARGET_DIR:-target}"
wasm_of() { echo "$TARGET_DIR/wasm32-unknown-unknown/$1/logic_lfd.wasm"; }
OUT="${PKG_DIR:-pkg}"
case "$OUT" in /*) ;; *) OUT="$PWD/$OUT" ;; esac
BUILDER="${WASM_BUILDER:-wasm-pack}"

want="$(grep -A1 '^name = "wasm-bindgen"$' Cargo.lock | sed -n 's/^version = "\(.*\)"/\1/p' | head -1)"
have="$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')"
if [ "$want" != "$have" ]; then
  echo "wasm-bindgen $want is needed (found '${have:-none}'): run scripts/setup.sh" >&2
  exit 1
fi
case "$BUILDER" in
  wasm-pack)
    wp_want="$(sed -n 's/^WASM_PACK_VERSION=//p' scripts/setup.sh)"
    wp_have="$(wasm-pack --version 2>/dev/null | awk '{print $2}' || true)"
    if [ "$wp_want" != "$wp_have" ]; then
      echo "wasm-pack $wp_want is needed (found '${wp_have:-none}'): run scripts/setup.sh" >&2
      exit 1
    fi
    ;;
  wasm-bindgen) ;;
  *)
    echo "WASM_BUILDER must be wasm-pack or wasm-bindgen (got '$BUILDER')" >&2
    exit 1
    ;;
esac
if [ ! -x node_modules/.bin/wasm-opt ]; then
  echo "node_modules/.bin/wasm-opt missing: run npm ci (scripts/setup.sh does)" >&2
  exit 1
fi

# bind PROFILE FEATURES TARGET DIR NAME: the crate for wasm32 in cargo profile PROFILE with
# FEATURES, and its bindings for TARGET (web or nodejs) as DIR/NAME.js, NAME_bg.wasm, *.d.ts.
# Keep the target_features section for wasm-bindgen; wasm-opt strips names afterwards.
# wasm-pack: --mode no-install takes wasm-bindgen from the PATH (the pinned one, never a
# download); --no-opt because its wasm-opt is a download (binaryen from node_modules runs below);
# --no-pack and --no-gitignore because the package's files are written below.
bind() {
  if [ "$BUILDER" = wasm-pack ]; then
    echo "== wasm-pack build (profile $1, features $2, target $3) -> ${4#"$PWD"/}/$5"
    CARGO_PROFILE_WASM_RELEASE_STRIP=false CARGO_PROFILE_WASM_SPEED_STRIP=false \
      wasm-pack build crate --mode no-install --no-opt --no-pack --no-gitignore \
      --target "$3" --profile "$1" --out-dir "$4" --out-name "$5" -- --features "$2" --locked
  else
    echo "== cargo build (wasm32, profile $1, features $2), wasm-bindgen $have (target $3) -> ${4#"$PWD"/}/$5"
    CARGO_PROFILE_WASM_RELEASE_STRIP=false CARGO_PROFILE_WASM_SPEED_STRIP=false \
      cargo build --target wasm32-unknown-unknown --profile "$1" --features "$2" -p logic-lfd --lib --locked
    wasm-bindgen "$(wasm_of "$1")" --target "$3" --out-dir "$4" --out-name "$5"
  fi
}
FEATURES=(--enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext
  --enable-mutable-globals --enable-reference-types --enable-multivalue)
wasm_opt() {
  local file="$1"
  shift
  echo "== wasm-opt $* ${file#"$PWD"/}"
  node_modules/.bin/wasm-opt "$@" --strip-debug --strip-producers "${FEATURES[@]}" "$file" -o "$file"
}

rm -rf "$OUT"
mkdir -p "$OUT/web" "$OUT/node" "$OUT/page"

bind wasm-release wasm-core web "$OUT/page" logic_lfd
# -Os on the size-built module: as fast as -O3 on the page's replans and episodes, 2.2 KB gzipped
# smaller (docs/performance.md).
wasm_opt "$OUT/page/logic_lfd_bg.wasm" -Os

bind wasm-speed wasm web "$OUT/web" logic_lfd
bind wasm-speed wasm nodejs "$OUT/node" logic_lfd
bind wasm-speed wasm web "$OUT/page" logic_lfd_teach
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
  echo "== ${OUT#"$PWD"/}/$f ready: $raw bytes ($gz gzipped)"
done
