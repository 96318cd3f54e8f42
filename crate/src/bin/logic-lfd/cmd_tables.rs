//! `logic-lfd bench table1 [--tasks 100] [--seed S] [--markdown|--json] [--task-scene I]` and
//! `logic-lfd bench table2 [--trials 10] [--seed S] [--markdown|--json]`: the paper's Tables I
//! and II with our numbers beside the paper's (planning times by the wall clock; run in release).
//! Logic-LfD's TAMP fallback is off unless `--tamp-fallback`.

use std::process::ExitCode;

use logic_lfd::experiments::tables::{table1, table1_scene, table1_task_seed, table2};
use logic_lfd::experiments::Level;
use logic_lfd::lfd::session::{SessionError, SessionParams};
use logic_lfd::sim::benchmark::Benchmark;

use crate::cmd_plan::WallClock;
use crate::exit;

/// Arguments of `bench table1`.
#[derive(clap::Args)]
pub struct Table1Args {
    /// Random initial states per benchmark (levels L1..L4 in turn).
    #[arg(long, default_value_t = 100)]
    tasks: usize,
    /// Seed of the task generator and the episodes.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Benchmarks, comma-separated.
    #[arg(long, default_value = "b1,b2,b3", value_delimiter = ',')]
    benchmarks: Vec<String>,
    /// Print markdown (the default).
    #[arg(long)]
    markdown: bool,
    /// Print JSON (every cell with its raw numbers).
    #[arg(long)]
    json: bool,
    /// Print the initial scene JSON of task I of the first benchmark instead (stderr: its level,
    /// seed and draw; replay it with `logic-lfd run --scene FILE --seed SEED --method …`).
    #[arg(long, value_name = "I")]
    task_scene: Option<usize>,
    /// Let Logic-LfD plan to G from scratch when none of its skeletons binds (its TAMP
    /// fallback; off by default, so the table counts Logic-LfD's own success).
    #[arg(long)]
    tamp_fallback: bool,
}

/// Arguments of `bench table2`.
#[derive(clap::Args)]
pub struct Table2Args {
    /// Trials per level, method and benchmark.
    #[arg(long, default_value_t = 10)]
    trials: usize,
    /// Seed of the first trial (trial i uses seed + i).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Benchmarks, comma-separated.
    #[arg(long, default_value = "b1,b2,b3", value_delimiter = ',')]
    benchmarks: Vec<String>,
    /// Print markdown (the default).
    #[arg(long)]
    markdown: bool,
    /// Print JSON (every cell with its raw numbers).
    #[arg(long)]
    json: bool,
    /// Let Logic-LfD plan to G from scratch when none of its skeletons binds (its TAMP
    /// fallback; off by default, so the table counts Logic-LfD's own success).
    #[arg(long)]
    tamp_fallback: bool,
}

fn benchmarks(names: &[String]) -> Result<Vec<Benchmark>, String> {
    names
        .iter()
        .map(|n| {
            Benchmark::parse(n).ok_or_else(|| format!("--benchmarks: unknown benchmark {n:?}"))
        })
        .collect()
}

/// The session parameters of a table run: the defaults, with Logic-LfD's TAMP fallback as asked.
fn table_params(tamp_fallback: bool) -> SessionParams {
    let mut p = SessionParams::default();
    p.control.tamp_fallback = tamp_fallback;
    p
}

fn progress(line: &str) {
    eprintln!("{line}");
}

/// `bench table1`.
pub fn run_table1(a: Table1Args) -> ExitCode {
    let bs = match benchmarks(&a.benchmarks) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    if let Some(i) = a.task_scene {
        let Some(&b) = bs.first() else {
            eprintln!("--benchmarks: none given");
            return ExitCode::from(exit::BAD_INPUT);
        };
        let level = Level::ALL[i % 4];
        let seed = table1_task_seed(b, i, a.seed);
        return match table1_scene(b, level, seed) {
            Ok((scene, draw)) => {
                eprintln!(
                    "{} task {i}: level {}, episode seed {seed}, draw {draw}",
                    b.as_str(),
                    level.as_str()
                );
                println!("{scene}");
                ExitCode::from(exit::OK)
            }
            Err(e) => {
                eprintln!("{e}");
                ExitCode::from(exit::BAD_INPUT)
            }
        };
    }
    let clock = WallClock::start();
    let mut p = progress;
    let result = table1(
        &bs,
        a.tasks,
        a.seed,
        table_params(a.tamp_fallback),
        &clock,
        &mut p,
    );
    report(
        result.map(|t| (serde_json::to_string(&t), t.markdown())),
        a.json,
    )
}

/// `bench table2`.
pub fn run_table2(a: Table2Args) -> ExitCode {
    let bs = match benchmarks(&a.benchmarks) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    let clock = WallClock::start();
    let mut p = progress;
    let result = table2(
        &bs,
        a.trials,
        a.seed,
        table_params(a.tamp_fallback),
        &clock,
        &mut p,
    );
    report(
        result.map(|t| (serde_json::to_string(&t), t.markdown())),
        a.json,
    )
}

/// Prints a finished table as JSON or markdown, or its error on stderr (exit 2).
fn report(
    table: Result<(serde_json::Result<String>, String), SessionError>,
    json: bool,
) -> ExitCode {
    match table {
        Ok((as_json, markdown)) => {
            if json {
                println!("{}", as_json.unwrap_or_default());
            } else {
                print!("{markdown}");
            }
            ExitCode::from(exit::OK)
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(exit::BAD_INPUT)
        }
    }
}
