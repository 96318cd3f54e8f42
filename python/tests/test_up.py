"""The unified-planning engine "logic-lfd": registration, the kind check, oneshot planning
checked by UP's own validator, and Logic-LfD replanning from a demonstration."""

from __future__ import annotations

import io
from typing import Any, Dict, List, Tuple

import pytest

pytest.importorskip("unified_planning")

from unified_planning.engines import (  # type: ignore[import-untyped]  # noqa: E402
    PlanGenerationResultStatus as Status,
)
from unified_planning.environment import (  # type: ignore[import-untyped]  # noqa: E402
    Environment,
    get_environment,
)
from unified_planning.exceptions import (  # type: ignore[import-untyped]  # noqa: E402
    UPNoSuitableEngineAvailableException,
    UPUsageError,
)
from unified_planning.io import PDDLReader  # type: ignore[import-untyped]  # noqa: E402
from unified_planning.plans import SequentialPlan  # type: ignore[import-untyped]  # noqa: E402
from unified_planning.shortcuts import (  # type: ignore[import-untyped]  # noqa: E402
    BoolType,
    Equals,
    Fluent,
    InstantaneousAction,
    Int,
    IntType,
    MinimizeActionCosts,
    Not,
    Object,
    OneshotPlanner,
    OptimalityGuarantee,
    PlanValidator,
    Problem,
    Replanner,
    SequentialSimulator,
    UserType,
)

import logic_lfd  # noqa: E402
import up_logic_lfd  # noqa: E402
from up_logic_lfd import LogicLfdEngine  # noqa: E402

from conftest import DOMAINS  # noqa: E402

get_environment().credits_stream = None

SOLVED = (Status.SOLVED_OPTIMALLY, Status.SOLVED_SATISFICING)


# ---- problems built with UP's Python API ----


def blocks(goal_tower: Tuple[str, ...] = ("C", "B", "A")) -> Problem:
    """Blocks world: the tower A on B on C (A on top) to `goal_tower` (top first)."""
    block = UserType("Block")
    on = Fluent("on", BoolType(), x=block, y=block)
    ontable = Fluent("ontable", BoolType(), x=block)
    clear = Fluent("clear", BoolType(), x=block)
    holding = Fluent("holding", BoolType(), x=block)
    handempty = Fluent("handempty", BoolType())

    pickup = InstantaneousAction("pickup", x=block)
    x = pickup.parameter("x")
    pickup.add_precondition(clear(x))
    pickup.add_precondition(ontable(x))
    pickup.add_precondition(handempty)
    pickup.add_effect(ontable(x), False)
    pickup.add_effect(clear(x), False)
    pickup.add_effect(handempty, False)
    pickup.add_effect(holding(x), True)

    putdown = InstantaneousAction("putdown", x=block)
    x = putdown.parameter("x")
    putdown.add_precondition(holding(x))
    putdown.add_effect(holding(x), False)
    putdown.add_effect(clear(x), True)
    putdown.add_effect(handempty, True)
    putdown.add_effect(ontable(x), True)

    stack = InstantaneousAction("stack", x=block, y=block)
    x, y = stack.parameter("x"), stack.parameter("y")
    stack.add_precondition(holding(x))
    stack.add_precondition(clear(y))
    stack.add_precondition(Not(Equals(x, y)))
    stack.add_effect(holding(x), False)
    stack.add_effect(clear(y), False)
    stack.add_effect(clear(x), True)
    stack.add_effect(handempty, True)
    stack.add_effect(on(x, y), True)

    unstack = InstantaneousAction("unstack", x=block, y=block)
    x, y = unstack.parameter("x"), unstack.parameter("y")
    unstack.add_precondition(on(x, y))
    unstack.add_precondition(clear(x))
    unstack.add_precondition(handempty)
    unstack.add_effect(holding(x), True)
    unstack.add_effect(clear(y), True)
    unstack.add_effect(clear(x), False)
    unstack.add_effect(handempty, False)
    unstack.add_effect(on(x, y), False)

    problem = Problem("Blocks")
    for f in (on, ontable, clear, holding, handempty):
        problem.add_fluent(f, default_initial_value=False)
    for a in (pickup, putdown, stack, unstack):
        problem.add_action(a)
    a, b, c = (Object(n, block) for n in "ABC")
    problem.add_objects([a, b, c])
    problem.set_initial_value(on(a, b), True)
    problem.set_initial_value(on(b, c), True)
    problem.set_initial_value(ontable(c), True)
    problem.set_initial_value(clear(a), True)
    problem.set_initial_value(handempty, True)
    tower = [problem.object(n) for n in goal_tower]
    for top, below in zip(tower, tower[1:]):
        problem.add_goal(on(top, below))
    return problem


def route() -> Problem:
    """Roads l0 → l1 priced by a static fluent (direct 8, round about 1 + 2 + 3) and a
    `jump` of constant cost 10: the cheapest plan costs 6 in 3 steps."""
    loc = UserType("Loc")
    at = Fluent("at", BoolType(), l=loc)
    road = Fluent("road", BoolType(), a=loc, b=loc)
    dist = Fluent("dist", IntType(), a=loc, b=loc)
    drive = InstantaneousAction("drive", a=loc, b=loc)
    a, b = drive.parameter("a"), drive.parameter("b")
    drive.add_precondition(at(a))
    drive.add_precondition(road(a, b))
    drive.add_effect(at(a), False)
    drive.add_effect(at(b), True)
    jump = InstantaneousAction("jump", a=loc, b=loc)
    a2, b2 = jump.parameter("a"), jump.parameter("b")
    jump.add_precondition(at(a2))
    jump.add_effect(at(a2), False)
    jump.add_effect(at(b2), True)
    problem = Problem("route")
    problem.add_fluent(at, default_initial_value=False)
    problem.add_fluent(road, default_initial_value=False)
    problem.add_fluent(dist, default_initial_value=0)
    problem.add_actions([drive, jump])
    l0, l1, l2, l3 = (Object(f"l{i}", loc) for i in range(4))
    problem.add_objects([l0, l1, l2, l3])
    problem.set_initial_value(at(l0), True)
    for u, v, d in ((l0, l1, 8), (l0, l2, 1), (l2, l3, 2), (l3, l1, 3)):
        problem.set_initial_value(road(u, v), True)
        problem.set_initial_value(dist(u, v), d)
    problem.add_goal(at(l1))
    problem.add_quality_metric(MinimizeActionCosts({drive: dist(a, b), jump: Int(10)}))
    return problem


def fuel() -> Problem:
    """A numeric-fluent problem: each step burns fuel."""
    fuel_left = Fluent("fuel", IntType(0, 10))
    done = Fluent("done", BoolType())
    go = InstantaneousAction("go")
    go.add_precondition(fuel_left() >= 1)
    go.add_decrease_effect(fuel_left(), 1)
    go.add_effect(done, True)
    problem = Problem("fuel")
    problem.add_fluent(fuel_left, default_initial_value=3)
    problem.add_fluent(done, default_initial_value=False)
    problem.add_action(go)
    problem.add_goal(done)
    return problem


# ---- plans, states and validation ----


def valid(problem: Problem, plan: Any) -> bool:
    """UP's SequentialPlanValidator accepts `plan` on `problem`."""
    with PlanValidator(name="sequential_plan_validator") as validator:
        return bool(validator.validate(problem, plan).status)


def pddl_actions(plan: Any) -> List[str]:
    """A UP plan as `(name arg …)` strings in the problem's own (lower-case) names."""
    out = []
    for ai in plan.actions:
        args = [str(p.object().name) for p in ai.actual_parameters]
        out.append("(" + " ".join([ai.action.name, *args]) + ")")
    return out


def names(actions: Any) -> List[str]:
    """Action instances as text, e.g. `unstack(A, B)` (instances compare by identity)."""
    return [str(ai) for ai in actions]


def states(problem: Problem, plan: Any) -> List[Any]:
    """The states a plan visits, from the initial state (UP's sequential simulator)."""
    with SequentialSimulator(problem) as sim:
        state = sim.get_initial_state()
        out = [state]
        for ai in plan.actions:
            state = sim.apply(state, ai)
            assert state is not None
            out.append(state)
    return out


def bool_values(problem: Problem, state: Any) -> Dict[Any, bool]:
    """The value of every boolean fluent expression of `problem` in a simulator state."""
    return {
        f: state.get_value(f).is_true()
        for f in problem.initial_values
        if f.type.is_bool_type()
    }


def with_state(problem: Problem, values: Dict[Any, bool]) -> Problem:
    """A copy of `problem` whose initial state is `values`."""
    copy = problem.clone()
    for f, v in values.items():
        copy.set_initial_value(f, v)
    return copy


def solve(problem: Problem, **params: Any) -> Any:
    with OneshotPlanner(name="logic-lfd", params=params) as planner:
        return planner.solve(problem)


@pytest.fixture(scope="module")
def kitchen_up() -> Tuple[Problem, Any]:
    """The kitchen task and its demonstration, read with UP's PDDLReader."""
    reader = PDDLReader()
    folder = DOMAINS / "kitchen"
    problem = reader.parse_problem(str(folder / "domain.pddl"), str(folder / "problem.pddl"))
    return problem, reader.parse_plan(problem, str(folder / "demo.plan"))


# ---- registration and kinds ----


def test_import_registers_the_engine_once() -> None:
    factory = get_environment().factory
    assert factory.engine("logic-lfd") is LogicLfdEngine
    before = list(factory.engines)
    up_logic_lfd.register()
    up_logic_lfd.register(get_environment())
    assert list(factory.engines) == before
    assert LogicLfdEngine.is_oneshot_planner() and LogicLfdEngine.is_replanner()


def test_problem_kind_selection_in_a_fresh_environment() -> None:
    env = Environment()
    env.credits_stream = None
    up_logic_lfd.register(env)
    env.factory.preference_list = ["logic-lfd"]
    kind = blocks().kind
    with env.factory.OneshotPlanner(problem_kind=kind) as planner:
        assert planner.name == "logic-lfd"
    with env.factory.OneshotPlanner(
        problem_kind=route().kind, optimality_guarantee=OptimalityGuarantee.SOLVED_OPTIMALLY
    ) as planner:
        assert planner.name == "logic-lfd"
    with pytest.raises(UPNoSuitableEngineAvailableException):
        env.factory.OneshotPlanner(problem_kind=fuel().kind)


def test_supported_kind_is_the_pddl_readers() -> None:
    kind = LogicLfdEngine.supported_kind()
    for feature in ("ACTION_BASED", "FLAT_TYPING", "HIERARCHICAL_TYPING", "NEGATIVE_CONDITIONS",
                    "DISJUNCTIVE_CONDITIONS", "EQUALITIES", "ACTIONS_COST",
                    "STATIC_FLUENTS_IN_ACTIONS_COST", "INT_NUMBERS_IN_ACTIONS_COST"):
        assert feature in kind.features
    for feature in ("CONDITIONAL_EFFECTS", "EXISTENTIAL_CONDITIONS", "UNIVERSAL_CONDITIONS",
                    "INT_FLUENTS", "REAL_FLUENTS", "CONTINUOUS_TIME",
                    "REAL_NUMBERS_IN_ACTIONS_COST", "FLUENTS_IN_ACTIONS_COST"):
        assert feature not in kind.features
    assert LogicLfdEngine.supports(blocks().kind)
    assert LogicLfdEngine.supports(route().kind)


def test_numeric_fluents_are_refused_by_the_kind_check() -> None:
    problem = fuel()
    assert "INT_FLUENTS" in problem.kind.features
    assert not LogicLfdEngine.supports(problem.kind)
    with OneshotPlanner(name="logic-lfd") as planner:
        # Named engines only warn on a failed check (UP's rule); the engine then refuses.
        with pytest.warns(UserWarning, match="logic-lfd"):
            result = planner.solve(problem)
        assert result.status == Status.UNSUPPORTED_PROBLEM
        assert "INT_FLUENTS" in result.log_messages[0].message
        planner.error_on_failed_checks = True
        with pytest.raises(UPUsageError):
            planner.solve(problem)


# ---- oneshot planning ----


def test_blocks_world_is_solved_optimally_and_validated() -> None:
    problem = blocks()
    result = solve(problem)
    assert result.status == Status.SOLVED_OPTIMALLY
    assert result.engine_name == "logic-lfd"
    assert valid(problem, result.plan)
    # unstack A B, put A down, unstack B C, stack B on A, pick C up, stack C on B.
    assert len(result.plan.actions) == 6
    assert result.metrics["cost"] == "6"
    assert int(result.metrics["expanded"]) > 0
    # Upper-case UP names come back as the problem's own objects.
    assert {p.object() for ai in result.plan.actions for p in ai.actual_parameters} <= set(
        problem.all_objects
    )


def test_greedy_search_is_satisficing_and_valid() -> None:
    problem = blocks()
    out = io.StringIO()
    with OneshotPlanner(name="logic-lfd", params={"search": "gbfs", "heuristic": "hff"}) as p:
        result = p.solve(problem, output_stream=out)
    assert result.status == Status.SOLVED_SATISFICING
    assert valid(problem, result.plan)
    assert out.getvalue().startswith(f"logic-lfd: Plan({len(result.plan.actions)} actions")


def test_kitchen_matches_the_planner_on_the_raw_files(kitchen_up: Tuple[Problem, Any]) -> None:
    problem, _ = kitchen_up
    assert "HIERARCHICAL_TYPING" in problem.kind.features
    result = solve(problem)
    assert result.status == Status.SOLVED_OPTIMALLY
    assert valid(problem, result.plan)
    domain = (DOMAINS / "kitchen" / "domain.pddl").read_text()
    task = (DOMAINS / "kitchen" / "problem.pddl").read_text()
    raw = logic_lfd.plan(domain, task)
    assert result.metrics["cost"] == str(raw.cost)
    assert len(result.plan.actions) == raw.cost  # unit costs
    replay = logic_lfd.validate(domain, task, pddl_actions(result.plan))
    assert replay.valid and replay.cost == raw.cost


def test_action_costs_are_minimised() -> None:
    problem = route()
    assert "STATIC_FLUENTS_IN_ACTIONS_COST" in problem.kind.features
    result = solve(problem)
    assert result.status == Status.SOLVED_OPTIMALLY
    assert result.metrics["cost"] == "6"
    assert [ai.action.name for ai in result.plan.actions] == ["drive"] * 3
    with PlanValidator(name="sequential_plan_validator") as validator:
        check = validator.validate(problem, result.plan)
    assert check.status
    assert list(check.metric_evaluations.values()) == [6]


def test_unsolvable_is_proven() -> None:
    problem = blocks(("A", "A"))  # on(A, A): `stack` needs two different blocks
    result = solve(problem)
    assert result.status == Status.UNSOLVABLE_PROVEN
    assert result.plan is None


def test_budgets_stop_the_search(kitchen_up: Tuple[Problem, Any]) -> None:
    problem, _ = kitchen_up
    assert solve(problem, max_nodes="5").status == Status.UNSOLVABLE_INCOMPLETELY
    assert solve(problem, time_limit=0).status == Status.TIMEOUT
    with OneshotPlanner(name="logic-lfd") as planner:
        assert planner.solve(problem, timeout=0.0).status == Status.TIMEOUT


def test_bad_engine_parameters_raise_up_errors() -> None:
    with pytest.raises(UPUsageError, match="search"):
        solve(blocks(), search="no-such-search")
    with pytest.raises(UPUsageError, match="max_nodes"):
        OneshotPlanner(name="logic-lfd", params={"max_nodes": "many"})


# ---- replanning (Logic-LfD) ----


@pytest.fixture(scope="module")
def blocks_demo() -> Tuple[Problem, Any]:
    problem = blocks()
    return problem, solve(problem).plan


def resolve_from(problem: Problem, demo: Any, values: Dict[Any, bool]) -> Any:
    with Replanner(problem, name="logic-lfd", params={"demonstration": demo}) as replanner:
        for f, v in values.items():
            replanner.update_initial_value(f, v)
        return replanner.resolve()


@pytest.mark.parametrize("index", [0, 2, 4, 6])
def test_replanning_mid_demonstration_returns_the_suffix(
    blocks_demo: Tuple[Problem, Any], index: int
) -> None:
    problem, demo = blocks_demo
    state = states(problem, demo)[index]
    result = resolve_from(problem, demo, bool_values(problem, state))
    assert result.status in SOLVED
    # In the goal state the plan is empty and joins no demonstration state.
    assert result.metrics["k"] == ("none" if index == 6 else str(index))
    assert result.metrics["prefix_length"] == "0"
    assert result.metrics["source"] == ("goal-holds" if index == 6 else "logic-in")
    assert names(result.plan.actions) == names(demo.actions[index:])
    assert len(result.plan.actions) == len(demo.actions) - index


def test_replanning_from_a_disturbed_state(blocks_demo: Tuple[Problem, Any]) -> None:
    problem, demo = blocks_demo
    # After 3 steps B is held and A lies on the table; a disturbance drops B onto the table,
    # a state of no L_k: the plan picks B up again (L_3) and then follows the demonstration.
    values = bool_values(problem, states(problem, demo)[3])
    holding, ontable = problem.fluent("holding"), problem.fluent("ontable")
    clear, handempty = problem.fluent("clear"), problem.fluent("handempty")
    b = problem.object("B")
    assert values[holding(b)]
    values.update({holding(b): False, ontable(b): True, clear(b): True, handempty(): True})
    result = resolve_from(problem, demo, values)
    assert result.status in SOLVED
    assert result.metrics["valid"] == "True"
    k, prefix = int(result.metrics["k"]), int(result.metrics["prefix_length"])
    assert (k, prefix) == (3, 1)
    assert names(result.plan.actions[prefix:]) == names(demo.actions[k:])
    assert valid(with_state(problem, values), result.plan)
    assert not valid(with_state(problem, values), demo)


def test_kitchen_replanning_mid_demonstration(kitchen_up: Tuple[Problem, Any]) -> None:
    problem, demo = kitchen_up
    state = states(problem, demo)[10]
    with Replanner(problem, name="logic-lfd", params={"demonstration": demo}) as replanner:
        replanner.update_state(state)  # a UP State: every boolean fluent at once
        result = replanner.resolve()
    assert result.metrics["k"] == "10" and result.metrics["source"] == "logic-in"
    assert names(result.plan.actions) == names(demo.actions[10:])
    assert valid(with_state(problem, bool_values(problem, state)), result.plan)


def test_kitchen_replanning_after_a_disturbance(kitchen_up: Tuple[Problem, Any]) -> None:
    problem, demo = kitchen_up
    # Mid-demonstration (both vegetables on the counter, the knife in hand) the knife is
    # dropped at the counter and the fridge swings open again.
    values = bool_values(problem, states(problem, demo)[11])
    holding, item_at = problem.fluent("holding"), problem.fluent("item-at")
    hand_empty, closed = problem.fluent("hand-empty"), problem.fluent("closed")
    chef, knife = problem.object("chef"), problem.object("kitchen-knife")
    counter, fridge = problem.object("counter"), problem.object("fridge")
    assert values[holding(chef, knife)] and values[closed(fridge)]
    values.update({holding(chef, knife): False, item_at(knife, counter): True,
                   hand_empty(chef): True, closed(fridge): False})
    with Replanner(problem, name="logic-lfd", params={"demonstration": demo}) as replanner:
        replanner.update_state(values)  # a mapping: only these fluents change
        result = replanner.resolve()
    assert result.status in SOLVED and result.metrics["valid"] == "True"
    k, prefix = int(result.metrics["k"]), int(result.metrics["prefix_length"])
    assert prefix > 0
    assert names(result.plan.actions[prefix:]) == names(demo.actions[k:])
    assert valid(with_state(problem, values), result.plan)
    assert not valid(with_state(problem, values), SequentialPlan(demo.actions[11:]))


def test_replanner_without_a_demonstration_plans(blocks_demo: Tuple[Problem, Any]) -> None:
    problem, _ = blocks_demo
    with Replanner(problem, name="logic-lfd") as replanner:
        replanner.update_initial_value(problem.fluent("on")(*map(problem.object, "AB")), False)
        replanner.update_initial_value(problem.fluent("ontable")(problem.object("A")), True)
        replanner.update_initial_value(problem.fluent("clear")(problem.object("B")), True)
        result = replanner.resolve()
    assert result.status == Status.SOLVED_OPTIMALLY
    assert "k" not in result.metrics
    # From three blocks on the table: pick up B, stack it on A, pick up C, stack it on B.
    assert len(result.plan.actions) == 4


def test_a_demonstration_that_misses_the_goal_is_an_error(
    blocks_demo: Tuple[Problem, Any]
) -> None:
    problem, demo = blocks_demo
    short = SequentialPlan(demo.actions[:2])
    with Replanner(problem, name="logic-lfd", params={"demonstration": short}) as replanner:
        result = replanner.resolve()
    assert result.status == Status.INTERNAL_ERROR
    assert "goal" in result.log_messages[0].message


def test_replanner_goal_changes(blocks_demo: Tuple[Problem, Any]) -> None:
    problem, demo = blocks_demo
    on = problem.fluent("on")
    a, c = problem.object("A"), problem.object("C")
    with Replanner(problem, name="logic-lfd", params={"demonstration": demo}) as replanner:
        replanner.remove_goal(problem.goals[0])
        result = replanner.resolve()
        assert result.status in SOLVED
        # Named engines only warn on a failed check (UP's rule).
        with pytest.warns(UserWarning, match="not a goal"):
            replanner.remove_goal(on(a, c))
        replanner.error_on_failed_checks = True
        with pytest.raises(UPUsageError):
            replanner.remove_goal(on(a, c))


def test_a_demonstration_as_pddl_text_and_the_modes(kitchen_up: Tuple[Problem, Any]) -> None:
    problem, demo = kitchen_up
    text = (DOMAINS / "kitchen" / "demo.plan").read_text()
    for mode in ("paper", "prioritised"):
        params = {"demonstration": text, "mode": mode}
        with Replanner(problem, name="logic-lfd", params=params) as replanner:
            result = replanner.resolve()
        assert result.metrics["k"] == "0" and result.metrics["source"] == "logic-in"
        assert names(result.plan.actions) == names(demo.actions)
    params = {"demonstration": text, "mode": "fastest"}
    with Replanner(problem, name="logic-lfd", params=params) as replanner:
        with pytest.raises(UPUsageError, match="mode"):
            replanner.resolve()
