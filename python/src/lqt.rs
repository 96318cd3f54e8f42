//! `lqt`: one LQT-CP solve (the paper's eqs. 1–4) on a case of `docs/formats.md`, as
//! `logic-lfd lqt CASE.json` and the npm package's `lqt(case)`, its arrays as numpy arrays.

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde_json::{Map, Number, Value};

use logic_lfd::lqt::{run_case, CaseInput, LqtError};

use crate::errors::{load_error, option_error, LogicLfdError};
use crate::task::{array, path_arg, to_py};

/// Keys of the output whose values are matrices (lists of rows), returned as numpy arrays.
const ARRAYS: [&str; 7] = ["A", "B", "phi", "w", "u", "x", "pos"];
/// Keys of the output's `feedback` that are arrays.
const FEEDBACK_ARRAYS: [&str; 2] = ["F", "gains"];
/// Keys of a feedback rollout (`nominal`, `perturbed`) that are arrays.
const ROLLOUT_ARRAYS: [&str; 3] = ["x", "u", "pos"];

/// A Python value as JSON: dicts, lists, tuples, numbers, strings, booleans and `None`;
/// anything with `tolist()` (numpy arrays and scalars) through it. `at` is the key path.
fn json_of(v: &Bound<'_, PyAny>, at: &str) -> PyResult<Value> {
    let py = v.py();
    let bad = |what: &str| option_error(py, if at.is_empty() { "case" } else { at }, what);
    if v.is_none() {
        return Ok(Value::Null);
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(Value::Bool(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return match (v.extract::<i64>(), v.extract::<u64>()) {
            (Ok(i), _) => Ok(Value::from(i)),
            (_, Ok(u)) => Ok(Value::from(u)),
            _ => Err(bad("an integer out of range")),
        };
    }
    if v.is_instance_of::<PyFloat>() {
        let f: f64 = v.extract()?;
        return Number::from_f64(f)
            .map(Value::Number)
            .ok_or_else(|| bad(&format!("expected a finite number, got {f}")));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(Value::String(v.extract()?));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut m = Map::new();
        for (k, x) in d.iter() {
            let key: String = k.extract().map_err(|_| bad("keys must be strings"))?;
            let path = if at.is_empty() {
                key.clone()
            } else {
                format!("{at}.{key}")
            };
            m.insert(key, json_of(&x, &path)?);
        }
        return Ok(Value::Object(m));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items: Vec<Bound<'_, PyAny>> = v.try_iter()?.collect::<PyResult<_>>()?;
        return items
            .iter()
            .enumerate()
            .map(|(i, x)| json_of(x, &format!("{at}[{i}]")))
            .collect::<PyResult<Vec<_>>>()
            .map(Value::Array);
    }
    if v.hasattr("tolist")? {
        return json_of(&v.call_method0("tolist")?, at);
    }
    Err(bad(&format!(
        "expected JSON data (dict, list, number, string), got {}",
        v.get_type()
            .name()
            .map_or("an object".into(), |n| n.to_string())
    )))
}

/// The case argument parsed: a dict (numpy arrays allowed inside), JSON text, or the path of a
/// case file (`os.PathLike`).
fn case_input(case: &Bound<'_, PyAny>) -> PyResult<CaseInput> {
    let py = case.py();
    if let Ok(text) = case.extract::<String>() {
        return CaseInput::from_json_str(&text).map_err(|e| lqt_error(py, "", &e));
    }
    if case.is_instance_of::<PyDict>() {
        let v = json_of(case, "")?;
        return CaseInput::from_value(&v).map_err(|e| lqt_error(py, "", &e));
    }
    if case.hasattr("__fspath__")? {
        let path = path_arg("case", case)?;
        let file = path.display().to_string();
        let text = std::fs::read_to_string(&path)
            .map_err(|e| load_error(py, &file, &format!("cannot read: {e}")))?;
        return CaseInput::from_json_str(&text).map_err(|e| lqt_error(py, &file, &e));
    }
    Err(pyo3::exceptions::PyTypeError::new_err(format!(
        "case must be a dict, a JSON string or a path, got {}",
        case.get_type()
            .name()
            .map_or("an object".into(), |n| n.to_string())
    )))
}

/// An LQT error: a bad key as `OptionError` naming it (`.option` 'reference.mu'), bad JSON as
/// `OptionError` 'case' (or `LoadError` for a file), a numerical failure as `LogicLfdError`.
fn lqt_error(py: Python<'_>, file: &str, e: &LqtError) -> PyErr {
    match e {
        LqtError::Input { key, message } => option_error(py, key, message),
        LqtError::Json { .. } if !file.is_empty() => load_error(py, file, &e.to_string()),
        LqtError::Json { .. } => option_error(py, "case", &format!("bad JSON at {e}")),
        LqtError::Singular(_) | LqtError::NonFinite(_) => LogicLfdError::new_err(e.to_string()),
    }
}

/// Replaces the entries `keys` of dict `d` (those present) by float64 numpy arrays.
fn arrays(d: &Bound<'_, PyAny>, keys: &[&str]) -> PyResult<()> {
    for k in keys {
        if let Ok(v) = d.get_item(k) {
            d.set_item(k, array(&v)?)?;
        }
    }
    Ok(())
}

/// Solves one LQT-CP case (the contract of `docs/formats.md`, as `logic-lfd lqt CASE.json` and
/// the npm package's `lqt`).
///
/// `case` is the case as a dict (numpy arrays allowed inside), its JSON text, or the path of a
/// case file. With T = n_steps, N = T - 1, D = dim, nx = D * order and K = basis.n_fct, the
/// result is a dict of float64 numpy arrays `A` (nx, nx), `B` (nx, D), `phi` (N, K), `w` (K, D),
/// `u` (N, D), `x` (T, nx, with x[0] = x0), `pos` (T, D); `cost` (float); `target_errors`
/// (one dict per input target: `t`, `role`, `pos_dist`, `vel_dist`); and, when the case has a
/// `feedback` object, `feedback`: `F` (N*D, nx+1), `gains` (N, D, nx+1), `nominal` and
/// `perturbed` rollouts (`x` (T, nx), `u` (N, D), `pos` (T, D), `final_goal_pos_dist`).
///
/// Raises `OptionError` naming the key of a malformed case (`.option` 'reference.mu'),
/// `LoadError` for a case file that cannot be read, `LogicLfdError` for a singular system.
/// Releases the GIL.
#[pyfunction]
pub(crate) fn lqt<'py>(py: Python<'py>, case: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let input = case_input(case)?;
    let out = py
        .detach(|| run_case(&input))
        .map_err(|e| lqt_error(py, "", &e))?;
    let d = to_py(py, &out)?;
    arrays(&d, &ARRAYS)?;
    if let Ok(fb) = d.get_item("feedback") {
        arrays(&fb, &FEEDBACK_ARRAYS)?;
        for rollout in ["nominal", "perturbed"] {
            if let Ok(r) = fb.get_item(rollout) {
                arrays(&r, &ROLLOUT_ARRAYS)?;
            }
        }
    }
    Ok(d)
}

/// Adds `lqt` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(lqt, m)?)?;
    Ok(())
}
