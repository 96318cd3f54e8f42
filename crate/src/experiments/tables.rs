//! Table I (generalisation) and Table II (reactivity) runners and their markdown reports, with
//! the paper's numbers beside ours.

use serde::{Deserialize, Serialize};

use nalgebra::{Isometry3, Translation3, Vector3};

use crate::lfd::session::{mix, SessionError, SessionParams};
use crate::lfd::{Method, Mode};
use crate::plan::Clock;
use crate::sim::benchmark::Benchmark;
use crate::sim::demo::{pull_hook_poses, PULL_TARGET_RADIUS};
use crate::sim::geometry::grasp_pose;
use crate::sim::motions::Relation;
use crate::sim::snapshot::BodyKind;
use crate::sim::World;

use super::episode::{run_episode, EpisodeSpec, Level};

/// Mean, sample standard deviation and median of `v` (`None` when empty).
pub fn stats(v: &[f64]) -> Option<(f64, f64, f64)> {
    if v.is_empty() {
        return None;
    }
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = if v.len() > 1 {
        v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
    } else {
        0.0
    };
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.total_cmp(b));
    let median = if s.len() % 2 == 1 {
        s[s.len() / 2]
    } else {
        0.5 * (s[s.len() / 2 - 1] + s[s.len() / 2])
    };
    Some((mean, var.sqrt(), median))
}

/// Mean ± sd (s); `None` = N/A.
pub type MeanSd = Option<(f64, f64)>;

/// The paper's Table I: (success %, planning time mean, sd in s) per method column and benchmark.
pub const PAPER_TABLE1: [(&str, [(f64, MeanSd); 3]); 3] = [
    ("linear", [(27.0, None), (31.0, None), (24.0, None)]),
    (
        "tamp",
        [
            (100.0, Some((0.53, 0.10))),
            (100.0, Some((0.53, 0.23))),
            (100.0, Some((0.23, 0.09))),
        ],
    ),
    (
        "logic-lfd",
        [
            (100.0, Some((0.16, 0.07))),
            (100.0, Some((0.37, 0.27))),
            (100.0, Some((0.14, 0.06))),
        ],
    ),
];

/// The paper's Table II: execution time mean ± sd (s) per level, method, benchmark; `None` = N/A.
pub const PAPER_TABLE2: [(&str, [[MeanSd; 3]; 4]); 3] = [
    (
        "linear",
        [
            [
                Some((13.23, 0.58)),
                Some((12.50, 0.13)),
                Some((24.63, 0.05)),
            ],
            [None, None, None],
            [None, None, None],
            [None, None, None],
        ],
    ),
    (
        "rlds",
        [
            [
                Some((13.70, 1.23)),
                Some((12.59, 0.19)),
                Some((24.64, 0.04)),
            ],
            [
                Some((18.07, 0.95)),
                Some((19.08, 0.01)),
                Some((30.83, 0.04)),
            ],
            [None, None, None],
            [None, None, None],
        ],
    ),
    (
        "logic-lfd",
        [
            [
                Some((13.23, 0.35)),
                Some((12.50, 0.13)),
                Some((24.62, 0.03)),
            ],
            [
                Some((17.62, 0.67)),
                Some((19.08, 0.01)),
                Some((30.79, 0.02)),
            ],
            [
                Some((23.05, 0.49)),
                Some((26.03, 0.78)),
                Some((30.23, 0.08)),
            ],
            [
                Some((19.00, 1.29)),
                Some((12.60, 0.15)),
                Some((31.57, 0.04)),
            ],
        ],
    ),
];

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
    /// Actions executed per successful task.
    pub actions: Vec<usize>,
    /// Failure reasons seen (kind → count).
    pub failures: Vec<(String, usize)>,
}

impl Table1Cell {
    /// The method's row name: `linear`, `tamp`, `logic-lfd (paper)`, `logic-lfd (prioritised)`.
    pub fn method_label(&self) -> String {
        match (self.method, self.mode) {
            (Method::LogicLfd, Mode::Prioritised) => "logic-lfd (prioritised)".to_string(),
            (Method::LogicLfd, Mode::Paper) => "logic-lfd (paper)".to_string(),
            (m, _) => m.as_str().to_string(),
        }
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
    /// ([`ControlParams::tamp_fallback`](crate::lfd::control::ControlParams::tamp_fallback)).
    #[serde(default)]
    pub tamp_fallback: bool,
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

fn reason_kind(r: &crate::lfd::control::FailReason) -> String {
    serde_json::to_value(r)
        .ok()
        .and_then(|v| v.get("kind").and_then(|k| k.as_str()).map(str::to_string))
        .unwrap_or_else(|| "unknown".into())
}

fn count(failures: &mut Vec<(String, usize)>, k: String) {
    match failures.iter_mut().find(|(n, _)| *n == k) {
        Some((_, c)) => *c += 1,
        None => failures.push((k, 1)),
    }
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

/// Why no method could solve a task from `world` (`None`: it is feasible). The rule, the same for
/// every method and benchmark: every block and hook rests on a support (the simulator's
/// invariants hold), and every block can be grasped from above — grasp pose and its approach pose
/// 10 cm above reachable by some arm's IK, and, where the domain has `(inreach r x)`, inside r's
/// reach annulus — or, where the scene has a hook, pulled: the hook is graspable and some arm's
/// pull stroke (the executor's, to `PULL_TARGET_RADIUS`) is reachable at its contact and pulled
/// poses and leaves the block inside the annulus (a pull only brings a block nearer: a block
/// inside the annulus' inner radius can never be picked).
pub fn infeasible(world: &World) -> Option<String> {
    if let Err(v) = world.check_invariants() {
        return Some(format!("the world breaks its invariants: {v:?}"));
    }
    let arms = world.arm_names().len();
    let snap = world.snapshot();
    // Where the domain has `(inreach r x)`, a block is only picked inside r's reach annulus.
    let annulus = world.motions().reports(Relation::InReach);
    let in_annulus = |a: usize, p: &Vector3<f64>| {
        !annulus
            || match (snap.arms.get(a), world.arm_base(a)) {
                (Some(arm), Some(b)) => {
                    let d = libm::hypot(p.x - b.translation.x, p.y - b.translation.y);
                    d >= arm.reach.min_radius && d <= arm.reach.max_radius
                }
                _ => false,
            }
    };
    let reachable = |arm: usize, tcp: &Isometry3<f64>| {
        world.reachable(arm, tcp).is_ok()
            && world
                .reachable(
                    arm,
                    &Isometry3::from_parts(
                        Translation3::from(tcp.translation.vector + Vector3::z() * 0.10),
                        tcp.rotation,
                    ),
                )
                .is_ok()
    };
    let graspable = |body: &str| {
        (0..arms).any(|a| {
            grasp_pose(world, a, body)
                .is_some_and(|g| in_annulus(a, &g.translation.vector) && reachable(a, &g))
        })
    };
    let hooks: Vec<String> = snap
        .bodies
        .iter()
        .filter(|b| b.kind == BodyKind::Hook && !b.lost)
        .map(|b| b.name.clone())
        .collect();
    for h in &hooks {
        if !graspable(h) {
            return Some(format!("the hook {h} cannot be grasped"));
        }
    }
    let pullable = |body: &str| {
        let Some(bp) = world.body_pose(body) else {
            return false;
        };
        hooks.iter().any(|h| {
            (0..arms).any(|a| {
                let (Some(base), Some(hp), Some(g)) = (
                    world.arm_base(a),
                    world.body_pose(h),
                    grasp_pose(world, a, h),
                ) else {
                    return false;
                };
                let grip = g.inverse() * hp;
                let (contact, pulled) = pull_hook_poses(&base, &bp, PULL_TARGET_RADIUS);
                // A pull only brings a block nearer: it must end inside the annulus.
                let moved = bp.translation.vector
                    + (pulled.translation.vector - contact.translation.vector);
                in_annulus(a, &moved)
                    && reachable(a, &(contact * grip.inverse()))
                    && reachable(a, &(pulled * grip.inverse()))
            })
        })
    };
    for b in world.block_names() {
        if world.is_lost(b) {
            return Some(format!("block {b} is lost"));
        }
        if !graspable(b) && !pullable(b) {
            return Some(format!(
                "block {b} can be neither grasped nor pulled into reach"
            ));
        }
    }
    None
}

/// The initial scene of Table I task `index` of benchmark `b` at `level`: the first feasible
/// ([`infeasible`]) of up to [`MAX_DRAWS`] draws, draw `d` from seed `mix(task_seed, d)` (draw 0:
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
            mix(task_seed, draw as u64)
        };
        let scene = super::tasks::initial_scene(b, level, seed)?;
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
    mix(seed, (b as u64) << 32 | index as u64)
}

/// Runs Table I: `tasks` initial states per benchmark ([`table1_scene`]), levels L1..L4 in
/// turn; every method runs the closed loop from each state.
pub fn table1(
    benchmarks: &[Benchmark],
    tasks: usize,
    seed: u64,
    params: SessionParams,
    clock: &dyn Clock,
    progress: &mut dyn FnMut(&str),
) -> Result<Table1, SessionError> {
    let mut cells = vec![];
    let mut redrawn = vec![];
    for &b in benchmarks {
        let mut row: Vec<Table1Cell> = TABLE1_METHODS
            .iter()
            .map(|&(method, mode)| Table1Cell {
                benchmark: b,
                method,
                mode,
                successes: 0,
                tasks: 0,
                plan_ms: vec![],
                search_ms: vec![],
                bind_ms: vec![],
                fallbacks: 0,
                actions: vec![],
                failures: vec![],
            })
            .collect();
        for i in 0..tasks {
            let level = Level::ALL[i % 4];
            let task_seed = table1_task_seed(b, i, seed);
            let (scene, draw) = table1_scene(b, level, task_seed)?;
            if draw > 0 {
                redrawn.push(Redraw {
                    benchmark: b,
                    task: i,
                    draws: draw + 1,
                });
            }
            for cell in &mut row {
                let spec = EpisodeSpec {
                    benchmark: b,
                    level: None,
                    method: cell.method,
                    mode: cell.mode,
                    seed: task_seed,
                    scene: Some(scene.clone()),
                };
                let r = run_episode(&spec, params, clock)?;
                cell.tasks += 1;
                if let Some(first) = r.log.replans.first() {
                    cell.plan_ms.push(first.time_ms);
                    cell.search_ms.push(first.time_ms - first.bind_ms);
                    cell.bind_ms.push(first.bind_ms);
                }
                cell.fallbacks += r.log.replans.iter().filter(|p| p.fallback).count();
                if r.success {
                    cell.successes += 1;
                    cell.actions.push(r.actions_executed);
                } else if let Some(reason) = &r.reason {
                    count(&mut cell.failures, reason_kind(reason));
                    progress(&format!(
                        "table1 {} task {i} ({}) {}: failed: {reason}",
                        b.as_str(),
                        level.as_str(),
                        cell.method_label()
                    ));
                }
            }
            progress(&format!("table1 {} task {}/{}", b.as_str(), i + 1, tasks));
        }
        cells.extend(row);
    }
    Ok(Table1 {
        tasks,
        seed,
        cells,
        redrawn,
        tamp_fallback: params.control.tamp_fallback,
    })
}

/// Medians of the search and binding parts of the first plans: `0.21 / 0.09`.
fn fmt_split(search: &[f64], bind: &[f64]) -> String {
    match (stats(search), stats(bind)) {
        (Some((_, _, s)), Some((_, _, b))) => format!("{s:.3} / {b:.3}"),
        _ => "N/A".into(),
    }
}

fn fmt_ms(v: &[f64]) -> String {
    match stats(v) {
        Some((m, sd, med)) => format!("{m:.3} ± {sd:.3} (median {med:.3})"),
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
                "Every first draw was feasible (rule: `experiments::tables::infeasible`, up to {MAX_DRAWS} draws).\n\n"
            ));
        } else {
            out.push_str(&format!(
                "Redrawn as infeasible (rule: `experiments::tables::infeasible`, up to {MAX_DRAWS} draws): {}.\n\n",
                self.redrawn
                    .iter()
                    .map(|r| format!("{} task {} ({} draws)", r.benchmark.as_str().to_uppercase(), r.task, r.draws))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
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

/// One (level, method, benchmark) cell of Table II.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table2Cell {
    /// Level.
    pub level: Level,
    /// Method.
    pub method: Method,
    /// Benchmark.
    pub benchmark: Benchmark,
    /// Execution times of successful trials (s).
    pub times: Vec<f64>,
    /// Trials run.
    pub trials: usize,
    /// Failure reasons seen (kind → count).
    pub failures: Vec<(String, usize)>,
    /// Seeds of the trials.
    pub seeds: Vec<u64>,
    /// Trials in which the level could not be injected (left out of `times` and `failures`).
    #[serde(default)]
    pub not_injected: usize,
    /// Trials whose disturbance hit a moving arm (L1: the approached body moved or the hand
    /// pushed).
    #[serde(default)]
    pub mid_motion: usize,
    /// Per mid-motion L1 trial: the TCP's largest distance from the undisturbed path (mm).
    #[serde(default)]
    pub deviation_mm: Vec<f64>,
    /// Per mid-motion L1 trial with a push: the push (mm).
    #[serde(default)]
    pub push_mm: Vec<f64>,
    /// Per successful trial: simulated time lost against the undisturbed run (s).
    #[serde(default)]
    pub time_lost_s: Vec<f64>,
}

/// Table II.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table2 {
    /// Trials per cell.
    pub trials: usize,
    /// Base seed.
    pub seed: u64,
    /// Cells.
    pub cells: Vec<Table2Cell>,
}

/// The methods of Table II.
pub const TABLE2_METHODS: [Method; 3] = [Method::Linear, Method::Rlds, Method::LogicLfd];

/// Runs Table II: `trials` disturbed episodes per level, method and benchmark.
pub fn table2(
    benchmarks: &[Benchmark],
    trials: usize,
    seed: u64,
    params: SessionParams,
    clock: &dyn Clock,
    progress: &mut dyn FnMut(&str),
) -> Result<Table2, SessionError> {
    let mut cells = vec![];
    for level in Level::ALL {
        for method in TABLE2_METHODS {
            for &b in benchmarks {
                let mut cell = Table2Cell {
                    level,
                    method,
                    benchmark: b,
                    times: vec![],
                    trials: 0,
                    failures: vec![],
                    seeds: vec![],
                    not_injected: 0,
                    mid_motion: 0,
                    deviation_mm: vec![],
                    push_mm: vec![],
                    time_lost_s: vec![],
                };
                for t in 0..trials {
                    let s = seed.wrapping_add(t as u64);
                    let spec = EpisodeSpec {
                        benchmark: b,
                        level: Some(level),
                        method,
                        mode: Mode::Paper,
                        seed: s,
                        scene: None,
                    };
                    let r = run_episode(&spec, params, clock)?;
                    cell.trials += 1;
                    cell.seeds.push(s);
                    record_trial(&mut cell, &r);
                }
                progress(&format!(
                    "table2 {} {} {}: {}/{} succeeded",
                    level.as_str(),
                    method.as_str(),
                    b.as_str(),
                    cell.times.len(),
                    cell.trials
                ));
                cells.push(cell);
            }
        }
    }
    Ok(Table2 {
        trials,
        seed,
        cells,
    })
}

/// Adds trial `r` to `cell`: a trial the level could not be injected into counts apart.
fn record_trial(cell: &mut Table2Cell, r: &super::episode::EpisodeReport) {
    if r.injection.is_none() {
        cell.not_injected += 1;
        return;
    }
    if let Some(m) = &r.motion {
        cell.mid_motion += 1;
        cell.deviation_mm.push(m.deviation_mm);
    }
    if let Some(p) = r.injection.as_ref().and_then(|i| i.push.as_ref()) {
        cell.push_mm.push(p.displacement_mm);
    }
    if r.success {
        cell.times.push(r.execution_s);
        cell.time_lost_s.extend(r.time_lost_s);
    } else if let Some(reason) = &r.reason {
        count(&mut cell.failures, reason_kind(reason));
    }
}

impl Table2 {
    /// Markdown: per level, each method × benchmark as "ours (paper)".
    pub fn markdown(&self) -> String {
        let mut out = String::new();
        out.push_str(&format!(
            "Table II — simulated execution time [s], mean ± sd over the successful trials of {} per cell (seeds {}..{}), [successes/trials the level was injected into]; paper in parentheses; N/A = no successful trial.\n\n",
            self.trials,
            self.seed,
            self.seed + self.trials as u64 - 1
        ));
        let mut benches: Vec<Benchmark> = self.cells.iter().map(|c| c.benchmark).collect();
        benches.dedup();
        benches.sort_by_key(|b| *b as usize);
        benches.dedup();
        out.push_str("| level |");
        for m in TABLE2_METHODS {
            for b in &benches {
                out.push_str(&format!(" {} {} |", m.as_str(), b.as_str().to_uppercase()));
            }
        }
        out.push('\n');
        out.push_str("|---|");
        for _ in 0..TABLE2_METHODS.len() * benches.len() {
            out.push_str("---|");
        }
        out.push('\n');
        for level in Level::ALL {
            out.push_str(&format!("| {} |", level.as_str().to_uppercase()));
            for (mi, m) in TABLE2_METHODS.iter().enumerate() {
                for b in &benches {
                    let cell = self
                        .cells
                        .iter()
                        .find(|c| c.level == level && c.method == *m && c.benchmark == *b);
                    let injected = cell.map_or(0, |c| c.trials - c.not_injected);
                    let ours = match cell.and_then(|c| stats(&c.times)) {
                        Some((mean, sd, _)) => format!(
                            "{mean:.2} ± {sd:.2} [{}/{injected}]",
                            cell.map_or(0, |c| c.times.len()),
                        ),
                        None => format!("N/A [0/{injected}]"),
                    };
                    let paper = PAPER_TABLE2[mi].1[level as usize][*b as usize]
                        .map(|(m, s)| format!("{m:.2} ± {s:.2}"))
                        .unwrap_or_else(|| "N/A".into());
                    out.push_str(&format!(" {ours} ({paper}) |"));
                }
            }
            out.push('\n');
        }
        out.push_str(&self.motion_markdown());
        out.push_str("\nFailure reasons (ours):\n\n");
        for c in &self.cells {
            if !c.failures.is_empty() {
                out.push_str(&format!(
                    "- {} {} {}: {}\n",
                    c.level.as_str().to_uppercase(),
                    c.method.as_str(),
                    c.benchmark.as_str().to_uppercase(),
                    c.failures
                        .iter()
                        .map(|(k, n)| format!("{k} ×{n}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_are_mean_sample_sd_and_median() {
        let (m, sd, med) = stats(&[1.0, 2.0, 3.0, 10.0]).unwrap();
        assert!((m - 4.0).abs() < 1e-12);
        assert!((sd - ((9.0_f64 + 4.0 + 1.0 + 36.0) / 3.0).sqrt()).abs() < 1e-12);
        assert!((med - 2.5).abs() < 1e-12);
        assert!(stats(&[]).is_none());
    }
}
