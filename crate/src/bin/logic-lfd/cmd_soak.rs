//! `logic-lfd soak --episodes N --seed S [--max-disturbances K] [--blocks N | --domain DIR]
//! [--no-replay] [--json] [--threads N] [--shard K/N]` — random
//! closed-loop Logic-LfD episodes over B1–B3, or on a task folder's task in its own scene, with
//! random disturbances (levels L1–L4 and user-like drags), checking world invariants every tick, every adopted plan with the PDDL validator, that
//! refusals change nothing, that every episode succeeds or states a legitimate reason, and that
//! each episode replays byte-identically (see `experiments::soak`).
//!
//! Episodes run on every core (`--threads`) or in shards (`--shard`, joined by `logic-lfd
//! merge`; see [`crate::sweep`]).
//!
//! Exit codes: 0 every guarantee held, 5 a guarantee was broken (the findings say which, with the
//! episode and seed to replay), 2 bad input. A shard exits 0 once its file is written: `merge`
//! gives the sweep's verdict.

use std::process::ExitCode;

use logic_lfd::experiments::{SoakParams, SoakReport, SoakRunner};

use crate::exit;
use crate::sweep::{print_shard, SweepArgs};

/// The command's name in shard files.
pub const COMMAND: &str = "soak";

/// Arguments of `soak`.
#[derive(clap::Args)]
pub struct Args {
    /// Number of random episodes.
    #[arg(long, default_value_t = 20)]
    episodes: usize,
    /// Seed of the soak (every episode's benchmark, mode, seed and disturbances derive from it).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Most disturbances per episode (uniform in 0..=K, at random ticks of the first 25 s).
    #[arg(long, default_value_t = 6)]
    max_disturbances: usize,
    /// Index of the first episode (re-run episode E of a soak alone: `--first-episode E
    /// --episodes 1`).
    #[arg(long, default_value_t = 0)]
    first_episode: usize,
    /// Save the episode JSON of every episode with a finding or a failure accepted as legitimate
    /// to this directory (`soak-<seed>-<episode>.json`; re-run it with `logic-lfd run --replay`).
    #[arg(long)]
    save_findings: Option<std::path::PathBuf>,
    /// Skip the replay-identity check of every episode (halves the run time).
    #[arg(long)]
    no_replay: bool,
    /// Run the generated tower tasks with N blocks instead of the template tasks, on the
    /// benchmarks that take N (`sim::block_range`).
    #[arg(long, help = blocks_help())]
    blocks: Option<usize>,
    /// Soak a task folder's task (domain.pddl, problem.pddl, motions.json, scene.json, and
    /// demo.json or expert.json) instead of the benchmarks': every episode starts in its
    /// scene.json, with the disturbances drawn in it. Shards record the folder's file hashes.
    #[arg(long, conflicts_with = "blocks")]
    domain: Option<std::path::PathBuf>,
    /// Print the report as JSON.
    #[arg(long, conflicts_with = "shard")]
    json: bool,
    #[arg(long, value_name = "ROBOT", help = crate::robot_arg::HELP)]
    robot: Vec<std::path::PathBuf>,
    #[command(flatten)]
    sweep: SweepArgs,
}

/// Help of `--blocks`, with the block counts each benchmark takes.
fn blocks_help() -> String {
    format!(
        "Run the generated tower tasks with N blocks instead of the template tasks, on the \
         benchmarks that take N ({})",
        logic_lfd::sim::block_ranges_text()
    )
}

/// Runs the subcommand.
pub fn run(args: Args) -> ExitCode {
    let params = SoakParams {
        episodes: args.episodes,
        seed: args.seed,
        max_disturbances: args.max_disturbances,
        check_replay: !args.no_replay,
        first_episode: args.first_episode,
        blocks: args.blocks,
        ..SoakParams::default()
    };
    if let Some(dir) = &args.save_findings {
        if let Err(e) = std::fs::create_dir_all(dir) {
            eprintln!("soak: cannot create {}: {e}", dir.display());
            return ExitCode::from(exit::BAD_INPUT);
        }
    }
    let runner = match &args.domain {
        Some(dir) => crate::domain_dir::read(dir).and_then(|f| SoakRunner::in_folder(&params, &f)),
        None => SoakRunner::new(&params),
    };
    let robots = crate::robot_arg::load(&args.robot);
    let runner = match runner.and_then(|r| robots.map(|robots| r.with_robots(robots))) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("soak: {e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    // With the task folder it runs, if any.
    let params = runner.params();
    let indices = args.sweep.indices(params.episodes);
    let episodes = args.sweep.map(&indices, |i| {
        let (ep, json) = runner.episode(i)?;
        if let Some(dir) = &args.save_findings {
            if !ep.findings.is_empty() || !ep.explained.is_empty() {
                let e = params.first_episode + i;
                let name = dir.join(format!("soak-{}-{e}.json", args.seed));
                if let Err(err) = std::fs::write(&name, json) {
                    eprintln!("soak: cannot save {}: {err}", name.display());
                }
            }
        }
        Ok::<_, String>(ep)
    });
    let episodes = match episodes {
        Ok(eps) => eps,
        Err(e) => {
            eprintln!("soak: {e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    match args.sweep.shard {
        Some(shard) => print_shard(COMMAND, params, params.episodes, shard, &indices, episodes),
        None => print_report(&params.report(episodes), args.json),
    }
}

/// Prints a soak's report as JSON or as the summary; the exit code says whether every
/// guarantee held.
pub fn print_report(report: &SoakReport, json: bool) -> ExitCode {
    if json {
        match serde_json::to_string_pretty(report) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("soak: cannot write JSON: {e}");
                return ExitCode::from(exit::BAD_INPUT);
            }
        }
    } else {
        print_summary(report);
    }
    if report.is_clean() {
        ExitCode::from(exit::OK)
    } else {
        ExitCode::from(exit::INVALID_PLAN)
    }
}

fn print_summary(r: &SoakReport) {
    if let Some(robots) = r
        .params
        .as_ref()
        .map(|p| &p.robots)
        .filter(|r| !r.is_empty())
    {
        println!("robots: {}", robots.join(", "));
    }
    println!(
        "episodes {} ({:?}), {} ticks ({:.0} simulated s)",
        r.episodes,
        r.per_benchmark,
        r.ticks,
        r.ticks as f64 * 0.01
    );
    println!(
        "disturbances applied {} (injections {:?}, drags accepted {}); refused: drags {}, injections {}",
        r.disturbances, r.injections, r.drags_accepted, r.drags_refused, r.injections_refused
    );
    println!(
        "invariant checks {}: violations {}; partial applies {}",
        r.invariant_checks, r.invariant_violations, r.partial_applies
    );
    println!(
        "plans validated {}: invalid {}; made by the TAMP fallback {}",
        r.plans_checked, r.invalid_plans, r.tamp_fallbacks
    );
    println!(
        "outcomes: success {}, legitimate failures {:?}, budget exhausted {}, stalls {}, no outcome {}, input errors {}, unexplained {}",
        r.successes,
        r.legitimate_failures,
        r.budget_exhausted,
        r.stalls,
        r.no_outcome,
        r.input_errors,
        r.unexplained_failures
    );
    for x in &r.explained {
        println!(
            "  legitimate: episode {} {} session seed {}: {} ({}): {}",
            x.episode, x.benchmark, x.session_seed, x.reason, x.class, x.proof
        );
    }
    println!(
        "replays checked {}: mismatches {}; panics {}",
        r.replays_checked, r.replay_mismatches, r.panics
    );
    for f in &r.findings {
        println!(
            "  episode {} {} session seed {} tick {}: {}: {}",
            f.episode, f.benchmark, f.session_seed, f.tick, f.kind, f.detail
        );
    }
}
