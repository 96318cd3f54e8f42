"""LQT-CP through `logic_lfd.lqt`: numpy arrays of the documented shapes, the contract's
invariants, errors naming the key, and the CLI's `logic-lfd lqt` output."""

from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from logic_lfd import LoadError, LogicLfdError, OptionError, lqt

from conftest import ROOT, cli

EXAMPLE = ROOT / "tests" / "data" / "lqt" / "lqt-cp-example.json"

# The 1-D example of docs/formats.md, with a nominal rollout from x0 and a perturbed one.
DOCS_CASE: dict[str, Any] = {
    "dim": 1,
    "order": 2,
    "dt": 0.1,
    "n_steps": 5,
    "r": 0.01,
    "basis": {"type": "bernstein", "n_fct": 3},
    "x0": [0.0, 0.0],
    "reference": {
        "mu": [[0, 0], [0, 0], [0.5, 0], [0, 0], [1, 0]],
        "q_diag": [[0, 0], [0, 0], [100, 0], [0, 0], [1000, 1000]],
    },
    "targets": [
        {"t": 2, "role": "via", "pos": [0.5], "w_pos": 100},
        {"t": 4, "role": "goal", "pos": [1.0], "w_pos": 1000, "vel": [0.0], "w_vel": 1000},
    ],
    "tracking": None,
    "feedback": {"x_init": [0.0, 0.0], "perturbation": {"after_step": 1, "delta": [0.05, 0.0]}},
}


def example() -> dict[str, Any]:
    case: dict[str, Any] = json.loads(EXAMPLE.read_text())
    return case


def test_arrays_have_the_documented_shapes() -> None:
    case = example()
    out = lqt(case)
    t, d, order, k = case["n_steps"], case["dim"], case["order"], case["basis"]["n_fct"]
    n, nx = t - 1, d * order
    shapes = {
        "A": (nx, nx),
        "B": (nx, d),
        "phi": (n, k),
        "w": (k, d),
        "u": (n, d),
        "x": (t, nx),
        "pos": (t, d),
    }
    for key, shape in shapes.items():
        assert isinstance(out[key], np.ndarray) and out[key].dtype == np.float64, key
        assert out[key].shape == shape, key
    assert isinstance(out["cost"], float) and out["cost"] > 0
    assert out["feedback"]["F"].shape == (n * d, nx + 1)
    assert out["feedback"]["gains"].shape == (n, d, nx + 1)
    no_feedback = example()
    del no_feedback["feedback"]
    assert "feedback" not in lqt(no_feedback)
    # The first state is the initial state given; positions are the state's first D columns.
    np.testing.assert_array_equal(out["x"][0], case["x0"])
    np.testing.assert_array_equal(out["pos"], out["x"][:, :d])
    # The states follow the dynamics x_{t+1} = A x_t + B u_t.
    np.testing.assert_allclose(
        out["x"][1:], out["x"][:-1] @ out["A"].T + out["u"] @ out["B"].T, atol=1e-9
    )
    # u = phi w (control primitives).
    np.testing.assert_allclose(out["u"], out["phi"] @ out["w"], atol=1e-9)
    # The targets are reached to the reported distances.
    for tg, err in zip(case["targets"], out["target_errors"]):
        assert err["t"] == tg["t"] and err["role"] == tg["role"]
        assert np.linalg.norm(out["pos"][tg["t"]] - tg["pos"]) == pytest.approx(
            err["pos_dist"], abs=1e-12
        )
    assert out["target_errors"][-1]["pos_dist"] < 0.05


def test_feedback_gains_and_rollouts() -> None:
    out = lqt(DOCS_CASE)
    t, d, nx = 5, 1, 2
    n = t - 1
    fb = out["feedback"]
    assert fb["F"].shape == (n * d, nx + 1)
    assert fb["gains"].shape == (n, d, nx + 1)
    for name in ("nominal", "perturbed"):
        r = fb[name]
        assert (r["x"].shape, r["u"].shape, r["pos"].shape) == ((t, nx), (n, d), (t, d)), name
    # x_init == x0: the nominal rollout is the batch solution.
    np.testing.assert_allclose(fb["nominal"]["x"], out["x"], atol=1e-9)
    np.testing.assert_allclose(fb["nominal"]["u"], out["u"], atol=1e-9)
    # The documented numbers.
    np.testing.assert_allclose(out["pos"][:, 0], [0, 0.148, 0.492, 0.834, 0.981], atol=1e-3)
    assert out["cost"] == pytest.approx(19.6, abs=0.05)
    # The perturbed rollout starts like the nominal one and is pushed at step 2.
    np.testing.assert_allclose(fb["perturbed"]["x"][:2], fb["nominal"]["x"][:2])
    assert fb["perturbed"]["final_goal_pos_dist"] == pytest.approx(0.011, abs=1e-3)


def test_text_path_and_numpy_inputs_give_the_same_result() -> None:
    by_dict = lqt(example())
    by_text = lqt(EXAMPLE.read_text())
    by_path = lqt(EXAMPLE)
    case = example()
    case["reference"]["mu"] = np.asarray(case["reference"]["mu"])
    case["x0"] = np.zeros(4)
    by_numpy = lqt(case)
    for other in (by_text, by_path, by_numpy):
        for key in ("x", "u", "w", "pos"):
            np.testing.assert_array_equal(other[key], by_dict[key])


def test_equals_the_cli(tmp_path: Path) -> None:
    path = tmp_path / "case.json"
    path.write_text(json.dumps(DOCS_CASE))
    want = json.loads(cli("lqt", str(path)))
    got = lqt(DOCS_CASE)
    assert sorted(got) == sorted(want)
    for key in ("A", "B", "phi", "w", "u", "x", "pos"):
        np.testing.assert_array_equal(
            got[key], np.asarray(want[key], dtype=np.float64), err_msg=key
        )
    assert got["cost"] == want["cost"]
    assert got["target_errors"] == want["target_errors"]
    for key in ("F", "gains"):
        np.testing.assert_array_equal(got["feedback"][key], np.asarray(want["feedback"][key]))


def test_a_bad_case_raises_naming_the_key(tmp_path: Path) -> None:
    short = copy.deepcopy(DOCS_CASE)
    short["reference"]["mu"] = short["reference"]["mu"][:-1]
    with pytest.raises(OptionError) as e:
        lqt(short)
    assert e.value.option == "reference.mu" and "rows" in e.value.message
    missing = copy.deepcopy(DOCS_CASE)
    del missing["dt"]
    with pytest.raises(OptionError) as e:
        lqt(missing)
    assert e.value.option == "dt"
    nan = copy.deepcopy(DOCS_CASE)
    nan["x0"] = [float("nan"), 0.0]
    with pytest.raises(OptionError) as e:
        lqt(nan)
    assert e.value.option == "x0[0]"
    with pytest.raises(OptionError) as e:
        lqt("{not json")
    assert e.value.option == "case"
    with pytest.raises(LoadError) as f:
        lqt(tmp_path / "absent.json")
    assert f.value.path == str(tmp_path / "absent.json")
    with pytest.raises(TypeError):
        lqt(3)  # type: ignore[arg-type]
    assert issubclass(OptionError, LogicLfdError)
