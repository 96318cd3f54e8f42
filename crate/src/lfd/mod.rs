//! Logic-LfD: the demonstration as a multi-goal specification, LogicIn, suffix merging, the
//! reactive closed loop of the paper's Algorithm 1, its baselines, and the browser [`session::Session`].
//!
//! * [`demo`]: L_0..L_N from the demonstrated actions, the goals 𝒢 with terminal costs c_k;
//! * [`logic`]: LogicIn, merge, Logic-LfD planning in `paper` and `prioritised` modes;
//! * [`symbolic`]: [`LogicLfd`], the method on any PDDL domain (text in, merged plans out);
//! * [`catalogue`]: every method, mode, benchmark and disturbance level by id, label and
//!   description;
//! * the reactive loop and the session (see their modules).

pub mod alternatives;
pub mod catalogue;
pub mod control;
pub mod demo;
pub mod disturb;
mod error;
pub mod exec;
pub mod logic;
pub mod model;
pub mod session;
pub mod skill;
pub mod symbolic;
#[cfg(test)]
pub(crate) mod testing;

pub use alternatives::{Alternative, AlternativeStatus};
pub use catalogue::{Method, Mode};
pub use control::TaskBuilder;
pub use demo::{DemoTrace, MultiGoalSpec};
pub use error::LfdError;
pub use logic::{
    logic_in, merge_suffix, plan_logic_lfd, plan_logic_lfd_prepared, prepare_search, LfdPlan,
    PlanSource,
};
pub use symbolic::observed::Observed;
pub use symbolic::{LogicLfd, Perturbed};
