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
pub mod exec;
pub mod logic;
pub mod model;
pub mod session;
pub mod skill;
pub mod symbolic;
#[cfg(test)]
pub(crate) mod testing;

use crate::pddl::PddlError;

pub use alternatives::{Alternative, AlternativeStatus};
pub use catalogue::{Method, Mode};
pub use control::TaskBuilder;
pub use demo::{DemoTrace, MultiGoalSpec};
pub use logic::{
    logic_in, merge_suffix, plan_logic_lfd, plan_logic_lfd_prepared, prepare_search, LfdPlan,
    PlanSource,
};
pub use symbolic::{LogicLfd, Observed, Perturbed};

/// What went wrong in the Logic-LfD layer.
#[derive(Debug, thiserror::Error)]
pub enum LfdError {
    /// A file or text input does not parse, or names something the domain does not have
    /// (`file:line:col: message`).
    #[error(transparent)]
    Input(#[from] PddlError),
    /// A demonstrated action is not an operator of the grounded task.
    #[error("demonstration step {} `{action}` is not an action of the domain", index + 1)]
    UnknownAction {
        /// Position in the demonstration (0-based).
        index: usize,
        /// The action as written.
        action: String,
    },
    /// A demonstrated action's preconditions do not hold where the demo applies it.
    #[error(
        "{}demonstration step {} `{action}` is not applicable: {}",
        location.as_deref().map(|l| format!("{l}: ")).unwrap_or_default(),
        index + 1,
        false_precondition(false_literals)
    )]
    DemoNotApplicable {
        /// Position in the demonstration (0-based).
        index: usize,
        /// The action.
        action: String,
        /// The precondition literals that are false there (empty when not known).
        false_literals: Vec<String>,
        /// `file:line:col` of the step, when read from a file.
        location: Option<String>,
    },
    /// Applying the whole demonstration does not reach the task's goal.
    #[error(
        "the demonstration does not reach the goal{}",
        goal_literals(false_literals)
    )]
    DemoMissesGoal {
        /// The goal literals false at the end of the demonstration (empty when not known).
        false_literals: Vec<String>,
    },
    /// A plan prefix given as the current state does not apply.
    #[error(
        "{location}: step {step} `{action}` is not applicable: {}",
        false_precondition(false_literals)
    )]
    PrefixNotApplicable {
        /// 1-based step number.
        step: usize,
        /// The step.
        action: String,
        /// `file:line:col` of the step.
        location: String,
        /// The precondition literals that are false there.
        false_literals: Vec<String>,
    },
    /// The search proved that no demonstration state and not the goal can be reached.
    #[error("no plan: {0}")]
    NoPlan(String),
    /// The search ran out of its node or time budget.
    #[error("no plan: {0} exhausted")]
    Budget(String),
    /// The benchmark's PDDL, scene or demonstration could not be read.
    #[error("{0}")]
    Model(String),
    /// The prefix found to L_k could not be merged with the demo suffix.
    #[error("the plan to demonstration state L_{k} does not merge with the demo suffix")]
    MergeFailed {
        /// The demonstration state index.
        k: usize,
    },
}

fn false_precondition(literals: &[String]) -> String {
    if literals.is_empty() {
        "a precondition is false".into()
    } else {
        format!("false precondition {}", literals.join(" "))
    }
}

fn goal_literals(literals: &[String]) -> String {
    if literals.is_empty() {
        String::new()
    } else {
        format!(": {} false at its end", literals.join(" "))
    }
}
