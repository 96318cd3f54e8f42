//! Typed errors of the LQT-CP layer: every bad input names its key and the expected shape.

use thiserror::Error;

/// Everything that can go wrong when building or solving an LQT-CP problem, a skill or a DMP.
///
/// Nothing in [`crate::lqt`] panics on user input; a malformed case is one of these.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LqtError {
    /// A key of the input is missing, has the wrong type or shape, or an invalid value.
    ///
    /// `key` is a dotted path such as `reference.mu` or `targets[1].pos`.
    #[error("{key}: {message}")]
    Input {
        /// Dotted path of the offending key (`reference.q_diag`, `basis.n_fct`, …).
        key: String,
        /// What was expected and what was found.
        message: String,
    },
    /// The input is not valid JSON.
    #[error("{line}:{column}: {message}")]
    Json {
        /// 1-based line of the syntax error.
        line: usize,
        /// 1-based column of the syntax error.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// A linear system of the solve is singular (e.g. a basis function that is never active and
    /// `r = 0`, or a closed-loop transition matrix that cannot be inverted in the gain recursion).
    #[error("singular system: {0}")]
    Singular(String),
    /// The computation produced a non-finite number (overflow with extreme weights).
    #[error("numerical failure: {0}")]
    NonFinite(String),
}

impl LqtError {
    /// Shorthand for [`LqtError::Input`].
    pub(crate) fn input(key: impl Into<String>, message: impl Into<String>) -> Self {
        LqtError::Input {
            key: key.into(),
            message: message.into(),
        }
    }
}
