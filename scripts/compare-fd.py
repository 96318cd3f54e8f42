#!/usr/bin/env python3
"""Compares logic-lfd's A* + LM-cut with Fast Downward's astar(lmcut()) problem by problem.

For every problem of the IPC folders given (default: every folder of tests/data/ipc) and for
seeded random STRIPS tasks, both planners run with the same time limit; the script prints the
initial LM-cut value, the plan cost and the expansions of each, and ends with a summary.

An LM-cut value is not a function of the task alone: it depends on how ties in the precondition
choice function are broken, hence on the order in which facts are met. Where the two initial
values differ, FD runs again on its own SAS+ task with the variables renumbered (same task, other
order); logic-lfd's value is expected no lower than the least of FD's own values (above is
admissible too: a stronger bound; docs/planner.md). The script exits 1 when a value is below
that range, when logic-lfd proves a dead end FD solves, or when a proved optimal cost differs
(expansions are reported, not checked).

    python3 scripts/compare-fd.py [DIR ...] [--time-limit S] [--random N] [--seed S] [--json]
                                  [--h0-only] [--renumberings K] [--stop-after N]
                                  [--expansion-renumberings K]

Problems run in natural order (probBLOCKS-9-0 before probBLOCKS-10-0), so that with
--stop-after N a domain's remaining problems (not the random tasks) are skipped, and reported as skipped, once N in a
row were solved by neither planner: IPC problems grow with their number, and the skipped ones
would each cost both time limits for nothing.

Expansions depend on that order too (A* meets other LM-cut values on the way). With
--expansion-renumberings K, where the two counts differ by more than 20 %, FD solves the problem
again over K renumberings, and the row shows FD's own spread of expansions.

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
import resource
import statistics
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


def run_fd(py, script, domain, problem, limit, h0_only=False, satisficing=False):
    if satisficing:
        config = ["--alias", "lama-first", domain, problem]
    else:
        config = [domain, problem, "--search",
                  "astar(lmcut(), bound=0)" if h0_only else "astar(lmcut())"]
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.monotonic()
        p = subprocess.run(
            [py, script, "--overall-time-limit", f"{int(limit)}s", "--plan-file",
             os.path.join(tmp, "plan")] + config,
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
        "search_s": grab(r"Search time: ([\d.]+)s", float),
        "solved": solved,
        "wall_s": wall,
    }


def renumber_sas(text, seed):
    """The SAS+ task `text` with its variables renumbered by a seeded permutation.

    The task is the same; only the order in which Fast Downward's LM-cut meets facts changes,
    and with it the precondition choice function's tie-breaking.
    """
    L = text.split("\n")
    i = L.index("begin_variable")
    n = int(L[i - 1])
    blocks, j = [], i
    while L[j] == "begin_variable":
        k = L.index("end_variable", j)
        blocks.append(L[j:k + 1])
        j = k + 1
    perm = list(range(n))
    random.Random(seed).shuffle(perm)
    new_blocks = [None] * n
    for old, b in enumerate(blocks):
        new_blocks[perm[old]] = b
    out = L[:i] + sum(new_blocks, [])
    rest, r = L[j:], 0

    def pair(line):
        v, val = line.split()
        return f"{perm[int(v)]} {val}"

    def by_var(lines):
        return sorted(lines, key=lambda x: int(x.split()[0]))

    groups = int(rest[r]); out.append(rest[r]); r += 1
    for _ in range(groups):
        out.append(rest[r]); r += 1
        c = int(rest[r]); out.append(rest[r]); r += 1
        out += [pair(rest[r + q]) for q in range(c)]; r += c
        out.append(rest[r]); r += 1
    out.append(rest[r]); r += 1  # begin_state
    values = [None] * n
    for old in range(n):
        values[perm[old]] = rest[r + old]
    out += values; r += n
    out.append(rest[r]); r += 1  # end_state
    out.append(rest[r]); r += 1  # begin_goal
    g = int(rest[r]); out.append(rest[r]); r += 1
    out += by_var(pair(rest[r + q]) for q in range(g)); r += g
    out.append(rest[r]); r += 1  # end_goal
    ops = int(rest[r]); out.append(rest[r]); r += 1
    for _ in range(ops):
        out += rest[r:r + 2]; r += 2  # begin_operator, name
        c = int(rest[r]); out.append(rest[r]); r += 1
        out += by_var(pair(rest[r + q]) for q in range(c)); r += c
        e = int(rest[r]); out.append(rest[r]); r += 1
        effects = []
        for _ in range(e):
            f = rest[r].split(); r += 1
            nc = int(f[0])
            conds = [pair(" ".join(f[1 + 2 * q:3 + 2 * q])) for q in range(nc)]
            var = perm[int(f[1 + 2 * nc])]
            effects.append((var, " ".join([str(nc)] + conds + [str(var)] + f[2 + 2 * nc:])))
        out += [x for _, x in sorted(effects)]
        out += rest[r:r + 2]; r += 2  # cost, end_operator
    out += rest[r:]
    return "\n".join(out)


def fd_renumbered(py, script, domain, problem, count, limit, pattern, search):
    """What `pattern` captures from Fast Downward's output, over `count` renumberings of its
    SAS+ variables (one int per run that printed it)."""
    binary = os.path.join(os.path.dirname(script), "builds", "release", "bin", "downward")
    values = []
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([py, script, "--translate", domain, problem], cwd=tmp,
                       capture_output=True, text=True, timeout=limit)
        sas_path = os.path.join(tmp, "output.sas")
        if not os.path.exists(sas_path):
            return values
        text = open(sas_path).read()
        for seed in range(count):
            try:
                p = subprocess.run([binary, "--search", search],
                                   input=renumber_sas(text, seed), cwd=tmp,
                                   capture_output=True, text=True, timeout=limit)
            except subprocess.TimeoutExpired:
                continue
            m = re.search(pattern, p.stdout)
            if m:
                values.append(int(m.group(1)))
    return values


def fd_h0_range(py, script, domain, problem, count, limit):
    """Fast Downward's initial LM-cut values over `count` renumberings of its SAS+ variables."""
    return fd_renumbered(py, script, domain, problem, count, limit,
                         r"Initial heuristic value for lmcut: (\d+)", "astar(lmcut(), bound=0)")


def fd_expanded_range(py, script, domain, problem, count, limit):
    """Fast Downward's A* + LM-cut expansions over `count` renumberings of its SAS+ variables."""
    return fd_renumbered(py, script, domain, problem, count, limit,
                         r"Expanded (\d+) state", "astar(lmcut())")


def cpu_limit(seconds):
    """A child's CPU-time limit, as Fast Downward's driver sets its own (RLIMIT_CPU)."""
    def apply():
        resource.setrlimit(resource.RLIMIT_CPU, (int(seconds), int(seconds) + 1))
    return apply


def run_ours(binary, domain, problem, limit, h0_only=False, satisficing=False):
    # FD's limit and its "Search time" are CPU time; so are logic-lfd's here, so that a loaded
    # machine costs both the same: the process gets `limit` s of CPU (killed after), and the
    # wall-clock limit it is given only stops it first on an idle machine.
    budget = ["--max-nodes", "1"] if h0_only else []
    if satisficing:
        budget += ["--search", "lazy-gbfs", "--heuristic", "hff"]
    t0 = time.monotonic()
    cpu0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run([binary, "plan", domain, problem, "--json", "--time-limit",
                        str(limit * 20)] + budget, capture_output=True, text=True,
                       preexec_fn=cpu_limit(limit))
    cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall = time.monotonic() - t0
    cpu = (cpu1.ru_utime - cpu0.ru_utime) + (cpu1.ru_stime - cpu0.ru_stime)
    try:
        j = json.loads(p.stdout)
    except json.JSONDecodeError:
        if p.returncode < 0:  # killed at the CPU limit
            return {"initial_h": None, "cost": None, "expanded": None, "solved": False,
                    "wall_s": wall, "cpu_s": cpu, "killed": True}
        return {"error": (p.stderr or p.stdout).strip().splitlines()[:1], "wall_s": wall}
    return {
        "initial_h": j.get("initial_h"),
        "cost": j.get("cost"),
        "expanded": j.get("expanded"),
        "search_s": cpu,
        "solved": j.get("status") == "solved",
        "wall_s": wall,
        "cpu_s": cpu,
    }


GRID_DOMAIN = """(define (domain grid-visit)
  (:requirements :typing)
  (:types place)
  (:predicates (connected ?a ?b - place) (at-robot ?x - place) (visited ?x - place))
  (:action move
    :parameters (?from ?to - place)
    :precondition (and (at-robot ?from) (connected ?from ?to))
    :effect (and (at-robot ?to) (not (at-robot ?from)) (visited ?to))))
"""


def grid_problem(n, half):
    """An n × n grid to visit from a corner (every cell, or every other cell with `half`)."""
    cells = [(x, y) for x in range(n) for y in range(n)]
    name = lambda c: f"c{c[0]}-{c[1]}"
    links = [f"(connected {name((x, y))} {name((x + dx, y + dy))})" for x, y in cells
             for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)) if 0 <= x + dx < n and 0 <= y + dy < n]
    goal = [c for c in cells if not half or (c[0] + c[1]) % 2 == 0]
    return (f"(define (problem grid-{n}) (:domain grid-visit)\n"
            f"  (:objects {' '.join(name(c) for c in cells)} - place)\n"
            f"  (:init (at-robot c0-0) (visited c0-0) {' '.join(links)})\n"
            f"  (:goal (and {' '.join(f'(visited {name(c)})' for c in goal)})))\n")


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


def natural_key(path):
    """Sort key that orders the numbers in a name by value (p9 before p10)."""
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", os.path.basename(path))]


def family(name):
    """The domain a case belongs to: the part of its name before the first `/`."""
    return name.split("/", 1)[0]


def by_domain(rows):
    """The rows grouped by domain, in the order the domains first appear."""
    for fam in dict.fromkeys(family(r["problem"]) for r in rows):
        yield fam, [r for r in rows if family(r["problem"]) == fam]


def domain_table(rows):
    """Per domain: solved by each, equal optimal costs, expansions within ±20 %, speeds."""
    print("| domain | problems | skipped | solved FD | solved logic-lfd | same optimal cost "
          "| expansions within ±20 % | expansions/s FD, median | expansions/s logic-lfd, median |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for fam, rs in by_domain(rows):
        both = [r for r in rs if r["fd"]["solved"] and r["ours"].get("solved")]
        rates = [(r["fd"]["expanded"] / r["fd"]["search_s"],
                  r["ours"]["expanded"] / r["ours"]["search_s"])
                 for r in both if min(r["fd"]["expanded"], r["ours"]["expanded"]) >= 1000
                 and r["fd"].get("search_s") and r["ours"].get("search_s")]
        med = lambda xs: f"{statistics.median(xs):,.0f}".replace(",", " ") if xs else "—"
        print(f"| {fam} | {len(rs)} | {sum(bool(r.get('skipped')) for r in rs)} | "
              f"{sum(r['fd']['solved'] for r in rs)} | "
              f"{sum(bool(r['ours'].get('solved')) for r in rs)} | "
              f"{sum(r['fd']['cost'] == r['ours']['cost'] for r in both)} of {len(both)} | "
              f"{sum(within_20(r) for r in both)} of {len(both)} | "
              f"{med([f for f, _ in rates])} | {med([o for _, o in rates])} |")


def within_20(r):
    return abs(r["ours"]["expanded"] - r["fd"]["expanded"]) <= 0.2 * max(r["fd"]["expanded"], 1)


UNRUN = {"initial_h": None, "dead_end": False, "cost": None, "expanded": None, "solved": False}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dirs", nargs="*")
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--random", type=int, default=50, help="random STRIPS tasks (0: none)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--h0-only", action="store_true", help="compare initial LM-cut values only")
    ap.add_argument("--satisficing", action="store_true",
                    help="lazy GBFS + h_FF against FD's lama-first (plan cost and wall time)")
    ap.add_argument("--grids", default="3,4,5,6,7",
                    help="sizes of generated grid-visit tasks, full and half goals ('': none)")
    ap.add_argument("--renumberings", type=int, default=40,
                    help="where initial values differ, FD's values over this many renumberings "
                         "of its SAS+ variables (0: none)")
    ap.add_argument("--expansion-renumberings", type=int, default=0,
                    help="where expansions differ by more than 20 %%, FD's expansions over this "
                         "many renumberings of its SAS+ variables (0: none)")
    ap.add_argument("--stop-after", type=int, default=0,
                    help="skip a domain's remaining problems once this many in a row were solved "
                         "by neither planner (0: never)")
    a = ap.parse_args()
    # Absolute: Fast Downward runs in a temporary directory.
    dirs = [os.path.abspath(d) for d in a.dirs] or sorted(d for d in glob.glob(os.path.join(ROOT, "tests", "data", "ipc", "*"))
                            if os.path.isdir(d))
    py = fd_python()
    script = fd_script(py)
    ours_bin = logic_lfd_bin()
    cases = []
    for d in dirs:
        domain = os.path.join(d, "domain.pddl")
        for prob in sorted(glob.glob(os.path.join(d, "*.pddl")), key=natural_key):
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
    grid_domain = os.path.join(tmp, "grid-domain.pddl")
    open(grid_domain, "w").write(GRID_DOMAIN)
    for n in [int(x) for x in a.grids.split(",") if x.strip()]:
        for half in (False, True):
            pp = os.path.join(tmp, f"grid-{n}-{'half' if half else 'full'}.pddl")
            open(pp, "w").write(grid_problem(n, half))
            cases.append((f"grid/{n}x{n}-{'half' if half else 'full'}", grid_domain, pp))
    if a.satisficing:
        return satisficing_report(py, script, ours_bin, cases, a)
    rows, h_diff, below, above, cost_diff, dead_wrong = [], [], [], [], [], []
    misses = {}
    for name, domain, prob in cases:
        # Random tasks are in no order of difficulty: --stop-after never skips them.
        if a.stop_after and family(name) != "random" \
                and misses.get(family(name), 0) >= a.stop_after:
            rows.append({"problem": name, "fd": dict(UNRUN), "ours": dict(UNRUN),
                         "skipped": True})
            continue
        fd = run_fd(py, script, domain, prob, a.time_limit, a.h0_only)
        us = run_ours(ours_bin, domain, prob, a.time_limit, a.h0_only)
        fd_h, our_h = (None if fd["dead_end"] else fd["initial_h"]), us.get("initial_h")
        row = {"problem": name, "fd": fd, "ours": us}
        # A run stopped at the CPU limit printed no initial value: nothing to compare.
        if (fd["initial_h"] is not None or fd["dead_end"]) and fd_h != our_h \
                and not us.get("killed"):
            h_diff.append(name)
            if our_h is None:
                # Ours proved a dead end FD's relaxation misses: wrong if FD found a plan.
                if fd["solved"]:
                    dead_wrong.append(name)
            elif a.renumberings > 0 and fd_h is not None:
                vals = fd_h0_range(py, script, domain, prob, a.renumberings, a.time_limit)
                row["fd_renumbered_h0"] = vals
                if vals and our_h < min(vals + [fd_h]):
                    below.append(name)
                elif vals and our_h > max(vals + [fd_h]):
                    above.append(name)
        if fd["solved"] and us.get("solved") and fd["cost"] != us["cost"]:
            cost_diff.append(name)
        if a.expansion_renumberings > 0 and fd["solved"] and us.get("solved") \
                and not within_20(row):
            row["fd_renumbered_expanded"] = fd_expanded_range(
                py, script, domain, prob, a.expansion_renumberings, a.time_limit)
        rows.append(row)
        unsolved = not a.h0_only and not fd["solved"] and not us.get("solved")
        misses[family(name)] = misses.get(family(name), 0) + 1 if unsolved else 0
        print(f"{name}: h0 FD {fd_h} {row.get('fd_renumbered_h0', '')} ours {our_h}; cost FD "
              f"{fd['cost']} ours {us.get('cost')}; expanded FD {fd['expanded']} "
              f"{row.get('fd_renumbered_expanded', '')} ours "
              f"{us.get('expanded')}", file=sys.stderr)
    both = [r for r in rows if r["fd"]["solved"] and r["ours"].get("solved")]
    paired_h = [(r["fd"]["initial_h"], r["ours"]["initial_h"]) for r in rows
                if not r["fd"]["dead_end"] and r["fd"]["initial_h"] is not None
                and r["ours"].get("initial_h") is not None]
    # Expansions per second of search, on problems long enough to time (≥ 1000 expansions).
    rates = [(r["fd"]["expanded"] / r["fd"]["search_s"],
              r["ours"]["expanded"] / r["ours"]["search_s"])
             for r in both if min(r["fd"]["expanded"], r["ours"]["expanded"]) >= 1000
             and r["fd"].get("search_s") and r["ours"].get("search_s")]
    summary = {
        "problems": len(rows),
        "fd_solved": sum(r["fd"]["solved"] for r in rows),
        "ours_solved": sum(bool(r["ours"].get("solved")) for r in rows),
        "solved_by_fd_only": [r["problem"] for r in rows
                              if r["fd"]["solved"] and not r["ours"].get("solved")],
        "initial_h_equal": sum(f == o for f, o in paired_h),
        "initial_h_ours_higher": sum(o > f for f, o in paired_h),
        "initial_h_ours_lower": sum(o < f for f, o in paired_h),
        "initial_h_sum": {"fd": sum(f for f, _ in paired_h), "ours": sum(o for _, o in paired_h)},
        "initial_h_differs": h_diff,
        "initial_h_below_fd_renumbered_range": below,
        "initial_h_above_fd_renumbered_range": above,
        "dead_end_but_fd_solved": dead_wrong,
        "cost_differs": cost_diff,
        "expansions_within_20_percent": sum(within_20(r) for r in both),
        "skipped": [r["problem"] for r in rows if r.get("skipped")],
        "both_solved": len(both),
        "expansions_per_s_median": {
            "fd": statistics.median(f for f, _ in rates) if rates else None,
            "ours": statistics.median(o for _, o in rates) if rates else None,
            "problems": len(rates)},
        "time_limit_s": a.time_limit,
        "renumberings": a.renumberings,
    }
    if a.json:
        print(json.dumps({"rows": rows, "summary": summary}, indent=1))
    else:
        print("| problem | h0 FD | h0 FD renumbered | h0 ours | cost FD | cost ours "
              "| expanded FD | expanded ours |")
        print("|---|---:|---|---:|---:|---:|---:|---:|")
        cell = lambda v: "—" if v is None else str(v)
        for r in rows:
            if r.get("skipped"):
                continue
            fd, us = r["fd"], r["ours"]
            vals = r.get("fd_renumbered_h0")
            span = f"{min(vals)}–{max(vals)}" if vals else ""
            print(f"| {r['problem']} | {cell(None if fd['dead_end'] else fd['initial_h'])} | "
                  f"{span} | {cell(us.get('initial_h'))} | {cell(fd['cost'])} | "
                  f"{cell(us.get('cost'))} | {cell(fd['expanded'])} | {cell(us.get('expanded'))} |")
        print()
        domain_table(rows)
        print()
        sm = summary
        print(f"{sm['problems']} problems ({len(sm['skipped'])} skipped after {a.stop_after} "
              f"unsolved in a row), {a.time_limit:g} s each: FD solved {sm['fd_solved']}, "
              f"logic-lfd {sm['ours_solved']} (FD only: {sm['solved_by_fd_only']}). Initial LM-cut "
              f"values: equal {sm['initial_h_equal']}, ours higher {sm['initial_h_ours_higher']}, "
              f"lower {sm['initial_h_ours_lower']}, sums FD {sm['initial_h_sum']['fd']} ours "
              f"{sm['initial_h_sum']['ours']}; below FD's own range over {a.renumberings} "
              f"renumberings: {len(below)} {below}, above it: {len(above)} {above}; dead ends "
              f"FD solved: {dead_wrong}. "
              f"Optimal costs differ on {len(cost_diff)} {cost_diff}; expansions within ±20 % on "
              f"{sm['expansions_within_20_percent']} of {sm['both_solved']} solved by both; median "
              f"expansions/s FD {sm['expansions_per_s_median']['fd']} ours "
              f"{sm['expansions_per_s_median']['ours']} ({len(rates)} problems).")
    return 1 if below or cost_diff or dead_wrong else 0


def satisficing_domain_table(rows):
    """Per domain: solved by each, median plan-cost and wall-time ratios where both solve."""
    print("| domain | problems | solved lama-first | solved logic-lfd | plan cost ours / FD, "
          "median | wall time FD / ours, median |")
    print("|---|---:|---:|---:|---:|---:|")
    for fam, rs in by_domain(rows):
        both = [r for r in rs if r["fd"]["solved"] and r["ours"].get("solved") and r["fd"]["cost"]]
        med = lambda xs, fmt: fmt.format(statistics.median(xs)) if xs else "—"
        print(f"| {fam} | {len(rs)} | {sum(r['fd']['solved'] for r in rs)} | "
              f"{sum(bool(r['ours'].get('solved')) for r in rs)} | "
              f"{med([r['ours']['cost'] / r['fd']['cost'] for r in both], '{:.2f}')} | "
              f"{med([r['fd']['wall_s'] / r['ours']['wall_s'] for r in both], '{:.0f}×')} |")


def satisficing_report(py, script, ours_bin, cases, a):
    """Lazy GBFS + h_FF against lama-first: solved, plan cost and wall time per process."""
    rows = []
    for name, domain, prob in cases:
        fd = run_fd(py, script, domain, prob, a.time_limit, satisficing=True)
        us = run_ours(ours_bin, domain, prob, a.time_limit, satisficing=True)
        rows.append({"problem": name, "fd": fd, "ours": us})
        print(f"{name}: cost FD {fd['cost']} ours {us.get('cost')}; wall FD {fd['wall_s']:.3f} s "
              f"ours {us['wall_s']:.3f} s", file=sys.stderr)
    both = [r for r in rows if r["fd"]["solved"] and r["ours"].get("solved")
            and r["fd"]["cost"]]
    cost_ratio = [r["ours"]["cost"] / r["fd"]["cost"] for r in both]
    speed = [r["fd"]["wall_s"] / r["ours"]["wall_s"] for r in both]
    summary = {
        "problems": len(rows),
        "fd_solved": sum(r["fd"]["solved"] for r in rows),
        "ours_solved": sum(bool(r["ours"].get("solved")) for r in rows),
        "cost_ratio_median": statistics.median(cost_ratio) if both else None,
        "cost_ratio_max": max(cost_ratio) if both else None,
        "wall_speedup_median": statistics.median(speed) if both else None,
        "time_limit_s": a.time_limit,
    }
    if a.json:
        print(json.dumps({"rows": rows, "summary": summary}, indent=1))
    else:
        print("| problem | cost lama-first | cost logic-lfd | wall FD (s) | wall logic-lfd (s) |")
        print("|---|---:|---:|---:|---:|")
        cell = lambda v: "—" if v is None else str(v)
        for r in rows:
            print(f"| {r['problem']} | {cell(r['fd']['cost'])} | {cell(r['ours'].get('cost'))} | "
                  f"{r['fd']['wall_s']:.3f} | {r['ours']['wall_s']:.3f} |")
        print()
        satisficing_domain_table(rows)
        print()
        print(f"{summary['problems']} problems, {a.time_limit:g} s each: lama-first solved "
              f"{summary['fd_solved']}, logic-lfd lazy GBFS + h_FF {summary['ours_solved']}; on "
              f"the {len(both)} both solve, plan cost ours/FD median "
              f"{summary['cost_ratio_median']}, max {summary['cost_ratio_max']}; wall time per "
              f"process FD/ours median {summary['wall_speedup_median']}.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
