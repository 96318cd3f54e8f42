"""logic-lfd as a unified-planning (UP) engine named "logic-lfd".

Importing this package registers the engine in UP's global environment, so that

    import up_logic_lfd
    from unified_planning.shortcuts import OneshotPlanner, Replanner

    with OneshotPlanner(name="logic-lfd") as planner:
        result = planner.solve(problem)

plans `problem` with logic-lfd's A* and LM-cut (optimal), and

    with Replanner(problem, name="logic-lfd", params={"demonstration": demo}) as replanner:
        replanner.update_initial_value(on(a, b), False)   # the current state
        result = replanner.resolve()

runs Logic-LfD: a plan to the latest demonstration state L_k reachable from the current state,
then the demonstration's rest (`result.metrics["k"]`, `["source"]`, `["prefix_length"]`).
The engine is also picked by `OneshotPlanner(problem_kind=…)` for the problem kinds it
supports (`LogicLfdEngine.supported_kind()`), after the engines UP prefers.
"""

from __future__ import annotations

from typing import Any, Optional

from unified_planning.environment import get_environment  # type: ignore[import-untyped]

from .engine import LogicLfdEngine
from .results import ENGINE_NAME

__all__ = ["ENGINE_NAME", "LogicLfdEngine", "register"]


def register(env: Optional[Any] = None) -> None:
    """Adds the engine "logic-lfd" to the factory of `env` (UP's global environment when
    `None`); a second call does nothing."""
    factory = get_environment(env).factory
    if ENGINE_NAME not in factory.engines:
        factory.add_engine(ENGINE_NAME, __name__, "LogicLfdEngine")


register()
