//! Table II: `trials` disturbed episodes per level, method and benchmark; simulated execution
//! time of the successful ones, beside the paper's.

use crate::sim::ArmModel;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

use crate::lfd::{Method, Mode};
use crate::lfd::{SessionError, SessionParams};
use crate::plan::Clock;
use crate::sim::Benchmark;

use super::common::{count, reason_kind, summary, PAPER_TABLE2};
use crate::experiments::{run_episode, EpisodeSpec};
use crate::lfd::Level;

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
    /// The robots the episodes ran on (empty: the scenes' own, the built-in Panda).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub robots: Vec<String>,
}

/// The methods of Table II.
pub const TABLE2_METHODS: [Method; 3] = [Method::Linear, Method::Rlds, Method::LogicLfd];

/// What one Table II trial gave (a record of the sweep, joined by [`Table2Sweep::report`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table2Trial {
    /// The trial's seed.
    pub seed: u64,
    /// Whether the level was injected (a trial it was not counts apart).
    pub injected: bool,
    /// The TCP's largest distance from the undisturbed path, if the disturbance hit a moving
    /// arm (mm).
    pub deviation_mm: Option<f64>,
    /// The push of the hand, if there was one (mm).
    pub push_mm: Option<f64>,
    /// Simulated execution time, if the trial succeeded (s).
    pub execution_s: Option<f64>,
    /// Simulated time lost against the undisturbed run (s).
    pub time_lost_s: Option<f64>,
    /// The failure's kind, if it failed with a stated reason.
    pub failure: Option<String>,
}

/// Table II as a sweep: cells by level, then method, then benchmark, each `trials` trials;
/// item `i` is trial `i mod trials` of cell `i / trials`, seeded `seed + trial` alone, so items
/// run in any order (or on other machines) and [`Table2Sweep::report`] joins them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table2Sweep {
    /// Benchmarks.
    pub benchmarks: Vec<Benchmark>,
    /// Trials per cell.
    pub trials: usize,
    /// Seed of the first trial (trial t uses `seed + t`).
    pub seed: u64,
    /// Whether Logic-LfD may fall back to TAMP from scratch.
    pub tamp_fallback: bool,
    /// Robots in place of the scenes' arms ([`EpisodeSpec::robots`]).
    #[serde(skip)]
    pub robots: Vec<Arc<ArmModel>>,
}

impl Table2Sweep {
    /// Number of items (trials over all cells).
    pub fn items(&self) -> usize {
        Level::ALL.len() * TABLE2_METHODS.len() * self.benchmarks.len() * self.trials
    }

    /// The (level, method, benchmark) of cell `c`.
    fn cell(&self, c: usize) -> (Level, Method, Benchmark) {
        let nb = self.benchmarks.len();
        let per_level = TABLE2_METHODS.len() * nb;
        (
            Level::ALL[c / per_level],
            TABLE2_METHODS[c % per_level / nb],
            self.benchmarks[c % nb],
        )
    }

    /// Runs item `index` with `params` (their `control.tamp_fallback` set from the sweep's);
    /// `progress` hears of its end.
    pub fn run(
        &self,
        index: usize,
        params: SessionParams,
        clock: &dyn Clock,
        progress: &mut dyn FnMut(&str),
    ) -> Result<Table2Trial, SessionError> {
        let mut params = params;
        params.control.tamp_fallback = self.tamp_fallback;
        let (level, method, b) = self.cell(index / self.trials);
        let t = index % self.trials;
        let s = self.seed.wrapping_add(t as u64);
        let spec = EpisodeSpec {
            benchmark: b,
            level: Some(level),
            method,
            mode: Mode::Paper,
            seed: s,
            scene: None,
            robots: self.robots.clone(),
        };
        let r = run_episode(&spec, params, clock)?;
        let trial = Table2Trial {
            seed: s,
            injected: r.injection.is_some(),
            deviation_mm: r.motion.as_ref().map(|m| m.deviation_mm),
            push_mm: r
                .injection
                .as_ref()
                .and_then(|i| i.push.as_ref())
                .map(|p| p.displacement_mm),
            execution_s: r.success.then_some(r.execution_s),
            time_lost_s: r.time_lost_s,
            failure: r.reason.as_ref().map(reason_kind),
        };
        let outcome = match (&trial.execution_s, &trial.failure) {
            _ if !trial.injected => "not injected".to_string(),
            (Some(_), _) => "succeeded".to_string(),
            (None, Some(kind)) => format!("failed: {kind}"),
            (None, None) => "failed".to_string(),
        };
        progress(&format!(
            "table2 {} {} {} trial {}/{}: {outcome}",
            level.as_str(),
            method.as_str(),
            b.as_str(),
            t + 1,
            self.trials
        ));
        Ok(trial)
    }

    /// Table II from the sweep's items, given in item order.
    pub fn report(&self, items: impl IntoIterator<Item = Table2Trial>) -> Table2 {
        let cells = self.benchmarks.len() * Level::ALL.len() * TABLE2_METHODS.len();
        let mut cells: Vec<Table2Cell> = (0..cells)
            .map(|c| {
                let (level, method, benchmark) = self.cell(c);
                Table2Cell {
                    level,
                    method,
                    benchmark,
                    times: vec![],
                    trials: 0,
                    failures: vec![],
                    seeds: vec![],
                    not_injected: 0,
                    mid_motion: 0,
                    deviation_mm: vec![],
                    push_mm: vec![],
                    time_lost_s: vec![],
                }
            })
            .collect();
        for (p, trial) in items.into_iter().enumerate() {
            if let Some(cell) = cells.get_mut(p / self.trials) {
                record_trial(cell, trial);
            }
        }
        Table2 {
            trials: self.trials,
            seed: self.seed,
            cells,
            robots: self.robots.iter().map(|r| r.name().to_string()).collect(),
        }
    }
}

/// Runs Table II: `trials` disturbed episodes per level, method and benchmark (the items of
/// [`Table2Sweep`], one after another).
pub fn table2(
    benchmarks: &[Benchmark],
    trials: usize,
    seed: u64,
    params: SessionParams,
    clock: &dyn Clock,
    progress: &mut dyn FnMut(&str),
) -> Result<Table2, SessionError> {
    let sweep = Table2Sweep {
        benchmarks: benchmarks.to_vec(),
        trials,
        seed,
        tamp_fallback: params.control.tamp_fallback,
        robots: vec![],
    };
    let items = (0..sweep.items())
        .map(|i| sweep.run(i, params, clock, progress))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(sweep.report(items))
}

/// Adds a trial to `cell`: a trial the level could not be injected into counts apart.
fn record_trial(cell: &mut Table2Cell, t: Table2Trial) {
    cell.trials += 1;
    cell.seeds.push(t.seed);
    if !t.injected {
        cell.not_injected += 1;
        return;
    }
    if let Some(d) = t.deviation_mm {
        cell.mid_motion += 1;
        cell.deviation_mm.push(d);
    }
    if let Some(p) = t.push_mm {
        cell.push_mm.push(p);
    }
    if let Some(time) = t.execution_s {
        cell.times.push(time);
        cell.time_lost_s.extend(t.time_lost_s);
    } else if let Some(kind) = t.failure {
        count(&mut cell.failures, kind);
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
        if !self.robots.is_empty() {
            out.push_str(&format!("Robot: {}.\n\n", self.robots.join(", ")));
        }
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
                    let ours = match cell.and_then(|c| summary(&c.times)) {
                        Some(s) => format!(
                            "{:.2} ± {:.2} [{}/{injected}]",
                            s.mean,
                            s.sd,
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
