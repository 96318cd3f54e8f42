//! The steps of an action's motion: phases, via-points and the body a segment follows.

use nalgebra::Vector3;

use crate::sim::GripperCommand;
use crate::tamp::Placement;

/// One step of an action's motion.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Phase {
    /// Move the TCP to a via-point defined relative to the anchor.
    Move(Via),
    /// Open or close the gripper and wait.
    Gripper(GripperCommand),
}

/// A via-point: where the TCP goes, computed from the world when the segment starts (and again
/// when its anchor moves).
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Via {
    /// Above the grasp pose of `body` by `dz` (`skill`: run the learned grasp-approach skill).
    Grasp { body: String, dz: f64, skill: bool },
    /// The TCP pose that puts the held body at the placement, raised by `dz` (`skill`: the
    /// learned place-approach skill).
    Place {
        placement: Placement,
        dz: f64,
        skill: bool,
    },
    /// Straight up by `dz` from where the TCP is (`skill`: the learned retreat of the action,
    /// in the frame recorded at the gripper event).
    Up { dz: f64, skill: bool },
    /// A pull stroke: hook blade behind `body`, then dragged towards the base (`stage` 0..3),
    /// the stroke turned by `turn` rad.
    Pull { body: String, stage: u8, turn: f64 },
    /// A pull's learned stroke (stages 1 and 2 in one skill): from above the contact pose down
    /// behind `body`, through the skill's via-points, and the drag to the pulled pose.
    Stroke { body: String, turn: f64 },
    /// Transit: straight up (or down) to TCP height `z`.
    Rise { z: f64 },
    /// Where the TCP is, with the joints that leave the most room to their limits: a joint-space
    /// move that unwinds an arm left with a joint at its limit ([`unwound`](super::recovery::unwound); none if that move
    /// would sweep the arm through something).
    Unwind,
    /// Transit: above the goal of `inner`, at TCP height `z`.
    Over { inner: Box<Via>, z: f64 },
}

impl Via {
    /// A learned skill's approach to a grasp or a release (its shape is the demonstration's, not
    /// the straight line the streams certify).
    pub(super) fn is_learned_approach(&self) -> bool {
        matches!(
            self,
            Via::Grasp { skill: true, .. } | Via::Place { skill: true, .. }
        )
    }
}

/// Whether a segment to `via` must not be replaced by a transit: the hook's stroke itself (from
/// its contact pose on), and transits.
pub(super) fn no_transit(via: &Via) -> bool {
    matches!(
        via,
        Via::Rise { .. } | Via::Over { .. } | Via::Unwind | Via::Stroke { .. }
    ) || matches!(via, Via::Pull { stage, .. } if *stage > 0)
}

/// A body followed for re-anchoring: its name and where it was.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Anchor {
    pub(super) body: String,
    pub(super) at: Vector3<f64>,
}
