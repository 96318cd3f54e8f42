//! Task and motion planning: plan a skeleton, bind its continuous parameters with certified
//! streams, retry (PDDLStream's lazy idea, our own code).
//!
//! ```text
//!   repeat up to max_skeletons (the first try and its retries):
//!     π ← Search(task with bans, S_C → G)            (the action skeleton)
//!     bind π: roll the geometry forward; for each action draw samples from its stream (grasp,
//!             placement on table/shelf/block, pull stroke, hand-over spot) until one is
//!             certified (collision-free along its motion with parry, trackable by IK) — or
//!             report the first failing action a_i
//!     success → π with its bindings
//!     failure at a_i → ban a_i at the state where it failed (not everywhere) or, when movable
//!             bodies were in its way, until one of them has moved; more samples
//! ```
//!
//! This is what Logic-LfD uses to bind the actions it adds, and the "plan from scratch" baseline
//! of the paper's Table I (the PDDLStream column). Streams live in [`StreamBinder`].

mod action;
mod binder;
mod motion;
mod streams;

pub use action::{
    classify, moves_body, release_target, ActionKind, Binding, Placement, PlanarPose, ReleaseTarget,
};
pub use motion::MotionParams;
pub(crate) use motion::{
    grasp_pose, joint_recovery, release_turns, rise_before_action, transit_height, JointMoves,
    LiveArm, RecoveryRoute,
};
pub use streams::{StreamBinder, StreamParams, StreamStats, WIDEN_LIMIT};

pub use binder::{BindFailure, Binder, TimedBinder};

use crate::plan::{
    replay, search, BannedTask, Clock, Operator, SearchConfig, SearchOutcome, State, Task,
};

/// Why TAMP found no plan.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TampError {
    /// The symbolic search found no skeleton (unsolvable or out of budget).
    #[error("no action skeleton: {0}")]
    NoSkeleton(String),
    /// Every skeleton tried had an action whose parameters no sample could certify.
    #[error("{skeletons} skeletons tried; last failure: cannot bind {action}{}", why.as_ref().map(|w| format!(" ({w})")).unwrap_or_default())]
    Unbindable {
        /// Skeletons tried.
        skeletons: usize,
        /// The action that failed last.
        action: String,
        /// Why its last candidate was rejected.
        why: Option<String>,
    },
}

/// A plan whose continuous parameters are bound: the operators and one binding per operator.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BoundPlan {
    /// Operator indices of the task, in order.
    pub ops: Vec<usize>,
    /// What the streams bound for each operator of `ops`.
    pub bindings: Vec<Binding>,
    /// States the skeleton searches expanded, over every try.
    pub expanded: u64,
}

/// TAMP from scratch: skeletons from `s` to the task's goal, bound by `binder`.
pub fn plan_from_scratch(
    task: &Task,
    s: &State,
    binder: &mut dyn Binder,
    config: &SearchConfig,
    max_skeletons: usize,
    clock: &dyn Clock,
) -> Result<BoundPlan, TampError> {
    let mut t = task.clone();
    t.init = s.clone();
    let mut banned = BannedTask::new(&t);
    let mut last = String::new();
    let mut why = None;
    let mut tries = 0;
    let mut expanded = 0;
    for tried in 0..max_skeletons.max(1) {
        tries = tried + 1;
        let r = search(&banned.task, config, clock);
        expanded += r.stats.expanded;
        let ops = match r.outcome {
            SearchOutcome::Plan(p) => banned.original(&p.operators),
            SearchOutcome::Unsolvable if tried == 0 => {
                return Err(TampError::NoSkeleton("the goal is unreachable".into()))
            }
            SearchOutcome::Unsolvable => break,
            SearchOutcome::BudgetExhausted { which } => {
                return Err(TampError::NoSkeleton(format!("{which} exhausted")))
            }
        };
        match binder.bind(&t, &ops, ops.len()) {
            Ok(bindings) => {
                return Ok(BoundPlan {
                    ops,
                    bindings,
                    expanded,
                })
            }
            Err(failure) => {
                let i = failure.action;
                last = t.operators[ops[i]].name.clone();
                if let Ok(at) = replay(&t, s, &ops[..i]) {
                    let moves = |_: &Task, o: &Operator, b: &str| binder.moves_body(o, b);
                    banned.ban_failed(ops[i], &at, &ops[..i], &failure.blockers, &moves);
                }
                why = failure.reason;
                binder.widen();
            }
        }
    }
    Err(TampError::Unbindable {
        skeletons: tries,
        action: last,
        why,
    })
}
