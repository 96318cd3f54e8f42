"""Sweeps of episodes on any `concurrent.futures` executor.

`sweep` runs a soak or the rows of Table I or II as independent items spread over an executor
(a thread or process pool on one machine, Dask's `Client.get_executor()` across machines, or
any other `Executor`) and joins the items' records into the report the CLI prints with `--json`.
"""

from __future__ import annotations

import json
import os
from concurrent.futures import Executor, Future, ThreadPoolExecutor
from typing import Any, Iterable, Mapping, Optional, Union, overload

from . import _core

Spec = Mapping[str, Any]
"""A sweep: `{"command": "soak" | "table1" | "table2", ...its options}`."""


def _run_chunk(spec_json: str, indices: list[int]) -> str:
    """Run items `indices` of a sweep and return their records (a JSON array).

    Module-level so process pools and Dask can pickle it.
    """
    return _core._sweep_run(spec_json, indices)


def _report(spec: Spec, executor: Optional[Executor], chunks: Optional[int]) -> dict[str, Any]:
    spec_json = json.dumps(dict(spec))
    items = _core._sweep_items(spec_json)
    own = executor is None
    pool: Executor = executor if executor is not None else ThreadPoolExecutor(os.cpu_count() or 1)
    try:
        # Items differ in cost by orders of magnitude: one item a task unless told otherwise;
        # chunk c takes items c, c + n, c + 2n, … as the CLI's shards do.
        n = max(1, min(items, chunks if chunks is not None else items))
        parts = [list(range(c, items, n)) for c in range(n)]
        futures: list[Future[str]] = [pool.submit(_run_chunk, spec_json, p) for p in parts]
        results = [f.result() for f in futures]
    finally:
        if own:
            pool.shutdown()
    # Back into item order: chunk c holds items c, c + n, …
    records: list[Any] = [None] * items
    for part, text in zip(parts, results):
        for index, record in zip(part, json.loads(text)):
            records[index] = record
    report_json, markdown = _core._sweep_report(spec_json, [json.dumps(records)])
    report: dict[str, Any] = json.loads(report_json)
    if markdown:
        report["markdown"] = markdown
    return report


@overload
def sweep(
    specs: Spec, executor: Optional[Executor] = None, *, chunks: Optional[int] = None
) -> dict[str, Any]: ...
@overload
def sweep(
    specs: Iterable[Spec], executor: Optional[Executor] = None, *, chunks: Optional[int] = None
) -> list[dict[str, Any]]: ...


def sweep(
    specs: Union[Spec, Iterable[Spec]],
    executor: Optional[Executor] = None,
    *,
    chunks: Optional[int] = None,
) -> Union[dict[str, Any], list[dict[str, Any]]]:
    """Run a sweep (or several) on `executor` and return the CLI's report.

    - `specs`: one spec or a list of them. `{"command": "soak", "episodes": 20, "seed": 0}`
      takes the options of `logic-lfd soak` (`episodes`, `seed`, `max_disturbances`,
      `first_episode`, `check_replay`, `blocks`, `folder`, `robot`); `"table1"` those of
      `logic-lfd bench table1` (`tasks`, `seed`, `benchmarks`, `tamp_fallback`, `robot`);
      `"table2"` those of `bench table2` (`trials` in place of `tasks`). Left-out options take
      the CLI's defaults; an unknown one raises `OptionError`.
    - `executor`: any `concurrent.futures.Executor`; `None` runs on a thread pool of every core
      (the core releases the GIL).
    - `chunks`: how many tasks to submit (default: one per item).

    Returns the report as a dict, equal to the CLI's `--json` output for the same options
    (wall-clock fields aside); the tables' dicts also hold their `markdown`.
    """
    if isinstance(specs, Mapping):
        return _report(specs, executor, chunks)
    return [_report(s, executor, chunks) for s in specs]
