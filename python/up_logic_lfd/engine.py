"""`LogicLfdEngine`: logic-lfd as a unified-planning engine (oneshot planner and replanner).

As a `OneshotPlanner` it writes the problem with UP's `PDDLWriter`, plans with
`logic_lfd.plan` (A* with LM-cut by default: optimal) and reads the plan back. As a
`Replanner` it runs Logic-LfD: given a demonstration (engine parameter `demonstration`, a UP
`SequentialPlan` of the problem) and the current state (the problem's initial values, changed
with `update_initial_value`), `resolve()` plans to the latest demonstration state L_k the
current state can reach and appends the demonstration's rest.
"""

from __future__ import annotations

import time
import warnings
from fractions import Fraction
from typing import IO, Any, Callable, Mapping, Optional, Tuple, Union

from unified_planning.engines import (  # type: ignore[import-untyped]
    Engine,
    LogLevel,
    PlanGenerationResult,
)
from unified_planning.engines.mixins import (  # type: ignore[import-untyped]
    OneshotPlannerMixin,
    ReplannerMixin,
)
from unified_planning.engines.mixins.oneshot_planner import (  # type: ignore[import-untyped]
    OptimalityGuarantee,
)
from unified_planning.exceptions import (  # type: ignore[import-untyped]
    UPException,
    UPUsageError,
)
from unified_planning.io import PDDLReader  # type: ignore[import-untyped]
from unified_planning.model import ProblemKind  # type: ignore[import-untyped]
from unified_planning.model.problem_kind_versioning import (  # type: ignore[import-untyped]
    LATEST_PROBLEM_KIND_VERSION,
)
from unified_planning.plans import SequentialPlan  # type: ignore[import-untyped]

import logic_lfd

from .results import (
    ENGINE_NAME,
    internal_error,
    message,
    metrics_of,
    no_plan,
    pddl_error_text,
    solved,
    unsupported,
)
from .translate import PddlTask, true_atoms

Value = Union[Any, bool, int, float, Fraction]
"""A value of `update_initial_value`: an expression, an object, a bool or a number."""


def _optional_int(name: str, value: Optional[Union[int, str]]) -> Optional[int]:
    """An integer engine parameter (UP configuration files give strings), or `UPUsageError`."""
    if value is None:
        return None
    try:
        number = int(value)
    except (TypeError, ValueError):
        raise UPUsageError(f"{ENGINE_NAME}: `{name}` must be an integer, got {value!r}")
    if number < 0:
        raise UPUsageError(f"{ENGINE_NAME}: `{name}` must be non-negative, got {value!r}")
    return number


def _optional_float(name: str, value: Optional[Union[float, str]]) -> Optional[float]:
    """A number-of-seconds engine parameter, or `UPUsageError`."""
    if value is None:
        return None
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise UPUsageError(f"{ENGINE_NAME}: `{name}` must be a number, got {value!r}")
    if not number >= 0:
        raise UPUsageError(f"{ENGINE_NAME}: `{name}` must be non-negative, got {value!r}")
    return number


class LogicLfdEngine(Engine, OneshotPlannerMixin, ReplannerMixin):  # type: ignore[misc]
    """The logic-lfd planner as a UP engine: `OneshotPlanner` and `Replanner` (Logic-LfD).

    Engine parameters (UP's `params`; strings are accepted for the numbers):

    - `search`: 'astar' (default), 'gbfs', 'wastar', 'ucs', 'bfs', … (as `logic_lfd.plan`).
    - `heuristic`: 'lmcut' (default with A*), 'hff', 'hmax', … (as `logic_lfd.plan`).
    - `max_nodes`: stop after this many expansions (`UNSOLVABLE_INCOMPLETELY`).
    - `time_limit`: seconds (`TIMEOUT`); `solve`'s and `resolve`'s `timeout` also bound it.
    - `demonstration`: (replanner) a `SequentialPlan` of the problem from its initial state to
      the goal, or its PDDL text in the problem's own names.
    - `mode`: (replanner) 'paper' (the first L_k reached, default) or 'prioritised'.
    - `validate`: (replanner) replay each Logic-LfD plan with the lifted validator (default
      true); a plan that fails is reported with a WARNING log message.

    As a replanner without a demonstration, `resolve()` plans from the current state like
    `solve`. The optimality guarantee holds for `solve` with the default search; a Logic-LfD
    plan (prefix to L_k, then the demonstration's rest) is `SOLVED_SATISFICING`.
    """

    def __init__(
        self,
        problem: Optional[Any] = None,
        error_on_failed_checks: bool = True,
        *,
        search: str = "astar",
        heuristic: Optional[str] = None,
        max_nodes: Optional[Union[int, str]] = None,
        time_limit: Optional[Union[float, str]] = None,
        demonstration: Optional[Union[SequentialPlan, str]] = None,
        mode: str = "paper",
        validate: Union[bool, str] = True,
    ) -> None:
        Engine.__init__(self)
        OneshotPlannerMixin.__init__(self)
        self._search = search
        self._heuristic = heuristic
        self._max_nodes = _optional_int("max_nodes", max_nodes)
        self._time_limit = _optional_float("time_limit", time_limit)
        self._mode = mode
        self._validate = validate if isinstance(validate, bool) else validate.lower() == "true"
        self._demonstration = demonstration
        self._problem: Optional[Any] = None
        self._demo_problem: Optional[Any] = None
        self._lfd: Optional[Tuple[logic_lfd.LogicLfd, PddlTask]] = None
        if problem is not None:
            ReplannerMixin.__init__(self, problem, error_on_failed_checks)
            self._demo_problem = problem.clone()

    @property
    def name(self) -> str:
        """The engine's name in UP's factory: `logic-lfd`."""
        return ENGINE_NAME

    @staticmethod
    def supported_kind() -> ProblemKind:
        """Classical planning as the logic-lfd PDDL reader takes it.

        Typed STRIPS (flat or hierarchical types) with negative, disjunctive and equality
        conditions, and action costs made of integers and static fluents (minimised, or plan
        length). Numeric fluents, conditional effects, quantifiers, time and the rest are not
        supported.
        """
        kind = ProblemKind(version=LATEST_PROBLEM_KIND_VERSION)
        kind.set_problem_class("ACTION_BASED")
        kind.set_typing("FLAT_TYPING")
        kind.set_typing("HIERARCHICAL_TYPING")
        kind.set_conditions_kind("NEGATIVE_CONDITIONS")
        kind.set_conditions_kind("DISJUNCTIVE_CONDITIONS")
        kind.set_conditions_kind("EQUALITIES")
        kind.set_quality_metrics("ACTIONS_COST")
        kind.set_quality_metrics("PLAN_LENGTH")
        kind.set_actions_cost_kind("INT_NUMBERS_IN_ACTIONS_COST")
        kind.set_actions_cost_kind("STATIC_FLUENTS_IN_ACTIONS_COST")
        return kind

    @staticmethod
    def supports(problem_kind: ProblemKind) -> bool:
        """Whether every feature of `problem_kind` is in `supported_kind()`."""
        ok: bool = problem_kind <= LogicLfdEngine.supported_kind()
        return ok

    @staticmethod
    def satisfies(optimality_guarantee: OptimalityGuarantee) -> bool:
        """Both guarantees: A* with LM-cut (the default) proves its plans optimal."""
        return optimality_guarantee in (
            OptimalityGuarantee.SATISFICING,
            OptimalityGuarantee.SOLVED_OPTIMALLY,
        )

    @staticmethod
    def get_credits(**kwargs: Any) -> None:
        """No credits are printed."""
        return None

    # ---- oneshot planning ----

    def _solve(
        self,
        problem: Any,
        heuristic: Optional[Callable[[Any], Optional[float]]] = None,
        timeout: Optional[float] = None,
        output_stream: Optional[IO[str]] = None,
    ) -> PlanGenerationResult:
        """Plans `problem` with `logic_lfd.plan` (see the class for the parameters)."""
        if heuristic is not None:
            warnings.warn(
                f"{ENGINE_NAME} ignores a Python heuristic; use the engine parameter `heuristic`"
            )
        return self._plan(problem, timeout, output_stream)

    def _limit(self, timeout: Optional[float]) -> Optional[float]:
        """The tighter of the `time_limit` parameter and a call's `timeout`."""
        limits = [t for t in (self._time_limit, timeout) if t is not None]
        return min(limits) if limits else None

    def _guarded(
        self, problem: Any, work: Callable[[float], PlanGenerationResult]
    ) -> PlanGenerationResult:
        """`work(start)` after UP's kind check, with logic-lfd's and UP's errors as results; a bad
        engine parameter raises `UPUsageError`."""
        if not self.skip_checks and not self.supports(problem.kind):
            return unsupported(problem.kind, self.supported_kind())
        start = time.perf_counter()
        try:
            return work(start)
        except logic_lfd.NoPlanError as e:
            return no_plan(e, time.perf_counter() - start)
        except logic_lfd.OptionError as e:
            raise UPUsageError(f"{ENGINE_NAME}: engine parameter `{e.option}`: {e.message}")
        except logic_lfd.PddlError as e:
            return internal_error(pddl_error_text(e))
        except (logic_lfd.LogicLfdError, UPException) as e:
            return internal_error(str(e))

    def _plan(
        self, problem: Any, timeout: Optional[float], output_stream: Optional[IO[str]]
    ) -> PlanGenerationResult:
        """Writes `problem` as PDDL, plans it and reads the plan back."""

        def work(start: float) -> PlanGenerationResult:
            pddl = PddlTask.of(problem)
            found = logic_lfd.plan(
                pddl.domain,
                pddl.task,
                self._search,
                self._heuristic,
                max_nodes=self._max_nodes,
                time_limit=self._limit(timeout),
            )
            plan = pddl.plan_of(found.actions)
            elapsed = time.perf_counter() - start
            if output_stream is not None:
                output_stream.write(
                    f"{ENGINE_NAME}: {found!r}, {found.stats['expanded']} expanded\n"
                )
            metrics = metrics_of(
                found.stats,
                cost=found.cost,
                plan_length=len(found),
                optimal=found.optimal,
                engine_internal_time=elapsed,
            )
            return solved(plan, found.optimal, metrics)

        return self._guarded(problem, work)

    # ---- replanning (Logic-LfD) ----

    def _current(self) -> Any:
        """The replanner's problem (its initial state is the current state)."""
        if self._problem is None:
            raise UPUsageError(
                f"{ENGINE_NAME}: replanning needs a problem: use "
                f"Replanner(problem, name='{ENGINE_NAME}', params={{'demonstration': plan}})"
            )
        return self._problem

    def _logic_lfd(self) -> Tuple[logic_lfd.LogicLfd, PddlTask]:
        """The `logic_lfd.LogicLfd` of the demonstration's problem, built once per change."""
        if self._lfd is None:
            assert self._demo_problem is not None
            pddl = PddlTask.of(self._demo_problem)
            demo = self._demonstration
            if isinstance(demo, str):
                demo = PDDLReader(environment=self._demo_problem.environment).parse_plan_string(
                    self._demo_problem, demo
                )
            lfd = logic_lfd.LogicLfd(
                pddl.domain, pddl.task, pddl.plan_text(demo), demo_file="demonstration"
            )
            self._lfd = (lfd, pddl)
        return self._lfd

    def _resolve(
        self, timeout: Optional[float] = None, output_stream: Optional[IO[str]] = None
    ) -> PlanGenerationResult:
        """Logic-LfD from the current state, or plain planning without a demonstration.

        Metrics: `k` (the demonstration state joined, `none` for the goal directly),
        `logic_in`, `source` ('goal-holds', 'logic-in' or 'multi-goal'), `prefix_length`,
        `suffix_length`, `cost`, `valid` and the search statistics.
        """
        problem = self._current()
        if self._demonstration is None:
            return self._plan(problem, timeout, output_stream)

        def work(start: float) -> PlanGenerationResult:
            lfd, pddl = self._logic_lfd()
            state = true_atoms(pddl, problem.initial_values)
            found = lfd.replan(
                state,
                self._mode,
                search=self._search,
                heuristic=self._heuristic,
                max_nodes=self._max_nodes,
                time_limit=self._limit(timeout),
                validate=self._validate,
            )
            plan = pddl.plan_of(found.actions, problem)
            elapsed = time.perf_counter() - start
            if output_stream is not None:
                output_stream.write(f"{ENGINE_NAME}: {found!r}\n")
            metrics = metrics_of(
                found.stats,
                k=found.k,
                logic_in=found.logic_in,
                source=found.source,
                prefix_length=len(found.prefix),
                suffix_length=len(found.suffix),
                cost=found.cost,
                valid=found.valid,
                engine_internal_time=elapsed,
            )
            result = solved(plan, len(found) == 0, metrics)
            if found.valid is False:
                result.log_messages = message(
                    LogLevel.WARNING, "the lifted validator rejects the Logic-LfD plan"
                )
            return result

        return self._guarded(problem, work)

    def _problems(self) -> Tuple[Any, Any]:
        """The current problem and the demonstration's problem (both changed by goal and
        action edits)."""
        current = self._current()
        assert self._demo_problem is not None
        return current, self._demo_problem

    def _changed(self) -> None:
        """Forgets the `LogicLfd` built for the demonstration's problem."""
        self._lfd = None

    def _update_initial_value(self, fluent: Any, value: Value) -> None:
        """Sets one value of the current state.

        Numeric values (static action costs) change the demonstration's problem too.
        """
        current, demo = self._problems()
        current.set_initial_value(fluent, value)
        (expression,) = current.environment.expression_manager.auto_promote(fluent)
        if not expression.type.is_bool_type():
            demo.set_initial_value(fluent, value)
            self._changed()

    def update_state(self, state: Union[Mapping[Any, bool], Any]) -> None:
        """Sets the current state at once: a mapping from boolean fluent expressions to
        values (the others keep theirs), or a UP `State` (e.g. a `SequentialSimulator`'s),
        which gives every boolean fluent expression of the problem its value."""
        current = self._current()
        if isinstance(state, Mapping):
            for fluent, value in state.items():
                self._update_initial_value(fluent, value)
            return
        for expression in current.initial_values:
            if expression.type.is_bool_type():
                self._update_initial_value(expression, state.get_value(expression))

    def _add_goal(self, goal: Union[Any, bool]) -> None:
        """Adds a goal to the problem (the demonstration must still reach it)."""
        for problem in self._problems():
            problem.add_goal(goal)
        self._changed()

    def _remove_goal(self, goal: Union[Any, bool]) -> None:
        """Removes a goal; an absent goal is an error (or a warning, as the checks say)."""
        removed = False
        for problem in self._problems():
            (target,) = problem.environment.expression_manager.auto_promote(goal)
            goals = problem.goals
            problem.clear_goals()
            for g in goals:
                if g is target:
                    removed = True
                else:
                    problem.add_goal(g)
        self._changed()
        self._check(removed, f"goal to remove: {goal} is not a goal of the problem")

    def _add_action(self, action: Any) -> None:
        """Adds an action to the problem."""
        for problem in self._problems():
            problem.add_action(action)
        self._changed()

    def _remove_action(self, name: str) -> None:
        """Removes the action named `name` (the demonstration must not use it)."""
        removed = False
        for problem in self._problems():
            actions = problem.actions
            problem.clear_actions()
            for a in actions:
                if a.name == name:
                    removed = True
                else:
                    problem.add_action(a)
        self._changed()
        self._check(removed, f"action to remove: {name} is not an action of the problem")

    def _check(self, ok: bool, text: str) -> None:
        """A failed check: `UPUsageError`, or a warning when the checks only warn."""
        if ok or self.skip_checks:
            return
        if self.error_on_failed_checks:
            raise UPUsageError(text)
        warnings.warn(text)

    def destroy(self) -> None:
        """Drops the cached Logic-LfD instance."""
        self._lfd = None

