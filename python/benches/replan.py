"""`LogicLfd.replan` from Python against the same native Rust calls, side by side in one run.

For each case, the median of `--repeats` calls of `LogicLfd.replan(state)` (timed in Python,
so the binding's argument conversion and result building count) and of the same core calls
timed inside Rust (`LogicLfd._native_replan_seconds`), and their ratio.

    python python/benches/replan.py --repeats 300
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

import logic_lfd

DOMAINS = Path(__file__).resolve().parents[2] / "domains"


def cases() -> list[tuple[str, logic_lfd.LogicLfd, list[str]]]:
    """(name, task, state): a state the demonstration passes through, and disturbed ones."""

    def task(name: str) -> logic_lfd.LogicLfd:
        folder = DOMAINS / name
        return logic_lfd.LogicLfd(
            (folder / "domain.pddl").read_text(),
            (folder / "problem.pddl").read_text(),
            (folder / "demo.plan").read_text(),
        )

    kitchen, delivery = task("kitchen"), task("delivery")
    moved = [a for a in kitchen.demo_states[6] if not a.startswith("(robot-at chef ")]
    disturbed = (DOMAINS / "delivery" / "disturbed.facts").read_text()
    return [
        ("kitchen: LogicIn matches L_3", kitchen, kitchen.demo_states[3]),
        ("kitchen: the cook moved, a prefix searched", kitchen, moved + ["(robot-at chef sink)"]),
        ("delivery: LogicIn matches L_3", delivery, delivery.demo_states[3]),
        ("delivery: disturbed.facts, a prefix searched", delivery, disturbed.split("\n")),
    ]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("--repeats", type=int, default=300)
    a = ap.parse_args()
    print("| case | Python replan, µs (median) | native, µs (median) | ratio |")
    print("|---|---|---|---|")
    for name, lfd, state in cases():
        lfd.replan(state)  # warm-up
        py = []
        for _ in range(a.repeats):
            t0 = time.perf_counter()
            lfd.replan(state)
            py.append(time.perf_counter() - t0)
        native = lfd._native_replan_seconds(state, a.repeats)
        p, n = statistics.median(py) * 1e6, statistics.median(native) * 1e6
        print(f"| {name} | {p:.1f} | {n:.1f} | {p / n:.3f} |")


if __name__ == "__main__":
    main()
