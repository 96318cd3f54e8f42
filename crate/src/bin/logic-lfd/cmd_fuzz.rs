//! `logic-lfd fuzz --target pddl|plan|scene|case|episode|world-ops --iterations N --seed S
//! [--max-edits K] [--corpus DIR] [--replay FILE] [--json]` — mutation fuzzing of one input
//! parser with the same mutators and guarantees as the CI property tests
//! (`logic_lfd::experiments::fuzz`), for longer runs.
//!
//! With `--corpus DIR`, every input that panics or breaks a guarantee is saved as
//! `DIR/<target>-<seed>-<index>.<ext>` (turn each into a regression test named after it), and the
//! input being tried is kept in `DIR/<target>.in-progress` until it returns, so an input that
//! aborts the process (a stack overflow) is not lost. `--replay FILE` runs one saved input.
//!
//! Exit codes: 0 no finding, 5 a finding (listed), 2 bad input.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use logic_lfd::experiments::fuzz::{self, FuzzParams, FuzzTarget};

use crate::exit;

/// Elapsed time below which a rate is not divided by the time itself (s).
const MIN_ELAPSED_S: f64 = 1e-9;

/// Arguments of `fuzz`.
#[derive(clap::Args)]
pub struct Args {
    /// Input format: pddl, plan, scene, case, episode, world-ops (or `all`).
    #[arg(long)]
    target: String,
    /// Inputs to try (per target).
    #[arg(long, default_value_t = 10_000)]
    iterations: u64,
    /// Seed of the run (input i is a function of seed and i).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Most edits per input.
    #[arg(long, default_value_t = 4)]
    max_edits: usize,
    /// Directory where failing inputs are saved.
    #[arg(long)]
    corpus: Option<PathBuf>,
    /// Run one saved input instead of a campaign.
    #[arg(long)]
    replay: Option<PathBuf>,
    /// Print the report(s) as JSON.
    #[arg(long)]
    json: bool,
}

/// Runs the subcommand.
pub fn run(args: Args) -> ExitCode {
    let targets: Vec<FuzzTarget> = if args.target == "all" {
        FuzzTarget::ALL.to_vec()
    } else {
        match FuzzTarget::parse(&args.target) {
            Some(t) => vec![t],
            None => {
                eprintln!(
                    "fuzz: unknown target {:?} (pddl, plan, scene, case, episode, world-ops, all)",
                    args.target
                );
                return ExitCode::from(exit::BAD_INPUT);
            }
        }
    };
    if let Some(file) = &args.replay {
        let Ok(input) = std::fs::read_to_string(file) else {
            eprintln!("fuzz: cannot read {}", file.display());
            return ExitCode::from(exit::BAD_INPUT);
        };
        let mut clean = true;
        for t in targets {
            match fuzz::check_catching(t, &input) {
                Ok(v) => println!("{}: {:?}", t.as_str(), v),
                Err((kind, msg)) => {
                    clean = false;
                    println!("{}: {kind}: {msg}", t.as_str());
                }
            }
        }
        return ExitCode::from(if clean { exit::OK } else { exit::INVALID_PLAN });
    }
    if let Some(dir) = &args.corpus {
        if let Err(e) = std::fs::create_dir_all(dir) {
            eprintln!("fuzz: cannot create {}: {e}", dir.display());
            return ExitCode::from(exit::BAD_INPUT);
        }
    }
    let mut clean = true;
    let mut reports = Vec::new();
    for target in targets {
        let params = FuzzParams {
            target,
            iterations: args.iterations,
            seed: args.seed,
            max_edits: args.max_edits,
        };
        let progress = args
            .corpus
            .as_ref()
            .map(|d| d.join(format!("{}.in-progress", target.as_str())));
        let start = Instant::now();
        let mut slowest = (0u64, 0.0f64);
        let mut last: Option<(u64, Instant)> = None;
        let report = fuzz::run(&params, |i, input| {
            if let Some((j, t)) = last {
                let s = t.elapsed().as_secs_f64();
                if s > slowest.1 {
                    slowest = (j, s);
                }
            }
            last = Some((i, Instant::now()));
            if let Some(p) = &progress {
                let _ = std::fs::write(p, input);
            }
        });
        let report = match report {
            Ok(r) => r,
            Err(e) => {
                eprintln!("fuzz: {e}");
                return ExitCode::from(exit::BAD_INPUT);
            }
        };
        if let Some(p) = &progress {
            let _ = std::fs::remove_file(p);
        }
        let secs = start.elapsed().as_secs_f64();
        if let Some(dir) = &args.corpus {
            for f in &report.findings {
                let name = format!(
                    "{}-{}-{}.{}",
                    target.as_str(),
                    args.seed,
                    f.index,
                    target.extension()
                );
                if let Err(e) = std::fs::write(dir.join(&name), &f.input) {
                    eprintln!("fuzz: cannot save {name}: {e}");
                }
            }
        }
        clean &= report.is_clean();
        if !args.json {
            println!(
                "{}: {} inputs in {:.1} s ({:.0}/s; slowest input #{} {:.3} s): accepted {}, refused with a located error {}, findings {}",
                target.as_str(),
                report.inputs,
                secs,
                report.inputs as f64 / secs.max(MIN_ELAPSED_S),
                slowest.0,
                slowest.1,
                report.accepted,
                report.refused,
                report.findings.len()
            );
            for f in &report.findings {
                println!("  #{} {}: {}", f.index, f.kind, f.message);
            }
        }
        reports.push(report);
    }
    if args.json {
        match serde_json::to_string_pretty(&reports) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("fuzz: cannot write JSON: {e}");
                return ExitCode::from(exit::BAD_INPUT);
            }
        }
    }
    ExitCode::from(if clean { exit::OK } else { exit::INVALID_PLAN })
}
