//! The hot paths timed the same way natively and in WebAssembly (`logic-lfd bench wasm-rows`, the
//! npm package's `benchRows`, `npm run bench:wasm`): the same Rust code on the same inputs, so
//! the ratio of the two timings is the cost of the target alone.
//!
//! Rows: parse + ground + search on IPC problems (A* + LM-cut, lazy GBFS + h_FF), one Logic-LfD
//! replan (the reactive loop's search, A* + LM-cut) per state from seeded disturbed states of
//! B1/B2/B3, the LQT-CP pipeline (T = 100, D = 3, jerk, K = 10 RBF: weights, F, gains, one
//! rollout), one B3 world step with the scene graph, one IK solve, and the replans of the page
//! benchmark's scenario (`page_replans`). Every row runs untimed first, [`RowParams::warmup`]
//! times and for at least [`RowParams::warmup_secs`] (the first run also gives the digest; a
//! JIT-compiled target tiers up its hot code during these: V8 runs wasm in its baseline tier
//! first and compiles a hot function with its optimising tier only after it has run a while, in
//! the background), then
//! repeats its batch at least [`RowParams::min_runs`] and at most [`RowParams::runs`] times
//! (fewer once [`RowParams::budget_secs`] is spent) and keeps the best; the caller's clock
//! times it. Each row also reports a digest of the work done (plan lengths, expansions, facts),
//! so two builds can be checked to have done the same work.

use crate::lfd::ControlParams;
use crate::lfd::{LogicLfd, Method, Mode};
use crate::lfd::{Session, SessionOptions, SkillKind};
use crate::lqt::{build_reference, Target, TargetRole, Tracking};
use crate::lqt::{full_pipeline, Basis, LqtConfig};
use crate::plan::{self, Algorithm, Clock, HeuristicKind, NoClock, SearchConfig, SearchOutcome};
use crate::sim::panda;
use crate::sim::Benchmark;
use crate::sim::{ArmModel, IkParams};
use crate::sim::{GripperCommand, SceneGraph};
use nalgebra::{DMatrix, Isometry3, Translation3};
use serde::{Deserialize, Serialize};

/// Disturbed states per benchmark for the Logic-LfD rows.
pub const DISTURBED_STATES: usize = 20;
/// Seed of the disturbed states (`LogicLfd::perturb`).
pub const DISTURBANCE_SEED: u64 = 1;
/// Longest random walk of a disturbance (the default of `logic-lfd lfd --perturb`).
const DISTURBANCE_STEPS: usize = 8;
/// World steps per timed batch of the simulator row (one step is a few microseconds).
const SIM_STEPS_PER_BATCH: usize = 50;
/// IK targets per timed batch (top grasps over the table, all reachable).
const IK_TARGETS: usize = 64;
/// LQT-CP pipelines per timed batch.
const LQT_PER_BATCH: usize = 10;

/// The PDDL texts of the planning rows (the caller reads the files: wasm has no file system).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct RowInputs {
    /// IPC blocksworld `domain.pddl`.
    pub blocks_domain: String,
    /// `probBLOCKS-8-0.pddl`.
    pub blocks_8: String,
    /// `probBLOCKS-9-0.pddl`.
    pub blocks_9: String,
    /// IPC logistics `domain.pddl`.
    pub logistics_domain: String,
    /// A logistics problem.
    pub logistics: String,
    /// The logistics problem's name, for the row's label (e.g. `probLOGISTICS-10-0`).
    pub logistics_name: String,
}

/// How many times each row runs.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct RowParams {
    /// Untimed warm-up runs before the timed ones (at least one: it gives the digest).
    pub warmup: usize,
    /// Warm-up goes on until this much time is spent too (s): a row of a few microseconds runs
    /// thousands of times before V8 has compiled its hot code with the optimising tier.
    pub warmup_secs: f64,
    /// Timed runs at most (after the warm-up runs).
    pub runs: usize,
    /// Timed runs at least, whatever the budget.
    pub min_runs: usize,
    /// Time per row after which no further run starts once `min_runs` are done (s).
    pub budget_secs: f64,
    /// Only rows whose id contains one of these (all rows when empty).
    pub only: Vec<String>,
}

impl Default for RowParams {
    fn default() -> Self {
        RowParams {
            warmup: 1,
            warmup_secs: 0.0,
            runs: 10,
            min_runs: 3,
            budget_secs: 5.0,
            only: Vec::new(),
        }
    }
}

/// One timed row.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct RowTiming {
    /// Stable identifier, e.g. `astar-lmcut-blocks-9-0`.
    pub id: String,
    /// What was timed, for a table.
    pub label: String,
    /// Best time of one unit of work (ms): the batch's best time divided by `per_batch`.
    pub best_ms: f64,
    /// Units of work per timed batch (e.g. 20 replans).
    pub per_batch: usize,
    /// Timed batches.
    pub runs: usize,
    /// The work done, identical on every target (plan lengths, expansions, facts).
    pub digest: String,
}

/// A row's batch: runs the work once and returns its digest.
type Batch = Box<dyn FnMut() -> Result<String, String>>;

struct Row {
    id: String,
    label: String,
    per_batch: usize,
    batch: Batch,
}

/// Runs every selected row on `clock`; `Err` names the row whose setup or work failed.
pub fn run_rows(
    inputs: &RowInputs,
    params: &RowParams,
    clock: &dyn Clock,
) -> Result<Vec<RowTiming>, String> {
    let selected = |id: &str| params.only.is_empty() || params.only.iter().any(|o| id.contains(o));
    let mut out = Vec::new();
    for row in rows(inputs, &selected)? {
        out.push(time_row(row, params, clock)?);
    }
    if selected("page-replans-b1") {
        out.push(page_replans(params, clock)?);
    }
    Ok(out)
}

/// Disturbances of the page benchmark (tests/e2e/bench.mjs): (simulated time, level).
const PAGE_DISTURBANCES: [(f64, &str); 3] = [(1.0, "l3"), (4.0, "l4"), (7.0, "l3")];
/// Seeds of the page benchmark's runs.
const PAGE_SEEDS: [u64; 3] = [1, 2, 3];

/// The page benchmark's B1 scenario (seeds 1–3; L3 after 1 s, L4 after 4 s, L3 after 7 s of
/// simulated time): every replan's time as the loop logs it (search + binding), each replan's
/// best over the runs (after the warm-up passes), and their median as the row's time.
fn page_replans(params: &RowParams, clock: &dyn Clock) -> Result<RowTiming, String> {
    let pass = || -> Result<Vec<(f64, String)>, String> {
        let mut out = Vec::new();
        for seed in PAGE_SEEDS {
            let mut s = Session::new(SessionOptions {
                benchmark: Benchmark::B1,
                method: Method::LogicLfd,
                mode: Mode::Paper,
                seed,
                skill: SkillKind::Lqt,
                blocks: None,
            })
            .map_err(|e| e.to_string())?;
            let mut pending = PAGE_DISTURBANCES.iter().peekable();
            while s.outcome().is_none() {
                if let Some(&&(t, level)) = pending.peek() {
                    if s.world().time() > t {
                        s.inject(level).map_err(|e| e.to_string())?;
                        pending.next();
                    }
                }
                s.tick_once(clock);
            }
            out.extend(
                s.controller()
                    .replans()
                    .iter()
                    .map(|r| (r.time_ms, format!("{}", r.plan.len()))),
            );
        }
        Ok(out)
    };
    let warm_from = clock.now_secs();
    let first = pass()?;
    let digest = first.iter().map(|(_, n)| n.as_str()).collect::<Vec<_>>();
    let mut warm = 1;
    while warm < params.warmup || clock.now_secs() - warm_from < params.warmup_secs {
        warm += 1;
        if pass()?
            .iter()
            .map(|(_, n)| n.as_str())
            .ne(digest.iter().copied())
        {
            return Err("page-replans-b1: the episodes changed between runs".into());
        }
    }
    let mut best: Vec<f64> = vec![f64::INFINITY; first.len()];
    let started = clock.now_secs();
    let mut runs = 0;
    while runs < params.runs.max(1)
        && (runs < params.min_runs || clock.now_secs() - started < params.budget_secs)
    {
        let p = pass()?;
        if p.iter().map(|(_, n)| n.as_str()).ne(digest.iter().copied()) {
            return Err("page-replans-b1: the episodes changed between runs".into());
        }
        for (b, (ms, _)) in best.iter_mut().zip(&p) {
            *b = b.min(*ms);
        }
        runs += 1;
    }
    best.sort_by(f64::total_cmp);
    Ok(RowTiming {
        id: "page-replans-b1".into(),
        label: format!(
            "the page benchmark's {} B1 replans (search + binding), median of each one's best",
            best.len()
        ),
        best_ms: best.get(best.len() / 2).copied().unwrap_or(f64::NAN),
        per_batch: 1,
        runs,
        digest: format!("{} replans, plan lengths {}", best.len(), digest.join(" ")),
    })
}

fn time_row(mut row: Row, params: &RowParams, clock: &dyn Clock) -> Result<RowTiming, String> {
    let fail = |e: String| format!("{}: {e}", row.id);
    let warm_from = clock.now_secs();
    let digest = (row.batch)().map_err(fail)?;
    let mut warm = 1;
    while warm < params.warmup || clock.now_secs() - warm_from < params.warmup_secs {
        warm += 1;
        let d = (row.batch)().map_err(fail)?;
        if d != digest {
            return Err(fail(format!("work changed between runs: {digest} / {d}")));
        }
    }
    let started = clock.now_secs();
    let mut best = f64::INFINITY;
    let mut runs = 0;
    while runs < params.runs.max(1)
        && (runs < params.min_runs || clock.now_secs() - started < params.budget_secs)
    {
        let t0 = clock.now_secs();
        let d = (row.batch)().map_err(fail)?;
        best = best.min(clock.now_secs() - t0);
        runs += 1;
        if d != digest {
            return Err(fail(format!("work changed between runs: {digest} / {d}")));
        }
    }
    Ok(RowTiming {
        id: row.id,
        label: row.label,
        best_ms: best * 1e3 / row.per_batch as f64,
        per_batch: row.per_batch,
        runs,
        digest,
    })
}

fn rows(inputs: &RowInputs, selected: &dyn Fn(&str) -> bool) -> Result<Vec<Row>, String> {
    let lmcut = SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut);
    let gbfs = SearchConfig::new(Algorithm::LazyGbfs, HeuristicKind::HFf);
    let planning = [
        (
            "astar-lmcut-blocks-8-0",
            "probBLOCKS-8-0",
            &inputs.blocks_domain,
            &inputs.blocks_8,
            &lmcut,
        ),
        (
            "astar-lmcut-blocks-9-0",
            "probBLOCKS-9-0",
            &inputs.blocks_domain,
            &inputs.blocks_9,
            &lmcut,
        ),
        (
            "gbfs-hff-blocks-9-0",
            "probBLOCKS-9-0",
            &inputs.blocks_domain,
            &inputs.blocks_9,
            &gbfs,
        ),
        (
            "gbfs-hff-logistics",
            &inputs.logistics_name,
            &inputs.logistics_domain,
            &inputs.logistics,
            &gbfs,
        ),
    ];
    let mut out = Vec::new();
    for (id, problem_name, domain, problem, config) in planning {
        if selected(id) {
            out.push(plan_row(id, problem_name, domain, problem, config));
        }
    }
    for b in [Benchmark::B1, Benchmark::B2, Benchmark::B3] {
        let id = format!("lfd-replan-{}", b.as_str());
        if selected(&id) {
            out.push(replan_row(id, b)?);
        }
    }
    if selected("lqt-pipeline") {
        out.push(lqt_row()?);
    }
    if selected("sim-b3-step") {
        out.push(sim_row());
    }
    if selected("ik-solve") {
        out.push(ik_row());
    }
    Ok(out)
}

/// Parse + ground + search, as `logic-lfd plan` and the package's `plan()` do.
fn plan_row(id: &str, name: &str, domain: &str, problem: &str, config: &SearchConfig) -> Row {
    let (domain, problem, config) = (domain.to_string(), problem.to_string(), *config);
    Row {
        id: id.to_string(),
        label: format!(
            "plan {name}, {} + {} (parse + ground + search)",
            config.algorithm.name(),
            config.heuristic.name()
        ),
        per_batch: 1,
        batch: Box::new(move || {
            let d = crate::pddl::parse_domain(&domain, "domain.pddl").map_err(|e| e.to_string())?;
            let p = crate::pddl::parse_problem(&problem, "problem.pddl", &d)
                .map_err(|e| e.to_string())?;
            let task = plan::ground(&d, &p).map_err(|e| e.to_string())?;
            let r = plan::search(&task, &config, &NoClock);
            match r.outcome {
                SearchOutcome::Plan(p) => Ok(format!(
                    "cost {}, {} expanded, {} generated",
                    p.cost, r.stats.expanded, r.stats.generated
                )),
                other => Err(format!("no plan: {other:?}")),
            }
        }),
    }
}

/// One replan per disturbed state of the benchmark's template task (the reactive loop's search).
fn replan_row(id: String, b: Benchmark) -> Result<Row, String> {
    let (template, trace) = super::tasks::template_task_for(b, None).map_err(|e| e.to_string())?;
    let lfd = LogicLfd::from_task(template, trace);
    let states: Vec<_> = lfd
        .perturb(DISTURBED_STATES, DISTURBANCE_SEED, DISTURBANCE_STEPS)
        .into_iter()
        .map(|p| p.state)
        .collect();
    let config = ControlParams::default().search;
    Ok(Row {
        id,
        label: format!(
            "Logic-LfD replan, {}, {} disturbed states (per replan)",
            b.as_str().to_uppercase(),
            states.len()
        ),
        per_batch: states.len().max(1),
        batch: Box::new(move || {
            let mut lengths = Vec::with_capacity(states.len());
            for s in &states {
                let p = lfd
                    .replan(s, Mode::Paper, &config, &NoClock)
                    .map_err(|e| e.to_string())?;
                lengths.push(format!("{}+{}", p.prefix_len, p.ops.len() - p.prefix_len));
            }
            Ok(format!("plans {}", lengths.join(" ")))
        }),
    })
}

/// A minimum-jerk-like demonstration of `t_n` samples (the criterion benchmark's).
fn demo(t_n: usize) -> DMatrix<f64> {
    DMatrix::from_fn(t_n, 3, |t, c| {
        let s = t as f64 / (t_n - 1) as f64;
        let e = s * s * (3.0 - 2.0 * s);
        match c {
            0 => -0.3 * (1.0 - e),
            1 => 0.1 * libm::sin(std::f64::consts::PI * e),
            _ => 0.3 - 0.28 * e,
        }
    })
}

/// The DMP-mode pipeline of one skill: T = 100, D = 3, jerk control, K = 10 RBF.
fn lqt_row() -> Result<Row, String> {
    const T: usize = 100;
    let config = LqtConfig {
        dim: 3,
        order: 3,
        dt: 0.01,
        n_steps: T,
        r: 1e-9,
        basis: Basis::rbf_uniform(10, 100.0),
    };
    let tracking = Tracking {
        demo_pos: demo(T),
        weights_per_order: vec![0.0, 0.0, 1e-2],
    };
    let targets = [Target {
        t: T - 1,
        role: TargetRole::Goal,
        pos: vec![0.0, 0.0, 0.02],
        w_pos: 1e6,
        vel: Some(vec![0.0; 3]),
        w_vel: Some(1e3),
    }];
    let (mu, q) = build_reference(&config, &targets, Some(&tracking)).map_err(|e| e.to_string())?;
    let x0 = vec![-0.3, 0.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    Ok(Row {
        id: "lqt-pipeline".into(),
        label: "LQT-CP pipeline, T = 100, D = 3, jerk, K = 10 RBF (weights, gains, rollout)".into(),
        per_batch: LQT_PER_BATCH,
        batch: Box::new(move || {
            let mut last = String::new();
            for _ in 0..LQT_PER_BATCH {
                let (w, _, rollout) =
                    full_pipeline(&config, &mu, &q, &x0).map_err(|e| e.to_string())?;
                last = format!("w {:.9e}, x_T {:?}", w.sum(), rollout.x.row(T - 1).sum());
            }
            Ok(last)
        }),
    })
}

/// B3 world steps with both arms tracking a slow circle (IK every step) and the scene graph.
fn sim_row() -> Row {
    let start = Benchmark::B3.scene();
    let homes: Vec<Isometry3<f64>> = (0..start.arm_names().len())
        .filter_map(|a| start.tcp_pose(a))
        .collect();
    Row {
        id: "sim-b3-step".into(),
        label: "B3 world step (two arms, IK) + scene graph".into(),
        per_batch: SIM_STEPS_PER_BATCH,
        batch: Box::new(move || {
            let mut world = start.clone();
            let mut facts = 0;
            for k in 1..=SIM_STEPS_PER_BATCH {
                // r = 5 cm, 4 s period: both arms keep moving.
                let t = k as f64 * 0.01;
                for (a, h) in homes.iter().enumerate() {
                    let mut p = *h;
                    p.translation.vector.x += 0.05 * libm::cos(t * 1.57) - 0.05;
                    p.translation.vector.y += 0.05 * libm::sin(t * 1.57);
                    world
                        .command_arm(a, p, GripperCommand::Open)
                        .map_err(|e| e.to_string())?;
                }
                world.step();
                facts += SceneGraph::from_world(&world).to_strings().len();
            }
            Ok(format!("{facts} facts"))
        }),
    }
}

/// The IK row's targets: top grasps over the table in front of an arm at the origin, all
/// reachable from the ready pose (also the criterion benchmark's).
pub fn ik_targets() -> Vec<Isometry3<f64>> {
    (0..IK_TARGETS)
        .map(|i| {
            let r = 0.35 + 0.3 * ((i * 37 % 64) as f64 / 64.0);
            let a = -1.2 + 2.4 * ((i * 11 % 64) as f64 / 64.0);
            Isometry3::from_parts(
                Translation3::new(
                    r * libm::cos(a),
                    r * libm::sin(a),
                    0.03 + 0.1 * ((i % 3) as f64),
                ),
                panda::down_orientation(a + 0.3 * ((i % 5) as f64 - 2.0)),
            )
        })
        .collect()
}

/// Top grasps over the table from the ready pose.
fn ik_row() -> Row {
    let base = Isometry3::identity();
    let params = IkParams::default();
    let targets = ik_targets();
    let arm = ArmModel::panda();
    Row {
        id: "ik-solve".into(),
        label: "IK solve, top grasp from the ready pose".into(),
        per_batch: targets.len(),
        batch: Box::new(move || {
            let (mut solved, mut iterations) = (0, 0);
            for t in &targets {
                if let Ok(s) = arm.inverse_kinematics(&base, t, &arm.ready(), &params) {
                    solved += 1;
                    iterations += s.iterations;
                }
            }
            Ok(format!("{solved} solved, {iterations} iterations"))
        }),
    }
}
