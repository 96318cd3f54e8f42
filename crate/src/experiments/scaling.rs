//! Scaling study (`logic-lfd bench scaling`): B1 tower tasks with N blocks from random L3
//! initial states, per method the success rate, the first plan's time (median, p95, caller's
//! clock) and length.

pub mod plot;

use serde::Serialize;

use super::episode::{run_episode_with_blocks, EpisodeSpec};
use super::tasks::initial_scene_for;
use crate::lfd::disturb::Level;
use crate::lfd::session::{mix, SessionError, SessionParams};
use crate::lfd::{Method, Mode};
use crate::plan::Clock;
use crate::sim::benchmark::Benchmark;

/// The methods compared: label, method and multi-goal mode.
pub const METHODS: [(&str, Method, Mode); 3] = [
    ("logic-lfd (paper)", Method::LogicLfd, Mode::Paper),
    (
        "logic-lfd (prioritised)",
        Method::LogicLfd,
        Mode::Prioritised,
    ),
    ("tamp", Method::Tamp, Mode::Paper),
];

/// One row of the study: a block count and a method.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScalingRow {
    /// Blocks of the task.
    pub blocks: usize,
    /// Method label (see [`METHODS`]).
    pub method: String,
    /// Tasks run.
    pub tasks: usize,
    /// Tasks whose episode reached the goal.
    pub successes: usize,
    /// Median first-plan time (ms).
    pub first_plan_ms_median: f64,
    /// 95th percentile first-plan time (ms).
    pub first_plan_ms_p95: f64,
    /// Median first-plan length (actions).
    pub plan_length_median: f64,
}

/// The `q`-quantile (nearest rank) of `v`; 0 when empty.
fn quantile(v: &mut [f64], q: f64) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    let i = libm::ceil(q * v.len() as f64) as usize;
    v[i.clamp(1, v.len()) - 1]
}

/// Runs `tasks` B1-N tasks (L3 initial states, seeded from `seed`) for every N of `blocks` and
/// every method of [`METHODS`].
pub fn scaling(
    blocks: &[usize],
    tasks: usize,
    seed: u64,
    clock: &dyn Clock,
) -> Result<Vec<ScalingRow>, SessionError> {
    let b = Benchmark::B1;
    let mut rows = Vec::new();
    for &n in blocks {
        let scenes: Vec<String> = (0..tasks as u64)
            .map(|t| initial_scene_for(b, Some(n), Level::L3, mix(seed, t)))
            .collect::<Result<_, _>>()?;
        for (label, method, mode) in METHODS {
            let mut times = Vec::new();
            let mut lengths = Vec::new();
            let mut successes = 0;
            for (t, scene) in scenes.iter().enumerate() {
                let spec = EpisodeSpec {
                    benchmark: b,
                    level: None,
                    method,
                    mode,
                    seed: mix(seed, t as u64),
                    scene: Some(scene.clone()),
                };
                let r = run_episode_with_blocks(&spec, Some(n), SessionParams::default(), clock)?;
                successes += usize::from(r.success);
                if let Some(first) = r.log.replans.first() {
                    times.push(first.time_ms);
                    lengths.push(first.plan.len() as f64);
                }
            }
            rows.push(ScalingRow {
                blocks: n,
                method: label.to_string(),
                tasks,
                successes,
                first_plan_ms_median: quantile(&mut times.clone(), 0.5),
                first_plan_ms_p95: quantile(&mut times, 0.95),
                plan_length_median: quantile(&mut lengths, 0.5),
            });
        }
    }
    Ok(rows)
}

/// The rows as a markdown table.
pub fn markdown(rows: &[ScalingRow]) -> String {
    let mut s = String::from(
        "| N | method | success | first plan median (ms) | p95 (ms) | plan length |\n\
         |---|---|---|---|---|---|\n",
    );
    for r in rows {
        s += &format!(
            "| {} | {} | {}/{} | {:.3} | {:.3} | {} |\n",
            r.blocks,
            r.method,
            r.successes,
            r.tasks,
            r.first_plan_ms_median,
            r.first_plan_ms_p95,
            r.plan_length_median
        );
    }
    s
}

/// The median first-plan time per method against N, for [`plot::svg`].
pub fn series(rows: &[ScalingRow]) -> Vec<plot::Series> {
    METHODS
        .iter()
        .map(|(label, _, _)| plot::Series {
            label: label.to_string(),
            points: rows
                .iter()
                .filter(|r| r.method == *label)
                .map(|r| (r.blocks as f64, r.first_plan_ms_median))
                .collect(),
        })
        .collect()
}
