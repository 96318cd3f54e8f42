//! `logic-lfd lfd … --perturb N --seed S`: Logic-LfD against planning from scratch on N
//! disturbed states drawn by seeded random walks ([`LogicLfd::perturb`]).
//!
//! For each state: Logic-LfD (the chosen mode and search), planning to G from scratch with the
//! same search, and A* with LM-cut within `--optimal-time-limit` for the optimal length. Times
//! are wall-clock per call, one run each. Every merged plan is replayed on the lifted domain; one
//! that does not replay makes the study exit 5. The JSON names (`states[i].facts`,
//! `summary.median_lfd_ms`, …) are read by other tools: they may grow, not change.
//!
//! The states are drawn first (one random stream); each is then measured on its own, so they
//! run on every core (`--threads`) or in shards (`--shard`, joined by `logic-lfd merge`; see
//! [`crate::sweep`]).

use std::path::Path;
use std::process::ExitCode;

use logic_lfd::lfd::PlanSource;
use logic_lfd::pddl::read_source;
use logic_lfd::plan::SearchOutcome;
use logic_lfd::prelude::{
    Algorithm, Clock, HeuristicKind, LfdError, LogicLfd, Mode, Perturbed, SearchConfig,
};
use serde::{Deserialize, Serialize};

use crate::cmd_plan::{outcome_name, status_name, WallClock};
use crate::exit;
use crate::sweep::{print_shard, SweepArgs};

/// The study's name in shard files.
pub const COMMAND: &str = "lfd --perturb";

/// The study's options (part of `lfd`'s arguments).
#[derive(clap::Args)]
pub struct StudyArgs {
    /// Instead of one state: draw N disturbed states by seeded random walks from demonstration
    /// states and compare Logic-LfD with planning from scratch on each (wall-clock times).
    #[arg(long, value_name = "N", conflicts_with_all = ["state", "after"])]
    pub perturb: Option<usize>,
    /// Seed of the random walks (--perturb).
    #[arg(long, default_value_t = 0, requires = "perturb")]
    pub seed: u64,
    /// Longest random walk, in actions (--perturb).
    #[arg(long, default_value_t = 8, requires = "perturb")]
    pub max_steps: usize,
    /// Seconds A* with LM-cut may take to prove a state's optimal plan length (--perturb).
    #[arg(long, value_name = "SECS", default_value_t = 1.0, requires = "perturb")]
    pub optimal_time_limit: f64,
}

/// The study's configuration, as it is printed and as shard files record it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Study {
    /// The domain file, as given.
    pub domain: String,
    /// The problem file, as given.
    pub problem: String,
    /// The demonstration file, as given.
    pub demo: String,
    /// FNV-1a hash of the three files' texts: the shards of a study read the same files.
    pub inputs: String,
    /// Logic-LfD's mode.
    pub mode: Mode,
    /// The search Logic-LfD and the from-scratch baseline both use.
    pub search: String,
    /// Its heuristic.
    pub heuristic: String,
    /// Its node budget.
    pub max_nodes: Option<u64>,
    /// Its time budget (s).
    pub time_limit: Option<f64>,
    /// Seed of the random walks.
    pub seed: u64,
    /// States drawn.
    pub count: usize,
    /// Longest random walk, in actions.
    pub max_steps: usize,
    /// Seconds A* with LM-cut may take to prove a state's optimal plan length.
    pub optimal_time_limit: f64,
}

/// What the rest of the command line gives the study.
pub struct Given<'a> {
    /// The domain file.
    pub domain: &'a Path,
    /// The problem file.
    pub problem: &'a Path,
    /// The demonstration file.
    pub demo: &'a Path,
    /// Logic-LfD's mode.
    pub mode: Mode,
    /// The search Logic-LfD and the from-scratch baseline both use.
    pub config: &'a SearchConfig,
    /// JSON on stdout instead of the table.
    pub json: bool,
}

/// FNV-1a (64 bits) of `texts`, each followed by a 0xff byte (no UTF-8 text holds one).
fn fnv1a(texts: &[&str]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for t in texts {
        for &b in t.as_bytes().iter().chain([0xff].iter()) {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    }
    format!("fnv1a:{h:016x}")
}

/// One disturbed state and the three planners' results on it (a record of the sweep).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Row {
    /// The demonstration state the walk started from.
    from_k: usize,
    /// Actions walked.
    steps: usize,
    /// The state's fluents.
    facts: Vec<String>,
    logic_in: Option<usize>,
    /// Logic-LfD's plan, if it found one.
    plan: Option<PlanRow>,
    /// `solved`, `unsolvable`, `budget` or `error`.
    lfd_status: String,
    /// The message of a prefix that could not be merged (a bug: exit 5).
    merge_failed: Option<String>,
    lfd_ms: f64,
    /// The merged plan's replay on the lifted domain: `None` without a plan, else the failure
    /// message (empty when valid).
    invalid: Option<String>,
    scratch_status: String,
    scratch_len: Option<usize>,
    scratch_ms: f64,
    scratch_expanded: u64,
    optimal_len: Option<usize>,
}

/// What the study keeps of Logic-LfD's plan.
#[derive(Clone, Debug, Serialize, Deserialize)]
struct PlanRow {
    k: Option<usize>,
    source: PlanSource,
    prefix_len: usize,
    merged_len: usize,
    expanded: u64,
}

fn millis(clock: &WallClock) -> f64 {
    clock.now_secs() * 1000.0
}

fn measure(lfd: &LogicLfd, study: &Configured, drawn: &Perturbed) -> Row {
    let s = &drawn.state;
    let (config, optimal) = (&study.config, &study.optimal);
    let clock = WallClock::start();
    let result = lfd.replan(s, study.mode, config, &clock);
    let lfd_ms = millis(&clock);
    let invalid = result
        .as_ref()
        .ok()
        .map(|p| match lfd.validate(s, &p.names) {
            Ok(r) if r.is_valid() => String::new(),
            Ok(r) => r.to_string(),
            Err(e) => e.to_string(),
        });
    let clock = WallClock::start();
    let scratch = lfd.plan_from_scratch(s, config, &clock);
    let scratch_ms = millis(&clock);
    let scratch_len = scratch.outcome.plan().map(|p| p.len());
    // The baseline already is A* with LM-cut: its plan is optimal, no need to search twice.
    let optimal_len = if config.algorithm == optimal.algorithm
        && config.heuristic == optimal.heuristic
        && scratch_len.is_some()
    {
        scratch_len
    } else {
        let clock = WallClock::start();
        match lfd.plan_from_scratch(s, optimal, &clock).outcome {
            SearchOutcome::Plan(p) => Some(p.len()),
            _ => None,
        }
    };
    Row {
        from_k: drawn.from_k,
        steps: drawn.steps,
        facts: lfd.names(s),
        logic_in: lfd.logic_in(s),
        plan: result.as_ref().ok().map(|p| PlanRow {
            k: p.k,
            source: p.source,
            prefix_len: p.prefix_len,
            merged_len: p.names.len(),
            expanded: p.stats.expanded,
        }),
        lfd_status: status_name(&result).into(),
        merge_failed: match &result {
            Err(e @ LfdError::MergeFailed { .. }) => Some(e.to_string()),
            _ => None,
        },
        lfd_ms,
        invalid,
        scratch_status: outcome_name(&scratch.outcome).into(),
        scratch_len,
        scratch_ms,
        scratch_expanded: scratch.stats.expanded,
        optimal_len,
    }
}

/// The median of `xs` (mean of the middle two for an even count), `None` when empty.
fn median(mut xs: Vec<f64>) -> Option<f64> {
    if xs.is_empty() {
        return None;
    }
    xs.sort_by(f64::total_cmp);
    let m = xs.len() / 2;
    Some(if xs.len() % 2 == 1 {
        xs[m]
    } else {
        (xs[m - 1] + xs[m]) / 2.0
    })
}

/// The study's summary numbers.
struct Summary {
    lfd_solved: usize,
    scratch_solved: usize,
    median_lfd_ms: Option<f64>,
    median_scratch_ms: Option<f64>,
    /// median scratch ms / median Logic-LfD ms.
    speedup: Option<f64>,
    /// Median of merged length / optimal length over the states with both.
    median_length_ratio: Option<f64>,
    /// States with a proved optimum and a merged plan.
    compared: usize,
    /// Of those, how many merged plans have the optimal length.
    merged_optimal: usize,
}

fn summarise(rows: &[Row]) -> Summary {
    let lengths: Vec<(usize, usize)> = rows
        .iter()
        .filter_map(|r| Some((r.plan.as_ref()?.merged_len, r.optimal_len?)))
        .collect();
    let median_lfd_ms = median(rows.iter().map(|r| r.lfd_ms).collect());
    let median_scratch_ms = median(rows.iter().map(|r| r.scratch_ms).collect());
    Summary {
        lfd_solved: rows.iter().filter(|r| r.plan.is_some()).count(),
        scratch_solved: rows.iter().filter(|r| r.scratch_len.is_some()).count(),
        median_lfd_ms,
        median_scratch_ms,
        speedup: median_scratch_ms
            .zip(median_lfd_ms)
            .filter(|&(_, l)| l > 0.0)
            .map(|(s, l)| s / l),
        median_length_ratio: median(
            lengths
                .iter()
                .filter(|&&(_, o)| o > 0)
                .map(|&(m, o)| m as f64 / o as f64)
                .collect(),
        ),
        compared: lengths.len(),
        merged_optimal: lengths.iter().filter(|&&(m, o)| m == o).count(),
    }
}

/// The study's searches, ready to run.
struct Configured {
    mode: Mode,
    config: SearchConfig,
    optimal: SearchConfig,
}

/// Runs the study on `count` states (all, on the threads asked for, or one shard's).
pub fn run(
    lfd: &LogicLfd,
    given: &Given,
    count: usize,
    args: &StudyArgs,
    sweep: &SweepArgs,
) -> ExitCode {
    let (mode, config) = (given.mode, given.config);
    let t = args.optimal_time_limit;
    if t.is_nan() || t < 0.0 {
        eprintln!("--optimal-time-limit: expected a non-negative number of seconds");
        return ExitCode::from(exit::BAD_INPUT);
    }
    let read = |p: &Path| read_source(p).unwrap_or_default();
    let study = Study {
        domain: given.domain.display().to_string(),
        problem: given.problem.display().to_string(),
        demo: given.demo.display().to_string(),
        inputs: fnv1a(&[&read(given.domain), &read(given.problem), &read(given.demo)]),
        mode,
        search: config.algorithm.name().into(),
        heuristic: config.heuristic.name().into(),
        max_nodes: config.max_nodes,
        time_limit: config.time_limit_secs,
        seed: args.seed,
        count,
        max_steps: args.max_steps,
        optimal_time_limit: t,
    };
    let configured = Configured {
        mode,
        config: *config,
        optimal: SearchConfig {
            time_limit_secs: Some(t),
            ..SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut)
        },
    };
    let drawn = lfd.perturb(count, args.seed, args.max_steps);
    let indices = sweep.indices(drawn.len());
    let rows = sweep.map(&indices, |i| {
        Ok::<_, std::convert::Infallible>(measure(lfd, &configured, &drawn[i]))
    });
    let Ok(rows) = rows;
    match sweep.shard {
        Some(shard) => print_shard(COMMAND, &study, drawn.len(), shard, &indices, rows),
        None => print_study(&study, &rows, given.json),
    }
}

/// Prints the study's table (or JSON) from its rows in order; exit 5 when a merged plan
/// could not be made or does not replay.
pub fn print_study(study: &Study, rows: &[Row], json: bool) -> ExitCode {
    let summary = summarise(rows);
    if json {
        println!("{}", to_json(study, rows, &summary));
    } else {
        print_text(study, rows, &summary);
    }
    let mut code = exit::OK;
    for (i, r) in rows.iter().enumerate() {
        if let Some(e) = &r.merge_failed {
            eprintln!("state {i}: {e}");
            code = exit::INVALID_PLAN;
        }
        if let Some(m) = r.invalid.as_ref().filter(|m| !m.is_empty()) {
            eprintln!("state {i}: the merged plan does not replay: {m}");
            code = exit::INVALID_PLAN;
        }
    }
    ExitCode::from(code)
}

fn opt<T: ToString>(x: Option<T>) -> String {
    x.map_or_else(|| "-".into(), |v| v.to_string())
}

fn fixed(x: Option<f64>, digits: usize) -> String {
    x.map_or_else(|| "-".into(), |v| format!("{v:.digits$}"))
}

fn print_text(h: &Study, rows: &[Row], s: &Summary) {
    println!(
        "{} {}: {} states, seed {}, walks of 1 … {} actions; Logic-LfD ({} mode) and scratch: {} {}",
        h.domain,
        h.problem,
        rows.len(),
        h.seed,
        h.max_steps.max(1),
        h.mode.as_str(),
        h.search,
        h.heuristic,
    );
    println!(
        "{:>4} {:>5} {:>4} {:>5} {:>5} {:>4} {:>6} {:>7} {:>7} {:>9} {:>10}",
        "#",
        "from",
        "walk",
        "in",
        "k",
        "new",
        "merged",
        "scratch",
        "optimal",
        "lfd_ms",
        "scratch_ms"
    );
    for (i, r) in rows.iter().enumerate() {
        let plan = r.plan.as_ref();
        let k = match plan {
            Some(p) => p.k.map_or_else(|| "G".into(), |k| k.to_string()),
            None => r.lfd_status.clone(),
        };
        println!(
            "{:>4} {:>5} {:>4} {:>5} {:>5} {:>4} {:>6} {:>7} {:>7} {:>9.3} {:>10.3}",
            i,
            r.from_k,
            r.steps,
            opt(r.logic_in),
            k,
            opt(plan.map(|p| p.prefix_len)),
            opt(plan.map(|p| p.merged_len)),
            r.scratch_len
                .map_or_else(|| r.scratch_status.clone(), |l| l.to_string()),
            opt(r.optimal_len),
            r.lfd_ms,
            r.scratch_ms,
        );
    }
    let n = rows.len();
    println!(
        "solved: Logic-LfD {}/{n}, scratch {}/{n}",
        s.lfd_solved, s.scratch_solved
    );
    println!(
        "median ms: Logic-LfD {}, scratch {}, scratch/Logic-LfD {}",
        fixed(s.median_lfd_ms, 3),
        fixed(s.median_scratch_ms, 3),
        fixed(s.speedup, 1),
    );
    println!(
        "merged/optimal length: median {} over {} states with a proved optimum; merged == optimal in {}",
        fixed(s.median_length_ratio, 3),
        s.compared,
        s.merged_optimal,
    );
}

fn to_json(h: &Study, rows: &[Row], s: &Summary) -> serde_json::Value {
    let states: Vec<serde_json::Value> = rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let plan = r.plan.as_ref();
            serde_json::json!({
                "index": i,
                "from_k": r.from_k,
                "steps": r.steps,
                "facts": r.facts,
                "logic_in": r.logic_in,
                "k": plan.and_then(|p| p.k),
                "source": plan.map(|p| p.source),
                "prefix_len": plan.map(|p| p.prefix_len),
                "merged_len": plan.map(|p| p.merged_len),
                "valid": r.invalid.as_ref().map(String::is_empty),
                "lfd_status": r.lfd_status,
                "lfd_ms": r.lfd_ms,
                "lfd_expanded": plan.map(|p| p.expanded),
                "scratch_status": r.scratch_status,
                "scratch_len": r.scratch_len,
                "scratch_ms": r.scratch_ms,
                "scratch_expanded": r.scratch_expanded,
                "optimal_len": r.optimal_len,
            })
        })
        .collect();
    serde_json::json!({
        "domain": h.domain,
        "problem": h.problem,
        "mode": h.mode.as_str(),
        "search": h.search,
        "heuristic": h.heuristic,
        "seed": h.seed,
        "count": h.count,
        "max_steps": h.max_steps,
        "optimal_time_limit": h.optimal_time_limit,
        "states": states,
        "summary": {
            "lfd_solved": s.lfd_solved,
            "scratch_solved": s.scratch_solved,
            "median_lfd_ms": s.median_lfd_ms,
            "median_scratch_ms": s.median_scratch_ms,
            "speedup": s.speedup,
            "median_length_ratio": s.median_length_ratio,
            "length_compared": s.compared,
            "merged_optimal": s.merged_optimal,
        },
    })
}
