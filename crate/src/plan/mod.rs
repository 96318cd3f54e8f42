//! Grounded planning: the [`Task`] (facts as packed bitsets, operators with precondition/add/delete
//! lists), grounding from PDDL, search algorithms, heuristics, the multi-goal search of Logic-LfD
//! the plan validator, plan replay and the task rewrites (bans) of a replan's retries.

mod bans;
mod ground;
mod task;
mod validate;

pub use bans::{BannedTask, MovesBody, STATE_BANS};
pub use ground::{ground, GroundError};
pub use task::{fact_args, replay, Condition, FactId, Goal, Operator, State, Task, UnknownFact};
pub use validate::{
    parse_plan, validate, validate_names, Outcome, PlanStep, PlanToken, ValidationReport,
};

mod clock;
mod heuristic;
mod multigoal;
mod regress;
mod relevance;
mod search;

pub use clock::{Clock, NoClock, PROGRESS_EVERY};
pub use heuristic::{HeuristicEvaluator, HeuristicKind, UnknownName};
pub use multigoal::{search_multi_goal, MultiGoalMode, MultiGoalResult, MultiGoalSearch};
pub use regress::{reaches_goal, regress};
pub use relevance::{relevant_part, Relevance};
pub use search::{
    search, search_from, Algorithm, Budget, Plan, SearchConfig, SearchOutcome, SearchResult,
    SearchStats,
};
