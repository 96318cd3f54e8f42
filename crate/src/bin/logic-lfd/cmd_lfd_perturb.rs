//! `logic-lfd lfd … --perturb N --seed S`: Logic-LfD against planning from scratch on N
//! disturbed states drawn by seeded random walks ([`LogicLfd::perturb`]).
//!
//! For each state: Logic-LfD (the chosen mode and search), planning to G from scratch with the
//! same search, and A* with LM-cut within `--optimal-time-limit` for the optimal length. Times
//! are wall-clock per call, one run each. Every merged plan is replayed on the lifted domain; one
//! that does not replay makes the study exit 5. The JSON names (`states[i].facts`,
//! `summary.median_lfd_ms`, …) are read by other tools: they may grow, not change.

use std::path::Path;
use std::process::ExitCode;

use logic_lfd::plan::SearchOutcome;
use logic_lfd::prelude::{
    Algorithm, Clock, HeuristicKind, LfdError, LfdPlan, LogicLfd, Mode, Perturbed, SearchConfig,
};

use crate::cmd_plan::{outcome_name, status_name, WallClock};
use crate::exit;

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

/// What the study reports about its configuration.
pub struct Header<'a> {
    /// The domain file.
    pub domain: &'a Path,
    /// The problem file.
    pub problem: &'a Path,
    /// Logic-LfD's mode.
    pub mode: Mode,
    /// The search Logic-LfD and the from-scratch baseline both use.
    pub config: &'a SearchConfig,
    /// JSON on stdout instead of the table.
    pub json: bool,
}

/// One disturbed state and the three planners' results on it.
struct Row {
    drawn: Perturbed,
    facts: Vec<String>,
    logic_in: Option<usize>,
    lfd: Result<LfdPlan, LfdError>,
    lfd_ms: f64,
    /// The merged plan's replay on the lifted domain: `None` without a plan, else the failure
    /// message (empty when valid).
    invalid: Option<String>,
    scratch_status: &'static str,
    scratch_len: Option<usize>,
    scratch_ms: f64,
    scratch_expanded: u64,
    optimal_len: Option<usize>,
}

fn millis(clock: &WallClock) -> f64 {
    clock.now_secs() * 1000.0
}

fn measure(lfd: &LogicLfd, h: &Header, drawn: Perturbed, optimal: &SearchConfig) -> Row {
    let s = &drawn.state;
    let clock = WallClock::start();
    let result = lfd.replan(s, h.mode, h.config, &clock);
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
    let scratch = lfd.plan_from_scratch(s, h.config, &clock);
    let scratch_ms = millis(&clock);
    let scratch_len = scratch.outcome.plan().map(|p| p.len());
    // The baseline already is A* with LM-cut: its plan is optimal, no need to search twice.
    let optimal_len = if h.config.algorithm == optimal.algorithm
        && h.config.heuristic == optimal.heuristic
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
        facts: lfd.names(s),
        logic_in: lfd.logic_in(s),
        lfd: result,
        lfd_ms,
        invalid,
        scratch_status: outcome_name(&scratch.outcome),
        scratch_len,
        scratch_ms,
        scratch_expanded: scratch.stats.expanded,
        optimal_len,
        drawn,
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
        .filter_map(|r| Some((r.lfd.as_ref().ok()?.names.len(), r.optimal_len?)))
        .collect();
    let median_lfd_ms = median(rows.iter().map(|r| r.lfd_ms).collect());
    let median_scratch_ms = median(rows.iter().map(|r| r.scratch_ms).collect());
    Summary {
        lfd_solved: rows.iter().filter(|r| r.lfd.is_ok()).count(),
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

/// Runs the study on `count` states.
pub fn run(lfd: &LogicLfd, h: &Header, count: usize, args: &StudyArgs) -> ExitCode {
    let t = args.optimal_time_limit;
    if t.is_nan() || t < 0.0 {
        eprintln!("--optimal-time-limit: expected a non-negative number of seconds");
        return ExitCode::from(exit::BAD_INPUT);
    }
    let optimal = SearchConfig {
        time_limit_secs: Some(t),
        ..SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut)
    };
    let rows: Vec<Row> = lfd
        .perturb(count, args.seed, args.max_steps)
        .into_iter()
        .map(|drawn| measure(lfd, h, drawn, &optimal))
        .collect();
    let summary = summarise(&rows);
    if h.json {
        println!("{}", json(h, count, args, &rows, &summary));
    } else {
        print_text(h, args, &rows, &summary);
    }
    let mut code = exit::OK;
    for (i, r) in rows.iter().enumerate() {
        if let Err(e @ LfdError::MergeFailed { .. }) = &r.lfd {
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

fn print_text(h: &Header, args: &StudyArgs, rows: &[Row], s: &Summary) {
    println!(
        "{} {}: {} states, seed {}, walks of 1 … {} actions; Logic-LfD ({} mode) and scratch: {} {}",
        h.domain.display(),
        h.problem.display(),
        rows.len(),
        args.seed,
        args.max_steps.max(1),
        h.mode.as_str(),
        h.config.algorithm,
        h.config.heuristic,
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
        let plan = r.lfd.as_ref().ok();
        let k = match &r.lfd {
            Ok(p) => p.k.map_or_else(|| "G".into(), |k| k.to_string()),
            Err(_) => status_name(&r.lfd).into(),
        };
        println!(
            "{:>4} {:>5} {:>4} {:>5} {:>5} {:>4} {:>6} {:>7} {:>7} {:>9.3} {:>10.3}",
            i,
            r.drawn.from_k,
            r.drawn.steps,
            opt(r.logic_in),
            k,
            opt(plan.map(|p| p.prefix_len)),
            opt(plan.map(|p| p.names.len())),
            r.scratch_len
                .map_or_else(|| r.scratch_status.into(), |l| l.to_string()),
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

fn json(
    h: &Header,
    count: usize,
    args: &StudyArgs,
    rows: &[Row],
    s: &Summary,
) -> serde_json::Value {
    let states: Vec<serde_json::Value> = rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let plan = r.lfd.as_ref().ok();
            serde_json::json!({
                "index": i,
                "from_k": r.drawn.from_k,
                "steps": r.drawn.steps,
                "facts": r.facts,
                "logic_in": r.logic_in,
                "k": plan.and_then(|p| p.k),
                "source": plan.map(|p| p.source),
                "prefix_len": plan.map(|p| p.prefix_len),
                "merged_len": plan.map(|p| p.names.len()),
                "valid": r.invalid.as_ref().map(String::is_empty),
                "lfd_status": status_name(&r.lfd),
                "lfd_ms": r.lfd_ms,
                "lfd_expanded": plan.map(|p| p.stats.expanded),
                "scratch_status": r.scratch_status,
                "scratch_len": r.scratch_len,
                "scratch_ms": r.scratch_ms,
                "scratch_expanded": r.scratch_expanded,
                "optimal_len": r.optimal_len,
            })
        })
        .collect();
    serde_json::json!({
        "domain": h.domain.display().to_string(),
        "problem": h.problem.display().to_string(),
        "mode": h.mode.as_str(),
        "search": h.config.algorithm.name(),
        "heuristic": h.config.heuristic.name(),
        "seed": args.seed,
        "count": count,
        "max_steps": args.max_steps,
        "optimal_time_limit": args.optimal_time_limit,
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
