//! The task level's vocabulary: the decisions it hands the executor, why an episode failed,
//! the replans it logs and its tunables.

use serde::{Deserialize, Serialize};

use crate::plan::SearchConfig;

/// Why an episode failed (asserted by the tests, shown by the page).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum FailReason {
    /// The plan ran out but the goal does not hold (linear).
    GoalNotReached {
        /// Goal facts that do not hold.
        missing: Vec<String>,
    },
    /// No step of the demonstration has its remaining actions applicable in S_C and reaching
    /// the goal, and the method cannot plan (rlds).
    NoDemoStateMatches {
        /// S_C, sorted.
        facts: Vec<String>,
    },
    /// The planner found no plan.
    NoPlan {
        /// The planner's message.
        message: String,
    },
    /// An action could not be executed (linear executes blindly).
    ActionFailed {
        /// The action.
        action: String,
        /// Why.
        why: String,
    },
    /// Too many replans or too much simulated time.
    Budget {
        /// Which budget.
        what: String,
    },
}

impl std::fmt::Display for FailReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FailReason::GoalNotReached { missing } => {
                write!(f, "the plan ended but {} does not hold", missing.join(" "))
            }
            FailReason::NoDemoStateMatches { .. } => {
                write!(
                    f,
                    "no remaining part of the demonstration applies to the scene"
                )
            }
            FailReason::NoPlan { message } => write!(f, "no plan: {message}"),
            FailReason::ActionFailed { action, why } => write!(f, "{action} failed: {why}"),
            FailReason::Budget { what } => write!(f, "{what} exhausted"),
        }
    }
}

/// One replan, as logged.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Replan {
    /// Why: `start`, `(on c d) no longer holds`, `(on e b) appeared`, …
    pub reason: String,
    /// Planning time in milliseconds by the caller's clock (not part of the replay identity).
    pub time_ms: f64,
    /// The demonstration state index the plan joins.
    pub k: Option<usize>,
    /// The new plan.
    pub plan: Vec<String>,
    /// Simulation tick when it happened.
    pub tick: u64,
    /// How many leading actions of the plan are new (not from the demonstration).
    pub new_actions: usize,
    /// The part of `time_ms` spent binding actions to motions (streams: grasps, placements,
    /// pulls); the rest is symbolic search. By the caller's clock, not part of the replay
    /// identity.
    #[serde(default)]
    pub bind_ms: f64,
    /// States the symbolic searches of this replan expanded.
    #[serde(default)]
    pub expanded: u64,
    /// Logic-LfD found no skeleton joining the demonstration that binds and planned to G from
    /// scratch instead (the TAMP fallback, [`ControlParams::tamp_fallback`]).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub fallback: bool,
    /// Logic-LfD: every candidate L_k with the prefix, suffix and total cost its search found,
    /// the joined one marked (empty for the other methods and the TAMP fallback).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub alternatives: Vec<crate::lfd::Alternative>,
}

/// What the controller asks the executor to do.
#[derive(Clone, Debug, PartialEq)]
pub enum Decision {
    /// Execute this action (index into the current plan).
    Execute {
        /// Index into [`Controller::plan_names`](super::Controller::plan_names).
        index: usize,
        /// The action `(stack a b)`.
        action: String,
    },
    /// The goal holds.
    Done,
    /// The episode failed.
    Failed(FailReason),
}

/// Tunables of the task level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlParams {
    /// Search configuration for Logic-LfD's multi-goal search and the TAMP skeletons (default
    /// A* + LM-cut, 20 000 expansions). A Logic-LfD replan whose optimal search runs out of
    /// budget retries with lazy GBFS + h_FF under the same budget.
    pub search: SearchConfig,
    /// Maximum replans in an episode before giving up.
    pub max_replans: usize,
    /// Skeletons tried per replan when binding fails (TAMP / Logic-LfD): the first and up to
    /// `max_skeletons − 1` retries, each with the failed action banned at the state where it
    /// failed and more samples per parameter.
    pub max_skeletons: usize,
    /// When none of Logic-LfD's skeletons binds, plan to G from scratch (the TAMP solver it
    /// wraps) so the loop still finishes; logged in [`Replan::fallback`]. The page and the soak
    /// keep it on; the tables turn it off to count Logic-LfD's own success.
    pub tamp_fallback: bool,
}

impl Default for ControlParams {
    fn default() -> Self {
        ControlParams {
            search: SearchConfig {
                algorithm: crate::plan::Algorithm::Astar,
                heuristic: crate::plan::HeuristicKind::LmCut,
                max_nodes: Some(20_000),
                time_limit_secs: None,
            },
            max_replans: 40,
            max_skeletons: 10,
            tamp_fallback: true,
        }
    }
}
