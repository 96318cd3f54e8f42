"""`logic_lfd.sweep` gives the CLI's report on a thread pool, a process pool and Dask."""

from __future__ import annotations

import json
import multiprocessing
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from typing import Any

import pytest

import logic_lfd
from conftest import cli

SOAK = {"command": "soak", "episodes": 4, "seed": 5, "check_replay": False}


def process_pool(workers: int) -> ProcessPoolExecutor:
    """A pool of fresh interpreters: forking a process that runs threads (pytest's, Dask's) is
    unsafe, and spawn is what Python 3.14 and macOS do by default."""
    return ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn"))


def cli_json(*args: str) -> Any:
    """What `logic-lfd ARGS --json` prints (exit 5: a soak with findings still reports)."""
    return json.loads(cli(*args, "--json", ok=(0, 5)))


@pytest.fixture(scope="module")
def soak_cli() -> Any:
    return cli_json("soak", "--episodes", "4", "--seed", "5", "--no-replay")


def test_a_soak_on_a_process_pool_is_the_cli_report(soak_cli: Any) -> None:
    with process_pool(2) as pool:
        report = logic_lfd.sweep(SOAK, pool)
    assert report == soak_cli
    assert report["episodes"] == 4 and report["invariant_checks"] > 0


def test_chunks_and_thread_pools_do_not_change_the_report(soak_cli: Any) -> None:
    assert logic_lfd.sweep(SOAK) == soak_cli
    with ThreadPoolExecutor(3) as pool:
        assert logic_lfd.sweep(SOAK, pool, chunks=3) == soak_cli


def test_a_soak_on_a_local_dask_cluster_is_the_cli_report(soak_cli: Any) -> None:
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        report = logic_lfd.sweep(SOAK, client.get_executor())
    assert report == soak_cli


def without_wall_clock(value: Any) -> Any:
    """`value` with the tables' wall-clock fields (`*_ms`) zeroed."""
    if isinstance(value, dict):
        return {
            k: (0 if k.endswith("_ms") else without_wall_clock(v)) for k, v in value.items()
        }
    if isinstance(value, list):
        return [without_wall_clock(v) for v in value]
    return value


def test_table1_rows_are_the_cli_table() -> None:
    spec = {"command": "table1", "tasks": 2, "seed": 3, "benchmarks": "b1"}
    report = logic_lfd.sweep([spec])[0]
    markdown = report.pop("markdown")
    assert markdown.startswith("Table I")
    expected = cli_json("bench", "table1", "--tasks", "2", "--seed", "3", "--benchmarks", "b1")
    assert without_wall_clock(report) == without_wall_clock(expected)


def test_a_bad_spec_raises_with_the_option_named() -> None:
    with pytest.raises(logic_lfd.OptionError) as e:
        logic_lfd.sweep({"command": "soak", "episodez": 3})
    assert "episodez" in e.value.message
    with pytest.raises(logic_lfd.OptionError) as e:
        logic_lfd.sweep({"command": "table3"})
    assert e.value.option == "command"
    with pytest.raises(logic_lfd.LoadError) as le:
        logic_lfd.sweep({"command": "soak", "folder": "/no/such/folder"})
    assert le.value.path == "/no/such/folder"


def test_table2_rows_are_the_cli_table() -> None:
    spec = {"command": "table2", "trials": 1, "benchmarks": ["b1"]}
    with process_pool(2) as pool:
        report = logic_lfd.sweep(spec, pool)
    assert report.pop("markdown").startswith("Table II")
    expected = cli_json("bench", "table2", "--trials", "1", "--benchmarks", "b1")
    assert without_wall_clock(report) == without_wall_clock(expected)
