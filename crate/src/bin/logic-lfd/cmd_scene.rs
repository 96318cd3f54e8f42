//! `logic-lfd scene …`: inspect and perturb simulator scenes (the JSON of `sim::snapshot`).
//!
//! * `scene facts SCENE.json [--json]` — the scene graph, one fact per line;
//!   `scene facts --domain DIR` — the task folder's scene read through its `motions.json`;
//! * `scene check SCENE.json` — load with validation, then check the invariants;
//!   `scene check --domain DIR` — every check of a task folder (`lfd::check_folder`): each
//!   finding as `file: where: what`, exit 0 when clean and 2 otherwise;
//! * `scene template b1|b2|b3` — print a benchmark's template scene;
//! * `scene problem SCENE.json --benchmark b1` — the PDDL problem of that world and the goal;
//! * `scene disturb SCENE.json --benchmark b1 --level l3 [--seed N]` — apply the injector of
//!   Tables I/II, the soak and the page (`lfd::disturb`, "seen" meaning a state of the
//!   benchmark's demonstration), print `{"disturbance": …, "scene": …}`;
//!   `scene disturb --domain DIR --level l3` — the same in a task folder's scene, with its
//!   demonstration.

use crate::{exit, listed};
use logic_lfd::experiments::demo_trace;
use logic_lfd::lfd::{check_folder, demo_trace_of, inject, Level};
use logic_lfd::sim::{Benchmark, BenchmarkSources, TaskFolder};
use logic_lfd::sim::{SceneGraph, World};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

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
        /// Scene JSON (default with --domain: the folder's scene.json).
        #[arg(required_unless_present = "domain")]
        scene: Option<PathBuf>,
        /// A task folder: read the scene through its motions.json.
        #[arg(long)]
        domain: Option<PathBuf>,
        /// Print a JSON array instead of one fact per line.
        #[arg(long)]
        json: bool,
    },
    /// Validate a scene and check its invariants; with --domain, check a whole task folder.
    Check {
        /// Scene JSON.
        #[arg(required_unless_present = "domain", conflicts_with = "domain")]
        scene: Option<PathBuf>,
        /// A task folder: check its scene against its problem, the reach of every body, the
        /// room for each grasp from above, and its demonstration.
        #[arg(long)]
        domain: Option<PathBuf>,
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
        /// Scene JSON (default with --domain: the folder's scene.json).
        #[arg(required_unless_present = "domain")]
        scene: Option<PathBuf>,
        /// Benchmark.
        #[arg(long, value_parser = listed::one::<Benchmark>(), required_unless_present = "domain", conflicts_with = "domain")]
        benchmark: Option<Benchmark>,
        /// A task folder: its motions.json reads the scene, its demonstration says what is seen.
        #[arg(long)]
        domain: Option<PathBuf>,
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

/// A task folder's files; the message names what is missing or wrong.
fn folder(dir: &Path) -> Result<BenchmarkSources, ExitCode> {
    TaskFolder::read(dir)
        .and_then(|f| f.sources())
        .map_err(|e| {
            eprintln!("{e}");
            ExitCode::from(exit::BAD_INPUT)
        })
}

/// The world of `scene` (default: the folder's scene.json) read through the folder's
/// motions.json.
fn load_in(files: &BenchmarkSources, scene: Option<&Path>) -> Result<World, ExitCode> {
    let bad = |e: String| {
        eprintln!("{e}");
        ExitCode::from(exit::BAD_INPUT)
    };
    let motions = files.parse_motions().map_err(|e| {
        bad(match e {
            Ok(m) => m.to_string(),
            Err(pddl) => pddl,
        })
    })?;
    let (label, text) = match scene {
        Some(p) => (
            p.display().to_string(),
            std::fs::read_to_string(p)
                .map_err(|e| bad(format!("{}: cannot read: {e}", p.display())))?,
        ),
        None => (files.file("scene.json"), files.scene.clone()),
    };
    let world = logic_lfd::sim::world_from_json(&text).map_err(|e| bad(format!("{label}: {e}")))?;
    Ok(world.with_motions(Arc::new(motions)))
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
        Action::Facts {
            scene,
            domain,
            json,
        } => {
            let w = match &domain {
                Some(dir) => load_in(&folder(dir)?, scene.as_deref())?,
                None => load(scene.as_deref().unwrap_or(Path::new("")))?,
            };
            let facts = SceneGraph::from_world(&w).to_strings();
            if json {
                println!("{}", serde_json::to_string(&facts).unwrap_or_default());
            } else {
                for f in facts {
                    println!("{f}");
                }
            }
        }
        Action::Check {
            domain: Some(dir), ..
        } => {
            let f = TaskFolder::read(&dir).map_err(|e| {
                eprintln!("{e}");
                ExitCode::from(exit::BAD_INPUT)
            })?;
            let found = check_folder(&f);
            for x in &found {
                println!("{x}");
            }
            if !found.is_empty() {
                eprintln!("{}: {} finding(s)", f.dir, found.len());
                return Err(ExitCode::from(exit::BAD_INPUT));
            }
            println!("{}: ok", f.dir);
        }
        Action::Check {
            scene,
            domain: None,
        } => {
            let scene = scene.unwrap_or_default();
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
            benchmark,
            domain,
            level,
            seed,
        } => {
            let (mut w, trace, label) = match (&domain, benchmark) {
                (Some(dir), _) => {
                    let files = folder(dir)?;
                    let w = load_in(&files, scene.as_deref())?;
                    let trace = demo_trace_of(&files).map_err(|e| {
                        eprintln!("{e}");
                        ExitCode::from(exit::BAD_INPUT)
                    })?;
                    let label = scene
                        .as_ref()
                        .map(|p| p.display().to_string())
                        .unwrap_or_else(|| files.file("scene.json"));
                    (w, trace, label)
                }
                (None, Some(b)) => {
                    let scene = scene.unwrap_or_default();
                    let w = load(&scene)?;
                    let trace = demo_trace(b).map_err(|e| {
                        eprintln!("{}: {e}", b.dir_name());
                        ExitCode::from(exit::BAD_INPUT)
                    })?;
                    (w, trace, scene.display().to_string())
                }
                (None, None) => {
                    eprintln!("scene disturb: give --benchmark or --domain");
                    return Err(ExitCode::from(exit::BAD_INPUT));
                }
            };
            match inject(&mut w, level, &trace, &[], seed) {
                Ok(d) => {
                    let out = serde_json::json!({ "disturbance": d, "scene": w.snapshot() });
                    println!("{out}");
                }
                Err(e) => {
                    eprintln!("{label}: {e}");
                    return Err(ExitCode::from(exit::BAD_INPUT));
                }
            }
        }
    }
    Ok(())
}
