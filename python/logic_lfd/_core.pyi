# Type stubs of the extension module `logic_lfd._core` (checked by mypy in python/tests).
from __future__ import annotations

import os as _os

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
    "DragRefused",
    "Plan",
    "Validation",
    "plan",
    "validate",
    "LogicLfd",
    "LfdResult",
    "_sweep_items",
    "_sweep_run",
    "_sweep_report",
    "lqt",
    "Session",
    "run_episode",
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

class DragRefused(LogicLfdError):
    body: str
    reason: str

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
    def __new__(
        cls,
        actions: list[str],
        cost: int,
        optimal: bool = False,
        stats: Optional[dict[str, Any]] = None,
    ) -> Plan: ...
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
    def __new__(
        cls,
        valid: bool,
        message: str,
        steps_applied: int,
        cost: int,
        failed_step: Optional[int] = None,
        false_literals: list[str] = ...,
    ) -> Validation: ...
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
    def __new__(
        cls,
        actions: list[str],
        prefix: list[str],
        suffix: list[str],
        k: Optional[int],
        logic_in: Optional[int],
        source: str,
        cost: int,
        valid: Optional[bool],
        stats: dict[str, Any],
    ) -> LfdResult: ...
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

# ---- robot ----

# A file or folder path.
_Path = Union[str, "_os.PathLike[str]"]
# A shipped robot ('panda', 'ur5'), a robot file, or one of these per arm.
_Robot = Union[_Path, Iterable[_Path]]

def lqt(case: Union[dict[str, Any], str, "_os.PathLike[str]"]) -> dict[str, Any]:
    """Solves one LQT-CP case (docs/formats.md); arrays are float64 numpy arrays.

    With T = n_steps, N = T - 1, D = dim, nx = D * order, K = basis.n_fct: `A` (nx, nx),
    `B` (nx, D), `phi` (N, K), `w` (K, D), `u` (N, D), `x` (T, nx; x[0] = x0), `pos` (T, D),
    `cost` (float), `target_errors` (list of dicts) and, with a `feedback` case,
    `feedback`: `F` (N*D, nx+1), `gains` (N, D, nx+1), `nominal` / `perturbed` rollouts
    (`x` (T, nx), `u` (N, D), `pos` (T, D), `final_goal_pos_dist`).
    """
    ...

@final
class Session:
    """One closed-loop episode (paper Algorithm 1) in a kinematic workcell.

    Frames are dicts: the core's frame (`t`, `tick`, `status`, `plan`, `executing`, `demo`,
    `demo_states`, `matched_k`, `facts`, `facts_added`, `facts_removed`, `last_replan`,
    `replans`, `ee`, `world`) plus float64 numpy arrays `joints` (arm name -> (n_joints,)) and
    `poses` (body name -> (7,): x, y, z, qx, qy, qz, qw).
    """

    def __new__(
        cls,
        benchmark: Optional[str] = None,
        *,
        folder: Optional[_Path] = None,
        method: str = "logic-lfd",
        mode: str = "paper",
        seed: int = 0,
        skill: str = "lqt",
        blocks: Optional[int] = None,
        scene: Optional[str] = None,
        robot: Optional[_Robot] = None,
    ) -> Session: ...
    def step(self, dt: float) -> dict[str, Any]: ...
    def run(self) -> dict[str, Any]: ...
    def frame(self) -> dict[str, Any]: ...
    def inject(self, level: str) -> Optional[dict[str, Any]]: ...
    def can_inject(self, level: str) -> Optional[str]: ...
    def drag(self, body: str, to: Iterable[float]) -> dict[str, Any]: ...
    def cancel(self) -> None: ...
    def reset(self, seed: Optional[int] = None) -> None: ...
    @property
    def done(self) -> bool: ...
    @property
    def success(self) -> bool: ...
    @property
    def tick(self) -> int: ...
    @property
    def seed(self) -> int: ...
    def episode_json(self, *, with_files: bool = False) -> str: ...
    def scene_json(self) -> str: ...

def run_episode(
    benchmark: Optional[str] = None,
    *,
    folder: Optional[_Path] = None,
    level: Optional[str] = None,
    method: str = "logic-lfd",
    mode: str = "paper",
    seed: int = 0,
    blocks: Optional[int] = None,
    scene: Optional[str] = None,
    robot: Optional[_Robot] = None,
    canonical: bool = False,
    with_files: bool = False,
) -> dict[str, Any]:
    """One closed-loop episode to its end: the report of `logic-lfd run --json`."""
    ...
