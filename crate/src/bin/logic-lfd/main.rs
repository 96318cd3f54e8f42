//! `logic-lfd` — the scriptable face of the library (contract: DESIGN.md §4).
//!
//! Exit codes: 0 success, 2 bad input, 3 proved unsolvable, 4 budget exhausted, 5 invalid plan.
//! Errors go to stderr as `file:line:col: message`; `--json` output goes to stdout.

mod cmd_bench;
mod cmd_demo;
mod cmd_lqt;
mod cmd_plan;
mod cmd_validate;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Exit codes shared by every subcommand.
#[allow(dead_code)]
mod exit {
    pub const OK: u8 = 0;
    pub const BAD_INPUT: u8 = 2;
    pub const UNSOLVABLE: u8 = 3;
    pub const BUDGET: u8 = 4;
    pub const INVALID_PLAN: u8 = 5;
}

#[derive(Parser)]
#[command(
    name = "logic-lfd",
    version,
    about = "Logic-LfD: plan, validate, LQT-CP skills, closed-loop episodes and the paper's tables"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve an LQT-CP case (shared/lqt-cp-io.md) and print the output object as JSON.
    Lqt(cmd_lqt::Args),
    /// Replay a plan on a PDDL domain and problem; report the first failing step and why.
    Validate(cmd_validate::Args),
    /// Ground a PDDL task and search for a plan (default: A* with LM-cut, optimal).
    Plan(cmd_plan::Args),
    /// Benchmarks: `bench planner` runs planner configurations over IPC folders.
    Bench(cmd_bench::Args),
    /// Demonstrations: `demo segment` turns a raw recording into a demo.json.
    Demo(cmd_demo::Args),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() {
                exit::BAD_INPUT
            } else {
                exit::OK
            };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match cli.command {
        Command::Lqt(args) => cmd_lqt::run(args),
        Command::Validate(a) => cmd_validate::run(a),
        Command::Plan(args) => cmd_plan::run(args),
        Command::Bench(args) => cmd_bench::run(args),
        Command::Demo(args) => cmd_demo::run(args),
    }
}
