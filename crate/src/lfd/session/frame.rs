//! What the page draws: the [`Frame`] of a session (world, status line, plan, demonstration,
//! facts and their changes, end-effector points) and how it is read off the session.

use serde::{Deserialize, Serialize};

use crate::lfd::control::Replan;
use crate::sim::snapshot::WorldSnapshot;
use crate::sim::MoveOutcome;

use super::{facts_of, Session};

/// For this many ticks after a replan (other than the first plan) the status line says
/// "replanning because …".
const REPLAN_NOTICE_TICKS: u64 = 50;

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

impl Session {
    /// The current frame without stepping.
    pub fn frame(&self) -> Frame {
        let facts = facts_of(&self.world);
        let plan = self.controller.plan_names().to_vec();
        let executing = self.exec.as_ref().map(|_| self.controller.cursor());
        let replans = self.controller.replans();
        let status = self.status(&plan, executing);
        let ee = (0..self.world.arm_names().len())
            .filter_map(|a| {
                let tcp = self.world.tcp_pose(a)?.translation.vector;
                let target = self
                    .exec
                    .as_ref()
                    .filter(|e| e.arm() == a)
                    .and_then(|e| e.target())
                    .unwrap_or(tcp);
                Some(EePoint {
                    arm: a,
                    pos: [tcp.x, tcp.y, tcp.z],
                    target: [target.x, target.y, target.z],
                })
            })
            .collect();
        Frame {
            t: self.world.time(),
            tick: self.tick,
            world: self.world.snapshot(),
            status,
            plan,
            executing,
            demo: self.trace.actions.clone(),
            demo_states: self
                .trace
                .states
                .iter()
                .map(|s| s.iter().cloned().collect())
                .collect(),
            matched_k: self.controller.matched_k(),
            facts,
            facts_added: self.frame_added.clone(),
            facts_removed: self.frame_removed.clone(),
            last_replan: replans.last().cloned(),
            replans: replans.len(),
            ee,
        }
    }

    fn status(&self, plan: &[String], executing: Option<usize>) -> Status {
        let st = |kind, message: String, step: Option<usize>, of: Option<usize>| Status {
            kind,
            message,
            step,
            of,
        };
        match &self.outcome {
            Some(Ok(())) => return st(StatusKind::Done, "done: the goal holds".into(), None, None),
            Some(Err(r)) => {
                return st(
                    StatusKind::Failed,
                    format!("failed because {r}"),
                    None,
                    None,
                )
            }
            None => {}
        }
        match executing {
            Some(i) => {
                let replan = self.controller.replans().last();
                let fresh = replan.is_some_and(|r| {
                    r.tick + REPLAN_NOTICE_TICKS > self.tick && r.reason != "start"
                });
                let kind = if fresh {
                    StatusKind::Replanning
                } else {
                    StatusKind::Executing
                };
                let msg = match (fresh, replan) {
                    (true, Some(r)) => format!(
                        "replanned because {}; executing step {} of {}: {}",
                        r.reason,
                        i + 1,
                        plan.len(),
                        plan.get(i).cloned().unwrap_or_default()
                    ),
                    _ => format!(
                        "executing step {} of {}: {}",
                        i + 1,
                        plan.len(),
                        plan.get(i).cloned().unwrap_or_default()
                    ),
                };
                st(kind, msg, Some(i + 1), Some(plan.len()))
            }
            None if self.tick == 0 => st(StatusKind::Idle, "ready".into(), None, None),
            None => st(StatusKind::Planning, "planning".into(), None, None),
        }
    }
}
