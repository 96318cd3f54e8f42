//! The running execution of one action and how it stands after a tick.

use nalgebra::Isometry3;

use super::steps::{Anchor, Phase};
use crate::lfd::SkillSegment;
use crate::sim::{GripperCommand, WorldEvent};
use crate::tamp::ActionKind;
use crate::tamp::MotionParams;

/// The running execution of one action.
#[derive(Clone, Debug)]
pub struct ActionExec {
    /// The action `(stack a b)`.
    pub action: String,
    /// What it does.
    pub kind: ActionKind,
    pub(super) arm: usize,
    pub(super) phases: Vec<Phase>,
    pub(super) phase: usize,
    /// The segment being followed: planned TCP positions, one per tick, and its goal.
    pub(super) segment: Option<Running>,
    /// Ticks spent waiting in the current phase.
    pub(super) wait: usize,
    pub(super) gripper: GripperCommand,
    /// Events seen during the action.
    pub events: Vec<WorldEvent>,
    /// The anchor frame at the gripper event (frame of the retreat skill).
    pub(super) event_frame: Option<Isometry3<f64>>,
    /// Phase before which a transit (rise, move over, descend) was inserted.
    pub(super) transit_at: Option<usize>,
    /// The body acted on is the hook (its skills are the `…@hook` ones).
    pub(super) hook: bool,
    /// The motion's heights: the grasp is chosen with the hand clear up to half the approach
    /// height.
    pub(super) motion: MotionParams,
    /// The yaw of the TCP's x axis a release was certified with (`None`: the heading from the
    /// base).
    pub(super) hand_yaw: Option<f64>,
    /// Why the action failed, once its remaining phases only undo it (a lift stopped at the
    /// start: the body is let go where it was grasped).
    pub(super) abort: Option<String>,
    /// The TCP's height when the gripper closed on the body it grasps.
    pub(super) grasped_z: Option<f64>,
}

#[derive(Clone, Debug)]
pub(super) struct Running {
    pub(super) traj: SkillSegment,
    pub(super) t: usize,
    pub(super) goal: Isometry3<f64>,
    /// Body watched for re-anchoring, where it was, and the skill frame planned for.
    pub(super) anchor: Option<Anchor>,
    /// The step from which the anchor is no longer followed (a stroke's: the hook is behind the
    /// block, which moves because the hook drags it).
    pub(super) anchor_until: Option<usize>,
    pub(super) frame: Option<Isometry3<f64>>,
    pub(super) lag: usize,
    /// Joint-space recovery: the joint goals still to reach, the first followed instead of the
    /// Cartesian command while there is one (the planning IK's joints for `goal`, perhaps by
    /// way of the ready posture first); `recovered` once tried for this segment.
    pub(super) joint_goals: Vec<[f64; crate::sim::panda::DOF]>,
    pub(super) recovered: bool,
    /// Ticks spent in joint-space recovery.
    pub(super) joint_ticks: usize,
    /// A rise the arm could not make where it was, made by going to the ready posture instead
    /// (the segment ends there).
    pub(super) rise_by_ready: bool,
}

/// How an action's execution stands after a tick.
#[derive(Clone, Debug, PartialEq)]
pub enum ExecStatus {
    /// Still moving.
    Running,
    /// Finished; the world should now show the action's effects.
    Done,
    /// Could not be completed (why, in words).
    Failed(String),
}
