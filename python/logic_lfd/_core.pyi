# Type stubs of the extension module `logic_lfd._core` (checked by mypy in python/tests).
from __future__ import annotations

from typing import Any, Iterable, Iterator, Optional, Union, final

__version__: str
__all__ = [
    "__version__",
    "LogicLfdError",
    "PddlError",
    "DemoError",
    "LoadError",
    "NoPlanError",
    "OptionError",
    "Plan",
    "Validation",
    "plan",
    "validate",
    "LogicLfd",
    "LfdResult",
    "_sweep_items",
    "_sweep_run",
    "_sweep_report",
]

# A state: one text of PDDL atoms, or an iterable of atom strings such as "(on a b)".
_Atoms = Union[str, Iterable[str]]
# A plan: IPC text (one action a line), or an iterable of action strings.
_PlanText = Union[str, Iterable[str]]

class LogicLfdError(Exception): ...

class PddlError(LogicLfdError):
    file: str
    line: int
    col: int
    message: str

class DemoError(PddlError): ...

class LoadError(LogicLfdError):
    path: str
    message: str

class NoPlanError(LogicLfdError):
    reason: str
    budget: Optional[str]
    message: str
    stats: Optional[dict[str, Any]]

class OptionError(LogicLfdError):
    option: str
    message: str

# ---- planning ----

@final
class Plan:
    actions: list[str]
    cost: int
    optimal: bool
    stats: dict[str, Any]
    def __len__(self) -> int: ...
    def __iter__(self) -> Iterator[str]: ...

@final
class Validation:
    valid: bool
    message: str
    steps_applied: int
    cost: int
    failed_step: Optional[int]
    false_literals: list[str]
    def __bool__(self) -> bool: ...

def plan(
    domain: str,
    problem: str,
    search: str = "astar",
    heuristic: Optional[str] = None,
    *,
    max_nodes: Optional[int] = None,
    time_limit: Optional[float] = None,
    domain_file: str = "domain.pddl",
    problem_file: str = "problem.pddl",
) -> Plan: ...
def validate(
    domain: str,
    problem: str,
    plan: _PlanText,
    *,
    domain_file: str = "domain.pddl",
    problem_file: str = "problem.pddl",
    plan_file: str = "plan",
) -> Validation: ...

# ---- Logic-LfD ----

@final
class LfdResult:
    actions: list[str]
    prefix: list[str]
    suffix: list[str]
    k: Optional[int]
    logic_in: Optional[int]
    source: str
    cost: int
    valid: Optional[bool]
    stats: dict[str, Any]
    def __len__(self) -> int: ...

@final
class LogicLfd:
    def __new__(
        cls,
        domain: str,
        problem: str,
        demo: _PlanText,
        *,
        domain_file: str = "domain.pddl",
        problem_file: str = "problem.pddl",
        demo_file: str = "demo.plan",
    ) -> LogicLfd: ...
    @property
    def demo_actions(self) -> list[str]: ...
    @property
    def demo_states(self) -> list[list[str]]: ...
    @property
    def demo_costs(self) -> list[int]: ...
    @property
    def static_facts(self) -> list[str]: ...
    @property
    def fluents(self) -> list[str]: ...
    def logic_in(self, state: Optional[_Atoms] = None) -> Optional[int]: ...
    def replan(
        self,
        state: Optional[_Atoms] = None,
        mode: str = "paper",
        *,
        search: str = "astar",
        heuristic: Optional[str] = None,
        max_nodes: Optional[int] = None,
        time_limit: Optional[float] = 30.0,
        validate: bool = True,
    ) -> LfdResult: ...
    def validate(self, plan: _PlanText, state: Optional[_Atoms] = None) -> Validation: ...
    def _native_replan_seconds(
        self, state: Optional[_Atoms], repeats: int, mode: str = "paper"
    ) -> list[float]: ...

# ---- sweeps (used by logic_lfd.sweep) ----

def _sweep_items(spec: str) -> int: ...
def _sweep_run(spec: str, indices: list[int]) -> str: ...
def _sweep_report(spec: str, records: list[str]) -> tuple[str, str]: ...
