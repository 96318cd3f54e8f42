//! `logic-lfd validate DOMAIN PROBLEM PLANFILE [--json]`: replays a plan on the lifted domain.
//!
//! Exit 0 valid (`Plan valid, cost N`), 5 invalid (first failing step and why), 2 bad input
//! (`file:line:col: message` on stderr).

use std::path::PathBuf;
use std::process::ExitCode;

use logic_lfd::pddl::{parse_domain, parse_problem, read_source, PddlError};
use logic_lfd::plan::{parse_plan, validate, Outcome};

use crate::exit;

/// Arguments of `validate`.
#[derive(clap::Args)]
pub struct Args {
    /// The PDDL domain file.
    domain: PathBuf,
    /// The PDDL problem file.
    problem: PathBuf,
    /// The plan: one `(action arg …)` per line; `;` comments allowed.
    plan: PathBuf,
    /// Print a JSON report on stdout.
    #[arg(long)]
    json: bool,
}

fn load(args: &Args) -> Result<logic_lfd::plan::ValidationReport, PddlError> {
    let dtext = read_source(&args.domain)?;
    let domain = parse_domain(&dtext, &args.domain.display().to_string())?;
    let ptext = read_source(&args.problem)?;
    let problem = parse_problem(&ptext, &args.problem.display().to_string(), &domain)?;
    let plan_text = read_source(&args.plan)?;
    let plan = parse_plan(&plan_text, &args.plan.display().to_string())?;
    Ok(validate(&domain, &problem, &plan))
}

/// Runs the subcommand.
pub fn run(args: Args) -> ExitCode {
    let report = match load(&args) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    let code = match &report.outcome {
        Outcome::Valid => exit::OK,
        Outcome::Malformed(_) => exit::BAD_INPUT,
        _ => exit::INVALID_PLAN,
    };
    if args.json {
        let mut j = serde_json::json!({
            "valid": report.is_valid(),
            "cost": report.cost,
            "steps_applied": report.steps_applied,
        });
        match &report.outcome {
            Outcome::Valid => {}
            Outcome::Malformed(e) => {
                j["error"] = serde_json::json!({
                    "file": e.file, "line": e.line, "col": e.col, "message": e.message,
                });
            }
            Outcome::PreconditionFalse {
                step,
                action,
                location,
                false_literals,
            } => {
                j["failure"] = serde_json::json!({
                    "kind": "precondition",
                    "step": step,
                    "action": action,
                    "location": location,
                    "false_literals": false_literals,
                });
            }
            Outcome::GoalNotReached { false_literals } => {
                j["failure"] = serde_json::json!({
                    "kind": "goal",
                    "false_literals": false_literals,
                });
            }
        }
        println!("{j}");
        if let Outcome::Malformed(e) = &report.outcome {
            eprintln!("{e}");
        }
    } else if let Outcome::Malformed(e) = &report.outcome {
        eprintln!("{e}");
    } else {
        println!("{report}");
    }
    ExitCode::from(code)
}
