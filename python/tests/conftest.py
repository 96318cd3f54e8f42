"""Shared paths of the Python tests: the repository's own PDDL tasks."""

from __future__ import annotations

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
