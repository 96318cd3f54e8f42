//! Regenerates every `domains/*/demo.json` (and `scene.json`) with the scripted expert:
//!
//! ```sh
//! cargo run --release --example record_demos            # all benchmarks, seed 1
//! cargo run --release --example record_demos -- b2 7    # one benchmark, another seed
//! cargo run --release --example record_demos -- domains/b1-paper-naming   # a domain directory
//! ```
//!
//! A domain directory holds `domain.pddl`, `problem.pddl` (its goal is checked), `scene.json`,
//! `motions.json` and the expert's `expert.json`; its `demo.json` is written.
//!
//! Each demo is checked while it is recorded (invariants after every step, goal at the end).

use logic_lfd::pddl::{parse_domain, parse_problem};
use logic_lfd::sim::demo::{self, ExpertParams};
use logic_lfd::sim::Motions;
use logic_lfd::sim::World;
use logic_lfd::sim::{goal_facts, Benchmark};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(dir) = args.first().map(PathBuf::from).filter(|p| p.is_dir()) {
        return match record_dir(&dir, args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1)) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("{}: {e}", dir.display());
                ExitCode::from(1)
            }
        };
    }
    let which: Vec<Benchmark> = match args.first() {
        Some(s) => match Benchmark::parse(s) {
            Some(b) => vec![b],
            None => {
                eprintln!("unknown benchmark {s:?} (b1, b2, b3)");
                return ExitCode::from(2);
            }
        },
        None => Benchmark::ALL.to_vec(),
    };
    let seed: u64 = match args.get(1).map(|s| s.parse()) {
        None => 1,
        Some(Ok(s)) => s,
        Some(Err(_)) => {
            eprintln!("the seed must be an unsigned integer");
            return ExitCode::from(2);
        }
    };
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../domains");
    for b in which {
        let dir = root.join(b.dir_name());
        let scene = serde_json::to_string_pretty(&b.scene_snapshot()).expect("scene JSON");
        if let Err(e) = std::fs::write(dir.join("scene.json"), scene + "\n") {
            eprintln!("{}: {e}", dir.display());
            return ExitCode::from(1);
        }
        match demo::record(b, seed, &ExpertParams::default()) {
            Ok(d) => {
                let text = serde_json::to_string(&d).expect("demo JSON");
                let n: usize = d.actions.iter().map(|a| a.samples.len()).sum();
                if let Err(e) = std::fs::write(dir.join("demo.json"), text.clone() + "\n") {
                    eprintln!("{}: {e}", dir.display());
                    return ExitCode::from(1);
                }
                println!(
                    "{}: {} actions, {} samples ({:.1} s), {} KB",
                    b.dir_name(),
                    d.actions.len(),
                    n,
                    n as f64 * d.dt,
                    text.len() / 1024
                );
            }
            Err(e) => {
                eprintln!("{}: recording failed: {e}", b.dir_name());
                return ExitCode::from(1);
            }
        }
    }
    ExitCode::SUCCESS
}

/// Records the demonstration of a domain directory's `expert.json` in its scene.
fn record_dir(dir: &std::path::Path, seed: u64) -> Result<(), String> {
    let read = |f: &str| std::fs::read_to_string(dir.join(f)).map_err(|e| format!("{f}: {e}"));
    let domain = parse_domain(&read("domain.pddl")?, "domain.pddl").map_err(|e| e.to_string())?;
    let problem = parse_problem(&read("problem.pddl")?, "problem.pddl", &domain)
        .map_err(|e| e.to_string())?;
    let motions = Motions::parse(&read("motions.json")?, "motions.json", &domain)
        .map_err(|e| e.to_string())?;
    let script: demo::Script =
        serde_json::from_str(&read("expert.json")?).map_err(|e| format!("expert.json: {e}"))?;
    let world = World::from_json(&read("scene.json")?)
        .map_err(|e| format!("scene.json: {e}"))?
        .with_motions(Arc::new(motions));
    let name = dir
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().to_string());
    let goal = goal_facts(&domain, &problem);
    let d = demo::record_script(world, &script, &goal, &name, seed, &ExpertParams::default())
        .map_err(|e| format!("recording failed: {e}"))?;
    let text = serde_json::to_string(&d).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("demo.json"), text + "\n").map_err(|e| e.to_string())?;
    println!("{name}: {} actions", d.actions.len());
    Ok(())
}
