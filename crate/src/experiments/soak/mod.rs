//! Closed-loop soak: many random Logic-LfD episodes over B1–B3 with random disturbances,
//! checking the loop's guarantees at every step.
//!
//! Episode `e` of a soak with seed `S` draws everything from `Pcg64Mcg(mix(S, e))`: the benchmark,
//! the multi-goal mode, the session seed, and a schedule of `0..=max_disturbances` disturbances at
//! random ticks in `[0, horizon_ticks)`; each is an injected level `L1`–`L4` or a user-like drag
//! through [`Session::perturb`](crate::lfd::session::Session::perturb) (onto another block, to a
//! table spot, a small nudge, or a hostile request: a held or fixed body, an unknown name, a
//! non-finite or far-away position). Checked:
//!
//! * **world invariants** ([`crate::sim::World::check_invariants`]) after every tick and every
//!   disturbance: no interpenetration, every free body supported, nothing lost, joints in limits;
//! * **nothing partially applied**: a refused drag or a disturbance that cannot be produced leaves
//!   the world's snapshot and the episode's event log byte-identical;
//! * **plan validity**: every plan the loop adopts is replayed by the lifted PDDL validator
//!   ([`crate::plan::validate_names`]) from the observed state it was planned in (the scene graph
//!   of the world at that tick, as a PDDL problem) to the benchmark's goal;
//! * **stated outcome**: every episode ends in success or in a
//!   [`FailReason`](crate::lfd::control::FailReason) that is *legitimate*, each class with its
//!   proof (kept in [`SoakReport::explained`]):
//!   - "no plan", when breadth-first search of the observed task (the world's facts, the
//!     benchmark's goal; no heuristic, duplicate detection) exhausts its reachable states within
//!     [`SoakParams::check_nodes`] expansions without reaching the goal;
//!   - a failure whose action (the failed one, or the one the planner could not bind) acts on a
//!     block a user dragged, when IK ([`handleable`](crate::sim::reach::handleable): no arm can
//!     grasp it nor pull it in with a clear stroke of the hook) shows that block unworkable now
//!     or right after its last drag (a block in a hand is judged where it is);
//!   - a block the goal puts on a shelf finding no room on any (the footprints on its top all
//!     taken, `shelf_full_for`; B2 cannot take a block off a shelf).
//!
//!   Everything else is a finding: a failure without such a proof (a "no plan" for a task the
//!   check solves, or one it could not decide within its budget), an exhausted planning or
//!   simulated-time budget, a session that stops advancing without an outcome, an episode with no
//!   outcome after [`SoakParams::max_ticks`], an observed task that cannot be written, parsed or
//!   grounded;
//! * **replay identity** (optional): the episode JSON replays to the byte-identical log.
//!
//! No clock is read: planning runs under the controller's node budgets, so a soak's report is a
//! pure function of its seed.
//!
//! This file holds the parameters, the report and the driver; `episode.rs` runs one episode and
//! `reasons.rs` holds the checks behind every legitimate reason for a failure.

mod episode;
mod reasons;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::lfd::session::mix;

use episode::soak_episode;
use reasons::Models;

/// Most findings a report keeps.
const MAX_FINDINGS: usize = 100;

/// Tunables of a soak.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
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
        }
    }
}

/// A broken guarantee, with enough to replay it (`logic-lfd soak --episodes 1 --seed …` or the
/// episode seed with `logic-lfd run`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SoakFinding {
    /// Episode index within the soak.
    pub episode: usize,
    /// Benchmark.
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
    /// Benchmark.
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
    /// Episodes per benchmark.
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
    fn find(&mut self, f: SoakFinding) {
        if self.findings.len() < MAX_FINDINGS {
            self.findings.push(f);
        }
    }

    /// Keeps a legitimate failure's proof (at most [`MAX_FINDINGS`]).
    fn explain(&mut self, x: ExplainedFailure) {
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
    fn merge(&mut self, o: SoakReport) {
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

/// Runs a soak (see the module documentation). Every episode runs under `catch_unwind` on
/// native targets, so a panic is counted as a finding instead of ending the soak.
pub fn soak(params: &SoakParams) -> Result<SoakReport, String> {
    soak_with(params, |_, _, _| {})
}

/// [`soak`], calling `on_episode(index, episode_report, episode_json)` after each episode (the
/// CLI saves the JSON of episodes with findings; `logic-lfd run --replay` re-runs them).
pub fn soak_with(
    params: &SoakParams,
    mut on_episode: impl FnMut(usize, &SoakReport, &str),
) -> Result<SoakReport, String> {
    let runner = SoakRunner::new(params)?;
    let mut episodes = Vec::with_capacity(params.episodes);
    for i in 0..params.episodes {
        let (ep, json) = runner.episode(i)?;
        on_episode(params.first_episode + i, &ep, &json);
        episodes.push(ep);
    }
    Ok(params.report(episodes))
}

impl SoakParams {
    /// The soak's report from its episodes' reports, given in episode order (the order fixes
    /// which findings and proofs the report keeps).
    pub fn report(&self, episodes: impl IntoIterator<Item = SoakReport>) -> SoakReport {
        let mut report = SoakReport {
            params: Some(*self),
            ..SoakReport::default()
        };
        for ep in episodes {
            report.merge(ep);
        }
        report
    }
}

/// A soak ready to run episode by episode, in any order or on several threads: the models its
/// checks need are built once and only read.
pub struct SoakRunner {
    params: SoakParams,
    models: Models,
}

impl SoakRunner {
    /// Builds the checks' models for `params`.
    pub fn new(params: &SoakParams) -> Result<SoakRunner, String> {
        Ok(SoakRunner {
            params: *params,
            models: Models::new(params.blocks)?,
        })
    }

    /// Runs the soak's `i`-th episode (episode `first_episode + i`, seeded from the soak's seed
    /// and its own index alone): its report and its episode JSON. A panic is caught on native
    /// targets and counted as a finding; an episode that cannot start is an error.
    pub fn episode(&self, i: usize) -> Result<(SoakReport, String), String> {
        let (params, e) = (&self.params, self.params.first_episode + i);
        let mut ep = SoakReport::default();
        let mut json = String::new();
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            soak_episode(params, e, &self.models, &mut ep, &mut json)
        }));
        match r {
            Ok(Ok(())) => {}
            Ok(Err(msg)) => return Err(format!("episode {e}: {msg}")),
            Err(p) => {
                let msg = super::panic_message(p.as_ref());
                ep.panics += 1;
                ep.find(SoakFinding {
                    episode: e,
                    benchmark: String::new(),
                    session_seed: mix(params.seed, e as u64),
                    tick: 0,
                    kind: "panic".into(),
                    detail: msg,
                });
            }
        }
        Ok((ep, json))
    }
}
