"""Shared paths of the Python tests: the repository's own PDDL tasks."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOMAINS = ROOT / "domains"


def read_task(name: str) -> tuple[str, str, str]:
    """The domain, problem and demonstration texts of `domains/<name>`."""
    folder = DOMAINS / name
    return (
        (folder / "domain.pddl").read_text(),
        (folder / "problem.pddl").read_text(),
        (folder / "demo.plan").read_text(),
    )


@pytest.fixture
def kitchen() -> tuple[str, str, str]:
    return read_task("kitchen")


def cli(*args: str, ok: tuple[int, ...] = (0,)) -> str:
    """Stdout of `logic-lfd ARGS`: the command line of this checkout, through cargo's debug
    build (which `cargo build`, part of `npm test`, has made); fails on another exit code."""
    if shutil.which("cargo") is None:
        pytest.skip("cargo is not installed")
    out = subprocess.run(
        ["cargo", "run", "-q", "-p", "logic-lfd", "--bin", "logic-lfd", "--", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert out.returncode in ok, f"logic-lfd {' '.join(args)}: exit {out.returncode}\n{out.stderr}"
    return out.stdout
