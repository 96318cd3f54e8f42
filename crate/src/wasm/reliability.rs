//! Reliability exports: one closed-loop episode exactly as `logic-lfd run --json` prints it, so a
//! node test can check that the same seed gives byte-identical episode JSON natively and in wasm.

use super::args::string_arg;
use super::convert::{js_err, PerformanceClock};
use std::collections::BTreeMap;

use crate::experiments::{run_episode, run_episode_with, EpisodeSpec};
use crate::lfd::Level;
use crate::lfd::SessionParams;
use crate::lfd::{Listed, Method, Mode};
use crate::sim::{Benchmark, TaskFolder};
use serde::Deserialize;
use wasm_bindgen::prelude::*;

/// Options of [`run_episode_json`], the flags of `logic-lfd run` (same names, same defaults).
#[derive(Debug, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct EpisodeOptions {
    /// `b1`, `b2` or `b3` (default `b1`).
    benchmark: String,
    /// `l1`..`l4` or `none` (default `none`).
    level: String,
    /// `logic-lfd`, `linear`, `rlds` or `tamp` (default `logic-lfd`).
    method: String,
    /// `paper` or `prioritised` (default `paper`).
    mode: String,
    /// Seed of every random choice (default 0).
    seed: u64,
    /// Initial scene JSON text (default: the benchmark's template scene).
    scene: Option<String>,
    /// Zero the wall-clock planning times (the only fields that differ from run to run).
    canonical: bool,
    /// A task folder's files by name (`domain.pddl`, …) to run instead of the benchmark's task.
    folder: Option<BTreeMap<String, String>>,
    /// The folder's name in messages and in the log (default `folder`).
    dir: Option<String>,
    /// The log of a folder episode carries the folder's files (`log.folder.files`).
    #[serde(rename = "withFiles")]
    with_files: bool,
}

impl Default for EpisodeOptions {
    fn default() -> Self {
        EpisodeOptions {
            benchmark: "b1".into(),
            level: "none".into(),
            method: "logic-lfd".into(),
            mode: "paper".into(),
            seed: 0,
            scene: None,
            canonical: false,
            folder: None,
            dir: None,
            with_files: false,
        }
    }
}

fn spec_of(o: &EpisodeOptions) -> Result<EpisodeSpec, String> {
    let benchmark = Benchmark::from_id(&o.benchmark).map_err(|e| format!("benchmark: {e}"))?;
    let level = match o.level.as_str() {
        "none" => None,
        l => Some(Level::from_id(l).map_err(|e| format!("level: {e} or none"))?),
    };
    let method = Method::from_id(&o.method).map_err(|e| format!("method: {e}"))?;
    let mode = Mode::from_id(&o.mode).map_err(|e| format!("mode: {e}"))?;
    Ok(EpisodeSpec {
        benchmark,
        level,
        method,
        mode,
        seed: o.seed,
        scene: o.scene.clone(),
        robots: vec![],
    })
}

/// Runs one closed-loop episode to its end and returns the report JSON, byte for byte what
/// `logic-lfd run --benchmark … --level … --method … --mode … --seed N --json` prints (without
/// its newline).
///
/// `options_json` is a JSON object with the CLI's flags: `{"benchmark":"b1","level":"l3",
/// "method":"logic-lfd","mode":"paper","seed":7}`; all optional, unknown keys refused. With
/// `"canonical": true` the wall-clock planning times (`planning_ms`, `log.replans[].time_ms`) are
/// written as 0, so two runs anywhere give the same bytes. With `"folder": {"domain.pddl": …}` it
/// runs a task folder given by its files (`"dir"` names it in messages, `"withFiles": true` keeps
/// the files in the log for `Session.replay`). Rejects bad options, a bad scene or a folder's
/// missing or broken file with a message naming the field or the file.
#[wasm_bindgen(js_name = runEpisode)]
pub fn run_episode_json(
    #[wasm_bindgen(js_name = "optionsJson", unchecked_param_type = "string")] options_json: JsValue,
) -> Result<String, JsValue> {
    let options_json = string_arg("runEpisode", "optionsJson", &options_json)?;
    let o: EpisodeOptions =
        serde_json::from_str(&options_json).map_err(|e| js_err(format!("options: {e}")))?;
    let spec = spec_of(&o).map_err(|e| js_err(format!("options: {e}")))?;
    let mut report = match &o.folder {
        None => run_episode(&spec, SessionParams::default(), &PerformanceClock).map_err(js_err)?,
        Some(files) => {
            let folder = TaskFolder::new(o.dir.as_deref().unwrap_or("folder"), files.clone());
            let sources = folder.sources().map_err(js_err)?;
            let mut report =
                run_episode_with(&spec, &sources, SessionParams::default(), &PerformanceClock)
                    .map_err(|e| js_err(super::folder::named(&folder, e)))?;
            if o.with_files {
                if let Some(record) = report.log.folder.as_mut() {
                    record.files = Some(folder.files);
                }
            }
            report
        }
    };
    if o.canonical {
        report.planning_ms.iter_mut().for_each(|t| *t = 0.0);
        report.log = report.log.canonical();
    }
    Ok(serde_json::to_string(&report).map_err(js_err)?)
}
