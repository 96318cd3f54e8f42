"""`PlanGenerationResult`s of the logic-lfd engine: plans found, and each `logic_lfd` error.

Metrics are strings, as UP's `PlanGenerationResult.metrics` holds them.
"""

from __future__ import annotations

from typing import Any, Dict, List, Mapping, Optional

from unified_planning.engines import (  # type: ignore[import-untyped]
    LogLevel,
    LogMessage,
    PlanGenerationResult,
    PlanGenerationResultStatus,
)

import logic_lfd

ENGINE_NAME = "logic-lfd"
"""The name the engine is registered under in UP's factory."""


def metrics_of(stats: Optional[Mapping[str, Any]], **extra: Any) -> Dict[str, str]:
    """UP metrics (name → string) from a `logic_lfd` stats dict and extra values.

    `None` values are written `none`; floats keep their full precision.
    """
    out: Dict[str, str] = {}
    for key, value in list((stats or {}).items()) + list(extra.items()):
        out[key] = "none" if value is None else str(value)
    return out


def message(level: Any, text: str) -> List[Any]:
    """A one-message log list at UP `LogLevel` `level`."""
    return [LogMessage(level, text)]


def solved(plan: Any, optimal: bool, metrics: Dict[str, str]) -> PlanGenerationResult:
    """A plan found: `SOLVED_OPTIMALLY` when proved optimal, else `SOLVED_SATISFICING`."""
    status = (
        PlanGenerationResultStatus.SOLVED_OPTIMALLY
        if optimal
        else PlanGenerationResultStatus.SOLVED_SATISFICING
    )
    return PlanGenerationResult(status, plan, ENGINE_NAME, metrics=metrics)


def no_plan(error: logic_lfd.NoPlanError, elapsed: float) -> PlanGenerationResult:
    """No plan: `UNSOLVABLE_PROVEN` (reason 'unsolvable'), `TIMEOUT` (the time limit ran out)
    or `UNSOLVABLE_INCOMPLETELY` (the node budget ran out)."""
    if error.reason == "unsolvable":
        status = PlanGenerationResultStatus.UNSOLVABLE_PROVEN
    elif error.budget == "time":
        status = PlanGenerationResultStatus.TIMEOUT
    else:
        status = PlanGenerationResultStatus.UNSOLVABLE_INCOMPLETELY
    return PlanGenerationResult(
        status,
        None,
        ENGINE_NAME,
        metrics=metrics_of(error.stats, reason=error.reason, engine_internal_time=elapsed),
        log_messages=message(LogLevel.INFO, error.message),
    )


def internal_error(text: str) -> PlanGenerationResult:
    """`INTERNAL_ERROR` with `text` as an ERROR log message (e.g. a `PddlError` located in the
    PDDL that UP's writer produced)."""
    return PlanGenerationResult(
        PlanGenerationResultStatus.INTERNAL_ERROR,
        None,
        ENGINE_NAME,
        log_messages=message(LogLevel.ERROR, text),
    )


def unsupported(kind: Any, supported: Any) -> PlanGenerationResult:
    """`UNSUPPORTED_PROBLEM`, naming the features of `kind` that `supported` lacks."""
    missing = sorted(f for f in kind.features if f not in supported.features)
    return PlanGenerationResult(
        PlanGenerationResultStatus.UNSUPPORTED_PROBLEM,
        None,
        ENGINE_NAME,
        log_messages=message(
            LogLevel.ERROR,
            f"{ENGINE_NAME} does not support: {', '.join(missing) or 'this problem kind'}",
        ),
    )


def pddl_error_text(error: logic_lfd.PddlError) -> str:
    """A `PddlError` as one line: `file:line:col: message` (the file is UP's written PDDL)."""
    if error.file:
        return f"{error.file}:{error.line}:{error.col}: {error.message}"
    return error.message
