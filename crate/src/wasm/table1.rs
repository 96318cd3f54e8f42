//! Table I in parts, for a pool of workers: `table1Task` runs one item of the sweep exactly as
//! `logic-lfd bench table1` does, `table1Report` joins the items into the Table I that
//! `bench table1 --json` prints (plus per-level tables, Wilson intervals and failure groups), and
//! `table1Episode` re-runs one method of one item with its log, for `Session.replay`.

use super::args::{number_arg, string_arg};
use super::convert::{js_err, PerformanceClock};
use crate::experiments::{failure_group, wilson, Table1, Table1Sweep, Table1Task};
use crate::lfd::{Level, SessionParams};
use crate::sim::Benchmark;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use wasm_bindgen::prelude::*;

/// The sweep as `bench table1`'s flags give it, and the episodes' budgets.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "camelCase")]
struct SweepOptions {
    /// `b1`, `b2`, `b3`, in row order.
    benchmarks: Vec<String>,
    /// Tasks per benchmark.
    tasks: usize,
    /// Seed of the task generator and the episodes.
    seed: u64,
    /// Logic-LfD's TAMP fallback (`--tamp-fallback`; off by default).
    #[serde(default)]
    tamp_fallback: bool,
    /// States a search may expand (default: the core's, as the CLI).
    #[serde(default)]
    max_nodes: Option<u64>,
    /// Simulated seconds after which an episode fails (default: the core's, as the CLI).
    #[serde(default)]
    max_time_s: Option<f64>,
}

fn sweep_of(options_json: &str) -> Result<(Table1Sweep, SessionParams), JsError> {
    let o: SweepOptions =
        serde_json::from_str(options_json).map_err(|e| js_err(format!("options: {e}")))?;
    let benchmarks = o
        .benchmarks
        .iter()
        .map(|n| {
            Benchmark::parse(n).ok_or_else(|| js_err(format!("options: unknown benchmark {n:?}")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if benchmarks.is_empty() || o.tasks == 0 {
        return Err(js_err("options: no benchmark or no task"));
    }
    let mut params = SessionParams::default();
    if let Some(n) = o.max_nodes {
        params.control.search.max_nodes = Some(n);
    }
    if let Some(t) = o.max_time_s {
        params.max_time = t;
    }
    let sweep = Table1Sweep {
        benchmarks,
        tasks: o.tasks,
        seed: o.seed,
        tamp_fallback: o.tamp_fallback,
        robots: vec![],
    };
    Ok((sweep, params))
}

fn index_arg(func: &str, param: &str, v: &JsValue, below: usize) -> Result<usize, JsValue> {
    let x = number_arg(func, param, v)?;
    if x < 0.0 || x.fract() != 0.0 || x >= below as f64 {
        return Err(js_err(format!(
            "{func}: {param} must be a whole number below {below}"
        ))
        .into());
    }
    Ok(x as usize)
}

/// Runs item `index` of the sweep `optionsJson` (`{"benchmarks":["b1"],"tasks":50,"seed":1}`,
/// optionally `tampFallback`, `maxNodes`, `maxTimeS`) and returns the item's JSON (a
/// `Table1Task`: its draw and one run per method of Table I).
#[wasm_bindgen(js_name = table1Task)]
pub fn table1_task(
    #[wasm_bindgen(js_name = "optionsJson", unchecked_param_type = "string")] options_json: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number")] index: JsValue,
) -> Result<String, JsValue> {
    let (sweep, params) = sweep_of(&string_arg("table1Task", "optionsJson", &options_json)?)?;
    let index = index_arg("table1Task", "index", &index, sweep.items())?;
    let task = sweep
        .run(index, params, &PerformanceClock, &mut |_| {})
        .map_err(js_err)?;
    Ok(serde_json::to_string(&task).map_err(js_err)?)
}

/// Table I with what the page shows beside it.
#[derive(Serialize)]
struct Report {
    /// What `bench table1 --json` prints for the same sweep.
    table: Table1,
    /// The 95 % Wilson interval of each cell's success rate.
    intervals: Vec<(f64, f64)>,
    /// Table I of each level's tasks alone.
    levels: Vec<LevelReport>,
    /// The group (`logic`, `motion`, `budget`) of each failure kind seen.
    groups: BTreeMap<String, &'static str>,
}

/// Table I of one level's tasks.
#[derive(Serialize)]
struct LevelReport {
    level: Level,
    /// The items (tasks) at this level, by item index.
    items: Vec<usize>,
    table: Table1,
    intervals: Vec<(f64, f64)>,
}

fn intervals(t: &Table1) -> Vec<(f64, f64)> {
    t.cells
        .iter()
        .map(|c| wilson(c.successes, c.tasks))
        .collect()
}

/// Joins the items of the sweep `optionsJson` (`itemsJson`: every item's JSON from
/// `table1Task`, in item order) into `{table, intervals, levels, groups}`: `table` is the Table I
/// of `logic-lfd bench table1 --json`.
#[wasm_bindgen(js_name = table1Report)]
pub fn table1_report(
    #[wasm_bindgen(js_name = "optionsJson", unchecked_param_type = "string")] options_json: JsValue,
    #[wasm_bindgen(js_name = "itemsJson", unchecked_param_type = "string")] items_json: JsValue,
) -> Result<String, JsValue> {
    let (sweep, _) = sweep_of(&string_arg("table1Report", "optionsJson", &options_json)?)?;
    let items: Vec<Table1Task> =
        serde_json::from_str(&string_arg("table1Report", "itemsJson", &items_json)?)
            .map_err(|e| js_err(format!("items: {e}")))?;
    if items.len() != sweep.items() {
        return Err(js_err(format!(
            "items: {} given, the sweep has {}",
            items.len(),
            sweep.items()
        ))
        .into());
    }
    let table = sweep.report(items.clone());
    let groups = table
        .cells
        .iter()
        .flat_map(|c| c.failures.iter())
        .map(|(k, _)| (k.clone(), failure_group(k)))
        .collect();
    let levels = Level::ALL
        .iter()
        .filter(|&&l| (0..sweep.items()).any(|i| sweep.level(i) == l))
        .map(|&level| {
            let table = sweep.report_level(items.clone(), level);
            LevelReport {
                level,
                items: (0..sweep.items())
                    .filter(|&i| sweep.level(i) == level)
                    .collect(),
                intervals: intervals(&table),
                table,
            }
        })
        .collect();
    let report = Report {
        intervals: intervals(&table),
        table,
        levels,
        groups,
    };
    Ok(serde_json::to_string(&report).map_err(js_err)?)
}

/// Re-runs method `run` (0..4, Table I's order) of item `index` of the sweep `optionsJson` as
/// `table1Task` runs it and returns its episode log JSON (for `Session.replay`).
#[wasm_bindgen(js_name = table1Episode)]
pub fn table1_episode(
    #[wasm_bindgen(js_name = "optionsJson", unchecked_param_type = "string")] options_json: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number")] index: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number")] run: JsValue,
) -> Result<String, JsValue> {
    let (sweep, params) = sweep_of(&string_arg("table1Episode", "optionsJson", &options_json)?)?;
    let index = index_arg("table1Episode", "index", &index, sweep.items())?;
    let run = index_arg("table1Episode", "run", &run, 4)?;
    let report = sweep
        .episode(index, run, params, &PerformanceClock)
        .map_err(js_err)?;
    Ok(serde_json::to_string(&report.log).map_err(js_err)?)
}
