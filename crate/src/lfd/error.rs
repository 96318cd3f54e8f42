//! What went wrong in the Logic-LfD layer.

use crate::pddl::PddlError;

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
    Budget(crate::plan::Budget),
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
