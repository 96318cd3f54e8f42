//! The interface between a symbolic plan and the streams: bind an action skeleton's continuous
//! parameters, or say which action could not be bound and what was in its way.

use crate::plan::Task;

/// Binds the continuous parameters of a plan (TAMP streams) or reports the first unbindable action.
pub trait Binder {
    /// Binds `ops` (operator indices of `task`) executed from the current world. Actions from
    /// `demo_from` on come from the demonstration and may reuse its parameters.
    fn bind(&mut self, task: &Task, ops: &[usize], demo_from: usize) -> Result<(), usize>;

    /// Draws more samples per parameter from now on (a retry after a failed binding).
    fn widen(&mut self) {}

    /// Why the last candidate was rejected, in words (`None` if nothing was rejected).
    fn last_rejection(&self) -> Option<String> {
        None
    }

    /// The movable bodies that were in the way of action `i` of the last skeleton [`bind`]
    /// could not bind (empty if nothing movable blocked it).
    ///
    /// [`bind`]: Binder::bind
    fn obstructions(&self, _i: usize) -> Vec<String> {
        vec![]
    }
}
