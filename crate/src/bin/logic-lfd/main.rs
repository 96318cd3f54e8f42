//! `logic-lfd` — the scriptable face of the library (every command and its flags: `logic-lfd --help`).
//!
//! Exit codes: 0 success, 2 bad input, 3 proved unsolvable, 4 budget exhausted, 5 invalid plan.
//! Errors go to stderr as `file:line:col: message`; `--json` output goes to stdout.

mod cmd_bench;
mod cmd_bench_rows;
mod cmd_demo;
mod cmd_fuzz;
mod cmd_lfd;
mod cmd_lfd_perturb;
mod cmd_lqt;
mod cmd_merge;
mod cmd_plan;
mod cmd_robot;
mod cmd_robot_collision;
mod cmd_run;
mod cmd_scene;
mod cmd_soak;
mod cmd_tables;
mod cmd_validate;
mod domain_dir;
mod exit;
mod listed;
mod robot_arg;
mod sweep;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

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
    /// Solve an LQT-CP case (docs/formats.md) and print the output object as JSON.
    Lqt(cmd_lqt::Args),
    /// Replay a plan on a PDDL domain and problem; report the first failing step and why.
    Validate(cmd_validate::Args),
    /// Ground a PDDL task and search for a plan (default: A* with LM-cut, optimal).
    Plan(cmd_plan::Args),
    /// Logic-LfD on any PDDL domain: demonstration states, LogicIn, a new prefix, the merged plan.
    Lfd(cmd_lfd::Args),
    /// Benchmarks: `bench planner` runs planner configurations over IPC folders.
    Bench(cmd_bench::Args),
    /// Inspect and perturb simulator scenes: facts, check, template, problem, disturb.
    Scene(cmd_scene::Args),
    /// One closed-loop episode: a benchmark or a task folder, a disturbance level, a method, a seed.
    Run(cmd_run::Args),
    /// Demonstrations: `demo record` runs a task folder's scripted expert, `demo segment` turns a
    /// raw recording into a demo.json.
    Demo(cmd_demo::Args),
    /// Random closed-loop episodes with random disturbances (B1–B3 or a task folder), checking
    /// every guarantee.
    Soak(cmd_soak::Args),
    /// Mutation fuzzing of an input parser (same mutators and checks as the CI property tests).
    Fuzz(cmd_fuzz::Args),
    /// A robot from its URDF: `robot check` its file, `robot fk` the TCP for a joint vector.
    Robot(cmd_robot::Args),
    /// Join the shard files of a sweep (`--shard K/N` runs) into the whole sweep's report.
    Merge(cmd_merge::Args),
}

/// A closed stdout (`logic-lfd plan … | head`) ends the process quietly, as Unix tools do,
/// instead of printing a panic from `println!`. Every other panic keeps the default report.
fn exit_quietly_on_closed_stdout() {
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(0);
        }
        default_hook(info);
    }));
}

fn main() -> ExitCode {
    exit_quietly_on_closed_stdout();
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
        Command::Lfd(args) => cmd_lfd::run(args),
        Command::Bench(args) => cmd_bench::run(args),
        Command::Scene(args) => cmd_scene::run(args),
        Command::Run(args) => cmd_run::run(args),
        Command::Demo(args) => cmd_demo::run(args),
        Command::Soak(args) => cmd_soak::run(args),
        Command::Fuzz(args) => cmd_fuzz::run(args),
        Command::Merge(args) => cmd_merge::run(args),
        Command::Robot(args) => cmd_robot::run(args),
    }
}
