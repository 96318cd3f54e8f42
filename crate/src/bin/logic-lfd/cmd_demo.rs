//! `logic-lfd demo segment RECORDING.json --domain DOMAIN.pddl [--problem P] [-o demo.json]`:
//! turns a raw recording (time-stamped gripper poses and gripper states, see
//! `logic_lfd::recorder::recording`) into a `demo.json` whose every action is explained by the
//! domain's action schemas.
//!
//! Exit 0 with the demo JSON on stdout (or written to `-o`, with a summary on stdout); exit 2 on
//! bad input: `file: key.path: message` for malformed JSON, `file: at t = 1.23 s: …` for a fact
//! change the domain cannot explain or a physically implausible step. Nothing is written then.

use logic_lfd::pddl::Source;
use std::path::PathBuf;
use std::process::ExitCode;

use logic_lfd::pddl::read_source;
use logic_lfd::recorder::{segment_recording, RawRecording, RecorderParams};

use crate::exit;

/// Arguments of `demo`.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    command: DemoCommand,
}

#[derive(clap::Subcommand)]
enum DemoCommand {
    /// Segment a raw recording into the domain's actions and write a demo.json.
    Segment(SegmentArgs),
}

/// Arguments of `demo segment`.
#[derive(clap::Args)]
struct SegmentArgs {
    /// The raw recording (JSON: benchmark or scene, dt, samples).
    recording: PathBuf,
    /// The PDDL domain whose action schemas must explain every fact change.
    #[arg(long)]
    domain: PathBuf,
    /// A PDDL problem whose :init gives static facts the scene graph does not report.
    #[arg(long)]
    problem: Option<PathBuf>,
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
        DemoCommand::Segment(a) => segment(a),
    }
}

fn segment(a: SegmentArgs) -> ExitCode {
    let rec_file = a.recording.display().to_string();
    let bad = |m: String| {
        eprintln!("{m}");
        ExitCode::from(exit::BAD_INPUT)
    };
    let text = match std::fs::read_to_string(&a.recording) {
        Ok(t) => t,
        Err(e) => return bad(format!("{rec_file}: {e}")),
    };
    let recording = match RawRecording::from_json(&text) {
        Ok(r) => r,
        Err(e) => return bad(format!("{rec_file}: {e}")),
    };
    let domain_file = a.domain.display().to_string();
    let domain = match read_source(&a.domain) {
        Ok(t) => t,
        Err(e) => return bad(e.to_string()),
    };
    let problem = match &a.problem {
        Some(p) => match read_source(p) {
            Ok(t) => Some(Source::new(p.display().to_string(), t)),
            Err(e) => return bad(e.to_string()),
        },
        None => None,
    };
    let params = RecorderParams {
        learn_skills: !a.no_skills,
        ..RecorderParams::default()
    };
    let taught =
        match segment_recording(&recording, &domain, &domain_file, problem.as_ref(), params) {
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
