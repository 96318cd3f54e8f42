#!/usr/bin/env bash
# Regenerates every result the README and docs/ quote, into one folder (default docs/results),
# with an index naming the commit, the machine and the command of each file.
#
#   bash scripts/bench-all.sh [OUT] [--quick] [--no-web]     (npm run bench:all)
#
# --quick runs every experiment small (a smoke run: minutes, numbers not for quoting).
# --no-web skips the node/Chromium timings (they need the wasm package and Chromium).
# Not included: Fast Downward comparisons (need `up-fast-downward`, see docs/reproduction.md)
# and criterion (`cargo bench`), whose numbers are machine-specific micro-benchmarks.
set -euo pipefail
cd "$(dirname "$0")/.."

OUT=docs/results
QUICK=0
WEB=1
for a in "$@"; do
  case "$a" in
    --quick) QUICK=1 ;;
    --no-web) WEB=0 ;;
    -*) echo "bench-all: unknown option $a" >&2; exit 2 ;;
    *) OUT="$a" ;;
  esac
done
mkdir -p "$OUT"

if [ "$QUICK" = 1 ]; then
  TASKS=4 TRIALS=1 SCALE_BLOCKS=4,6 SCALE_TASKS=2 SOAK=10 LFD_COUNT=10 PAGE_RUNS=1 WASM_RUNS=1
else
  TASKS=100 TRIALS=10 SCALE_BLOCKS=4,8,12,16,20 SCALE_TASKS=30 SOAK=300 LFD_COUNT=200 PAGE_RUNS=3 WASM_RUNS=5
fi

cargo build --release --locked -q -p logic-lfd --bin logic-lfd
BIN=target/release/logic-lfd
COMMIT=$(git rev-parse --short HEAD)
DIRTY=$(git status --porcelain --untracked-files=no | grep -v " $OUT/" | head -1 || true)
[ -n "$DIRTY" ] && COMMIT="$COMMIT (with uncommitted changes)"
CPU=$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2 | sed 's/^ *//' || echo unknown)
INDEX="$OUT/README.md"

{
  echo "# Results"
  echo
  echo "Every file here was written by \`bash scripts/bench-all.sh$([ "$QUICK" = 1 ] && echo ' --quick')\`"
  echo "on commit \`$COMMIT\`, $(date -u +%Y-%m-%d), $(nproc) × $CPU, release build."
  echo "Wall-clock times depend on the machine and its load; success counts and simulated times"
  echo "are functions of the seeds."
  echo
  echo "| file | what | command |"
  echo "|---|---|---|"
} > "$INDEX"

# run NAME WHAT -- COMMAND…: stdout into $OUT/NAME, progress on stderr into $OUT/NAME.log.
run() {
  local name=$1 what=$2
  shift 3
  echo "bench-all: $name ($*)" >&2
  local t0=$SECONDS
  "$@" > "$OUT/$name" 2> "$OUT/$name.log"
  echo "| [$name]($name) | $what | \`${*/#$BIN/logic-lfd}\` |" >> "$INDEX"
  echo "bench-all: $name done in $((SECONDS - t0)) s" >&2
}

run table1.md "Table I, Logic-LfD's TAMP fallback off" -- \
  $BIN bench table1 --tasks $TASKS --seed 1
run table1.json "the same, every cell's raw numbers" -- \
  $BIN bench table1 --tasks $TASKS --seed 1 --json
run table1-fallback.md "Table I with the TAMP fallback on (its count)" -- \
  $BIN bench table1 --tasks $TASKS --seed 1 --tamp-fallback
run table2.md "Table II" -- $BIN bench table2 --trials $TRIALS --seed 1
run table2.json "the same, every cell's raw numbers" -- \
  $BIN bench table2 --trials $TRIALS --seed 1 --json
if $BIN bench --help | grep -q fig4; then
  run fig4.md "Fig. 4: LQT-CP and DMP, pick the hook, pull the block through via-points" -- \
    $BIN bench fig4 --svg "$OUT/fig4.svg"
  run fig4.json "the same as JSON" -- $BIN bench fig4 --json
fi
run scaling.md "first-plan time against the number of blocks (B1 towers)" -- \
  $BIN bench scaling --blocks $SCALE_BLOCKS --tasks $SCALE_TASKS --seed 1 --svg "$OUT/scaling.svg"
run soak.md "soak: disturbed episodes of every method, outcomes with reasons" -- \
  $BIN soak --episodes $SOAK --seed 4242 --max-disturbances 12

if [ "$WEB" = 1 ]; then
  bash scripts/build-wasm.sh > /dev/null
  run lfd-domains.md "Logic-LfD against planning from scratch on PDDL domains, native and wasm" -- \
    node tests/node/bench-lfd.mjs --count $LFD_COUNT --seed 1
  npm run -s build:web > /dev/null
  run wasm.md "native against wasm on the hot paths (same code, same inputs), module and page sizes" -- \
    node tests/node/bench-wasm.mjs --runs $WASM_RUNS
  run page.md "the page in Chromium: first load, tick, replanning" -- \
    node tests/e2e/bench.mjs --runs $PAGE_RUNS
fi
echo "bench-all: wrote $OUT (index: $INDEX)" >&2
