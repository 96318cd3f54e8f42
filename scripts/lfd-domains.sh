#!/usr/bin/env bash
# Logic-LfD against planning from scratch on every shipped domain and four IPC problems, in both
# modes: the README's "Logic-LfD on domains that are not the robot's" table.
#
#   [OPTIMAL_TIME_LIMIT=S] bash scripts/lfd-domains.sh [COUNT] [SEED] [SEARCH] [HEURISTIC]
#
# Defaults: 200 perturbed states, seed 1, lazy-gbfs with hff. IPC demonstrations are the
# planner's own A* + LM-cut plans (written to a temporary folder). Prints one summary line per
# domain and mode; exits non-zero if any merged plan fails to replay.
set -euo pipefail
cd "$(dirname "$0")/.."
count="${1:-200}"; seed="${2:-1}"; search="${3:-lazy-gbfs}"; heuristic="${4:-hff}"
# Seconds A* + LM-cut gets per state to prove the optimal length (merged/optimal column).
optimal="${OPTIMAL_TIME_LIMIT:-1}"
bin=target/release/logic-lfd
[ -x "$bin" ] || cargo build --release --locked
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
rows=()
for d in domains/kitchen domains/delivery; do
  rows+=("$(basename "$d")|$d/domain.pddl|$d/problem.pddl|$d/demo.plan")
done
for spec in blocks:probBLOCKS-8-0 blocks-typed:probBLOCKS-8-0 gripper:prob05 \
            logistics00:probLOGISTICS-6-0 depot-typed:p03; do
  dir="tests/data/ipc/${spec%%:*}"; prob="${spec#*:}"
  demo="$tmp/${spec%%:*}-$prob.plan"
  "$bin" plan "$dir/domain.pddl" "$dir/$prob.pddl" --search astar --heuristic lmcut >"$demo"
  rows+=("IPC ${spec%%:*} $prob|$dir/domain.pddl|$dir/$prob.pddl|$demo")
done
status=0
for row in "${rows[@]}"; do
  IFS='|' read -r name domain problem demo <<<"$row"
  for mode in paper prioritised; do
    out="$("$bin" lfd "$domain" "$problem" "$demo" --perturb "$count" --seed "$seed" \
      --mode "$mode" --search "$search" --heuristic "$heuristic" --optimal-time-limit "$optimal")" || status=1
    n="$(grep -c "^ *(" "$demo")"
    printf '%s | %s actions | %s | %s | %s\n' "$name" "$n" "$mode" \
      "$(grep '^median ms' <<<"$out")" "$(grep '^merged/optimal' <<<"$out")"
  done
done
exit "$status"
