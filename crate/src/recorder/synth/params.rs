//! Tunables of the synthesised motions, and the refusal every synthesiser returns.

use crate::recorder::RecorderError;
use serde::{Deserialize, Serialize};

/// Tunables of the synthesised motions.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SynthParams {
    /// Cartesian speed of transfers (m/s).
    pub speed: f64,
    /// Height of the approach way-points above the higher of grasp and place (m).
    pub approach_height: f64,
    /// Duration of every descent and lift (s).
    pub contact_time: f64,
    /// Time the gripper holds still while closing or opening (s).
    pub hold_time: f64,
    /// Speed of the hook while pulling (m/s).
    pub pull_speed: f64,
}

impl Default for SynthParams {
    fn default() -> Self {
        SynthParams {
            speed: 0.3,
            approach_height: 0.10,
            contact_time: 0.6,
            hold_time: 0.3,
            pull_speed: 0.25,
        }
    }
}

/// A refusal with the message `m`.
pub(super) fn refused(m: impl Into<String>) -> RecorderError {
    RecorderError::Refused(m.into())
}
