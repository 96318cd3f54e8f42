//! The pieces of an expert motion: way-point segments and what the expert does per action.

use crate::sim::world::GripperCommand;
use nalgebra::Isometry3;

/// One way-point segment of an expert motion.
pub(super) struct Seg {
    pub(super) to: Isometry3<f64>,
    pub(super) duration: f64,
    pub(super) gripper: Option<GripperCommand>,
    pub(super) key: Option<&'static str>,
}

/// What the expert does for one action.
pub(super) enum Step {
    Pick {
        arm: usize,
        x: String,
    },
    Place {
        arm: usize,
        x: String,
        /// Where the carried body should rest.
        target: Isometry3<f64>,
        /// Go back to the home pose afterwards (B3 hand-over, so the arms keep apart).
        retreat: bool,
    },
    Pull {
        arm: usize,
        hook: String,
        x: String,
    },
}

/// Shortest transfer segment (s).
pub(super) const MIN_TRANSFER_TIME: f64 = 0.6;
