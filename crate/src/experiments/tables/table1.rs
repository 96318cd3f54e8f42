//! Table I: `tasks` random initial states per benchmark (levels L1–L4 in turn), every method run
//! in closed loop from each; success, first-plan time split into search and binding, Logic-LfD's
//! TAMP fallbacks.

use serde::{Deserialize, Serialize};

use crate::lfd::{mix_seed, SessionError, SessionParams};
use crate::lfd::{Method, Mode};
use crate::plan::Clock;
use crate::sim::ArmModel;
use crate::sim::Benchmark;
use crate::sim::World;
use std::sync::Arc;

use super::common::{count, reason_kind, summary, PAPER_TABLE1};
use super::feasible::infeasible;
use crate::experiments::{run_episode, EpisodeSpec};
use crate::lfd::Level;

/// One method on one benchmark in Table I.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table1Cell {
    /// Benchmark.
    pub benchmark: Benchmark,
    /// Method.
    pub method: Method,
    /// Multi-goal mode (Logic-LfD; `paper` for the others).
    pub mode: Mode,
    /// Tasks solved.
    pub successes: usize,
    /// Tasks run.
    pub tasks: usize,
    /// Planning time of the first plan per task (ms).
    pub plan_ms: Vec<f64>,
    /// The part of each first plan's time spent in symbolic search (ms): `plan_ms − bind_ms`.
    #[serde(default)]
    pub search_ms: Vec<f64>,
    /// The part of each first plan's time spent binding actions to motions (ms).
    #[serde(default)]
    pub bind_ms: Vec<f64>,
    /// Replans of Logic-LfD that planned to G from scratch (the TAMP fallback), over all tasks.
    #[serde(default)]
    pub fallbacks: usize,
    /// Replans after the first plan, per task run (the first plan is not a replan).
    #[serde(default)]
    pub replans: Vec<usize>,
    /// Actions executed per successful task.
    pub actions: Vec<usize>,
    /// Failure reasons seen (kind → count).
    pub failures: Vec<(String, usize)>,
}

impl Table1Cell {
    /// The method's row name: `linear`, `tamp`, `logic-lfd (paper)`, `logic-lfd (prioritised)`.
    pub fn method_label(&self) -> String {
        method_label(self.method, self.mode)
    }
}

/// A method's row name in Table I.
fn method_label(method: Method, mode: Mode) -> String {
    match (method, mode) {
        (Method::LogicLfd, Mode::Prioritised) => "logic-lfd (prioritised)".to_string(),
        (Method::LogicLfd, Mode::Paper) => "logic-lfd (paper)".to_string(),
        (m, _) => m.as_str().to_string(),
    }
}

/// Table I.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table1 {
    /// Tasks per benchmark.
    pub tasks: usize,
    /// Seed of the task generator and episodes.
    pub seed: u64,
    /// Cells.
    pub cells: Vec<Table1Cell>,
    /// Tasks whose first draw was infeasible ([`infeasible`]) and were redrawn.
    pub redrawn: Vec<Redraw>,
    /// Whether Logic-LfD could fall back to TAMP from scratch
    /// ([`ControlParams::tamp_fallback`](crate::lfd::ControlParams::tamp_fallback)).
    #[serde(default)]
    pub tamp_fallback: bool,
    /// The robots the episodes ran on (empty: the scenes' own, the built-in Panda).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub robots: Vec<String>,
}

/// A Table I task whose initial state was redrawn.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Redraw {
    /// Benchmark.
    pub benchmark: Benchmark,
    /// Task index.
    pub task: usize,
    /// Draws made (the last one is used).
    pub draws: usize,
}

/// The methods of Table I (Logic-LfD in both modes).
pub const TABLE1_METHODS: [(Method, Mode); 4] = [
    (Method::Linear, Mode::Paper),
    (Method::Tamp, Mode::Paper),
    (Method::LogicLfd, Mode::Paper),
    (Method::LogicLfd, Mode::Prioritised),
];

/// Draws of a Table I initial state before the task is reported as infeasible.
pub const MAX_DRAWS: usize = 16;

/// The initial scene of Table I task `index` of benchmark `b` at `level`: the first feasible
/// ([`infeasible`]) of up to [`MAX_DRAWS`] draws, draw `d` from seed `mix_seed(task_seed, d)` (draw 0:
/// `task_seed` itself). Returns the scene JSON and the draw used; an error names the task when
/// every draw is infeasible (tasks are never dropped silently).
pub fn table1_scene(
    b: Benchmark,
    level: Level,
    task_seed: u64,
) -> Result<(String, usize), SessionError> {
    let mut why = String::new();
    for draw in 0..MAX_DRAWS {
        let seed = if draw == 0 {
            task_seed
        } else {
            mix_seed(task_seed, draw as u64)
        };
        let scene = crate::experiments::initial_scene(b, level, seed)?;
        let world = World::from_json(&scene)?.with_motions(b.motions());
        match infeasible(&world) {
            None => return Ok((scene, draw)),
            Some(w) => why = w,
        }
    }
    Err(SessionError::Json(format!(
        "{} {} task seed {task_seed}: no feasible initial state in {MAX_DRAWS} draws ({why})",
        b.as_str(),
        level.as_str()
    )))
}

/// The seed of Table I task `index` of benchmark `b` in a run seeded `seed`.
pub fn table1_task_seed(b: Benchmark, index: usize, seed: u64) -> u64 {
    mix_seed(seed, (b as u64) << 32 | index as u64)
}

/// What one Table I task gave: the draw its initial state came from and every method's run
/// from it (a record of the sweep, joined by [`Table1Sweep::report`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table1Task {
    /// Benchmark.
    pub benchmark: Benchmark,
    /// Task index within the benchmark.
    pub task: usize,
    /// The draw used (0: the first; see [`table1_scene`]).
    pub draw: usize,
    /// One run per method of [`TABLE1_METHODS`], in that order.
    pub runs: Vec<Table1Run>,
}

/// One method's closed-loop episode from a Table I task.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table1Run {
    /// Time of the first plan (ms, caller's clock), if the method planned.
    pub plan_ms: Option<f64>,
    /// The part of it spent binding actions to motions (ms).
    pub bind_ms: Option<f64>,
    /// Replans that planned to G from scratch (the TAMP fallback).
    pub fallbacks: usize,
    /// Replans after the first plan.
    #[serde(default)]
    pub replans: usize,
    /// Actions executed, if the episode reached the goal.
    pub success_actions: Option<usize>,
    /// The failure's kind, if it failed with a stated reason.
    pub failure: Option<String>,
}

/// Table I as a sweep: `tasks` tasks for each benchmark, benchmark by benchmark; item `i` is
/// task `i mod tasks` of benchmark `benchmarks[i / tasks]`, seeded by [`table1_task_seed`] alone,
/// so items run in any order (or on other machines) and [`Table1Sweep::report`] joins them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table1Sweep {
    /// Benchmarks, in row order.
    pub benchmarks: Vec<Benchmark>,
    /// Tasks per benchmark.
    pub tasks: usize,
    /// Seed of the task generator and episodes.
    pub seed: u64,
    /// Whether Logic-LfD may fall back to TAMP from scratch.
    pub tamp_fallback: bool,
    /// Robots in place of the scenes' arms ([`EpisodeSpec::robots`]); the tasks are drawn as
    /// without them, so every robot meets the same tasks.
    #[serde(skip)]
    pub robots: Vec<Arc<ArmModel>>,
}

impl Table1Sweep {
    /// Number of items (tasks over all benchmarks).
    pub fn items(&self) -> usize {
        self.benchmarks.len() * self.tasks
    }

    /// The level of item `index` (tasks take L1..L4 in turn).
    pub fn level(&self, index: usize) -> Level {
        Level::ALL[index % self.tasks % 4]
    }

    /// The initial scene of item `index` and the draw it came from ([`table1_scene`]).
    fn scene(&self, index: usize) -> Result<(String, usize), SessionError> {
        let (b, i) = (self.benchmarks[index / self.tasks], index % self.tasks);
        table1_scene(b, self.level(index), table1_task_seed(b, i, self.seed))
    }

    /// The episode of `method` in `mode` from item `index`'s initial `scene`.
    fn spec(&self, index: usize, method: Method, mode: Mode, scene: &str) -> EpisodeSpec {
        let (b, i) = (self.benchmarks[index / self.tasks], index % self.tasks);
        EpisodeSpec {
            benchmark: b,
            level: None,
            method,
            mode,
            seed: table1_task_seed(b, i, self.seed),
            scene: Some(scene.to_string()),
            robots: self.robots.clone(),
        }
    }

    /// Runs method `run` of [`TABLE1_METHODS`] alone from item `index` as [`Table1Sweep::run`]
    /// runs it, with its full report (the log replays it).
    pub fn episode(
        &self,
        index: usize,
        run: usize,
        params: SessionParams,
        clock: &dyn Clock,
    ) -> Result<crate::experiments::EpisodeReport, SessionError> {
        let mut params = params;
        params.control.tamp_fallback = self.tamp_fallback;
        let (method, mode) = TABLE1_METHODS
            .get(run)
            .copied()
            .ok_or_else(|| SessionError::Json(format!("run {run}: Table I has 4 methods")))?;
        let (scene, _) = self.scene(index)?;
        run_episode(&self.spec(index, method, mode, &scene), params, clock)
    }

    /// Runs item `index`: draws its initial state ([`table1_scene`]) and runs every method of
    /// [`TABLE1_METHODS`] in closed loop from it, with `params` (their
    /// `control.tamp_fallback` set from the sweep's). `progress` hears of failures and of the
    /// task's end.
    pub fn run(
        &self,
        index: usize,
        params: SessionParams,
        clock: &dyn Clock,
        progress: &mut dyn FnMut(&str),
    ) -> Result<Table1Task, SessionError> {
        let mut params = params;
        params.control.tamp_fallback = self.tamp_fallback;
        let (b, i) = (self.benchmarks[index / self.tasks], index % self.tasks);
        let level = Level::ALL[i % 4];
        let (scene, draw) = self.scene(index)?;
        let mut runs = Vec::with_capacity(TABLE1_METHODS.len());
        for (method, mode) in TABLE1_METHODS {
            let spec = self.spec(index, method, mode, &scene);
            let r = match run_episode(&spec, params, clock) {
                Ok(r) => r,
                // The robots cannot reach a block of this task: a failure of theirs, not the
                // table's.
                Err(SessionError::Reach(why)) => {
                    progress(&format!(
                        "table1 {} task {i} ({}) {}: refused: {why}",
                        b.as_str(),
                        level.as_str(),
                        method_label(method, mode)
                    ));
                    runs.push(Table1Run {
                        plan_ms: None,
                        bind_ms: None,
                        fallbacks: 0,
                        replans: 0,
                        success_actions: None,
                        failure: Some("out-of-reach".into()),
                    });
                    continue;
                }
                Err(e) => return Err(e),
            };
            let first = r.log.replans.first();
            let failure = match (&r.reason, r.success) {
                (Some(reason), false) => {
                    progress(&format!(
                        "table1 {} task {i} ({}) {}: failed: {reason}",
                        b.as_str(),
                        level.as_str(),
                        method_label(method, mode)
                    ));
                    Some(reason_kind(reason))
                }
                _ => None,
            };
            runs.push(Table1Run {
                plan_ms: first.map(|f| f.time_ms),
                bind_ms: first.map(|f| f.bind_ms),
                fallbacks: r.log.replans.iter().filter(|p| p.fallback).count(),
                replans: r.log.replans.len().saturating_sub(1),
                success_actions: r.success.then_some(r.actions_executed),
                failure,
            });
        }
        progress(&format!(
            "table1 {} task {}/{}",
            b.as_str(),
            i + 1,
            self.tasks
        ));
        Ok(Table1Task {
            benchmark: b,
            task: i,
            draw,
            runs,
        })
    }

    /// Table I from the sweep's items, given in item order.
    pub fn report(&self, items: impl IntoIterator<Item = Table1Task>) -> Table1 {
        self.report_of(items.into_iter().enumerate())
    }

    /// Table I of the items at `level` alone (items given in item order, all of them).
    pub fn report_level(
        &self,
        items: impl IntoIterator<Item = Table1Task>,
        level: Level,
    ) -> Table1 {
        self.report_of(
            items
                .into_iter()
                .enumerate()
                .filter(|(p, _)| self.level(*p) == level),
        )
    }

    /// Table I from items paired with their item index.
    fn report_of(&self, items: impl IntoIterator<Item = (usize, Table1Task)>) -> Table1 {
        let mut cells: Vec<Table1Cell> = self
            .benchmarks
            .iter()
            .flat_map(|&b| {
                TABLE1_METHODS
                    .iter()
                    .map(move |&(method, mode)| Table1Cell {
                        benchmark: b,
                        method,
                        mode,
                        successes: 0,
                        tasks: 0,
                        plan_ms: vec![],
                        search_ms: vec![],
                        bind_ms: vec![],
                        fallbacks: 0,
                        replans: vec![],
                        actions: vec![],
                        failures: vec![],
                    })
            })
            .collect();
        let mut redrawn = vec![];
        for (p, item) in items {
            if item.draw > 0 {
                redrawn.push(Redraw {
                    benchmark: item.benchmark,
                    task: item.task,
                    draws: item.draw + 1,
                });
            }
            // Item p is a task of the (p / tasks)-th benchmark: its row of cells starts there.
            let row = p / self.tasks * TABLE1_METHODS.len();
            for (cell, run) in cells.iter_mut().skip(row).zip(item.runs) {
                cell.tasks += 1;
                if let (Some(plan), Some(bind)) = (run.plan_ms, run.bind_ms) {
                    cell.plan_ms.push(plan);
                    cell.search_ms.push(plan - bind);
                    cell.bind_ms.push(bind);
                }
                cell.fallbacks += run.fallbacks;
                cell.replans.push(run.replans);
                if let Some(actions) = run.success_actions {
                    cell.successes += 1;
                    cell.actions.push(actions);
                } else if let Some(kind) = run.failure {
                    count(&mut cell.failures, kind);
                }
            }
        }
        Table1 {
            tasks: self.tasks,
            seed: self.seed,
            cells,
            redrawn,
            tamp_fallback: self.tamp_fallback,
            robots: self.robots.iter().map(|r| r.name().to_string()).collect(),
        }
    }
}

/// Runs Table I: `tasks` initial states per benchmark ([`table1_scene`]), levels L1..L4 in
/// turn; every method runs the closed loop from each state (the items of [`Table1Sweep`], one
/// after another).
pub fn table1(
    benchmarks: &[Benchmark],
    tasks: usize,
    seed: u64,
    params: SessionParams,
    clock: &dyn Clock,
    progress: &mut dyn FnMut(&str),
) -> Result<Table1, SessionError> {
    let sweep = Table1Sweep {
        benchmarks: benchmarks.to_vec(),
        tasks,
        seed,
        tamp_fallback: params.control.tamp_fallback,
        robots: vec![],
    };
    let items = (0..sweep.items())
        .map(|i| sweep.run(i, params, clock, progress))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(sweep.report(items))
}

/// Medians of the search and binding parts of the first plans: `0.21 / 0.09`.
fn fmt_split(search: &[f64], bind: &[f64]) -> String {
    match (summary(search), summary(bind)) {
        (Some(s), Some(b)) => format!("{:.3} / {:.3}", s.median, b.median),
        _ => "N/A".into(),
    }
}

fn fmt_ms(v: &[f64]) -> String {
    match summary(v) {
        Some(s) => format!("{:.3} ± {:.3} (median {:.3})", s.mean, s.sd, s.median),
        None => "N/A".into(),
    }
}

impl Table1 {
    /// Markdown: ours beside the paper's.
    pub fn markdown(&self) -> String {
        let mut out = String::new();
        out.push_str(&format!(
            "Table I — generalisation over {} random initial states per benchmark (levels L1–L4 in turn), seed {}.\n\n",
            self.tasks, self.seed
        ));
        if self.redrawn.is_empty() {
            out.push_str(&format!(
                "Every first draw was feasible (rule: `experiments::infeasible`, up to {MAX_DRAWS} draws).\n\n"
            ));
        } else {
            out.push_str(&format!(
                "Redrawn as infeasible (rule: `experiments::infeasible`, up to {MAX_DRAWS} draws): {}.\n\n",
                self.redrawn
                    .iter()
                    .map(|r| format!("{} task {} ({} draws)", r.benchmark.as_str().to_uppercase(), r.task, r.draws))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        if !self.robots.is_empty() {
            out.push_str(&format!("Robot: {}.\n\n", self.robots.join(", ")));
        }
        out.push_str(if self.tamp_fallback {
            "Logic-LfD's TAMP fallback on: the fallbacks column counts its replans that planned to G from scratch.\n\n"
        } else {
            "Logic-LfD's TAMP fallback off: its success is its own.\n\n"
        });
        out.push_str("| method | benchmark | success (ours) | success (paper) | first-plan time, ms (ours: mean ± sd, median) | of which search / binding, ms (medians) | planning time, s (paper) | TAMP fallbacks | failures (ours) |\n");
        out.push_str("|---|---|---|---|---|---|---|---|---|\n");
        for c in &self.cells {
            let col = match c.method {
                Method::Linear => 0,
                Method::Tamp => 1,
                _ => 2,
            };
            let (ps, pt) = PAPER_TABLE1[col].1[c.benchmark as usize];
            let name = c.method_label();
            let (ours_t, split) = if c.method == Method::Linear {
                ("N/A (no planning)".to_string(), "N/A".to_string())
            } else {
                (fmt_ms(&c.plan_ms), fmt_split(&c.search_ms, &c.bind_ms))
            };
            let fallbacks = match (c.method, self.tamp_fallback) {
                (Method::LogicLfd, true) => c.fallbacks.to_string(),
                (Method::LogicLfd, false) => "off".to_string(),
                _ => "—".to_string(),
            };
            let failures = if c.failures.is_empty() {
                "—".to_string()
            } else {
                c.failures
                    .iter()
                    .map(|(k, n)| format!("{k} ×{n}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            out.push_str(&format!(
                "| {} | {} | {:.0} % ({}/{}) | {:.0} % | {} | {} | {} | {} | {} |\n",
                name,
                c.benchmark.as_str().to_uppercase(),
                100.0 * c.successes as f64 / c.tasks.max(1) as f64,
                c.successes,
                c.tasks,
                ps,
                ours_t,
                split,
                pt.map(|(m, s)| format!("{m:.2} ± {s:.2}"))
                    .unwrap_or_else(|| "N/A".into()),
                fallbacks,
                failures
            ));
        }
        out
    }
}
