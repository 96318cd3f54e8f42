"""The type stubs match the built module, and the tests, examples and engine type-check."""

from __future__ import annotations

import subprocess
import sys
import tempfile

from conftest import ROOT

PYTHON = ROOT / "python"


def run(*args: str, cwd: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", *args], cwd=cwd, capture_output=True, text=True, check=False
    )


def test_the_stubs_match_the_built_module() -> None:
    # From an empty folder, so the installed package is checked, not the source tree.
    with tempfile.TemporaryDirectory() as empty:
        out = run("mypy.stubtest", "logic_lfd._core", cwd=empty)
    assert out.returncode == 0, out.stdout + out.stderr


def test_the_package_tests_and_examples_type_check_strictly() -> None:
    paths = ["logic_lfd", "up_logic_lfd", "tests", "examples", "benches"]
    out = run("mypy", "--strict", *paths, cwd=str(PYTHON))
    assert out.returncode == 0, out.stdout + out.stderr
