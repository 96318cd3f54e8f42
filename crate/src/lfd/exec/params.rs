//! Tunables of action execution: speeds, tolerances and timeouts of the executor's segments
//! and gripper events, in one struct with the few values derived from them.

use crate::tamp::MotionParams;

/// Tunables of action execution (metres, seconds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExecParams {
    /// The heights of the motion (the streams certify the same).
    pub motion: MotionParams,
    /// Mean Cartesian speed of the end effector along a segment (m/s).
    pub speed: f64,
    /// Shortest duration of a segment (s).
    pub min_segment: f64,
    /// The end effector is "there" when within this distance of the segment's goal (m).
    pub reach_tolerance: f64,
    /// How long the arm may lag behind a segment's end before the action fails (s).
    pub settle_timeout: f64,
    /// Time given to the fingers to open or close (s).
    pub gripper_time: f64,
    /// An anchor object moving more than this re-plans the segment (m).
    pub reanchor_tolerance: f64,
    /// A segment whose end lags by more than `recovery_distance` (m) for `recovery_after` (s)
    /// recovers in joint space (planning IK) once. Equal to `reach_tolerance`: a tracker stuck a
    /// few mm short (a wrist at its limit) recovers too (1 cm left such arms stuck).
    pub recovery_distance: f64,
    /// See `recovery_distance` (s).
    pub recovery_after: f64,
    /// At a grasp the hand is "there" when also turned within this angle of the grasp's (rad);
    /// a larger error after `recovery_after` also recovers in joint space.
    pub orientation_tolerance: f64,
}

impl ExecParams {
    /// How long a joint-space recovery may move before Cartesian tracking takes over again (s):
    /// twice `settle_timeout`.
    pub fn joint_recovery_timeout(&self) -> f64 {
        2.0 * self.settle_timeout
    }

    /// Mean speed of a pull's stroke and of the lift after it (m/s): half `speed`.
    pub fn stroke_speed(&self) -> f64 {
        0.5 * self.speed
    }
}

impl Default for ExecParams {
    fn default() -> Self {
        ExecParams {
            motion: MotionParams::default(),
            speed: 0.35,
            min_segment: 0.3,
            reach_tolerance: 0.004,
            settle_timeout: 1.5,
            gripper_time: 0.15,
            reanchor_tolerance: 0.005,
            recovery_distance: 0.004,
            recovery_after: 0.25,
            orientation_tolerance: 0.1,
        }
    }
}
