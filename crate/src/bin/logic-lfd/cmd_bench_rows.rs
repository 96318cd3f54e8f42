//! `logic-lfd bench wasm-rows [--ipc DIR] [--logistics NAME] [--warmup N] [--warmup-secs S]
//! [--runs N] [--only ID,…] [--json]`: the native side of `npm run bench:wasm` — the hot-path rows of
//! `logic_lfd::experiments::hot_paths`, best of N after a warm-up, on the wall clock.

use std::path::PathBuf;
use std::process::ExitCode;

use logic_lfd::experiments::hot_paths::{run_rows, RowInputs, RowParams};

use crate::cmd_plan::WallClock;
use crate::exit;

/// Arguments of `bench wasm-rows`.
#[derive(clap::Args)]
pub struct Args {
    /// Folder of the IPC benchmarks (`blocks/`, `logistics00/`).
    #[arg(long, default_value = "tests/data/ipc")]
    ipc: PathBuf,
    /// The logistics problem of the lazy GBFS row (a file of `logistics00/`, without `.pddl`).
    #[arg(long, default_value = "probLOGISTICS-10-0")]
    logistics: String,
    /// Untimed warm-up runs per row before the timed ones (at least 1).
    #[arg(long, default_value_t = 1)]
    warmup: usize,
    /// Seconds of warm-up per row at least (more runs than `--warmup` where one is short).
    #[arg(long, default_value_t = 0.0)]
    warmup_secs: f64,
    /// Timed runs per row at most (after the warm-up; at least 3).
    #[arg(long, default_value_t = 10)]
    runs: usize,
    /// Seconds per row after which no further run starts (once 3 are done).
    #[arg(long, default_value_t = 5.0)]
    budget: f64,
    /// Only the rows whose id contains one of these (comma-separated).
    #[arg(long, value_delimiter = ',')]
    only: Vec<String>,
    /// Print JSON (the rows with their ids and digests) instead of a markdown table.
    #[arg(long)]
    json: bool,
}

/// The rows' PDDL texts, read from the IPC folder.
fn inputs(a: &Args) -> Result<RowInputs, String> {
    let read = |dir: &str, file: &str| {
        let p = a.ipc.join(dir).join(file);
        std::fs::read_to_string(&p).map_err(|e| format!("{}: {e}", p.display()))
    };
    Ok(RowInputs {
        blocks_domain: read("blocks", "domain.pddl")?,
        blocks_8: read("blocks", "probBLOCKS-8-0.pddl")?,
        blocks_9: read("blocks", "probBLOCKS-9-0.pddl")?,
        logistics_domain: read("logistics00", "domain.pddl")?,
        logistics: read("logistics00", &format!("{}.pddl", a.logistics))?,
        logistics_name: a.logistics.clone(),
    })
}

/// Runs the subcommand.
pub fn run(a: Args) -> ExitCode {
    let params = RowParams {
        warmup: a.warmup.max(1),
        warmup_secs: a.warmup_secs,
        runs: a.runs.max(1),
        budget_secs: a.budget,
        only: a.only.clone(),
        ..RowParams::default()
    };
    let rows = inputs(&a).and_then(|i| run_rows(&i, &params, &WallClock::start()));
    let rows = match rows {
        Ok(r) => r,
        Err(e) => {
            eprintln!("bench wasm-rows: {e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    if a.json {
        match serde_json::to_string_pretty(&rows) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("bench wasm-rows: {e}");
                return ExitCode::from(exit::BAD_INPUT);
            }
        }
    } else {
        println!("| work | native (ms, best of N) | runs | work done |\n|---|---:|---:|---|");
        for r in &rows {
            println!(
                "| {} | {:.4} | {} | {} |",
                r.label, r.best_ms, r.runs, r.digest
            );
        }
    }
    ExitCode::from(exit::OK)
}
