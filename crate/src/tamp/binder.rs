//! The interface between a symbolic plan and the streams: bind an action skeleton's continuous
//! parameters, or say which action could not be bound and what was in its way.

use crate::plan::{Operator, Task};

use super::action::Binding;

/// Why a skeleton could not be bound: the action no certified sample was found for, why its
/// last candidate was rejected and the movable bodies that were in its way.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BindFailure {
    /// Index in the skeleton (`ops`) of the action that could not be bound (with backtracking,
    /// the deepest one reached).
    pub action: usize,
    /// Why the last rejected candidate was rejected, in words (`None` if nothing was rejected
    /// with a reason).
    pub reason: Option<String>,
    /// The movable bodies that were in the way of the action's candidates (empty if nothing
    /// movable blocked it).
    pub blockers: Vec<String>,
}

/// Binds the continuous parameters of a plan (TAMP streams) or reports the first unbindable action.
pub trait Binder {
    /// Binds `ops` (operator indices of `task`) executed from the current world: one binding
    /// per action. Actions from `demo_from` on come from the demonstration and may reuse its
    /// parameters.
    fn bind(
        &mut self,
        task: &Task,
        ops: &[usize],
        demo_from: usize,
    ) -> Result<Vec<Binding>, BindFailure>;

    /// Draws more samples per parameter from now on (a retry after a failed binding).
    fn widen(&mut self) {}

    /// Whether operator `op` moves `body` (grasps it or pulls it in): what a ban waiting for a
    /// blocker to move watches for ([`crate::plan::BannedTask::ban_failed`]).
    fn moves_body(&self, op: &Operator, body: &str) -> bool {
        let _ = (op, body);
        false
    }
}

/// A binder that measures the time its inner binder spends binding (by the caller's clock): how
/// a replan's time splits into symbolic search and geometric binding.
pub struct TimedBinder<'a> {
    inner: &'a mut dyn Binder,
    clock: &'a dyn crate::plan::Clock,
    /// Seconds spent in [`Binder::bind`] so far.
    pub secs: f64,
}

impl<'a> TimedBinder<'a> {
    /// Wraps `inner`, timing it by `clock`.
    pub fn new(inner: &'a mut dyn Binder, clock: &'a dyn crate::plan::Clock) -> Self {
        TimedBinder {
            inner,
            clock,
            secs: 0.0,
        }
    }
}

impl Binder for TimedBinder<'_> {
    fn bind(
        &mut self,
        task: &Task,
        ops: &[usize],
        demo_from: usize,
    ) -> Result<Vec<Binding>, BindFailure> {
        let t0 = self.clock.now_secs();
        let r = self.inner.bind(task, ops, demo_from);
        self.secs += self.clock.now_secs() - t0;
        r
    }

    fn widen(&mut self) {
        self.inner.widen();
    }

    fn moves_body(&self, op: &Operator, body: &str) -> bool {
        self.inner.moves_body(op, body)
    }
}
