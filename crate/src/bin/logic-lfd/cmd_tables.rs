//! `logic-lfd bench table1 [--tasks 100] [--seed S] [--markdown|--json] [--task-scene I] [--robot R]` and
//! `logic-lfd bench table2 [--trials 10] [--seed S] [--markdown|--json]`: the paper's Tables I
//! and II with our numbers beside the paper's (planning times by the wall clock; run in release).
//! Logic-LfD's TAMP fallback is off unless `--tamp-fallback`. Both take `--threads N` and
//! `--shard K/N` ([`crate::sweep`]).

use std::path::PathBuf;
use std::process::ExitCode;

use logic_lfd::experiments::{
    table1_scene, table1_task_seed, Table1, Table1Sweep, Table2, Table2Sweep,
};
use logic_lfd::lfd::Level;
use logic_lfd::lfd::SessionParams;
use logic_lfd::sim::Benchmark;

use crate::cmd_plan::WallClock;
use crate::exit;
use crate::sweep::{print_shard, SweepArgs};

/// `bench table1`'s name in shard files.
pub const TABLE1: &str = "bench table1";

/// `bench table2`'s name in shard files.
pub const TABLE2: &str = "bench table2";

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
    #[arg(long, conflicts_with = "shard")]
    markdown: bool,
    /// Print JSON (every cell with its raw numbers).
    #[arg(long, conflicts_with = "shard")]
    json: bool,
    /// Print the initial scene JSON of task I of the first benchmark instead (stderr: its level,
    /// seed and draw; replay it with `logic-lfd run --scene FILE --seed SEED --method …`).
    #[arg(long, value_name = "I", conflicts_with_all = ["shard", "threads"])]
    task_scene: Option<usize>,
    /// Let Logic-LfD plan to G from scratch when none of its skeletons binds (its TAMP
    /// fallback; off by default, so the table counts Logic-LfD's own success).
    #[arg(long)]
    tamp_fallback: bool,
    #[arg(long, value_name = "ROBOT", conflicts_with = "shard", help = crate::robot_arg::HELP)]
    robot: Vec<PathBuf>,
    #[command(flatten)]
    sweep: SweepArgs,
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
    #[arg(long, conflicts_with = "shard")]
    markdown: bool,
    /// Print JSON (every cell with its raw numbers).
    #[arg(long, conflicts_with = "shard")]
    json: bool,
    /// Let Logic-LfD plan to G from scratch when none of its skeletons binds (its TAMP
    /// fallback; off by default, so the table counts Logic-LfD's own success).
    #[arg(long)]
    tamp_fallback: bool,
    #[arg(long, value_name = "ROBOT", conflicts_with = "shard", help = crate::robot_arg::HELP)]
    robot: Vec<PathBuf>,
    #[command(flatten)]
    sweep: SweepArgs,
}

fn benchmarks(names: &[String]) -> Result<Vec<Benchmark>, String> {
    names
        .iter()
        .map(|n| {
            Benchmark::parse(n).ok_or_else(|| format!("--benchmarks: unknown benchmark {n:?}"))
        })
        .collect()
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
    let robots = match crate::robot_arg::load_or_exit(&a.robot) {
        Ok(r) => r,
        Err(code) => return code,
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
    let sweep = Table1Sweep {
        benchmarks: bs,
        tasks: a.tasks,
        seed: a.seed,
        tamp_fallback: a.tamp_fallback,
        robots,
    };
    let clock = WallClock::start();
    let indices = a.sweep.indices(sweep.items());
    let tasks = a.sweep.map(&indices, |i| {
        sweep.run(i, SessionParams::default(), &clock, &mut progress)
    });
    match flatten(tasks) {
        Err(code) => code,
        Ok(tasks) => match a.sweep.shard {
            Some(shard) => print_shard(TABLE1, &sweep, sweep.items(), shard, &indices, tasks),
            None => print_table1(&sweep.report(tasks), a.json),
        },
    }
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
    let robots = match crate::robot_arg::load_or_exit(&a.robot) {
        Ok(r) => r,
        Err(code) => return code,
    };
    let sweep = Table2Sweep {
        benchmarks: bs,
        trials: a.trials,
        seed: a.seed,
        tamp_fallback: a.tamp_fallback,
        robots,
    };
    let clock = WallClock::start();
    let indices = a.sweep.indices(sweep.items());
    let trials = a.sweep.map(&indices, |i| {
        sweep.run(i, SessionParams::default(), &clock, &mut progress)
    });
    match flatten(trials) {
        Err(code) => code,
        Ok(trials) => match a.sweep.shard {
            Some(shard) => print_shard(TABLE2, &sweep, sweep.items(), shard, &indices, trials),
            None => print_table2(&sweep.report(trials), a.json),
        },
    }
}

/// The records of a sweep, or the exit code of its error (printed on stderr).
fn flatten<R, E: std::fmt::Display>(records: Result<Vec<R>, E>) -> Result<Vec<R>, ExitCode> {
    records.map_err(|e| {
        eprintln!("{e}");
        ExitCode::from(exit::BAD_INPUT)
    })
}

/// Prints Table I as JSON or markdown.
pub fn print_table1(t: &Table1, json: bool) -> ExitCode {
    print_table(serde_json::to_string(t), t.markdown(), json)
}

/// Prints Table II as JSON or markdown.
pub fn print_table2(t: &Table2, json: bool) -> ExitCode {
    print_table(serde_json::to_string(t), t.markdown(), json)
}

/// Prints a finished table as JSON or markdown.
fn print_table(as_json: serde_json::Result<String>, markdown: String, json: bool) -> ExitCode {
    if json {
        println!("{}", as_json.unwrap_or_default());
    } else {
        print!("{markdown}");
    }
    ExitCode::from(exit::OK)
}
