//! A soak's parameters and its report: counts, findings and the explained failures.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::sim::FolderRecord;

/// Most findings a report keeps.
const MAX_FINDINGS: usize = 100;

/// Tunables of a soak.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SoakParams {
    /// Number of episodes.
    pub episodes: usize,
    /// Seed of the whole soak.
    pub seed: u64,
    /// Most disturbances scheduled per episode (uniform in `0..=max_disturbances`).
    pub max_disturbances: usize,
    /// Disturbances are scheduled uniformly over `[0, horizon_ticks)` (10 ms ticks).
    pub horizon_ticks: u64,
    /// Ticks after which an episode is stopped (the session's own simulated-time budget is 240 s).
    pub max_ticks: u64,
    /// Node budget of the independent search that checks a "no plan".
    pub check_nodes: u64,
    /// Replay every episode's JSON and compare the logs byte for byte.
    pub check_replay: bool,
    /// Index of the first episode (episodes `first_episode..first_episode + episodes` run, so
    /// one episode of a large soak can be re-run alone).
    #[serde(default)]
    pub first_episode: usize,
    /// Run the benchmarks' generated N-block tower tasks (B1, and B3 where N fits) instead of
    /// the template tasks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub blocks: Option<usize>,
    /// The task folder whose task every episode runs, in its own scene (`None`: the
    /// benchmarks'); set by [`SoakRunner::in_folder`](super::SoakRunner::in_folder). Its file
    /// hashes tell the shards of one folder's soak from another's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub folder: Option<FolderRecord>,
    /// The robots in place of the scenes' arms (empty: the scenes' own, the built-in Panda); set
    /// by [`SoakRunner::with_robots`](super::SoakRunner::with_robots).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub robots: Vec<String>,
}

impl Default for SoakParams {
    fn default() -> Self {
        SoakParams {
            episodes: 20,
            seed: 0,
            max_disturbances: 6,
            horizon_ticks: 2_500,
            max_ticks: 30_000,
            check_nodes: 2_000_000,
            check_replay: true,
            first_episode: 0,
            blocks: None,
            folder: None,
            robots: vec![],
        }
    }
}

/// A broken guarantee, with enough to replay it (`logic-lfd soak --episodes 1 --seed …` or the
/// episode seed with `logic-lfd run`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SoakFinding {
    /// Episode index within the soak.
    pub episode: usize,
    /// Benchmark, or the task folder.
    pub benchmark: String,
    /// The session seed of that episode.
    pub session_seed: u64,
    /// Tick at which it was found.
    pub tick: u64,
    /// `invariant`, `partial_apply`, `invalid_plan`, `unexplained_failure`, `budget`, `stall`,
    /// `no_outcome`, `input_error`, `replay`, `panic`.
    pub kind: String,
    /// What happened, in words.
    pub detail: String,
}

/// A failure the soak accepts as legitimate, with the proof that made it so.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ExplainedFailure {
    /// Episode index within the soak.
    pub episode: usize,
    /// Benchmark, or the task folder.
    pub benchmark: String,
    /// The session seed of that episode.
    pub session_seed: u64,
    /// The session's stated reason.
    pub reason: String,
    /// The legitimate class (a key of [`SoakReport::legitimate_failures`]).
    pub class: String,
    /// What proves it: the exhaustive search's state count, IK's reason, the full shelf.
    pub proof: String,
}

/// The figures of a soak.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SoakReport {
    /// The parameters.
    pub params: Option<SoakParams>,
    /// Episodes run.
    pub episodes: usize,
    /// Episodes per benchmark (a task folder's soak: per folder).
    pub per_benchmark: BTreeMap<String, usize>,
    /// Simulated 10 ms ticks in total.
    pub ticks: u64,
    /// Disturbances applied (accepted drags + produced injections).
    pub disturbances: usize,
    /// Injections produced per level.
    pub injections: BTreeMap<String, usize>,
    /// Drags accepted.
    pub drags_accepted: usize,
    /// Drags refused by the world (checked: nothing applied).
    pub drags_refused: usize,
    /// Injections the state did not allow (checked: nothing applied).
    pub injections_refused: usize,
    /// World-invariant checks performed.
    pub invariant_checks: u64,
    /// Invariant violations found.
    pub invariant_violations: usize,
    /// Refusals that changed the world or the log.
    pub partial_applies: usize,
    /// Plans adopted by the loop and replayed by the validator.
    pub plans_checked: usize,
    /// Plans the validator rejected.
    pub invalid_plans: usize,
    /// Of the plans, those Logic-LfD made from scratch because no skeleton joining the
    /// demonstration bound (its TAMP fallback).
    #[serde(default)]
    pub tamp_fallbacks: usize,
    /// Episodes that reached the goal.
    pub successes: usize,
    /// Episodes that ended with a legitimate stated reason, by reason.
    pub legitimate_failures: BTreeMap<String, usize>,
    /// Episodes that ended with an exhausted planning or simulated-time budget (findings).
    pub budget_exhausted: usize,
    /// Episodes whose session stopped advancing without an outcome (findings).
    #[serde(default)]
    pub stalls: usize,
    /// Episodes stopped at `max_ticks` without an outcome (findings).
    #[serde(default)]
    pub no_outcome: usize,
    /// Failures whose observed task could not be written, parsed or grounded for the check
    /// (findings).
    #[serde(default)]
    pub input_errors: usize,
    /// Episodes whose failure is not explained.
    pub unexplained_failures: usize,
    /// Episodes whose replay differed.
    pub replay_mismatches: usize,
    /// Episodes replayed.
    pub replays_checked: usize,
    /// Panics caught (the loop must never panic).
    pub panics: usize,
    /// Every broken guarantee (at most 100 kept).
    pub findings: Vec<SoakFinding>,
    /// Every legitimate failure with its proof (at most 100 kept).
    #[serde(default)]
    pub explained: Vec<ExplainedFailure>,
}

impl SoakReport {
    /// Whether every guarantee held.
    pub fn is_clean(&self) -> bool {
        self.invariant_violations == 0
            && self.partial_applies == 0
            && self.invalid_plans == 0
            && self.unexplained_failures == 0
            && self.budget_exhausted == 0
            && self.stalls == 0
            && self.no_outcome == 0
            && self.input_errors == 0
            && self.replay_mismatches == 0
            && self.panics == 0
    }

    /// Keeps a finding (at most [`MAX_FINDINGS`]).
    pub(super) fn find(&mut self, f: SoakFinding) {
        if self.findings.len() < MAX_FINDINGS {
            self.findings.push(f);
        }
    }

    /// Keeps a legitimate failure's proof (at most [`MAX_FINDINGS`]).
    pub(super) fn explain(&mut self, x: ExplainedFailure) {
        if self.explained.len() < MAX_FINDINGS {
            self.explained.push(x);
        }
    }

    /// Episodes that ended, each counted once: successes, legitimate failures and every kind of
    /// unlegitimate end. Equals `episodes` unless an episode panicked.
    pub fn ends(&self) -> usize {
        self.successes
            + self.legitimate_failures.values().sum::<usize>()
            + self.budget_exhausted
            + self.stalls
            + self.no_outcome
            + self.input_errors
            + self.unexplained_failures
    }

    /// Adds an episode's figures and findings.
    pub(super) fn merge(&mut self, o: SoakReport) {
        self.episodes += o.episodes;
        for (k, v) in o.per_benchmark {
            *self.per_benchmark.entry(k).or_default() += v;
        }
        self.ticks += o.ticks;
        self.disturbances += o.disturbances;
        for (k, v) in o.injections {
            *self.injections.entry(k).or_default() += v;
        }
        self.drags_accepted += o.drags_accepted;
        self.drags_refused += o.drags_refused;
        self.injections_refused += o.injections_refused;
        self.invariant_checks += o.invariant_checks;
        self.invariant_violations += o.invariant_violations;
        self.partial_applies += o.partial_applies;
        self.plans_checked += o.plans_checked;
        self.invalid_plans += o.invalid_plans;
        self.tamp_fallbacks += o.tamp_fallbacks;
        self.successes += o.successes;
        for (k, v) in o.legitimate_failures {
            *self.legitimate_failures.entry(k).or_default() += v;
        }
        self.budget_exhausted += o.budget_exhausted;
        self.stalls += o.stalls;
        self.no_outcome += o.no_outcome;
        self.input_errors += o.input_errors;
        self.unexplained_failures += o.unexplained_failures;
        self.replay_mismatches += o.replay_mismatches;
        self.replays_checked += o.replays_checked;
        self.panics += o.panics;
        for f in o.findings {
            self.find(f);
        }
        for x in o.explained {
            self.explain(x);
        }
    }
}
