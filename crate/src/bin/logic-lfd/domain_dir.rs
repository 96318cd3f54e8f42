//! A domain directory as the robot runs it: `domain.pddl`, `problem.pddl`, `demo.json`,
//! `motions.json` and, optionally, `scene.json` (default: the benchmark's scene).

use std::path::Path;

use logic_lfd::sim::{Benchmark, BenchmarkSources};

/// Reads the files of `dir`, the scene falling back to `benchmark`'s; the message names the file
/// that is missing or unreadable.
pub fn read(dir: &Path, benchmark: Benchmark) -> Result<BenchmarkSources, String> {
    let file = |name: &str| {
        let p = dir.join(name);
        std::fs::read_to_string(&p).map_err(|e| format!("{}: {e}", p.display()))
    };
    let scene = if dir.join("scene.json").exists() {
        file("scene.json")?
    } else {
        benchmark.sources().map_err(|e| e.to_string())?.scene
    };
    Ok(BenchmarkSources {
        folder: None,
        dir: dir.display().to_string(),
        domain: file("domain.pddl")?,
        problem: file("problem.pddl")?,
        scene,
        demo: file("demo.json")?,
        motions: file("motions.json")?,
    })
}
