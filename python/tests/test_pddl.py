"""`plan`, `validate` and `LogicLfd`: real plans replayed by the validator, errors with fields."""

from __future__ import annotations

import multiprocessing
import pickle
import threading
from concurrent.futures import ProcessPoolExecutor

import pytest

import logic_lfd
from conftest import DOMAINS, ROOT, read_task

Task = tuple[str, str, str]


def test_a_plan_is_valid_and_its_cost_is_the_validators(kitchen: Task) -> None:
    domain, problem, _ = kitchen
    p = logic_lfd.plan(domain, problem)
    assert p.optimal and len(p) == len(p.actions) > 0
    assert all(a.startswith("(") and a.endswith(")") for a in p)
    v = logic_lfd.validate(domain, problem, p.actions)
    assert v and v.cost == p.cost and v.steps_applied == len(p)
    assert p.stats["expanded"] > 0 and p.stats["search_seconds"] >= 0
    assert str(p).endswith(f"; cost = {p.cost}\n")


IPC = ROOT / "tests" / "data" / "ipc"


@pytest.mark.parametrize(
    "domain_file, problem_file",
    [
        ("blocks/domain.pddl", "blocks/probBLOCKS-6-0.pddl"),
        ("gripper/domain.pddl", "gripper/prob01.pddl"),
        ("logistics00/domain.pddl", "logistics00/probLOGISTICS-4-0.pddl"),
    ],
)
def test_optimal_searches_agree_on_the_cost(domain_file: str, problem_file: str) -> None:
    domain, problem = (IPC / domain_file).read_text(), (IPC / problem_file).read_text()
    costs = {
        (s, h): logic_lfd.plan(domain, problem, s, h).cost
        for s, h in [("astar", "lmcut"), ("astar", "hmax"), ("ucs", None)]
    }
    assert len(set(costs.values())) == 1, costs
    greedy = logic_lfd.plan(domain, problem, "gbfs", "hff")
    assert not greedy.optimal and greedy.cost >= costs[("ucs", None)]
    assert logic_lfd.validate(domain, problem, greedy.actions)


def test_validate_names_the_failing_step(kitchen: Task) -> None:
    domain, problem, demo = kitchen
    steps = [line for line in demo.splitlines() if line.startswith("(")]
    v = logic_lfd.validate(domain, problem, steps[1:])
    assert not v and v.failed_step == 1 and v.false_literals
    short = logic_lfd.validate(domain, problem, "\n".join(steps[:-1]))
    assert not short and short.failed_step is None and short.steps_applied == len(steps) - 1


def test_bad_pddl_raises_with_file_line_and_column(kitchen: Task) -> None:
    domain, problem, _ = kitchen
    broken = problem.replace("(:init", "(:init (no-such-predicate x)", 1)
    with pytest.raises(logic_lfd.PddlError) as e:
        logic_lfd.plan(domain, broken, problem_file="p.pddl")
    line = next(i for i, t in enumerate(broken.splitlines(), 1) if "no-such-predicate" in t)
    assert (e.value.file, e.value.line) == ("p.pddl", line)
    assert e.value.col > 0 and "no-such-predicate" in e.value.message
    assert str(e.value).startswith(f"p.pddl:{line}:{e.value.col}: ")
    with pytest.raises(logic_lfd.PddlError) as e:
        logic_lfd.validate(domain, problem, "(fly chef moon)")
    assert e.value.file == "plan" and e.value.line == 1


def test_options_and_no_plan_are_exceptions_with_fields(kitchen: Task) -> None:
    domain, problem, _ = kitchen
    with pytest.raises(logic_lfd.OptionError) as o:
        logic_lfd.plan(domain, problem, heuristic="hzz")
    assert o.value.option == "heuristic"
    with pytest.raises(logic_lfd.NoPlanError) as n:
        logic_lfd.plan(domain, problem, max_nodes=10)
    assert (n.value.reason, n.value.budget) == ("budget", "nodes") and n.value.stats is not None
    assert n.value.stats["expanded"] <= 11
    goal_false = problem.replace("(:goal (and", "(:goal (and (not (robot-at chef counter)) (robot-at chef counter)", 1)
    with pytest.raises(logic_lfd.NoPlanError) as n:
        logic_lfd.plan(domain, goal_false)
    assert (n.value.reason, n.value.budget) == ("unsolvable", None)
    with pytest.raises(TypeError):
        logic_lfd.validate(domain, problem, 42)  # type: ignore[arg-type]


def test_logic_in_and_replan_follow_the_demonstration(kitchen: Task) -> None:
    lfd = logic_lfd.LogicLfd(*kitchen)
    states = lfd.demo_states
    assert len(states) == len(lfd.demo_actions) + 1 == len(lfd.demo_costs)
    for k in (0, 5, len(states) - 2):
        assert lfd.logic_in(states[k]) == k
        r = lfd.replan(states[k])
        assert r.k == k and r.source == "logic-in" and not r.prefix
        assert r.actions == lfd.demo_actions[k:] and r.cost == lfd.demo_costs[k]
        assert r.valid is True
    assert lfd.replan(states[-1]).source == "goal-holds"


def test_replan_from_a_disturbed_state_is_valid_from_that_state(kitchen: Task) -> None:
    lfd = logic_lfd.LogicLfd(*kitchen)
    # L_6 with the chef moved elsewhere: no demonstration state holds, a prefix is searched.
    state = [a for a in lfd.demo_states[6] if not a.startswith("(robot-at chef ")] + ["(robot-at chef sink)"]
    for mode in ("paper", "prioritised"):
        r = lfd.replan(state, mode)
        assert r.source == "multi-goal" and r.prefix and r.k is not None
        assert r.actions == r.prefix + r.suffix
        assert r.suffix == lfd.demo_actions[r.k :]
        assert lfd.validate(r.actions, state)
        assert r.stats["expanded"] > 0


def test_bad_demonstrations_and_states_are_located(kitchen: Task) -> None:
    domain, problem, demo = kitchen
    steps = [line for line in demo.splitlines() if line.startswith("(")]
    with pytest.raises(logic_lfd.DemoError) as d:
        logic_lfd.LogicLfd(domain, problem, steps[1:], demo_file="d.plan")
    assert (d.value.file, d.value.line) == ("d.plan", 1)
    with pytest.raises(logic_lfd.DemoError):
        logic_lfd.LogicLfd(domain, problem, steps[:-1])
    lfd = logic_lfd.LogicLfd(domain, problem, steps)
    with pytest.raises(logic_lfd.PddlError) as e:
        lfd.replan(["(robot-at chef nowhere-at-all)"])
    assert "nowhere-at-all" in e.value.message
    with pytest.raises(logic_lfd.OptionError):
        lfd.replan(None, "greedy")


def test_replans_run_in_parallel_threads(kitchen: Task) -> None:
    lfd = logic_lfd.LogicLfd(*kitchen)
    state = [a for a in lfd.demo_states[3] if not a.startswith("(robot-at chef ")] + ["(robot-at chef table)"]
    expected = lfd.replan(state).actions
    results: list[list[str]] = []

    def work() -> None:
        results.append(lfd.replan(state).actions)

    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == [expected] * 4


def test_every_shipped_task_folder_with_a_plan_demonstration_loads() -> None:
    for folder in sorted(DOMAINS.iterdir()):
        if (folder / "demo.plan").exists():
            lfd = logic_lfd.LogicLfd(*read_task(folder.name))
            assert lfd.replan().actions == lfd.demo_actions


def test_tasks_and_results_pickle_across_process_pools(kitchen: Task) -> None:
    domain, problem, _ = kitchen
    p = logic_lfd.plan(domain, problem)
    back = pickle.loads(pickle.dumps(p))
    assert (back.actions, back.cost, back.optimal, back.stats) == (
        p.actions,
        p.cost,
        p.optimal,
        p.stats,
    )
    v = pickle.loads(pickle.dumps(logic_lfd.validate(domain, problem, p.actions[1:])))
    assert not v and v.failed_step == 1 and v.false_literals
    lfd = logic_lfd.LogicLfd(*kitchen, demo_file="kitchen.plan")
    state = [a for a in lfd.demo_states[6] if not a.startswith("(robot-at chef ")]
    state.append("(robot-at chef sink)")
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        remote = list(pool.map(lfd.replan, [state, lfd.demo_states[4]]))
    assert [r.actions for r in remote] == [lfd.replan(state).actions, lfd.demo_actions[4:]]
    assert remote[0].k == lfd.replan(state).k and remote[0].source == "multi-goal"
    copy = pickle.loads(pickle.dumps(lfd))
    assert copy.demo_states == lfd.demo_states
    assert copy.replan(state).actions == lfd.replan(state).actions
