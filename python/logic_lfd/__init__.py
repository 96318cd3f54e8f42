"""logic-lfd: learn a multi-step manipulation task from one demonstration (Logic-LfD).

The Rust core of logic-lfd as a Python package: a PDDL planner (`plan`, `validate`),
Logic-LfD replanning from one demonstration (`LogicLfd`), LQT-CP motion skills (`lqt`), the
simulated robot and its reactive loop (`Session`, `run_episode`) and sweeps of episodes on any
`concurrent.futures` executor (`sweep`).

Every error is an exception of this module with fields (`PddlError.file/.line/.col`,
`LoadError.path`, `NoPlanError.reason`); long calls release the GIL.
"""

from __future__ import annotations

from ._core import (
    DemoError,
    DragRefused,
    LfdResult,
    LoadError,
    LogicLfd,
    LogicLfdError,
    NoPlanError,
    OptionError,
    Plan,
    PddlError,
    Session,
    Validation,
    __version__,
    lqt,
    plan,
    run_episode,
    validate,
)
from .sweep import sweep

__all__ = [
    "DemoError",
    "DragRefused",
    "LfdResult",
    "LoadError",
    "LogicLfd",
    "LogicLfdError",
    "NoPlanError",
    "OptionError",
    "Plan",
    "PddlError",
    "Session",
    "Validation",
    "__version__",
    "lqt",
    "plan",
    "run_episode",
    "sweep",
    "validate",
]
