//! `logic-lfd demo record DIR [-o FILE] [--seed N]`: the scripted expert records a task
//! folder's demonstration from its `expert.json`, in its scene (`DIR/demo.json` by default).
//!
//! `logic-lfd demo segment RECORDING.json --domain DIR|DOMAIN.pddl [--problem P] [--motions M]
//! [-o demo.json]`: turns a raw recording (time-stamped gripper poses and gripper states, see
//! `logic_lfd::recorder::recording`) into a `demo.json` whose every action is explained by the
//! domain's action schemas; a task folder gives its domain, problem and motions.json.
//!
//! Exit 0 with the demo JSON on stdout (or written to `-o`, with a summary on stdout); exit 2 on
//! bad input: `file: key.path: message` for malformed JSON, `file: at t = 1.23 s: …` for a fact
//! change the domain cannot explain or a physically implausible step. Nothing is written then.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use logic_lfd::pddl::read_source;
use logic_lfd::pddl::Source;
use logic_lfd::recorder::{segment_recording_with, RawRecording, RecorderOptions, RecorderParams};

use crate::exit;

/// Arguments of `demo`.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    command: DemoCommand,
}

#[derive(clap::Subcommand)]
enum DemoCommand {
    /// Record a task folder's demonstration with the scripted expert (its expert.json, in its
    /// scene.json) and write its demo.json.
    Record(RecordArgs),
    /// Segment a raw recording into the domain's actions and write a demo.json.
    Segment(SegmentArgs),
}

/// Arguments of `demo record`.
#[derive(clap::Args)]
struct RecordArgs {
    /// The task folder: domain.pddl, problem.pddl (its goal is checked), motions.json,
    /// scene.json and the expert's steps, expert.json (a demo.plan beside it must list the same
    /// actions).
    dir: PathBuf,
    /// Write the demo JSON here (`-`: stdout) instead of DIR/demo.json.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Seed of the expert's variation.
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

/// Arguments of `demo segment`.
#[derive(clap::Args)]
struct SegmentArgs {
    /// The raw recording (JSON: benchmark or scene, dt, samples).
    recording: PathBuf,
    /// A task folder (its domain.pddl, problem.pddl and motions.json), or a PDDL domain file,
    /// whose action schemas must explain every fact change.
    #[arg(long)]
    domain: PathBuf,
    /// A PDDL problem whose :init gives static facts the scene graph does not report (default:
    /// the task folder's problem.pddl).
    #[arg(long)]
    problem: Option<PathBuf>,
    /// What the domain's names mean (default: the task folder's motions.json, else the
    /// benchmark's whose scene the recording starts in).
    #[arg(long)]
    motions: Option<PathBuf>,
    /// Write the demo JSON here instead of stdout.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Skip learning an LQT-CP skill from each action (faster).
    #[arg(long)]
    no_skills: bool,
}

/// Runs the subcommand.
pub fn run(args: Args) -> ExitCode {
    match args.command {
        DemoCommand::Record(a) => record(a),
        DemoCommand::Segment(a) => segment(a),
    }
}

fn bad(m: String) -> ExitCode {
    eprintln!("{m}");
    ExitCode::from(exit::BAD_INPUT)
}

fn record(a: RecordArgs) -> ExitCode {
    let folder = match crate::domain_dir::read(&a.dir) {
        Ok(f) => f,
        Err(e) => return bad(e),
    };
    if !folder.files.contains_key("expert.json") {
        return bad(format!(
            "{}: missing: `demo record` runs the scripted expert's steps of expert.json",
            folder.path("expert.json")
        ));
    }
    let text = match folder.record_demo(a.seed) {
        Ok(t) => t,
        Err(e) => return bad(e.to_string()),
    };
    let demo = match logic_lfd::sim::demo::parse(&text) {
        Ok(d) => d,
        Err(e) => return bad(format!("{}: {e}", folder.path("demo.json"))),
    };
    let samples: usize = demo.actions.iter().map(|a| a.samples.len()).sum();
    let summary = |to: &str| {
        format!(
            "{to}: {} actions, {samples} samples ({:.1} s), seed {}",
            demo.actions.len(),
            samples as f64 * demo.dt,
            a.seed
        )
    };
    match a.output.as_deref() {
        Some(p) if p == Path::new("-") => {
            println!("{text}");
            eprintln!("{}", summary("stdout"));
        }
        out => {
            let to = out.map_or_else(
                || PathBuf::from(folder.path("demo.json")),
                Path::to_path_buf,
            );
            if let Err(e) = std::fs::write(&to, text + "\n") {
                return bad(format!("{}: {e}", to.display()));
            }
            println!("{}", summary(&to.display().to_string()));
        }
    }
    ExitCode::from(exit::OK)
}

/// What `demo segment` segments against: the domain, and the problem and motions if given.
struct SegmentFiles {
    domain: Source,
    problem: Option<Source>,
    motions: Option<Source>,
}

/// The domain, problem and motions of `demo segment`: a task folder's, each replaced by the
/// file its flag gives.
fn segment_files(a: &SegmentArgs) -> Result<SegmentFiles, String> {
    let read = |p: &Path| {
        read_source(p)
            .map(|t| Source::new(p.display().to_string(), t))
            .map_err(|e| e.to_string())
    };
    let (domain, mut problem, mut motions) = if a.domain.is_dir() {
        let f = crate::domain_dir::read(&a.domain)?;
        let file = |name: &str| -> Result<Source, String> {
            let text = f.text(name).map_err(|e| e.to_string())?;
            Ok(Source::new(f.path(name), text.to_string()))
        };
        (
            file("domain.pddl")?,
            Some(file("problem.pddl")?),
            Some(file("motions.json")?),
        )
    } else {
        (read(&a.domain)?, None, None)
    };
    if let Some(p) = &a.problem {
        problem = Some(read(p)?);
    }
    if let Some(m) = &a.motions {
        motions = Some(read(m)?);
    }
    Ok(SegmentFiles {
        domain,
        problem,
        motions,
    })
}

fn segment(a: SegmentArgs) -> ExitCode {
    let rec_file = a.recording.display().to_string();
    let text = match std::fs::read_to_string(&a.recording) {
        Ok(t) => t,
        Err(e) => return bad(format!("{rec_file}: {e}")),
    };
    let recording = match RawRecording::from_json(&text) {
        Ok(r) => r,
        Err(e) => return bad(format!("{rec_file}: {e}")),
    };
    let files = match segment_files(&a) {
        Ok(f) => f,
        Err(e) => return bad(e),
    };
    let params = RecorderParams {
        learn_skills: !a.no_skills,
        ..RecorderParams::default()
    };
    let options = RecorderOptions {
        domain_file: files.domain.file.clone(),
        problem_pddl: files.problem,
        motions_json: files.motions,
        params,
    };
    let taught = match segment_recording_with(&recording, &files.domain.text, options) {
        Ok(t) => t,
        Err(e) => return bad(format!("{rec_file}: {e}")),
    };
    let json = match serde_json::to_string(&taught.demo) {
        Ok(j) => j,
        Err(e) => return bad(format!("{rec_file}: {e}")),
    };
    match &a.output {
        None => println!("{json}"),
        Some(out) => {
            if let Err(e) = std::fs::write(out, json + "\n") {
                eprintln!("{}: {e}", out.display());
                return ExitCode::from(exit::BAD_INPUT);
            }
            println!(
                "{}: {} actions, {} states",
                out.display(),
                taught.demo.demo.actions.len(),
                taught.states.len()
            );
            for (i, act) in taught.demo.demo.actions.iter().enumerate() {
                println!(
                    "  {:2} {:<32} {:4} samples",
                    i + 1,
                    act.action,
                    act.samples.len()
                );
                for f in taught
                    .skills
                    .iter()
                    .filter(|f| f.action.starts_with(&act.action))
                {
                    let part = f.action[act.action.len()..].trim();
                    println!(
                        "       {part:<9} LQT-CP skill: {:4} steps, rms {:.2} mm, goal {:.2} mm",
                        f.steps,
                        f.rms_error * 1000.0,
                        f.goal_error * 1000.0
                    );
                }
            }
            println!("  goal: {}", taught.demo.goal.join(" "));
        }
    }
    ExitCode::from(exit::OK)
}
