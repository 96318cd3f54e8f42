//! Closed-loop soak: many random Logic-LfD episodes over B1–B3 with random disturbances,
//! checking the loop's guarantees at every step.
//!
//! Episode `e` of a soak with seed `S` draws everything from `Pcg64Mcg(mix_seed(S, e))`: the benchmark
//! (unless the soak runs a task folder's task, [`SoakRunner::in_folder`], in the folder's own
//! scene), the multi-goal mode, the session seed, and a schedule of `0..=max_disturbances` disturbances at
//! random ticks in `[0, horizon_ticks)`; each is an injected level `L1`–`L4` or a user-like drag
//! through [`Session::perturb`](crate::lfd::Session::perturb) (onto another block, to a
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
//!   [`FailReason`](crate::lfd::FailReason) that is *legitimate*, each class with its
//!   proof (kept in [`SoakReport::explained`]):
//!   - "no plan", when breadth-first search of the observed task (the world's facts, the
//!     benchmark's goal; no heuristic, duplicate detection) exhausts its reachable states within
//!     [`SoakParams::check_nodes`] expansions without reaching the goal;
//!   - a failure whose action (the failed one, or the one the planner could not bind) acts on a
//!     block a user dragged, when IK ([`handleable`](crate::sim::handleable): no arm can
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
//! This file holds the driver; `report.rs` the parameters and the report, `episode.rs` runs one
//! episode and `reasons.rs` holds the checks behind every legitimate reason for a failure.

mod episode;
mod reasons;
mod report;

use crate::lfd::mix_seed;
use crate::sim::ArmModel;
use crate::sim::{BenchmarkSources, TaskFolder};
use std::sync::Arc;

use episode::soak_episode;
use reasons::Models;
pub use report::{ExplainedFailure, SoakFinding, SoakParams, SoakReport};

/// Runs a soak over the benchmarks (see the module documentation). Every episode runs under `catch_unwind` on
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
            params: Some(self.clone()),
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
    /// The task folder's files (`None`: the benchmarks').
    folder: Option<BenchmarkSources>,
    /// Robots in place of the scenes' arms.
    robots: Vec<Arc<ArmModel>>,
}

impl SoakRunner {
    /// Builds the checks' models for `params` (a soak over the benchmarks).
    pub fn new(params: &SoakParams) -> Result<SoakRunner, String> {
        if let Some(f) = &params.folder {
            return Err(format!(
                "the soak runs the task folder {}: start it with SoakRunner::in_folder",
                f.dir
            ));
        }
        Ok(SoakRunner {
            params: params.clone(),
            models: Models::new(params.blocks)?,
            folder: None,
            robots: vec![],
        })
    }

    /// A soak of `folder`'s task: every episode starts in the folder's scene, with random
    /// disturbances drawn in it; the parameters record the folder ([`SoakRunner::params`]).
    pub fn in_folder(params: &SoakParams, folder: &TaskFolder) -> Result<SoakRunner, String> {
        if params.blocks.is_some() {
            return Err(format!(
                "{}: a task folder runs its own task, not a generated tower of N blocks",
                folder.dir
            ));
        }
        let sources = folder.sources().map_err(|e| e.to_string())?;
        let models = Models::in_folder(&sources)?;
        Ok(SoakRunner {
            params: SoakParams {
                folder: sources.folder.clone(),
                ..params.clone()
            },
            models,
            folder: Some(sources),
            robots: vec![],
        })
    }

    /// The soak on `robots` in place of the scenes' arms (one for every arm, or one per arm;
    /// [`Session::set_robots`](crate::lfd::Session::set_robots)); the parameters name them.
    pub fn with_robots(mut self, robots: Vec<Arc<ArmModel>>) -> SoakRunner {
        self.params.robots = robots.iter().map(|r| r.name().to_string()).collect();
        self.robots = robots;
        self
    }

    /// The soak's parameters (with its task folder, if it runs one).
    pub fn params(&self) -> &SoakParams {
        &self.params
    }

    /// Runs the soak's `i`-th episode (episode `first_episode + i`, seeded from the soak's seed
    /// and its own index alone): its report and its episode JSON. A panic is caught on native
    /// targets and counted as a finding; an episode that cannot start is an error.
    pub fn episode(&self, i: usize) -> Result<(SoakReport, String), String> {
        let (params, e) = (&self.params, self.params.first_episode + i);
        let mut ep = SoakReport::default();
        let mut json = String::new();
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            soak_episode(
                params,
                e,
                &self.models,
                self.folder.as_ref(),
                &self.robots,
                &mut ep,
                &mut json,
            )
        }));
        match r {
            Ok(Ok(())) => {}
            Ok(Err(msg)) => return Err(format!("episode {e}: {msg}")),
            Err(p) => {
                let msg = crate::experiments::panic_message(p.as_ref());
                ep.panics += 1;
                ep.find(SoakFinding {
                    episode: e,
                    benchmark: String::new(),
                    session_seed: mix_seed(params.seed, e as u64),
                    tick: 0,
                    kind: "panic".into(),
                    detail: msg,
                });
            }
        }
        Ok((ep, json))
    }
}
