//! Grounded planning: the [`Task`] (facts as packed bitsets, operators with precondition/add/delete
//! lists), grounding from PDDL, search algorithms, heuristics, the multi-goal search of Logic-LfD
//! and the plan validator.

mod ground;
mod task;

pub use ground::{ground, GroundError};
pub use task::{Condition, FactId, Goal, Operator, State, Task};
