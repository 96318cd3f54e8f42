//! Regenerates every `domains/*/demo.json` (and `scene.json`) with the scripted expert:
//!
//! ```sh
//! cargo run --release --example record_demos            # all benchmarks, seed 1
//! cargo run --release --example record_demos -- b2 7    # one benchmark, another seed
//! cargo run --release --example record_demos -- domains/b1-paper-naming   # a task folder
//! ```
//!
//! A task folder's `demo.json` is recorded from its `expert.json` by
//! [`TaskFolder::record_demo`], the code behind `logic-lfd demo record DIR`, which needs no
//! checkout of the sources.
//!
//! Each demo is checked while it is recorded (invariants after every step, goal at the end).

use logic_lfd::sim::demo::{self, ExpertParams};
use logic_lfd::sim::{Benchmark, TaskFolder};
use std::path::PathBuf;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(dir) = args.first().map(PathBuf::from).filter(|p| p.is_dir()) {
        return match record_dir(&dir, args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1)) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("{e}");
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

/// Records a task folder's `demo.json` from its `expert.json` (as `logic-lfd demo record DIR`).
fn record_dir(dir: &std::path::Path, seed: u64) -> Result<(), String> {
    let folder = TaskFolder::read(dir).map_err(|e| e.to_string())?;
    let text = folder.record_demo(seed).map_err(|e| e.to_string())?;
    let d = demo::parse(&text).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("demo.json"), text + "\n").map_err(|e| e.to_string())?;
    println!("{}: {} actions", folder.dir, d.actions.len());
    Ok(())
}
