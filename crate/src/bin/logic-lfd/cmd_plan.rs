//! `logic-lfd plan DOMAIN PROBLEM [--search ALG] [--heuristic H] [--max-nodes N] [--time-limit S]
//! [--json]`: grounds a PDDL task and searches it.
//!
//! Prints the plan one `(action arg …)` per line as IPC planners do, then `; cost = N (unit cost)`
//! (or `(general cost)` with `:action-costs`) and a `;` statistics line. Default configuration:
//! A* with LM-cut (optimal). Exit 0 plan found, 3 proved unsolvable, 4 budget exhausted, 2 bad
//! input (`file:line:col: message` on stderr).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use logic_lfd::pddl::{parse_domain, parse_problem, read_source, Domain, Problem};
use logic_lfd::plan::{
    ground, relevant_part, search, Algorithm, Clock, HeuristicEvaluator, HeuristicKind,
    SearchConfig, SearchOutcome, SearchResult, SearchStats, Task,
};

use crate::exit;

/// Arguments of `plan`.
#[derive(clap::Args)]
pub struct Args {
    /// The PDDL domain file.
    domain: PathBuf,
    /// The PDDL problem file.
    problem: PathBuf,
    #[command(flatten)]
    search: SearchArgs,
    /// Print a JSON object on stdout instead of the plan text.
    #[arg(long)]
    json: bool,
}

/// The search options every planning command takes (`plan`, `lfd`), so they read the same.
#[derive(clap::Args)]
pub struct SearchArgs {
    /// Search algorithm: bfs|ucs|astar|gbfs|lazy-gbfs.
    #[arg(long, default_value = "astar")]
    search: Algorithm,
    /// Heuristic: blind|hmax|hadd|hff|lmcut (ignored by bfs and ucs).
    #[arg(long, default_value = "lmcut")]
    heuristic: HeuristicKind,
    /// Maximum number of expanded states.
    #[arg(long)]
    max_nodes: Option<u64>,
    /// Maximum search time in seconds.
    #[arg(long)]
    time_limit: Option<f64>,
}

impl SearchArgs {
    /// The search configuration, or the message for a time limit that is not a number of
    /// seconds (clap reads `NaN` and negative numbers as `f64`).
    pub fn config(&self) -> Result<SearchConfig, String> {
        if self.time_limit.is_some_and(|t| t.is_nan() || t < 0.0) {
            return Err("--time-limit: expected a non-negative number of seconds".into());
        }
        Ok(SearchConfig {
            algorithm: self.search,
            heuristic: self.heuristic,
            max_nodes: self.max_nodes,
            time_limit_secs: self.time_limit,
        })
    }
}

/// Wall-clock time for search budgets (the CLI side of [`Clock`]).
pub struct WallClock(Instant);

impl WallClock {
    /// A clock whose origin is now.
    pub fn start() -> Self {
        WallClock(Instant::now())
    }
}

impl Clock for WallClock {
    fn now_secs(&self) -> f64 {
        self.0.elapsed().as_secs_f64()
    }
}

/// Parses and grounds a domain/problem pair; the error is the located message.
pub fn load(domain: &Path, problem: &Path) -> Result<(Domain, Problem, Task), String> {
    let dtext = read_source(domain).map_err(|e| e.to_string())?;
    let d = parse_domain(&dtext, &domain.display().to_string()).map_err(|e| e.to_string())?;
    let ptext = read_source(problem).map_err(|e| e.to_string())?;
    let p = parse_problem(&ptext, &problem.display().to_string(), &d).map_err(|e| e.to_string())?;
    let t = ground(&d, &p).map_err(|e| e.to_string())?;
    Ok((d, p, t))
}

/// The exit code of a search outcome.
pub fn outcome_code(o: &SearchOutcome) -> u8 {
    match o {
        SearchOutcome::Plan(_) => exit::OK,
        SearchOutcome::Unsolvable => exit::UNSOLVABLE,
        SearchOutcome::BudgetExhausted { .. } => exit::BUDGET,
    }
}

/// `solved`, `unsolvable` or `budget`.
pub fn outcome_name(o: &SearchOutcome) -> &'static str {
    match o {
        SearchOutcome::Plan(_) => "solved",
        SearchOutcome::Unsolvable => "unsolvable",
        SearchOutcome::BudgetExhausted { .. } => "budget",
    }
}

/// Runs the subcommand.
pub fn run(args: Args) -> ExitCode {
    let config = match args.search.config() {
        Ok(c) => c,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    let clock = WallClock::start();
    let task = match load(&args.domain, &args.problem) {
        Ok((_, _, t)) => t,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    let r = search(&task, &config, &clock);
    let total = clock.now_secs();
    if args.json {
        println!("{}", json(&task, &config, &r, total));
    } else {
        print_text(&task, &config, &r);
    }
    ExitCode::from(outcome_code(&r.outcome))
}

/// The `;` statistics line printed under a plan.
pub fn stats_line(config: &SearchConfig, s: &SearchStats) -> String {
    format!(
        "; {} {}: expanded {}, generated {}, evaluated {}, search time {:.3} s",
        config.algorithm, config.heuristic, s.expanded, s.generated, s.evaluated, s.time_secs
    )
}

/// `unit cost` or `general cost` (`:action-costs`), the kind printed after `; cost = N`.
pub fn cost_kind(task: &Task) -> &'static str {
    if task.uses_costs {
        "general cost"
    } else {
        "unit cost"
    }
}

fn print_text(task: &Task, config: &SearchConfig, r: &SearchResult) {
    let stats = stats_line(config, &r.stats);
    match &r.outcome {
        SearchOutcome::Plan(p) => {
            for name in p.names(task) {
                println!("{name}");
            }
            println!("; cost = {} ({})", p.cost, cost_kind(task));
            println!("{stats}");
        }
        SearchOutcome::Unsolvable => {
            eprintln!("no plan: the task is unsolvable (reachable state space exhausted)");
            eprintln!("{stats}");
        }
        SearchOutcome::BudgetExhausted { which } => {
            eprintln!("no plan: {which} exhausted");
            eprintln!("{stats}");
        }
    }
}

fn json(task: &Task, config: &SearchConfig, r: &SearchResult, total: f64) -> serde_json::Value {
    let s = &r.stats;
    let plan = r.outcome.plan();
    let mut j = serde_json::json!({
        "status": outcome_name(&r.outcome),
        "plan": plan.map(|p| p.names(task)),
        "cost": plan.map(|p| p.cost),
        "length": plan.map(|p| p.len()),
        "expanded": s.expanded,
        "generated": s.generated,
        "evaluated": s.evaluated,
        "time_secs": s.time_secs,
        "total_secs": total,
        "search": config.algorithm.name(),
        "heuristic": config.heuristic.name(),
        // The heuristic's value of the initial state (null: a dead end), as Fast Downward
        // prints "Initial heuristic value".
        "initial_h": HeuristicEvaluator::for_search(
            task,
            std::slice::from_ref(&task.goal),
            config.heuristic,
            &task.init,
        )
        .value(&task.init),
    });
    // What the search ran on: the facts and operators the goal depends on (`relevant_part`).
    let rel = relevant_part(task);
    j["facts"] = task.facts.len().into();
    j["operators"] = task.operators.len().into();
    j["relevant_facts"] = rel
        .as_ref()
        .map_or(task.facts.len(), |r| r.facts.len())
        .into();
    j["relevant_operators"] = rel
        .as_ref()
        .map_or(task.operators.len(), |r| r.operators.len())
        .into();
    if let SearchOutcome::BudgetExhausted { which } = &r.outcome {
        j["budget"] = serde_json::Value::from(which.to_string());
    }
    j
}

/// `solved`, `unsolvable`, `budget` (as `plan`), or `error` for a prefix that does not merge.
pub fn status_name(r: &Result<logic_lfd::lfd::LfdPlan, logic_lfd::lfd::LfdError>) -> &'static str {
    match r {
        Ok(_) => "solved",
        Err(logic_lfd::lfd::LfdError::NoPlan(_)) => "unsolvable",
        Err(logic_lfd::lfd::LfdError::Budget(_)) => "budget",
        Err(_) => "error",
    }
}
