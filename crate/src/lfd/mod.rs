//! Logic-LfD: the demonstration as a multi-goal specification, LogicIn, suffix merging, the
//! reactive closed loop of the paper's Algorithm 1, its baselines, and the browser [`session::Session`].
//!
//! * [`demo`]: L_0..L_N from the demonstrated actions, the goals 𝒢 with terminal costs c_k;
//! * [`logic`]: LogicIn, merge, Logic-LfD planning in `paper` and `prioritised` modes;
//! * [`symbolic`]: [`LogicLfd`], the method on any PDDL domain (text in, merged plans out);
//! * the reactive loop and the session (see their modules).

pub mod alternatives;
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

use serde::{Deserialize, Serialize};

pub use alternatives::{Alternative, AlternativeStatus};
pub use control::TaskBuilder;
pub use demo::{DemoTrace, MultiGoalSpec};
pub use error::LfdError;
pub use logic::{
    logic_in, merge_suffix, plan_logic_lfd, plan_logic_lfd_prepared, prepare_search, LfdPlan, Mode,
    PlanSource,
};
pub use symbolic::observed::Observed;
pub use symbolic::{LogicLfd, Perturbed};

/// The method that closes the loop (the paper's method and its baselines).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Method {
    /// Logic-LfD (Algorithm 1): LogicIn, else multi-goal search + demo suffix.
    #[default]
    #[serde(rename = "logic-lfd")]
    LogicLfd,
    /// The demonstration's actions in order, skills re-targeted, no task-level feedback.
    #[serde(rename = "linear")]
    Linear,
    /// RLDS: jump backward/forward along the demonstration to the matching step; never a new plan.
    #[serde(rename = "rlds")]
    Rlds,
    /// TAMP from scratch at every task-level change (the paper's PDDLStream column).
    #[serde(rename = "tamp")]
    Tamp,
}

impl Method {
    /// All methods, in table order.
    pub const ALL: [Method; 4] = [Method::Linear, Method::Rlds, Method::Tamp, Method::LogicLfd];

    /// The name used on the CLI and in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            Method::LogicLfd => "logic-lfd",
            Method::Linear => "linear",
            Method::Rlds => "rlds",
            Method::Tamp => "tamp",
        }
    }

    /// Parses a CLI / JSON name.
    pub fn parse(s: &str) -> Option<Self> {
        Method::ALL.into_iter().find(|m| m.as_str() == s)
    }
}
