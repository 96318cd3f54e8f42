//! `logic-lfd run --benchmark b1|b2|b3 --level l1..l4 --method logic-lfd|linear|rlds|tamp
//! [--mode paper|prioritised] --seed N [--scene SCENE.json] [--blocks N | --domain DIR] [--json]`
//! — one closed-loop episode
//! with a disturbance injected during execution at a seeded time; prints success, actions
//! executed, replans, planning times and simulated execution time; `--json` prints the report
//! with the full episode log (it replays exactly: `logic-lfd run --replay EPISODE.json`).
//!
//! Exit codes: 0 the episode ran (success or not, see the output), 2 bad input, 5 a replay that
//! does not reproduce its log.

use std::path::PathBuf;
use std::process::ExitCode;

use logic_lfd::experiments::{
    run_episode_with, run_episode_with_blocks, EpisodeReport, EpisodeSpec,
};
use logic_lfd::lfd::Level;
use logic_lfd::lfd::{EpisodeLog, Session, SessionParams};
use logic_lfd::lfd::{Method, Mode};
use logic_lfd::sim::Benchmark;

use crate::cmd_plan::WallClock;
use crate::{exit, listed};

/// Arguments of `run`.
#[derive(clap::Args)]
pub struct Args {
    /// Benchmark.
    #[arg(long, default_value = "b1", value_parser = listed::one::<Benchmark>())]
    benchmark: Benchmark,
    /// Disturbance level injected during execution.
    // A qualified `Option`: clap reads `none` as a value, not as a missing flag.
    #[arg(long, default_value = "none", value_parser = listed::or_none::<Level>("No disturbance."))]
    level: ::std::option::Option<Level>,
    /// Method.
    #[arg(long, default_value = "logic-lfd", value_parser = listed::one::<Method>())]
    method: Method,
    /// Multi-goal mode of Logic-LfD.
    #[arg(long, default_value = "paper", value_parser = listed::one::<Mode>())]
    mode: Mode,
    /// Seed of every random choice of the episode.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Initial scene (a world snapshot JSON); default: the benchmark's template scene.
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Run a domain directory of its own (domain.pddl, problem.pddl, demo.json, motions.json,
    /// optional scene.json) in the benchmark's workcell, with the benchmark's disturbances.
    #[arg(long, conflicts_with = "blocks")]
    domain: Option<PathBuf>,
    /// Run the benchmark's generated tower task with N blocks (the counts each benchmark takes
    /// come from `sim::block_range`).
    #[arg(long, help = blocks_help())]
    blocks: Option<usize>,
    /// Print the report and the full episode log as JSON.
    #[arg(long)]
    json: bool,
    /// Replay an episode JSON (the `log` of `--json`, or the whole report) and check it.
    #[arg(long)]
    replay: Option<PathBuf>,
}

/// Help of `--blocks`, with the block counts each benchmark takes.
fn blocks_help() -> String {
    format!(
        "Run the benchmark's generated tower task with N blocks ({})",
        logic_lfd::sim::block_ranges_text()
    )
}

fn bad(msg: String) -> ExitCode {
    eprintln!("{msg}");
    ExitCode::from(exit::BAD_INPUT)
}

/// Runs the subcommand.
pub fn run(args: Args) -> ExitCode {
    if let Some(path) = &args.replay {
        if args.domain.is_some() {
            return bad("--replay replays the shipped benchmarks' episodes; drop --domain".into());
        }
        return replay(path);
    }
    let (benchmark, level, method, mode) = (args.benchmark, args.level, args.method, args.mode);
    let scene = match &args.scene {
        Some(p) => match std::fs::read_to_string(p) {
            Ok(t) => Some(t),
            Err(e) => return bad(format!("{}: {e}", p.display())),
        },
        None => None,
    };
    let spec = EpisodeSpec {
        benchmark,
        level,
        method,
        mode,
        seed: args.seed,
        scene,
    };
    let clock = WallClock::start();
    let sources = match &args.domain {
        Some(dir) => match crate::domain_dir::read(dir, benchmark) {
            Ok(s) => Some(s),
            Err(e) => return bad(e),
        },
        None => None,
    };
    let result = match &sources {
        Some(files) => run_episode_with(&spec, files, SessionParams::default(), &clock),
        None => run_episode_with_blocks(&spec, args.blocks, SessionParams::default(), &clock),
    };
    let report = match result {
        Ok(r) => r,
        Err(e) => {
            if let Some(dir) = &args.domain {
                return bad(in_domain_file(dir, &e.to_string()));
            }
            let file = args
                .scene
                .as_ref()
                .map(|p| format!("{}: ", p.display()))
                .unwrap_or_default();
            return bad(format!("{file}{e}"));
        }
    };
    if args.json {
        match serde_json::to_string(&report) {
            Ok(s) => println!("{s}"),
            Err(e) => return bad(format!("cannot write JSON: {e}")),
        }
    } else {
        print_summary(&spec, &report);
    }
    ExitCode::from(exit::OK)
}

/// An error about a domain directory's demonstration or scene, named by its file
/// (`demo: actions[2]…` → `DIR/demo.json: actions[2]…`).
fn in_domain_file(dir: &std::path::Path, e: &str) -> String {
    for (prefix, name) in [("demo: ", "demo.json"), ("scene: ", "scene.json")] {
        if let Some(rest) = e.strip_prefix(prefix) {
            return format!("{}: {rest}", dir.join(name).display());
        }
    }
    e.to_string()
}

fn print_summary(spec: &EpisodeSpec, r: &EpisodeReport) {
    println!(
        "benchmark {}  level {}  method {}  mode {}  seed {}",
        spec.benchmark.as_str(),
        spec.level.map_or("none", |l| l.as_str()),
        spec.method.as_str(),
        spec.mode.as_str(),
        spec.seed
    );
    if let Some(i) = &r.injection {
        match &i.during {
            Some(a) => println!("disturbance: {} (during {a})", i.description),
            None => println!("disturbance: {}", i.description),
        }
    }
    if let Some(why) = &r.not_injected {
        println!("no disturbance injected: {why}");
    }
    if let Some(m) = &r.motion {
        println!(
            "  absorbed: the TCP left the undisturbed path by at most {:.1} mm; {} took {:+.2} s",
            m.deviation_mm, m.action, m.action_time_lost_s
        );
    }
    if let Some(t) = r.time_lost_s {
        println!("  time lost against the undisturbed run: {t:+.2} s");
    }
    match &r.reason {
        None => println!("success: true"),
        Some(reason) => println!("success: false ({reason})"),
    }
    println!("actions executed: {}", r.actions_executed);
    println!("replans: {} (initial plan included)", r.replans);
    for p in &r.log.replans {
        println!(
            "  t={:.2}s  {:.3} ms  k={}  because {}: {}",
            p.tick as f64 * 0.01,
            p.time_ms,
            p.k.map_or("-".to_string(), |k| k.to_string()),
            p.reason,
            p.plan.join(" ")
        );
    }
    println!("simulated execution time: {:.2} s", r.execution_s);
}

/// The `--json` report as `replay` reads it: its episode log.
#[derive(serde::Deserialize)]
struct Report {
    log: EpisodeLog,
}

fn replay(path: &PathBuf) -> ExitCode {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) => return bad(format!("{}: {e}", path.display())),
    };
    // Accept the whole `--json` report or the bare log; errors name the JSON path and position.
    let value: serde_json::Value = match logic_lfd::sim::parse_json(&text) {
        Ok(v) => v,
        Err(e) => return bad(format!("{}: {e}", path.display())),
    };
    let log = if value.get("log").is_some() {
        logic_lfd::sim::parse_json::<Report>(&text).map(|r| r.log)
    } else {
        logic_lfd::sim::parse_json::<EpisodeLog>(&text)
    };
    let log = match log {
        Ok(l) => l,
        Err(e) => return bad(format!("{}: {e}", path.display())),
    };
    let log_text = serde_json::to_string(&log).unwrap_or_default();
    let replayed = match Session::replay(&log_text) {
        Ok(s) => s.log(),
        Err(e) => return bad(format!("{}: {e}", path.display())),
    };
    if replayed.canonical() == log.canonical() {
        println!(
            "replayed exactly: {} ticks, {} replans, success {}",
            replayed.ticks,
            replayed.replans.len(),
            replayed.result.as_ref().is_some_and(|r| r.success)
        );
        ExitCode::from(exit::OK)
    } else {
        eprintln!("{}: the replay differs from the log", path.display());
        ExitCode::from(exit::INVALID_PLAN)
    }
}
