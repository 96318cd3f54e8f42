//! Scaling study (`logic-lfd bench scaling`): B1 tower tasks with N blocks from random L3
//! initial states (facts the demonstration never visits), per method the success rate, the first
//! plan's time (median, p95; caller's clock) split into symbolic search and geometric binding,
//! its length and the states its searches expanded.

pub mod plot;

use serde::{Deserialize, Serialize};

use super::episode::{run_episode_with_blocks, EpisodeSpec};
use super::tasks::initial_scene_for;
use crate::lfd::Level;
use crate::lfd::{mix_seed, SessionError, SessionParams};
use crate::lfd::{Method, Mode};
use crate::plan::{Algorithm, Clock, HeuristicKind};
use crate::sim::Benchmark;

/// The methods compared: label, method, multi-goal mode and whether the symbolic search is the
/// satisficing lazy GBFS with h_FF instead of the loop's default (A* with LM-cut). Each search
/// runs Logic-LfD in both modes and TAMP from scratch.
pub const METHODS: [(&str, Method, Mode, bool); 6] = [
    ("logic-lfd (paper)", Method::LogicLfd, Mode::Paper, false),
    (
        "logic-lfd (prioritised)",
        Method::LogicLfd,
        Mode::Prioritised,
        false,
    ),
    ("tamp", Method::Tamp, Mode::Paper, false),
    (
        "logic-lfd (paper, gbfs, h_ff)",
        Method::LogicLfd,
        Mode::Paper,
        true,
    ),
    (
        "logic-lfd (prioritised, gbfs, h_ff)",
        Method::LogicLfd,
        Mode::Prioritised,
        true,
    ),
    ("tamp (gbfs, h_ff)", Method::Tamp, Mode::Paper, true),
];

/// Per search (A* with LM-cut, lazy GBFS with h_FF): the indices in [`METHODS`] of Logic-LfD's
/// paper mode and of TAMP from scratch, compared by [`markdown`].
const SAME_SEARCH: [(usize, usize); 2] = [(0, 2), (3, 5)];

/// The block counts `logic-lfd bench scaling` runs by default: from the template's 4 blocks to
/// B1's most ([`crate::sim::MAX_BLOCKS`]), one and two towers.
pub const DEFAULT_BLOCKS: [usize; 5] = [4, 8, 12, 16, 20];

/// Wall-clock budget of one symbolic search in the study (s): a method that needs more has
/// failed on that task.
pub const SEARCH_TIME_LIMIT_SECS: f64 = 2.0;

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
    /// Median time of the first plan's symbolic search (ms): its time less its binding.
    pub search_ms_median: f64,
    /// Median time of the first plan's geometric binding (ms).
    pub bind_ms_median: f64,
    /// Median first-plan length (actions).
    pub plan_length_median: f64,
    /// Median states expanded by the first plan's searches.
    pub expanded_median: f64,
    /// Why the first failed task failed, if one did.
    pub first_failure: Option<String>,
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

/// What one method's episode on one task of the study gave.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScalingRun {
    /// The episode reached the goal.
    pub success: bool,
    /// Why it failed, if it did.
    pub failure: Option<String>,
    /// Its first plan, if it planned.
    pub first_plan: Option<FirstPlan>,
}

/// The first plan of a study episode.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FirstPlan {
    /// Its time (ms, caller's clock).
    pub time_ms: f64,
    /// The part of it spent binding actions to motions (ms).
    pub bind_ms: f64,
    /// States its searches expanded.
    pub expanded: u64,
    /// Its length (actions).
    pub length: usize,
}

/// What one task of the study gave: one run per method of [`METHODS`], in that order (a record
/// of the sweep, joined by [`ScalingSweep::report`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScalingTask {
    /// Blocks of the task.
    pub blocks: usize,
    /// Task index within its block count.
    pub task: usize,
    /// One run per method.
    pub runs: Vec<ScalingRun>,
}

/// The study as a sweep: `tasks` tasks per block count; item `i` is task `i mod tasks` of
/// `blocks[i / tasks]`, seeded `mix_seed(seed, task)` alone, so items run in any order (or on other
/// machines) and [`ScalingSweep::report`] joins them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScalingSweep {
    /// Block counts, in row order.
    pub blocks: Vec<usize>,
    /// Tasks per block count.
    pub tasks: usize,
    /// Seed of the tasks and episodes.
    pub seed: u64,
}

impl ScalingSweep {
    /// Number of items (tasks over all block counts).
    pub fn items(&self) -> usize {
        self.blocks.len() * self.tasks
    }

    /// Runs item `index`: draws its L3 initial state and runs every method of [`METHODS`] from
    /// it (each symbolic search within [`SEARCH_TIME_LIMIT_SECS`] of `clock`).
    pub fn run(&self, index: usize, clock: &dyn Clock) -> Result<ScalingTask, SessionError> {
        let b = Benchmark::B1;
        let (n, t) = (self.blocks[index / self.tasks], index % self.tasks);
        let seed = mix_seed(self.seed, t as u64);
        let scene = initial_scene_for(b, Some(n), Level::L3, seed)?;
        let mut runs = Vec::with_capacity(METHODS.len());
        for (_, method, mode, satisficing) in METHODS {
            let mut params = SessionParams::default();
            params.control.search.time_limit_secs = Some(SEARCH_TIME_LIMIT_SECS);
            if satisficing {
                params.control.search.algorithm = Algorithm::LazyGbfs;
                params.control.search.heuristic = HeuristicKind::HFf;
            }
            let spec = EpisodeSpec {
                benchmark: b,
                level: None,
                method,
                mode,
                seed,
                scene: Some(scene.clone()),
                robots: vec![],
            };
            let r = run_episode_with_blocks(&spec, Some(n), params, clock)?;
            runs.push(ScalingRun {
                success: r.success,
                failure: r.reason.as_ref().map(|why| why.to_string()),
                first_plan: r.log.replans.first().map(|first| FirstPlan {
                    time_ms: first.time_ms,
                    bind_ms: first.bind_ms,
                    expanded: first.expanded,
                    length: first.plan.len(),
                }),
            });
        }
        Ok(ScalingTask {
            blocks: n,
            task: t,
            runs,
        })
    }

    /// The study's rows (block count by block count, method by method) from its items, given
    /// in item order.
    pub fn report(&self, items: impl IntoIterator<Item = ScalingTask>) -> Vec<ScalingRow> {
        let mut items = items.into_iter();
        let mut rows = Vec::new();
        for &n in &self.blocks {
            let tasks: Vec<ScalingTask> = items.by_ref().take(self.tasks).collect();
            for (m, (label, ..)) in METHODS.iter().enumerate() {
                let runs = tasks.iter().filter_map(|t| t.runs.get(m));
                rows.push(row(n, label, self.tasks, runs));
            }
        }
        rows
    }
}

/// The row of block count `n` and method `label` from its runs, in task order.
fn row<'a>(
    n: usize,
    label: &str,
    tasks: usize,
    runs: impl Iterator<Item = &'a ScalingRun>,
) -> ScalingRow {
    let mut failure = None;
    let mut times = Vec::new();
    let mut search = Vec::new();
    let mut bind = Vec::new();
    let mut expanded = Vec::new();
    let mut lengths = Vec::new();
    let mut successes = 0;
    for r in runs {
        successes += usize::from(r.success);
        if let (None, Some(why)) = (&failure, &r.failure) {
            failure = Some(why.clone());
        }
        if let Some(first) = &r.first_plan {
            times.push(first.time_ms);
            search.push((first.time_ms - first.bind_ms).max(0.0));
            bind.push(first.bind_ms);
            expanded.push(first.expanded as f64);
            lengths.push(first.length as f64);
        }
    }
    ScalingRow {
        blocks: n,
        method: label.to_string(),
        tasks,
        successes,
        first_plan_ms_median: quantile(&mut times.clone(), 0.5),
        first_plan_ms_p95: quantile(&mut times, 0.95),
        search_ms_median: quantile(&mut search, 0.5),
        bind_ms_median: quantile(&mut bind, 0.5),
        plan_length_median: quantile(&mut lengths, 0.5),
        expanded_median: quantile(&mut expanded, 0.5),
        first_failure: failure,
    }
}

/// Runs `tasks` B1-N tasks (L3 initial states, seeded from `seed`) for every N of `blocks` and
/// every method of [`METHODS`] (the items of [`ScalingSweep`], one after another).
pub fn scaling(
    blocks: &[usize],
    tasks: usize,
    seed: u64,
    clock: &dyn Clock,
) -> Result<Vec<ScalingRow>, SessionError> {
    let sweep = ScalingSweep {
        blocks: blocks.to_vec(),
        tasks,
        seed,
    };
    let items = (0..sweep.items())
        .map(|i| sweep.run(i, clock))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(sweep.report(items))
}

/// The rows as a markdown table, then Logic-LfD's advantage per N (TAMP's median first-plan
/// time over each Logic-LfD mode's).
pub fn markdown(rows: &[ScalingRow]) -> String {
    let mut s = String::from(
        "| N | method | success | first plan median (ms) | p95 (ms) | search (ms) | binding (ms) | plan length | expanded |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    let ms = |v: f64, any: bool| if any { format!("{v:.3}") } else { "–".into() };
    for r in rows {
        let any = r.successes > 0 || r.plan_length_median > 0.0;
        s += &format!(
            "| {} | {} | {}/{} | {} | {} | {} | {} | {} | {} |\n",
            r.blocks,
            r.method,
            r.successes,
            r.tasks,
            ms(r.first_plan_ms_median, any),
            ms(r.first_plan_ms_p95, any),
            ms(r.search_ms_median, any),
            ms(r.bind_ms_median, any),
            r.plan_length_median,
            r.expanded_median
        );
    }
    let failures: Vec<String> = rows
        .iter()
        .filter_map(|r| {
            r.first_failure
                .as_ref()
                .map(|f| format!("- N = {}, {}: {f}", r.blocks, r.method))
        })
        .collect();
    if !failures.is_empty() {
        s += "\nFirst failure of each row with one:\n\n";
        s += &failures.join("\n");
        s += "\n";
    }
    s += "\nMedian first-plan time of TAMP from scratch over Logic-LfD's (paper mode), with the \
          same search:\n\n| N | A*, LM-cut | lazy GBFS, h_FF |\n|---|---|---|\n";
    let mut ns: Vec<usize> = rows.iter().map(|r| r.blocks).collect();
    ns.dedup();
    for n in ns {
        let median = |i: usize| {
            rows.iter()
                .find(|r| r.blocks == n && r.method == METHODS[i].0 && r.successes > 0)
                .map(|r| r.first_plan_ms_median)
        };
        let ratio = |(lfd, tamp): (usize, usize)| match (median(tamp), median(lfd)) {
            (Some(t), Some(l)) if l > 0.0 => format!("{:.1}×", t / l),
            (None, Some(_)) => "TAMP failed".into(),
            _ => "–".into(),
        };
        s += &format!(
            "| {n} | {} | {} |\n",
            ratio(SAME_SEARCH[0]),
            ratio(SAME_SEARCH[1])
        );
    }
    s
}

/// The median first-plan time per method against N, for [`plot::svg`].
pub fn series(rows: &[ScalingRow]) -> Vec<plot::Series> {
    METHODS
        .iter()
        .map(|(label, _, _, _)| plot::Series {
            label: label.to_string(),
            points: rows
                .iter()
                .filter(|r| r.method == *label && r.successes > 0)
                .map(|r| (r.blocks as f64, r.first_plan_ms_median))
                .collect(),
        })
        .collect()
}
