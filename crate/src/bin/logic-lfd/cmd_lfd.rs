//! `logic-lfd lfd DOMAIN PROBLEM DEMO.plan [--state FACTS | --after PREFIX] [--mode M]
//! [--search ALG] [--heuristic H] [--max-nodes N] [--time-limit S] [--json]`: symbolic
//! Logic-LfD on any PDDL domain (DESIGN.md §4).
//!
//! The demonstration's states L_0 … L_N are derived by applying its actions. From the current
//! state S_C (the problem's initial state, a facts file, or the state a plan prefix reaches)
//! LogicIn takes the largest k with L_k ⊆ S_C (and, with negative preconditions, none of the facts
//! the rest of the demonstration needs false) and the plan is a_{k+1} … a_N; otherwise one
//! multi-goal search plans a new prefix to some L_k (or to G) and the rest of the demonstration
//! follows. Every merged plan is replayed on the lifted domain before it is printed, so a
//! grounding or merging bug cannot pass as a plan. Exit codes as `plan`: 0 plan, 2 bad input,
//! 3 proved unsolvable, 4 budget exhausted; 5 for a merged plan that does not replay.
//! `--perturb N` runs the perturbation study of [`crate::cmd_lfd_perturb`] instead.

use logic_lfd::pddl::Source;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use logic_lfd::pddl::read_source;
use logic_lfd::prelude::{
    Clock, LfdError, LfdPlan, LogicLfd, Mode, Observed, PlanSource, SearchConfig,
};

use crate::cmd_lfd_perturb::{self, StudyArgs};
use crate::cmd_plan::{cost_kind, stats_line, status_name, SearchArgs, WallClock};
use crate::exit;
use crate::sweep::SweepArgs;

/// Arguments of `lfd`.
#[derive(clap::Args)]
#[command(
    after_help = "Times (`time_secs`, `total_secs`, the study's `*_ms`) are wall-clock, \
one run per call. With --perturb, each drawn state runs Logic-LfD, planning to G from scratch \
with the same search, and A* with LM-cut within --optimal-time-limit (the optimal length); the \
medians are over all drawn states."
)]
pub struct Args {
    /// The PDDL domain file.
    domain: PathBuf,
    /// The PDDL problem file (its `:init` is S_C unless --state or --after is given).
    problem: PathBuf,
    /// The demonstration: one `(action arg …)` per line, `;` comments allowed.
    demo: PathBuf,
    /// S_C as PDDL atoms (fluents; the problem's static facts may be listed or left out).
    #[arg(long, value_name = "FACTS_FILE", conflicts_with = "after")]
    state: Option<PathBuf>,
    /// S_C as the state a plan prefix reaches from the problem's initial state.
    #[arg(long, value_name = "PLAN_PREFIX")]
    after: Option<PathBuf>,
    /// Multi-goal mode.
    #[arg(long, default_value = "paper", value_parser = crate::listed::one::<Mode>())]
    mode: Mode,
    #[command(flatten)]
    search: SearchArgs,
    /// Print a JSON object on stdout instead of the annotated plan.
    #[arg(long, conflicts_with = "shard")]
    json: bool,
    #[command(flatten)]
    study: StudyArgs,
    #[command(flatten)]
    sweep: SweepArgs,
}

/// Reads the domain, the problem and the demonstration; the error is the located message
/// (`file:line:col: message`, or the demonstration step and its false precondition).
pub fn load_lfd(domain: &Path, problem: &Path, demo: &Path) -> Result<LogicLfd, String> {
    let read = |p: &Path| {
        read_source(p)
            .map(|text| Source::new(p.display().to_string(), text))
            .map_err(|e| e.to_string())
    };
    let (d, p, m) = (read(domain)?, read(problem)?, read(demo)?);
    LogicLfd::named(&d, &p, &m).map_err(|e| e.to_string())
}

/// The exit code of a failed Logic-LfD call: a plan that cannot be merged is a bug, like an
/// invalid one; everything that is not a search outcome is bad input.
pub fn error_code(e: &LfdError) -> u8 {
    match e {
        LfdError::NoPlan(_) => exit::UNSOLVABLE,
        LfdError::Budget(_) => exit::BUDGET,
        LfdError::MergeFailed { .. } => exit::INVALID_PLAN,
        _ => exit::BAD_INPUT,
    }
}

/// S_C (with the instance it is a state of) and what it was read from.
struct Current<'a> {
    observed: Observed<'a>,
    origin: String,
}

fn current_state<'a>(lfd: &'a LogicLfd, args: &Args) -> Result<Current<'a>, String> {
    let read = |p: &Path| read_source(p).map_err(|e| e.to_string());
    let file = |p: &Path| p.display().to_string();
    if let Some(path) = &args.state {
        let observed = lfd
            .state_in(&file(path), &read(path)?)
            .map_err(|e| e.to_string())?;
        Ok(Current {
            observed,
            origin: file(path),
        })
    } else if let Some(path) = &args.after {
        let state = lfd
            .state_after(&file(path), &read(path)?)
            .map_err(|e| e.to_string())?;
        Ok(Current {
            observed: lfd.observed(state),
            origin: format!("after {}", file(path)),
        })
    } else {
        Ok(Current {
            observed: lfd.observed(lfd.task().init.clone()),
            origin: "the problem's initial state".into(),
        })
    }
}

/// Runs the subcommand.
pub fn run(args: Args) -> ExitCode {
    let clock = WallClock::start();
    if args.study.perturb.is_none() && (args.sweep.threads.is_some() || args.sweep.shard.is_some())
    {
        return bad_input("--threads, --shard: they split the study's states; give --perturb N");
    }
    let config = match args.search.config() {
        Ok(c) => c,
        Err(e) => return bad_input(&e),
    };
    let lfd = match load_lfd(&args.domain, &args.problem, &args.demo) {
        Ok(l) => l,
        Err(e) => return bad_input(&e),
    };
    if let Some(count) = args.study.perturb {
        let given = cmd_lfd_perturb::Given {
            domain: &args.domain,
            problem: &args.problem,
            demo: &args.demo,
            mode: args.mode,
            config: &config,
            json: args.json,
        };
        return cmd_lfd_perturb::run(&lfd, &given, count, &args.study, &args.sweep);
    }

    let current = match current_state(&lfd, &args) {
        Ok(c) => c,
        Err(e) => return bad_input(&e),
    };
    let observed = &current.observed;
    let logic_in = observed.logic_in();
    let result = observed.replan(args.mode, &config, &clock);
    let total = clock.now_secs();
    let report = match &result {
        Ok(p) => match observed.validate(&p.names) {
            Ok(r) => Some(r),
            Err(e) => return bad_input(&e.to_string()),
        },
        Err(_) => None,
    };
    let valid = report.as_ref().map(|r| r.is_valid());
    let run = Run {
        lfd: &lfd,
        current: &current,
        logic_in,
        result: &result,
        valid,
    };
    if args.json {
        println!("{}", json(&run, args.mode, &config, total));
    } else {
        print_text(&run, args.mode, &config);
    }
    if let Some(r) = report.filter(|r| !r.is_valid()) {
        eprintln!("the merged plan does not replay from S_C: {r}");
        return ExitCode::from(exit::INVALID_PLAN);
    }
    match &result {
        Ok(_) => ExitCode::from(exit::OK),
        Err(e) => {
            if !args.json {
                eprintln!("{e}");
            }
            ExitCode::from(error_code(e))
        }
    }
}

fn bad_input(message: &str) -> ExitCode {
    eprintln!("{message}");
    ExitCode::from(exit::BAD_INPUT)
}

/// One Logic-LfD call and what it was called on, as printed.
struct Run<'a> {
    lfd: &'a LogicLfd,
    current: &'a Current<'a>,
    logic_in: Option<usize>,
    result: &'a Result<LfdPlan, LfdError>,
    valid: Option<bool>,
}

/// A state's fluents on one line: the atoms separated by spaces.
fn atoms<'a>(facts: impl IntoIterator<Item = &'a String>) -> String {
    facts
        .into_iter()
        .map(String::as_str)
        .collect::<Vec<_>>()
        .join(" ")
}

/// L_k as a change of L_{k-1}: `-(removed) … +(added) …`, one short line per demonstration step.
fn delta(before: &BTreeSet<String>, after: &BTreeSet<String>) -> String {
    let removed = before.difference(after).map(|f| format!("-{f}"));
    let added = after.difference(before).map(|f| format!("+{f}"));
    let change: Vec<String> = removed.chain(added).collect();
    if change.is_empty() {
        "(unchanged)".into()
    } else {
        change.join(" ")
    }
}

/// Everything but the plan's actions is a `;` comment, so the output stays an IPC plan file.
fn print_text(run: &Run, mode: Mode, config: &SearchConfig) {
    let lfd = run.lfd;
    let n = lfd.demo_actions().len();
    let states = lfd.demo_states();
    println!("; demonstration: {n} actions a_1 … a_{n}, states L_0 … L_{n} (fluents)");
    for (k, l) in states.iter().enumerate() {
        match k.checked_sub(1) {
            None => println!("; L_0 {}", atoms(l)),
            Some(j) => {
                println!(";   a_{k} {}", lfd.demo_actions()[j]);
                println!("; L_{k} = L_{j} {}", delta(&states[j], l));
            }
        }
    }
    let names = run.current.observed.names();
    println!("; S_C ({}): {}", run.current.origin, atoms(&names));
    if run.current.observed.is_regrounded() {
        println!("; S_C holds facts the problem's task cannot: re-grounded with S_C as its :init");
    }
    match run.logic_in {
        Some(k) => println!("; LogicIn: L_{k} ⊆ S_C"),
        None => println!("; LogicIn: no L_k ⊆ S_C that the rest of the demonstration runs from"),
    }
    let p = match run.result {
        Ok(p) => p,
        Err(_) => return,
    };
    let rest = |k: usize| {
        if k < n {
            format!("then the demonstration's a_{} … a_{n}", k + 1)
        } else {
            "the demonstration's end".to_string()
        }
    };
    match (p.source, p.k) {
        (PlanSource::GoalHolds, _) => println!("; matched: G holds in S_C, the plan is empty"),
        (PlanSource::LogicIn, Some(k)) => println!("; matched: L_{k} by LogicIn, {}", rest(k)),
        (_, Some(k)) => println!(
            "; matched: L_{k} by one multi-goal search ({} mode), {}",
            mode.as_str(),
            rest(k)
        ),
        (_, None) => println!(
            "; matched: G directly, by one multi-goal search ({} mode)",
            mode.as_str()
        ),
    }
    if let Some(l) = p.k.and_then(|k| Some((k, states.get(k)?))) {
        println!("; L_{} {}", l.0, atoms(l.1));
    }
    println!("; new prefix: {} actions", p.prefix_len);
    for a in p.prefix() {
        println!("{a} ; new");
    }
    let first = p.k.map_or(0, |k| k + 1);
    for (i, a) in p.suffix().iter().enumerate() {
        println!("{a} ; demo a_{}", first + i);
    }
    println!("; cost = {} ({})", p.cost, cost_kind(lfd.task()));
    match run.valid {
        Some(true) => println!("; replayed from S_C on the lifted domain: valid"),
        _ => println!("; replayed from S_C on the lifted domain: NOT valid"),
    }
    println!("{}", stats_line(config, &p.stats));
}

fn json(run: &Run, mode: Mode, config: &SearchConfig, total: f64) -> serde_json::Value {
    let lfd = run.lfd;
    let plan = run.result.as_ref().ok();
    let demo_states: Vec<Vec<&String>> = lfd
        .demo_states()
        .iter()
        .map(|l| l.iter().collect())
        .collect();
    let mut j = serde_json::json!({
        "status": status_name(run.result),
        "demo_states": demo_states,
        "demo_actions": lfd.demo_actions(),
        "state": run.current.observed.names(),
        "regrounded": run.current.observed.is_regrounded(),
        "logic_in": run.logic_in,
        "k": plan.and_then(|p| p.k),
        "source": plan.map(|p| p.source),
        "prefix": plan.map(LfdPlan::prefix),
        "suffix": plan.map(LfdPlan::suffix),
        "plan": plan.map(|p| &p.names),
        "cost": plan.map(|p| p.cost),
        "length": plan.map(|p| p.names.len()),
        "valid": run.valid,
        "expanded": plan.map(|p| p.stats.expanded),
        "generated": plan.map(|p| p.stats.generated),
        "evaluated": plan.map(|p| p.stats.evaluated),
        "time_secs": plan.map(|p| p.stats.time_secs),
        "total_secs": total,
        "search": config.algorithm.name(),
        "heuristic": config.heuristic.name(),
        "mode": mode.as_str(),
    });
    match run.result {
        Err(LfdError::Budget(which)) => j["budget"] = which.to_string().into(),
        Err(e) => j["message"] = e.to_string().into(),
        Ok(_) => {}
    }
    j
}
