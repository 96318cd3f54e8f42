"""The simulated robot: `Session` stepped to the end, disturbed and dragged, and `run_episode`
against the CLI's `logic-lfd run --json`."""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import logic_lfd
from logic_lfd import DragRefused, LoadError, OptionError, Session, run_episode

from conftest import DOMAINS, ROOT, cli

TOWER = ["(on a b)", "(on b c)", "(on c d)"]


def run_to_end(s: Session, dt: float = 0.5, max_steps: int = 1000) -> dict[str, Any]:
    """Steps `s` until its episode ends (or `max_steps` steps) and returns the last frame."""
    f = s.frame()
    for _ in range(max_steps):
        if s.done:
            break
        f = s.step(dt)
    return f


def test_b1_episode_reaches_the_goal() -> None:
    s = Session("b1", seed=1)
    first = s.frame()
    assert first["status"]["kind"] == "idle"
    assert len(first["demo_states"]) == len(first["demo"]) + 1
    assert set(first["poses"]) >= {"a", "b", "c", "d"}
    assert first["poses"]["a"].shape == (7,) and first["poses"]["a"].dtype == np.float64
    np.testing.assert_allclose(first["poses"]["a"][:3], [0.4, -0.25, 0.03], atol=1e-9)
    (arm,) = first["joints"]
    assert first["joints"][arm].shape == (7,)
    f = run_to_end(s)
    assert s.done and s.success, f["status"]["message"]
    assert f["status"]["kind"] == "done"
    for g in TOWER:
        assert g in f["facts"], f["facts"]
    # The tower stands: each block one block height (0.06 m) above the one below, same x, y.
    z = {n: f["poses"][n] for n in "abcd"}
    for top, below in [("a", "b"), ("b", "c"), ("c", "d")]:
        assert abs(z[top][2] - z[below][2] - 0.06) < 0.01
        assert np.linalg.norm(z[top][:2] - z[below][:2]) < 0.01
    # The joints moved from the ready posture, and the log says the same as the frame.
    assert not np.allclose(f["joints"][arm], first["joints"][arm])
    log = json.loads(s.episode_json())
    assert log["result"]["success"] is True
    assert sorted(log["final_facts"]) == f["facts"]
    # The executed actions replay on the PDDL task to its goal.
    domain = (DOMAINS / "b1-tower" / "domain.pddl").read_text()
    problem = (DOMAINS / "b1-tower" / "problem.pddl").read_text()
    executed = [a["action"] for a in log["actions"] if a["outcome"] == "done"]
    assert logic_lfd.validate(domain, problem, executed).valid, executed


def test_l3_changes_the_facts_and_the_episode_still_finishes() -> None:
    s = Session("b1", seed=2)
    f = s.step(3.0)
    assert not s.done
    before = f["facts"]
    replans = f["replans"]
    inj = s.inject("L3")
    assert inj is not None and inj["level"] == "l3" and inj["description"]
    after = s.frame()["facts"]
    assert after != before
    end = run_to_end(s)
    assert s.success, end["status"]["message"]
    assert end["replans"] > replans
    for g in TOWER:
        assert g in end["facts"]
    events = json.loads(s.episode_json())["events"]
    assert [e["level"] for e in events if e["event"] == "inject"] == ["l3"], events


def test_inject_takes_the_page_words_and_refuses_unknown_levels() -> None:
    s = Session("b1", seed=4)
    assert s.can_inject("scramble") is None
    inj = s.inject("new-block")
    assert inj is not None and inj["level"] == "l4"
    with pytest.raises(OptionError) as e:
        s.inject("l9")
    assert e.value.option == "level" and "l9" in e.value.message
    with pytest.raises(OptionError):
        s.can_inject("shake")


def test_drag_moves_a_block_and_the_frame_shows_it() -> None:
    s = Session("b1", seed=1)
    out = s.drag("a", (0.55, 0.26, 0.12))
    assert out["body"] == "a" and out["support"] == "d"
    f = s.frame()
    np.testing.assert_allclose(f["poses"]["a"][:3], [0.55, 0.26, 0.09], atol=1e-6)
    np.testing.assert_allclose(f["poses"]["a"][:3], out["to"], atol=1e-12)
    assert "(on a d)" in f["facts"]
    # A refused drag raises and leaves the world as it was.
    with pytest.raises(DragRefused) as r:
        s.drag("a", [5.0, 5.0, 0.03])
    assert r.value.body == "a" and "nothing is under it" in r.value.reason
    with pytest.raises(DragRefused) as r:
        s.drag("no-such-block", [0.3, 0.0, 0.03])
    assert r.value.body == "no-such-block"
    with pytest.raises(DragRefused) as r:
        s.drag("table", [0.3, 0.0, 0.03])
    assert r.value.body == "table" and "fixed" in r.value.reason
    with pytest.raises(OptionError) as e:
        s.drag("b", [0.3, 0.0, 0.03, 1.0])
    assert e.value.option == "to" and "yaw" in e.value.message
    np.testing.assert_allclose(s.frame()["poses"]["a"], f["poses"]["a"])
    # The drag is in the log, with its tick.
    events = json.loads(s.episode_json())["events"]
    assert [e["body"] for e in events if e["event"] == "perturb"] == ["a"]


def test_reset_restarts_from_the_initial_scene() -> None:
    s = Session("b1", seed=1)
    start = s.frame()["poses"]
    s.drag("c", (0.3, 0.1, 0.03))
    s.step(2.0)
    held = [a["holding"] for a in s.frame()["world"]["arms"] if a["holding"]]
    assert held, "no block held 2 s in"
    with pytest.raises(DragRefused) as r:
        s.drag(held[0], (0.3, -0.1, 0.03))
    assert r.value.body == held[0] and "held" in r.value.reason
    s.reset(seed=5)
    assert s.tick == 0 and s.seed == 5 and not s.done
    for name, pose in start.items():
        np.testing.assert_allclose(s.frame()["poses"][name], pose)


def test_bad_options_and_folders_raise_with_fields(tmp_path: Path) -> None:
    missing = tmp_path / "nope"
    with pytest.raises(LoadError) as e:
        Session(folder=missing)
    assert e.value.path == str(missing)
    partial = tmp_path / "partial"
    shutil.copytree(DOMAINS / "b1-tower", partial)
    (partial / "scene.json").unlink()
    with pytest.raises(LoadError) as e:
        Session(folder=partial)
    assert e.value.path == f"{partial}/scene.json"
    broken = tmp_path / "broken"
    shutil.copytree(DOMAINS / "b1-tower", broken)
    (broken / "scene.json").write_text("{")
    with pytest.raises(LoadError) as e:
        Session(folder=broken)
    assert e.value.path == f"{broken}/scene.json"
    with pytest.raises(OptionError) as o:
        Session("b9")
    assert o.value.option == "benchmark"
    with pytest.raises(OptionError) as o:
        Session(method="magic")
    assert o.value.option == "method"
    with pytest.raises(OptionError) as o:
        Session("b1", folder=DOMAINS / "b1-tower")
    assert o.value.option == "benchmark"
    with pytest.raises(OptionError) as o:
        Session().step(-1.0)
    assert o.value.option == "dt"


def test_folders_without_a_demonstration_or_a_scene(tmp_path: Path) -> None:
    # No demo.json: the demonstration is recorded from expert.json.
    expert = tmp_path / "expert-only"
    shutil.copytree(DOMAINS / "b1-tower", expert)
    (expert / "demo.json").unlink()
    s = Session(folder=expert, seed=1)
    assert s.frame()["demo"] == Session("b1", seed=1).frame()["demo"]
    assert s.run()["status"]["kind"] == "done"
    # A PDDL-only task (no motions, no scene) is no robot task.
    with pytest.raises(LoadError) as e:
        Session(folder=DOMAINS / "kitchen")
    assert e.value.path == f"{DOMAINS / 'kitchen'}/motions.json"


def test_a_folder_runs_its_own_task() -> None:
    s = Session(folder=DOMAINS / "b1-tower", seed=1)
    bench = Session("b1", seed=1)
    assert s.frame()["demo"] == bench.frame()["demo"]
    log = json.loads(s.episode_json())
    assert log["folder"]["dir"] == str(DOMAINS / "b1-tower")
    assert "domains" in repr(s)


def canonical(report: dict[str, Any]) -> dict[str, Any]:
    """`report` with its wall-clock times zeroed (as `run_episode(canonical=True)` writes them)."""
    report["planning_ms"] = [0.0 for _ in report["planning_ms"]]
    for r in report["log"]["replans"]:
        r["time_ms"] = 0.0
        r["bind_ms"] = 0.0
    return report


def test_run_episode_equals_the_cli_report() -> None:
    got = run_episode("b1", level="l3", seed=3, canonical=True)
    want = canonical(
        json.loads(cli("run", "--benchmark", "b1", "--level", "l3", "--seed", "3", "--json"))
    )
    assert sorted(got) == sorted(want)
    for key in want:
        assert got[key] == want[key], key
    assert got["success"] is True and got["injection"]["level"] == "l3"
    # The same episode twice gives the same report; wall-clock fields are the only difference.
    again = run_episode(level="scramble", seed=3)
    assert canonical(again) == got


def test_run_episode_options() -> None:
    with pytest.raises(OptionError) as o:
        run_episode(level="l7")
    assert o.value.option == "level"
    with pytest.raises(LoadError):
        run_episode(folder="/nonexistent/task")


def test_episode_json_replays_exactly_on_the_cli(tmp_path: Path) -> None:
    s = Session("b1", seed=2)
    s.step(1.0)
    s.drag("d", (0.3, 0.2, 0.03))
    s.step(2.0)
    # Refused now: `None`, with the reason `can_inject` gives, and nothing logged.
    reason = s.can_inject("set-back")
    assert reason is not None and reason.startswith("L2:")
    assert s.inject("set-back") is None
    assert s.inject("scramble") is not None
    s.run()
    assert s.success
    path = tmp_path / "episode.json"
    path.write_text(s.episode_json())
    log = json.loads(s.episode_json())
    assert [e["level"] for e in log["events"] if e["event"] == "inject"] == ["l3"]
    out = cli("run", "--replay", str(path))
    assert out.startswith("replayed exactly:"), out
    # The final scene starts another episode in the same facts.
    again = Session(scene=s.scene_json())
    assert again.frame()["facts"] == s.frame()["facts"]


def test_robots_and_generated_tasks() -> None:
    s = Session("b1", seed=1, robot="ur5")
    f = s.run()
    assert s.success, f["status"]["message"]
    assert f["world"]["arms"][0]["robot"] == "ur5"
    assert [j.shape for j in f["joints"].values()] == [(6,)]
    five = Session("b1", seed=1, blocks=5)
    f = five.run()
    assert five.success, f["status"]["message"]
    assert sum(b["kind"] == "block" for b in f["world"]["bodies"]) == 5
    with pytest.raises(LoadError) as e:
        Session(robot="/nonexistent/robot.json")
    assert e.value.path == "/nonexistent/robot.json"


def test_run_episode_on_a_folder_equals_the_cli() -> None:
    folder = DOMAINS / "b1-tower"
    got = run_episode(folder=folder, level="l4", seed=5, canonical=True)
    want = canonical(
        json.loads(cli("run", "--domain", str(folder), "--level", "l4", "--seed", "5", "--json"))
    )
    assert got == want
    assert got["log"]["folder"]["dir"] == str(folder)
