//! One closed-loop episode (`logic-lfd run`): a [`Session`] stepped to the end, with one
//! disturbance injected at a seeded action boundary.
//!
//! The disturbance of level `L` is injected once, when the arm is idle after action `j` of the
//! episode completed, `j ~ U{1, …, N − 2}` drawn from the seed (N = demonstration length), so it
//! always lands *during* execution.

use serde::{Deserialize, Serialize};

use crate::lfd::control::{FailReason, Replan};
pub use crate::lfd::disturb::Level;
use crate::lfd::session::{
    mix, sources_for, EpisodeLog, Injection, Session, SessionError, SessionOptions, SessionParams,
    SkillKind,
};
use crate::lfd::{Method, Mode};
use crate::plan::Clock;
use crate::sim::benchmark::{Benchmark, BenchmarkSources};

/// The draw of the episode's seed that picks the action after which the disturbance comes.
const INJECT_AFTER_DRAW: u64 = 77;

/// What to run.
#[derive(Clone, Debug, PartialEq)]
pub struct EpisodeSpec {
    /// Benchmark.
    pub benchmark: Benchmark,
    /// Disturbance injected during execution (`None`: undisturbed).
    pub level: Option<Level>,
    /// Method.
    pub method: Method,
    /// Multi-goal mode (Logic-LfD).
    pub mode: Mode,
    /// Seed of the episode.
    pub seed: u64,
    /// Initial scene JSON (`None`: the benchmark's template scene).
    pub scene: Option<String>,
}

/// What an episode did.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeReport {
    /// The goal holds at the end.
    pub success: bool,
    /// Why not.
    pub reason: Option<FailReason>,
    /// Actions executed with their effect.
    pub actions_executed: usize,
    /// Replans (the initial plan included).
    pub replans: usize,
    /// Planning time of every replan (ms, caller's clock).
    pub planning_ms: Vec<f64>,
    /// Simulated execution time (s).
    pub execution_s: f64,
    /// The injected disturbance.
    pub injection: Option<Injection>,
    /// The full log (replays exactly).
    pub log: EpisodeLog,
}

impl EpisodeReport {
    /// Planning time of the first plan (ms).
    pub fn first_plan_ms(&self) -> Option<f64> {
        self.planning_ms.first().copied()
    }

    /// The replans after the first.
    pub fn replans_after_start(&self) -> &[Replan] {
        self.log.replans.get(1..).unwrap_or(&[])
    }
}

/// Runs one episode to its end (at most `params.max_time` simulated seconds).
pub fn run_episode(
    spec: &EpisodeSpec,
    params: SessionParams,
    clock: &dyn Clock,
) -> Result<EpisodeReport, SessionError> {
    run_episode_with_blocks(spec, None, params, clock)
}

/// [`run_episode`] on the benchmark's generated tower task with `blocks` blocks (`None`: the
/// template task).
pub fn run_episode_with_blocks(
    spec: &EpisodeSpec,
    blocks: Option<usize>,
    params: SessionParams,
    clock: &dyn Clock,
) -> Result<EpisodeReport, SessionError> {
    let sources = sources_for(spec.benchmark, blocks)?;
    episode(spec, &sources, blocks, params, clock)
}

/// [`run_episode`] on other files: a domain of its own (its PDDL, demonstration and
/// `motions.json`) in the benchmark's workcell, with the benchmark's disturbances.
pub fn run_episode_with(
    spec: &EpisodeSpec,
    sources: &BenchmarkSources,
    params: SessionParams,
    clock: &dyn Clock,
) -> Result<EpisodeReport, SessionError> {
    episode(spec, sources, None, params, clock)
}

fn episode(
    spec: &EpisodeSpec,
    sources: &BenchmarkSources,
    blocks: Option<usize>,
    params: SessionParams,
    clock: &dyn Clock,
) -> Result<EpisodeReport, SessionError> {
    let options = SessionOptions {
        benchmark: spec.benchmark,
        method: spec.method,
        mode: spec.mode,
        seed: spec.seed,
        skill: SkillKind::Lqt,
        blocks,
    };
    let mut s = Session::with_sources(options, sources, spec.scene.as_deref(), None, params)?;
    let n = s.controller().trace().len().max(3);
    let inject_after = 1 + (mix(spec.seed, INJECT_AFTER_DRAW) % (n as u64 - 2)) as usize;
    let mut injection = None;
    let mut next_try = inject_after;
    let max_ticks = (params.max_time / s.world().dt()).ceil() as u64 + 10;
    for _ in 0..max_ticks {
        if s.outcome().is_some() {
            break;
        }
        if let Some(level) = spec.level {
            // At the first idle moment after action `inject_after`; if the level cannot be
            // produced in this state, try again at the next action boundary.
            if injection.is_none() && !s.is_executing() && s.actions_done() >= next_try {
                match s.inject(level.as_str()) {
                    Ok(i) => injection = Some(i),
                    Err(_) => next_try = s.actions_done() + 1,
                }
            }
        }
        s.tick_once(clock);
    }
    let log = s.log();
    let (success, reason) = match s.outcome() {
        Some(Ok(())) => (true, None),
        Some(Err(r)) => (false, Some(r.clone())),
        None => (
            false,
            Some(FailReason::Budget {
                what: "simulated time".into(),
            }),
        ),
    };
    Ok(EpisodeReport {
        success,
        reason,
        actions_executed: s.actions_done(),
        replans: log.replans.len(),
        planning_ms: log.replans.iter().map(|r| r.time_ms).collect(),
        execution_s: s.world().time(),
        injection,
        log,
    })
}
