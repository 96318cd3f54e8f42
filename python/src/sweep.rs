//! Sweeps from Python: the soak and Tables I and II as lists of independent items, run in any
//! process (`_sweep_run`) and joined by the parent (`_sweep_report`) into the report the CLI
//! prints with `--json`. `logic_lfd.sweep` spreads the items over a `concurrent.futures`
//! executor; every item is seeded from the sweep's seed and its index alone, so the report does
//! not depend on where or in which order the items ran.

use std::path::Path;
use std::sync::Arc;

use pyo3::prelude::*;
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::{json, Map, Value};

use logic_lfd::experiments::{SoakParams, SoakRunner, Table1Sweep, Table2Sweep};
use logic_lfd::lfd::SessionParams;
use logic_lfd::sim::{ArmModel, TaskFolder};

use crate::clock::WallClock;
use crate::errors::{load_error, option_error, LogicLfdError};

/// A sweep ready to run items.
enum Sweep {
    Soak(Box<SoakRunner>),
    Table1(Table1Sweep),
    Table2(Table2Sweep),
}

/// A failure to build a sweep, kept as data so it crosses `detach`.
enum SpecError {
    Option(&'static str, String),
    Load(String, String),
}

impl SpecError {
    fn into_py(self, py: Python<'_>) -> PyErr {
        match self {
            SpecError::Option(o, m) => option_error(py, o, &m),
            SpecError::Load(p, m) => load_error(py, &p, &m),
        }
    }
}

/// The keys each command takes besides `command`, `robot` and (soak) `folder`.
const SOAK_KEYS: [&str; 6] = [
    "episodes",
    "seed",
    "max_disturbances",
    "first_episode",
    "check_replay",
    "blocks",
];
const TABLE1_KEYS: [&str; 4] = ["tasks", "seed", "benchmarks", "tamp_fallback"];
const TABLE2_KEYS: [&str; 4] = ["trials", "seed", "benchmarks", "tamp_fallback"];

/// `base` with the spec's `keys` laid over it, read as `T`.
fn overlay<T: DeserializeOwned>(
    mut base: Map<String, Value>,
    spec: &Map<String, Value>,
    keys: &[&str],
) -> Result<T, SpecError> {
    for &k in keys {
        if let Some(v) = spec.get(k).filter(|v| !v.is_null()) {
            let v = match (k, v) {
                // `"b1,b2"` as the CLI takes it, or a list.
                ("benchmarks", Value::String(s)) => {
                    json!(s.split(',').map(str::trim).collect::<Vec<_>>())
                }
                _ => v.clone(),
            };
            base.insert(k.to_string(), v);
        }
    }
    serde_json::from_value(Value::Object(base))
        .map_err(|e| SpecError::Option("spec", e.to_string()))
}

/// The arms of `robot` (a name or a robot file, or a list of them: one per arm).
fn robots(spec: &Map<String, Value>) -> Result<Vec<Arc<ArmModel>>, SpecError> {
    let names: Vec<String> = match spec.get("robot") {
        None | Some(Value::Null) => vec![],
        Some(Value::String(s)) => vec![s.clone()],
        Some(v) => serde_json::from_value(v.clone()).map_err(|_| {
            SpecError::Option(
                "robot",
                "expected a robot's name or file, or a list of them".into(),
            )
        })?,
    };
    names
        .iter()
        .map(|n| ArmModel::load(Path::new(n)).map_err(|e| SpecError::Load(e.at, e.message)))
        .collect()
}

/// The sweep a spec (JSON object) describes, with the CLI's defaults for what it leaves out.
fn sweep_of(spec: &str) -> Result<Sweep, SpecError> {
    let spec: Map<String, Value> = serde_json::from_str(spec)
        .map_err(|e| SpecError::Option("spec", format!("expected a JSON object: {e}")))?;
    let command = spec
        .get("command")
        .and_then(Value::as_str)
        .unwrap_or("soak");
    let (keys, extra): (&[&str], &[&str]) = match command {
        "soak" => (&SOAK_KEYS, &["folder"]),
        "table1" => (&TABLE1_KEYS, &[]),
        "table2" => (&TABLE2_KEYS, &[]),
        other => {
            return Err(SpecError::Option(
                "command",
                format!("unknown sweep `{other}` (expected soak|table1|table2)"),
            ))
        }
    };
    if let Some(k) = spec.keys().find(|k| {
        !(["command", "robot"].contains(&k.as_str())
            || keys.contains(&k.as_str())
            || extra.contains(&k.as_str()))
    }) {
        return Err(SpecError::Option(
            "spec",
            format!(
                "unknown key `{k}` for `{command}` (expected {})",
                keys.join(", ")
            ),
        ));
    }
    let robots = robots(&spec)?;
    let to_map = |v: Value| v.as_object().cloned().unwrap_or_default();
    match command {
        "soak" => {
            let defaults = serde_json::to_value(SoakParams::default()).unwrap_or_default();
            let params: SoakParams = overlay(to_map(defaults), &spec, keys)?;
            let runner = match spec.get("folder").and_then(Value::as_str) {
                Some(dir) => TaskFolder::read(Path::new(dir))
                    .map_err(|e| SpecError::Load(dir.to_string(), e.to_string()))
                    .and_then(|f| {
                        SoakRunner::in_folder(&params, &f)
                            .map_err(|e| SpecError::Load(dir.to_string(), e))
                    })?,
                None => SoakRunner::new(&params).map_err(|e| SpecError::Option("spec", e))?,
            };
            Ok(Sweep::Soak(Box::new(runner.with_robots(robots))))
        }
        "table1" => {
            let base = json!({"benchmarks": ["b1", "b2", "b3"], "tasks": 100, "seed": 1,
                "tamp_fallback": false});
            let mut s: Table1Sweep = overlay(to_map(base), &spec, keys)?;
            s.robots = robots;
            Ok(Sweep::Table1(s))
        }
        _ => {
            let base = json!({"benchmarks": ["b1", "b2", "b3"], "trials": 10, "seed": 1,
                "tamp_fallback": false});
            let mut s: Table2Sweep = overlay(to_map(base), &spec, keys)?;
            s.robots = robots;
            Ok(Sweep::Table2(s))
        }
    }
}

impl Sweep {
    fn items(&self) -> usize {
        match self {
            Sweep::Soak(r) => r.params().episodes,
            Sweep::Table1(s) => s.items(),
            Sweep::Table2(s) => s.items(),
        }
    }

    /// Item `i`'s record as JSON, as a shard file holds it.
    fn run(&self, i: usize, clock: &WallClock) -> Result<Value, String> {
        fn value<T: Serialize>(r: Result<T, impl ToString>) -> Result<Value, String> {
            r.map_err(|e| e.to_string())
                .and_then(|t| serde_json::to_value(t).map_err(|e| e.to_string()))
        }
        let mut quiet = |_: &str| {};
        match self {
            Sweep::Soak(r) => value(r.episode(i).map(|(ep, _)| ep)),
            Sweep::Table1(s) => value(s.run(i, SessionParams::default(), clock, &mut quiet)),
            Sweep::Table2(s) => value(s.run(i, SessionParams::default(), clock, &mut quiet)),
        }
    }

    /// The report of every item's record, in item order: the CLI's `--json`, and markdown for
    /// the tables.
    fn report(&self, records: Vec<Value>) -> Result<(String, String), String> {
        fn typed<T: DeserializeOwned>(records: Vec<Value>) -> Result<Vec<T>, String> {
            records
                .into_iter()
                .enumerate()
                .map(|(i, v)| serde_json::from_value(v).map_err(|e| format!("item {i}: {e}")))
                .collect()
        }
        let json = |r: serde_json::Result<String>| r.map_err(|e| e.to_string());
        match self {
            Sweep::Soak(r) => {
                let report = r.params().report(typed(records)?);
                Ok((json(serde_json::to_string_pretty(&report))?, String::new()))
            }
            Sweep::Table1(s) => {
                let t = s.report(typed(records)?);
                Ok((json(serde_json::to_string(&t))?, t.markdown()))
            }
            Sweep::Table2(s) => {
                let t = s.report(typed(records)?);
                Ok((json(serde_json::to_string(&t))?, t.markdown()))
            }
        }
    }
}

/// The number of items of the sweep `spec` (a JSON object) describes.
#[pyfunction]
fn _sweep_items(py: Python<'_>, spec: &str) -> PyResult<usize> {
    py.detach(|| sweep_of(spec).map(|s| s.items()))
        .map_err(|e| e.into_py(py))
}

/// The records of items `indices` of the sweep `spec`, as one JSON array (in `indices`' order).
#[pyfunction]
fn _sweep_run(py: Python<'_>, spec: &str, indices: Vec<usize>) -> PyResult<String> {
    let out = py.detach(|| {
        let sweep = sweep_of(spec).map_err(Err)?;
        let n = sweep.items();
        let clock = WallClock::start();
        let mut records = Vec::with_capacity(indices.len());
        for &i in &indices {
            if i >= n {
                return Err(Ok(format!("item {i} of a sweep of {n} items")));
            }
            records.push(
                sweep
                    .run(i, &clock)
                    .map_err(|e| Ok(format!("item {i}: {e}")))?,
            );
        }
        serde_json::to_string(&records).map_err(|e| Ok(e.to_string()))
    });
    out.map_err(|e| match e {
        Err(spec) => spec.into_py(py),
        Ok(m) => LogicLfdError::new_err(m),
    })
}

/// The report of the sweep `spec` from the records of all its items (JSON arrays as
/// `_sweep_run` gives them, concatenated in item order): `(report JSON, markdown)`.
#[pyfunction]
fn _sweep_report(py: Python<'_>, spec: &str, records: Vec<String>) -> PyResult<(String, String)> {
    let out = py.detach(|| {
        let sweep = sweep_of(spec).map_err(Err)?;
        let mut all = Vec::new();
        for r in &records {
            let part: Vec<Value> = serde_json::from_str(r).map_err(|e| Ok(e.to_string()))?;
            all.extend(part);
        }
        if all.len() != sweep.items() {
            return Err(Ok(format!(
                "{} records for a sweep of {} items",
                all.len(),
                sweep.items()
            )));
        }
        sweep.report(all).map_err(Ok)
    });
    out.map_err(|e| match e {
        Err(spec) => spec.into_py(py),
        Ok(m) => LogicLfdError::new_err(m),
    })
}

/// Adds the sweep functions to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_sweep_items, m)?)?;
    m.add_function(wrap_pyfunction!(_sweep_run, m)?)?;
    m.add_function(wrap_pyfunction!(_sweep_report, m)?)?;
    Ok(())
}
