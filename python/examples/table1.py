"""Table I (generalisation over random initial states) from Python, plotted if matplotlib is there.

Runs `logic-lfd bench table1`'s sweep on a process pool and prints its markdown; with
matplotlib installed it also writes `table1.png`: the success rate of every method on every
benchmark (the markdown adds the 95 % intervals and the paper's numbers).

    python python/examples/table1.py --tasks 8 --benchmarks b1,b2 --out table1.png
"""

from __future__ import annotations

import argparse
import os
from concurrent.futures import ProcessPoolExecutor
from typing import Any

import logic_lfd


def label(cell: dict[str, Any]) -> str:
    """A method as the table names it: Logic-LfD with its mode."""
    m = str(cell["method"])
    return f"{m} ({cell['mode']})" if m == "logic-lfd" else m


def plot(table: dict[str, Any], out: str) -> bool:
    """Write the success rate of every method on every benchmark to `out`; False without
    matplotlib."""
    try:
        import matplotlib  # type: ignore[import-not-found,unused-ignore]

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt  # type: ignore[import-not-found,unused-ignore]
    except ImportError:
        return False
    cells = table["cells"]
    methods = list(dict.fromkeys(label(c) for c in cells))
    benchmarks = list(dict.fromkeys(str(c["benchmark"]) for c in cells))
    width = 0.8 / len(methods)
    fig, ax = plt.subplots(figsize=(max(6.0, len(benchmarks) * 2.2), 3.6))
    for m, method in enumerate(methods):
        xs, ys = [], []
        for b, bench in enumerate(benchmarks):
            for c in cells:
                if label(c) == method and c["benchmark"] == bench and c["tasks"] > 0:
                    xs.append(b + (m - (len(methods) - 1) / 2) * width)
                    ys.append(c["successes"] / c["tasks"])
        ax.bar(xs, ys, width, label=method)
    ax.set_xticks(range(len(benchmarks)), [b.upper() for b in benchmarks])
    ax.set_ylim(0, 1.25)
    ax.set_yticks([0, 0.25, 0.5, 0.75, 1.0])
    ax.set_ylabel("success rate")
    ax.set_title(f"Table I: {table['tasks']} tasks per benchmark, seed {table['seed']}")
    ax.legend(fontsize=8, ncol=len(methods), loc="upper center")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    return True


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("--tasks", type=int, default=8, help="random initial states per benchmark")
    ap.add_argument("--benchmarks", default="b1,b2,b3")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default="table1.png")
    a = ap.parse_args()
    spec = {"command": "table1", "tasks": a.tasks, "benchmarks": a.benchmarks, "seed": a.seed}
    with ProcessPoolExecutor(os.cpu_count()) as pool:
        table = logic_lfd.sweep(spec, pool)
    print(table["markdown"])
    if plot(table, a.out):
        print(f"wrote {a.out}")
    else:
        print("matplotlib is not installed: no plot (pip install matplotlib)")


if __name__ == "__main__":
    main()
