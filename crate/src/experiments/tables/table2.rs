//! Table II: `trials` disturbed episodes per level, method and benchmark; simulated execution
//! time of the successful ones, beside the paper's.

use serde::{Deserialize, Serialize};

use crate::lfd::session::{SessionError, SessionParams};
use crate::lfd::{Method, Mode};
use crate::plan::Clock;
use crate::sim::benchmark::Benchmark;

use super::common::{count, reason_kind, stats, PAPER_TABLE2};
use crate::experiments::episode::{run_episode, EpisodeSpec, Level};

/// One (level, method, benchmark) cell of Table II.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table2Cell {
    /// Level.
    pub level: Level,
    /// Method.
    pub method: Method,
    /// Benchmark.
    pub benchmark: Benchmark,
    /// Execution times of successful trials (s).
    pub times: Vec<f64>,
    /// Trials run.
    pub trials: usize,
    /// Failure reasons seen (kind → count).
    pub failures: Vec<(String, usize)>,
    /// Seeds of the trials.
    pub seeds: Vec<u64>,
    /// Trials in which the level could not be injected (left out of `times` and `failures`).
    #[serde(default)]
    pub not_injected: usize,
    /// Trials whose disturbance hit a moving arm (L1: the approached body moved or the hand
    /// pushed).
    #[serde(default)]
    pub mid_motion: usize,
    /// Per mid-motion L1 trial: the TCP's largest distance from the undisturbed path (mm).
    #[serde(default)]
    pub deviation_mm: Vec<f64>,
    /// Per mid-motion L1 trial with a push: the push (mm).
    #[serde(default)]
    pub push_mm: Vec<f64>,
    /// Per successful trial: simulated time lost against the undisturbed run (s).
    #[serde(default)]
    pub time_lost_s: Vec<f64>,
}

/// Table II.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table2 {
    /// Trials per cell.
    pub trials: usize,
    /// Base seed.
    pub seed: u64,
    /// Cells.
    pub cells: Vec<Table2Cell>,
}

/// The methods of Table II.
pub const TABLE2_METHODS: [Method; 3] = [Method::Linear, Method::Rlds, Method::LogicLfd];

/// Runs Table II: `trials` disturbed episodes per level, method and benchmark.
pub fn table2(
    benchmarks: &[Benchmark],
    trials: usize,
    seed: u64,
    params: SessionParams,
    clock: &dyn Clock,
    progress: &mut dyn FnMut(&str),
) -> Result<Table2, SessionError> {
    let mut cells = vec![];
    for level in Level::ALL {
        for method in TABLE2_METHODS {
            for &b in benchmarks {
                let mut cell = Table2Cell {
                    level,
                    method,
                    benchmark: b,
                    times: vec![],
                    trials: 0,
                    failures: vec![],
                    seeds: vec![],
                    not_injected: 0,
                    mid_motion: 0,
                    deviation_mm: vec![],
                    push_mm: vec![],
                    time_lost_s: vec![],
                };
                for t in 0..trials {
                    let s = seed.wrapping_add(t as u64);
                    let spec = EpisodeSpec {
                        benchmark: b,
                        level: Some(level),
                        method,
                        mode: Mode::Paper,
                        seed: s,
                        scene: None,
                    };
                    let r = run_episode(&spec, params, clock)?;
                    cell.trials += 1;
                    cell.seeds.push(s);
                    record_trial(&mut cell, &r);
                }
                progress(&format!(
                    "table2 {} {} {}: {}/{} succeeded",
                    level.as_str(),
                    method.as_str(),
                    b.as_str(),
                    cell.times.len(),
                    cell.trials
                ));
                cells.push(cell);
            }
        }
    }
    Ok(Table2 {
        trials,
        seed,
        cells,
    })
}

/// Adds trial `r` to `cell`: a trial the level could not be injected into counts apart.
fn record_trial(cell: &mut Table2Cell, r: &crate::experiments::episode::EpisodeReport) {
    if r.injection.is_none() {
        cell.not_injected += 1;
        return;
    }
    if let Some(m) = &r.motion {
        cell.mid_motion += 1;
        cell.deviation_mm.push(m.deviation_mm);
    }
    if let Some(p) = r.injection.as_ref().and_then(|i| i.push.as_ref()) {
        cell.push_mm.push(p.displacement_mm);
    }
    if r.success {
        cell.times.push(r.execution_s);
        cell.time_lost_s.extend(r.time_lost_s);
    } else if let Some(reason) = &r.reason {
        count(&mut cell.failures, reason_kind(reason));
    }
}

impl Table2 {
    /// Markdown: per level, each method × benchmark as "ours (paper)".
    pub fn markdown(&self) -> String {
        let mut out = String::new();
        out.push_str(&format!(
            "Table II — simulated execution time [s], mean ± sd over the successful trials of {} per cell (seeds {}..{}), [successes/trials the level was injected into]; paper in parentheses; N/A = no successful trial.\n\n",
            self.trials,
            self.seed,
            self.seed + self.trials as u64 - 1
        ));
        let mut benches: Vec<Benchmark> = self.cells.iter().map(|c| c.benchmark).collect();
        benches.dedup();
        benches.sort_by_key(|b| *b as usize);
        benches.dedup();
        out.push_str("| level |");
        for m in TABLE2_METHODS {
            for b in &benches {
                out.push_str(&format!(" {} {} |", m.as_str(), b.as_str().to_uppercase()));
            }
        }
        out.push('\n');
        out.push_str("|---|");
        for _ in 0..TABLE2_METHODS.len() * benches.len() {
            out.push_str("---|");
        }
        out.push('\n');
        for level in Level::ALL {
            out.push_str(&format!("| {} |", level.as_str().to_uppercase()));
            for (mi, m) in TABLE2_METHODS.iter().enumerate() {
                for b in &benches {
                    let cell = self
                        .cells
                        .iter()
                        .find(|c| c.level == level && c.method == *m && c.benchmark == *b);
                    let injected = cell.map_or(0, |c| c.trials - c.not_injected);
                    let ours = match cell.and_then(|c| stats(&c.times)) {
                        Some((mean, sd, _)) => format!(
                            "{mean:.2} ± {sd:.2} [{}/{injected}]",
                            cell.map_or(0, |c| c.times.len()),
                        ),
                        None => format!("N/A [0/{injected}]"),
                    };
                    let paper = PAPER_TABLE2[mi].1[level as usize][*b as usize]
                        .map(|(m, s)| format!("{m:.2} ± {s:.2}"))
                        .unwrap_or_else(|| "N/A".into());
                    out.push_str(&format!(" {ours} ({paper}) |"));
                }
            }
            out.push('\n');
        }
        out.push_str(&self.motion_markdown());
        out.push_str("\nFailure reasons (ours):\n\n");
        for c in &self.cells {
            if !c.failures.is_empty() {
                out.push_str(&format!(
                    "- {} {} {}: {}\n",
                    c.level.as_str().to_uppercase(),
                    c.method.as_str(),
                    c.benchmark.as_str().to_uppercase(),
                    c.failures
                        .iter()
                        .map(|(k, n)| format!("{k} ×{n}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
        }
        out
    }
}
