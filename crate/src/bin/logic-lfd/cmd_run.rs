//! `logic-lfd run [--benchmark b1|b2|b3 | --domain DIR] --level l1..l4
//! --method logic-lfd|linear|rlds|tamp [--mode paper|prioritised] --seed N [--scene SCENE.json]
//! [--blocks N] [--json]` — one closed-loop episode with a disturbance injected during execution
//! at a seeded time; prints success, actions executed, replans, planning times and simulated
//! execution time; `--json` prints the report with the full episode log (it replays exactly:
//! `logic-lfd run --replay EPISODE.json [--domain DIR]`).
//!
//! `--robot ROBOT.json` runs the episode on a robot read from its URDF (twice: one per arm).
//!
//! `--domain DIR` runs a task folder (`sim::TaskFolder`): its own scene, and the disturbances
//! drawn in it.
//!
//! Exit codes: 0 the episode ran (success or not, see the output), 2 bad input, 5 a replay that
//! does not reproduce its log.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use logic_lfd::experiments::{
    run_episode_with, run_episode_with_blocks, EpisodeReport, EpisodeSpec,
};
use logic_lfd::lfd::Level;
use logic_lfd::lfd::{EpisodeLog, Session, SessionParams};
use logic_lfd::lfd::{Method, Mode};
use logic_lfd::sim::ArmModel;
use logic_lfd::sim::{Benchmark, TaskFolder};
use std::sync::Arc;

use crate::cmd_plan::WallClock;
use crate::{exit, listed};

/// Arguments of `run`.
#[derive(clap::Args)]
pub struct Args {
    /// Benchmark (default: b1). Not with --domain: a task folder's own scene and the
    /// disturbances drawn in it define the episode.
    #[arg(long, value_parser = listed::one::<Benchmark>())]
    benchmark: Option<Benchmark>,
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
    /// Initial scene (a world snapshot JSON); default: the benchmark's template scene, or the
    /// task folder's scene.json.
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Run a task folder (domain.pddl, problem.pddl, motions.json, scene.json, and demo.json or
    /// expert.json) with the disturbances drawn in its own scene. With --replay: the folder the
    /// episode ran on, when its log does not carry the files.
    #[arg(long, conflicts_with = "blocks")]
    domain: Option<PathBuf>,
    /// Run the benchmark's generated tower task with N blocks (the counts each benchmark takes
    /// come from `sim::block_range`).
    #[arg(long, help = blocks_help())]
    blocks: Option<usize>,
    /// Print the report and the full episode log as JSON.
    #[arg(long)]
    json: bool,
    #[arg(long, value_name = "ROBOT", help = crate::robot_arg::HELP)]
    robot: Vec<PathBuf>,
    /// Replay an episode JSON (the `log` of `--json`, or the whole report) and check it. A task
    /// folder's episode replays on the files its log carries, else on --domain DIR, else on the
    /// folder it recorded; a file that differs from the episode's is named.
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
    let robots = match crate::robot_arg::load(&args.robot) {
        Ok(r) => r,
        Err(e) => return bad(e),
    };
    if let Some(path) = &args.replay {
        return replay(path, args.domain.as_deref(), &robots);
    }
    if let (Some(b), Some(dir)) = (args.benchmark, &args.domain) {
        return bad(format!(
            "--benchmark {} --domain {}: a task folder's own scene and the disturbances drawn in \
             it define the episode; drop --benchmark",
            b.as_str(),
            dir.display()
        ));
    }
    let folder = match &args.domain {
        Some(dir) => match crate::domain_dir::read(dir) {
            Ok(f) => Some(f),
            Err(e) => return bad(e),
        },
        None => None,
    };
    let scene = match &args.scene {
        Some(p) => match std::fs::read_to_string(p) {
            Ok(t) => Some(t),
            Err(e) => return bad(format!("{}: {e}", p.display())),
        },
        None => None,
    };
    let spec = EpisodeSpec {
        benchmark: args.benchmark.unwrap_or(Benchmark::B1),
        level: args.level,
        method: args.method,
        mode: args.mode,
        seed: args.seed,
        scene,
        robots,
    };
    let clock = WallClock::start();
    let sources = match &folder {
        Some(f) => match f.sources() {
            Ok(s) => Some(s),
            Err(e) => return bad(e.to_string()),
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
            let file = args
                .scene
                .as_ref()
                .map(|p| format!("{}: ", p.display()))
                .unwrap_or_default();
            if let (Some(f), None) = (&folder, &args.scene) {
                return bad(in_folder_file(f, &e.to_string()));
            }
            return bad(format!("{file}{e}"));
        }
    };
    if args.json {
        match serde_json::to_string(&report) {
            Ok(s) => println!("{s}"),
            Err(e) => return bad(format!("cannot write JSON: {e}")),
        }
    } else {
        let task = match &folder {
            Some(f) => format!("folder {}", f.dir),
            None => format!("benchmark {}", spec.benchmark.as_str()),
        };
        print_summary(&task, &spec, &report);
    }
    ExitCode::from(exit::OK)
}

/// An error about a task folder's demonstration or scene, named by its file
/// (`demo: actions[2]…` → `DIR/demo.json: actions[2]…`; a demonstration recorded from
/// `expert.json` is that file's).
fn in_folder_file(folder: &TaskFolder, e: &str) -> String {
    let demo = if folder.files.contains_key("demo.json") {
        "demo.json"
    } else {
        "expert.json"
    };
    for (prefix, name) in [("demo: ", demo), ("scene: ", "scene.json")] {
        if let Some(rest) = e.strip_prefix(prefix) {
            return format!("{}: {rest}", folder.path(name));
        }
    }
    e.to_string()
}

fn print_summary(task: &str, spec: &EpisodeSpec, r: &EpisodeReport) {
    println!(
        "{task}  level {}  method {}  mode {}  seed {}",
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

fn replay(path: &Path, domain: Option<&Path>, robots: &[Arc<ArmModel>]) -> ExitCode {
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
    let session = match (&log.folder, domain) {
        (None, Some(dir)) => {
            return bad(format!(
                "{}: an episode of benchmark {}, not of a task folder: drop --domain {}",
                path.display(),
                log.options.benchmark.as_str(),
                dir.display()
            ))
        }
        (None, None) => Session::replay_with_robots(&log_text, robots),
        (Some(record), _) => {
            let folder = match (TaskFolder::from_record(record), domain) {
                (Some(carried), _) => carried,
                (None, Some(dir)) => match crate::domain_dir::read(dir) {
                    Ok(f) => f,
                    Err(e) => return bad(e),
                },
                (None, None) => match TaskFolder::read(Path::new(&record.dir)) {
                    Ok(f) => f,
                    Err(e) => {
                        return bad(format!(
                            "{}: the episode ran on the task folder {}, which cannot be read \
                             ({e}); give it with --domain DIR",
                            path.display(),
                            record.dir
                        ))
                    }
                },
            };
            Session::replay_in_folder(&folder, &log_text, robots)
        }
    };
    let mut replayed = match session {
        Ok(s) => s.log(),
        Err(e) => return bad(format!("{}: {e}", path.display())),
    };
    // The folder's files were checked against the log's hashes: where they were read from (or
    // whether the log carried them) is no part of the episode.
    replayed.folder.clone_from(&log.folder);
    // Compared as saved: an arm's model is no part of its saved snapshot (its `robot` names it).
    let saved = |l: &EpisodeLog| serde_json::to_string(&l.canonical()).unwrap_or_default();
    if saved(&replayed) == saved(&log) {
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
