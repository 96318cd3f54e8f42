//! Which motion skill family executes the actions.

use serde::{Deserialize, Serialize};

/// Which motion skill family executes the actions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "lowercase")]
pub enum SkillKind {
    /// LQT-CP (the paper's).
    #[default]
    Lqt,
    /// Classic DMP (the comparison).
    Dmp,
}
