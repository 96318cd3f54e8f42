//! Grounded planning: the [`Task`] (facts as packed bitsets, operators with precondition/add/delete
//! lists), search algorithms, heuristics, the multi-goal search of Logic-LfD and the plan validator.

mod task;

pub use task::{Condition, FactId, Goal, Operator, State, Task};
