//! What the page draws: the [`Frame`] of a session (world, status line, plan, demonstration,
//! facts and their changes, end-effector points) and how it is read off the session.

use serde::{Deserialize, Serialize};

use crate::lfd::Replan;
use crate::sim::MoveOutcome;
use crate::sim::WorldSnapshot;

/// What the loop is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub enum StatusKind {
    /// Nothing has run yet.
    Idle,
    /// Looking for the first plan, or for a plan after an action ended.
    Planning,
    /// Executing a step of the plan.
    Executing,
    /// Executing the first steps of a plan made because the facts changed.
    Replanning,
    /// The goal holds.
    Done,
    /// The episode failed (the message says why).
    Failed,
}

/// The status line of the page.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct Status {
    /// What the loop is doing.
    pub kind: StatusKind,
    /// In words: "executing step 3 of 7: (stack c d)", "replanning because …", "failed because …".
    pub message: String,
    /// The step being executed (1-based), if any.
    pub step: Option<usize>,
    /// Number of steps in the plan, if any.
    pub of: Option<usize>,
}

/// End effector position and its commanded target (for the trajectory chart).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct EePoint {
    /// Arm index.
    pub arm: usize,
    /// TCP position (m).
    pub pos: [f64; 3],
    /// Commanded position (m); the TCP position when idle.
    pub target: [f64; 3],
}

/// Everything the page draws after a step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Frame {
    /// Simulated seconds.
    pub t: f64,
    /// 10 ms steps so far.
    pub tick: u64,
    /// Every body pose, arm joints and link capsules, grippers.
    pub world: WorldSnapshot,
    /// The status line.
    pub status: Status,
    /// The current plan, actions as `(stack a b)`.
    pub plan: Vec<String>,
    /// Index into `plan` of the action being executed.
    pub executing: Option<usize>,
    /// The demonstration's actions a_1..a_N.
    pub demo: Vec<String>,
    /// L_0..L_N (fluents).
    pub demo_states: Vec<Vec<String>>,
    /// Demonstration state index the current plan joins.
    pub matched_k: Option<usize>,
    /// S_C, sorted.
    pub facts: Vec<String>,
    /// Facts that appeared since the previous frame.
    pub facts_added: Vec<String>,
    /// Facts that disappeared since the previous frame.
    pub facts_removed: Vec<String>,
    /// The last replan.
    pub last_replan: Option<Replan>,
    /// Number of replans so far.
    pub replans: usize,
    /// End effector positions and targets.
    pub ee: Vec<EePoint>,
}

/// The outcome of an accepted drag.
pub type PerturbOutcome = MoveOutcome;
