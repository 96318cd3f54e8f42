//! `logic-lfd scene …`: inspect and perturb simulator scenes (the JSON of `sim::snapshot`).
//!
//! * `scene facts SCENE.json [--json]` — the scene graph, one fact per line;
//! * `scene check SCENE.json` — load with validation, then check the invariants;
//! * `scene template b1|b2|b3` — print a benchmark's template scene;
//! * `scene problem SCENE.json --benchmark b1` — the PDDL problem of that world and the goal;
//! * `scene disturb SCENE.json --benchmark b1 --level l3 [--seed N]` — apply the injector of
//!   Tables I/II, the soak and the page (`lfd::disturb`, "seen" meaning a state of the
//!   benchmark's demonstration), print `{"disturbance": …, "scene": …}`.

use crate::{exit, listed};
use logic_lfd::experiments::demo_trace;
use logic_lfd::lfd::{inject, Level};
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::{SceneGraph, World};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Arguments of `logic-lfd scene`.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    action: Action,
}

#[derive(clap::Subcommand)]
enum Action {
    /// Print the scene graph facts.
    Facts {
        /// Scene JSON.
        scene: PathBuf,
        /// Print a JSON array instead of one fact per line.
        #[arg(long)]
        json: bool,
    },
    /// Validate a scene and check its invariants.
    Check {
        /// Scene JSON.
        scene: PathBuf,
    },
    /// Print a benchmark's template scene JSON.
    Template {
        /// Benchmark.
        #[arg(value_parser = listed::one::<Benchmark>())]
        benchmark: Benchmark,
    },
    /// Print the PDDL problem of a scene for a benchmark's goal.
    Problem {
        /// Scene JSON.
        scene: PathBuf,
        /// Benchmark.
        #[arg(long, value_parser = listed::one::<Benchmark>())]
        benchmark: Benchmark,
    },
    /// Apply a disturbance (L1–L4) as Tables I/II, the soak and the page do, and print it with
    /// the new scene. L1 moves one block by 2–5 cm keeping the facts; L2 moves one block to a
    /// state of the demonstration; L3 to a state it never visits; L4 adds a block on top of a
    /// clear block (B1, B3) or on the table (B2).
    Disturb {
        /// Scene JSON.
        scene: PathBuf,
        /// Benchmark.
        #[arg(long, value_parser = listed::one::<Benchmark>())]
        benchmark: Benchmark,
        /// Disturbance level.
        #[arg(long, value_parser = listed::one::<Level>())]
        level: Level,
        /// Injector seed.
        #[arg(long, default_value_t = 0)]
        seed: u64,
    },
}

fn load(path: &Path) -> Result<World, ExitCode> {
    let file = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| {
        eprintln!("{file}: cannot read: {e}");
        ExitCode::from(exit::BAD_INPUT)
    })?;
    let world = logic_lfd::sim::world_from_json(&text).map_err(|e| {
        eprintln!("{file}: {e}");
        ExitCode::from(exit::BAD_INPUT)
    })?;
    // A benchmark's world reads its facts through that benchmark's motions.json.
    Ok(match Benchmark::parse(world.name()) {
        Some(b) => world.with_motions(b.motions()),
        None => world,
    })
}

/// Runs the subcommand.
pub fn run(args: Args) -> ExitCode {
    match run_inner(args) {
        Ok(()) => ExitCode::from(exit::OK),
        Err(code) => code,
    }
}

fn run_inner(args: Args) -> Result<(), ExitCode> {
    match args.action {
        Action::Facts { scene, json } => {
            let w = load(&scene)?;
            let facts = SceneGraph::from_world(&w).to_strings();
            if json {
                println!("{}", serde_json::to_string(&facts).unwrap_or_default());
            } else {
                for f in facts {
                    println!("{f}");
                }
            }
        }
        Action::Check { scene } => {
            let w = load(&scene)?;
            if let Err(v) = w.check_invariants() {
                for x in v {
                    eprintln!("{}: {x}", scene.display());
                }
                return Err(ExitCode::from(exit::BAD_INPUT));
            }
            println!("ok");
        }
        Action::Template { benchmark: b } => {
            println!("{}", b.scene().to_json());
        }
        Action::Problem {
            scene,
            benchmark: b,
        } => {
            let w = load(&scene)?;
            print!("{}", b.problem_for(&w, "scene"));
        }
        Action::Disturb {
            scene,
            benchmark: b,
            level,
            seed,
        } => {
            let mut w = load(&scene)?;
            let trace = demo_trace(b).map_err(|e| {
                eprintln!("{}: {e}", b.dir_name());
                ExitCode::from(exit::BAD_INPUT)
            })?;
            match inject(&mut w, level, &trace, &[], seed) {
                Ok(d) => {
                    let out = serde_json::json!({ "disturbance": d, "scene": w.snapshot() });
                    println!("{out}");
                }
                Err(e) => {
                    eprintln!("{}: {e}", scene.display());
                    return Err(ExitCode::from(exit::BAD_INPUT));
                }
            }
        }
    }
    Ok(())
}
