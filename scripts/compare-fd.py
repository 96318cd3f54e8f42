#!/usr/bin/env python3
"""Compares logic-lfd's A* + LM-cut with Fast Downward's astar(lmcut()) problem by problem.

For every problem of the IPC folders given (default: every folder of ../shared/ipc) and for
seeded random STRIPS tasks, both planners run with the same time limit; the script prints the
initial LM-cut value, the plan cost and the expansions of each, and ends with a summary. It
exits 1 when an initial LM-cut value or a proved optimal cost differs (expansions are reported,
not checked: tie-breaking differs).

    python3 scripts/compare-fd.py [DIR ...] [--time-limit S] [--random N] [--seed S] [--json]
                                  [--h0-only]

--h0-only compares the initial LM-cut values alone (both planners stop after the first state):
seconds per problem instead of the time limit.

Fast Downward comes from PyPI (`up-fast-downward`), installed on first use into a virtual
environment under target/fd-venv (FD_PYTHON=/path/to/python with it installed skips that).
logic-lfd is target/release/logic-lfd (built when missing; LOGIC_LFD_BIN overrides).
"""
import argparse
import glob
import json
import os
import random
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def fd_python():
    if os.environ.get("FD_PYTHON"):
        return os.environ["FD_PYTHON"]
    venv = os.path.join(ROOT, "target", "fd-venv")
    py = os.path.join(venv, "bin", "python")
    if not os.path.exists(py):
        print("compare-fd: installing up-fast-downward into target/fd-venv", file=sys.stderr)
        subprocess.run([sys.executable, "-m", "venv", venv], check=True)
        subprocess.run([py, "-m", "pip", "install", "-q", "up-fast-downward"], check=True)
    return py


def fd_script(py):
    out = subprocess.run(
        [py, "-c", "import importlib.util as u; "
             "print(u.find_spec('up_fast_downward').submodule_search_locations[0])"],
        check=True, capture_output=True, text=True).stdout.strip()
    return os.path.join(out, "downward", "fast-downward.py")


def logic_lfd_bin():
    b = os.environ.get("LOGIC_LFD_BIN", os.path.join(ROOT, "target", "release", "logic-lfd"))
    if not os.path.exists(b):
        subprocess.run(["cargo", "build", "--release", "--locked", "-q", "-p", "logic-lfd",
                        "--bin", "logic-lfd"], cwd=ROOT, check=True)
    return b


def run_fd(py, script, domain, problem, limit, h0_only=False):
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.monotonic()
        p = subprocess.run(
            [py, script, "--overall-time-limit", f"{int(limit)}s", "--plan-file",
             os.path.join(tmp, "plan"), domain, problem, "--search",
             "astar(lmcut(), bound=0)" if h0_only else "astar(lmcut())"],
            cwd=tmp, capture_output=True, text=True)
        wall = time.monotonic() - t0
    out = p.stdout
    def grab(pattern, cast=int):
        m = re.search(pattern, out)
        return cast(m.group(1)) if m else None
    solved = "Solution found." in out
    return {
        "initial_h": grab(r"Initial heuristic value for lmcut: (\d+)"),
        "dead_end": "Initial state is a dead end" in out,
        "cost": grab(r"Plan cost: (\d+)") if solved else None,
        "expanded": grab(r"Expanded (\d+) state\(s\)\.") if solved else None,
        "solved": solved,
        "wall_s": wall,
    }


def run_ours(binary, domain, problem, limit, h0_only=False):
    t0 = time.monotonic()
    budget = ["--max-nodes", "1"] if h0_only else []
    p = subprocess.run([binary, "plan", domain, problem, "--json", "--time-limit", str(limit)]
                       + budget, capture_output=True, text=True)
    wall = time.monotonic() - t0
    try:
        j = json.loads(p.stdout)
    except json.JSONDecodeError:
        return {"error": (p.stderr or p.stdout).strip().splitlines()[:1], "wall_s": wall}
    return {
        "initial_h": j.get("initial_h"),
        "cost": j.get("cost"),
        "expanded": j.get("expanded"),
        "solved": j.get("status") == "solved",
        "wall_s": wall,
    }


def random_strips(rng, n_facts, n_ops):
    """A random propositional STRIPS task (positive preconditions and goal, unit costs)."""
    facts = [f"p{i}" for i in range(n_facts)]
    dom = ["(define (domain rnd) (:requirements :strips)", "(:predicates " +
           " ".join(f"({f})" for f in facts) + ")"]
    for k in range(n_ops):
        pre = [f for f in facts if rng.random() < 0.2]
        add = [f for f in facts if rng.random() < 0.25]
        dele = [f for f in facts if f not in add and rng.random() < 0.25]
        if not add:
            add = [rng.choice(facts)]
        eff = " ".join(f"({f})" for f in add) + " " + " ".join(f"(not ({f}))" for f in dele)
        dom.append(f"(:action op{k} :parameters () :precondition (and " +
                   " ".join(f"({f})" for f in pre) + f") :effect (and {eff}))")
    dom.append(")")
    init = [f for f in facts if rng.random() < 0.3]
    goal = [f for f in facts if rng.random() < 0.3] or [rng.choice(facts)]
    prob = ("(define (problem r) (:domain rnd) (:init " + " ".join(f"({f})" for f in init) +
            ") (:goal (and " + " ".join(f"({f})" for f in goal) + ")))")
    return "\n".join(dom), prob


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dirs", nargs="*")
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--random", type=int, default=50, help="random STRIPS tasks (0: none)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--h0-only", action="store_true", help="compare initial LM-cut values only")
    a = ap.parse_args()
    dirs = a.dirs or sorted(d for d in glob.glob(os.path.join(ROOT, "..", "shared", "ipc", "*"))
                            if os.path.isdir(d))
    py = fd_python()
    script = fd_script(py)
    ours_bin = logic_lfd_bin()
    cases = []
    for d in dirs:
        domain = os.path.join(d, "domain.pddl")
        for prob in sorted(glob.glob(os.path.join(d, "*.pddl"))):
            if os.path.basename(prob) != "domain.pddl":
                cases.append((f"{os.path.basename(os.path.normpath(d))}/{os.path.basename(prob)}",
                              domain, prob))
    tmp = tempfile.mkdtemp(prefix="compare-fd-")
    rng = random.Random(a.seed)
    for i in range(a.random):
        dom, prob = random_strips(rng, rng.randint(4, 9), rng.randint(3, 14))
        dp, pp = os.path.join(tmp, f"r{i}-domain.pddl"), os.path.join(tmp, f"r{i}.pddl")
        open(dp, "w").write(dom)
        open(pp, "w").write(prob)
        cases.append((f"random/{a.seed}-{i}", dp, pp))
    rows, h_diff, cost_diff = [], [], []
    for name, domain, prob in cases:
        fd = run_fd(py, script, domain, prob, a.time_limit, a.h0_only)
        us = run_ours(ours_bin, domain, prob, a.time_limit, a.h0_only)
        fd_h = None if fd["dead_end"] else fd["initial_h"]
        if (fd["initial_h"] is not None or fd["dead_end"]) and fd_h != us.get("initial_h"):
            h_diff.append(name)
        if fd["solved"] and us.get("solved") and fd["cost"] != us["cost"]:
            cost_diff.append(name)
        rows.append({"problem": name, "fd": fd, "ours": us})
        print(f"{name}: h0 FD {fd_h} ours {us.get('initial_h')}; cost FD {fd['cost']} ours "
              f"{us.get('cost')}; expanded FD {fd['expanded']} ours {us.get('expanded')}",
              file=sys.stderr)
    both = [r for r in rows if r["fd"]["solved"] and r["ours"].get("solved")]
    summary = {
        "problems": len(rows),
        "fd_solved": sum(r["fd"]["solved"] for r in rows),
        "ours_solved": sum(bool(r["ours"].get("solved")) for r in rows),
        "initial_h_differs": h_diff,
        "cost_differs": cost_diff,
        "expansions_within_20_percent": sum(
            abs(r["ours"]["expanded"] - r["fd"]["expanded"]) <= 0.2 * max(r["fd"]["expanded"], 1)
            for r in both),
        "both_solved": len(both),
        "time_limit_s": a.time_limit,
    }
    if a.json:
        print(json.dumps({"rows": rows, "summary": summary}, indent=1))
    else:
        print("| problem | h0 FD | h0 ours | cost FD | cost ours | expanded FD | expanded ours |")
        print("|---|---:|---:|---:|---:|---:|---:|")
        for r in rows:
            fd, us = r["fd"], r["ours"]
            cell = lambda v: "—" if v is None else str(v)
            print(f"| {r['problem']} | {cell(None if fd['dead_end'] else fd['initial_h'])} | "
                  f"{cell(us.get('initial_h'))} | {cell(fd['cost'])} | {cell(us.get('cost'))} | "
                  f"{cell(fd['expanded'])} | {cell(us.get('expanded'))} |")
        print()
        print(f"{summary['problems']} problems, {a.time_limit:g} s each: FD solved "
              f"{summary['fd_solved']}, logic-lfd {summary['ours_solved']}; initial LM-cut values "
              f"differ on {len(h_diff)} {h_diff}; optimal costs differ on {len(cost_diff)} "
              f"{cost_diff}; expansions within ±20 % on {summary['expansions_within_20_percent']}"
              f" of {summary['both_solved']} solved by both.")
    return 1 if h_diff or cost_diff else 0


if __name__ == "__main__":
    sys.exit(main())
