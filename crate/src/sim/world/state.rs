//! The world's state: the [`World`] itself, its tunables and the small types its stages share.

use super::body::Body;
use crate::sim::panda::DOF;
use crate::sim::Motions;
use crate::sim::ReachSnapshot;
use crate::sim::{ArmModel, IkParams};
use nalgebra::Isometry3;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Tunables of the world (metres, seconds, radians).
#[derive(Clone, Debug, PartialEq)]
pub struct WorldParams {
    /// Largest interpenetration depth between two bodies still accepted (m).
    pub penetration_tolerance: f64,
    /// Largest gap between a body's bottom and its support's top for "resting on" (m).
    pub support_tolerance: f64,
    /// A closing gripper grasps a body when its tool centre point is inside the body grown by this (m).
    pub grasp_tolerance: f64,
    /// Finger speed when opening or closing (m/s).
    pub finger_speed: f64,
    /// IK used to follow end-effector commands each step (few iterations, warm start, no restarts).
    pub tracking_ik: IkParams,
    /// IK used by [`World::reachable`] (with restarts).
    pub planning_ik: IkParams,
}

impl WorldParams {
    /// How deep a carried body (or a block the carried hook pushes) may press into another
    /// before the arm stops at the contact (m): 0.9 of the penetration tolerance.
    pub fn carried_stop_depth(&self) -> f64 {
        0.9 * self.penetration_tolerance
    }

    /// How deep a body settling under an overhang may press into the bodies above it and
    /// still rest there (m): 0.9 of the penetration tolerance.
    pub fn wedged_rest_depth(&self) -> f64 {
        0.9 * self.penetration_tolerance
    }
}

impl Default for WorldParams {
    fn default() -> Self {
        WorldParams {
            penetration_tolerance: 0.002,
            support_tolerance: 0.005,
            grasp_tolerance: 0.005,
            finger_speed: 0.2,
            tracking_ik: IkParams {
                max_iterations: 6,
                restarts: 0,
                ..IkParams::default()
            },
            planning_ik: IkParams::default(),
        }
    }
}

/// What a gripper is told to do.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GripperCommand {
    /// Open the fingers; a held body is released and drops onto the highest support below it.
    Open,
    /// Close the fingers; a block or hook between the fingertips is grasped.
    Close,
}
/// How deep an arm link may press into a table or shelf before the arm stops (m): the link
/// capsules are rounded stand-ins for the real links.
pub(crate) const LINK_TOLERANCE: f64 = 0.01;

/// How far a joint angle (rad) or a finger opening (m) may lie beyond its limit and still count
/// as within it: room for the rounding of saved scenes.
pub(super) const LIMIT_SLACK: f64 = 1e-9;

/// One penetration depth counts as deeper than another only by more than this (m): the contact
/// queries' rounding noise is no deeper contact.
pub(super) const DEPTH_EPSILON: f64 = 1e-9;

/// One arm with its gripper.
#[derive(Clone, Debug)]
pub(crate) struct Arm {
    pub name: String,
    pub base: Isometry3<f64>,
    pub joints: [f64; DOF],
    pub gripper_opening: f64,
    /// Index of the held body and its pose in the TCP frame.
    pub holding: Option<(usize, Isometry3<f64>)>,
    pub reach: ReachSnapshot,
    pub target: Option<Isometry3<f64>>,
    pub gripper: GripperCommand,
    /// The gripper command of the previous step (to see it change).
    pub last_gripper: GripperCommand,
    /// The body the held one touched when the last step was stopped at contact (not saved).
    pub blocked_by: Option<String>,
    /// A joint-space target (instead of `target`), followed at the joint velocity limits.
    pub joint_target: Option<[f64; DOF]>,
    /// Its kinematics, limits and capsules.
    pub model: Arc<ArmModel>,
}

impl Arm {
    pub(crate) fn tcp(&self) -> Isometry3<f64> {
        self.model.forward_kinematics(&self.base, &self.joints)
    }
}

/// A named rectangle of table top.
#[derive(Clone, Debug)]
pub(crate) struct Region {
    pub name: String,
    pub min: [f64; 2],
    pub max: [f64; 2],
    pub color: String,
}

impl Region {
    pub(crate) fn contains(&self, x: f64, y: f64) -> bool {
        x >= self.min[0] && x <= self.max[0] && y >= self.min[1] && y <= self.max[1]
    }
}

/// Errors of world operations called by programs (bad indices, unknown names).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimError {
    /// No arm with this index.
    #[error("no arm with index {0}")]
    NoSuchArm(usize),
    /// No body or arm with this name.
    #[error("no body or arm named {0:?}")]
    UnknownName(String),
    /// A command with a non-finite number.
    #[error("a command is not finite")]
    NonFinite,
}

/// An error loading a scene: the JSON path of the offending field and what is wrong.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{path}: {message}")]
pub struct SceneError {
    /// Where: a JSON key path naming the body (e.g. `bodies[2] "c".pose.quaternion`) or
    /// `line L column C` for malformed JSON.
    pub path: String,
    /// What is wrong.
    pub message: String,
}

/// A [`SceneError`] at `path`.
pub(super) fn scene_err(path: impl Into<String>, message: impl Into<String>) -> SceneError {
    SceneError {
        path: path.into(),
        message: message.into(),
    }
}

/// The kinematic world (see the module documentation of [`crate::sim`] for the rules).
#[derive(Clone, Debug)]
pub struct World {
    pub(crate) name: String,
    pub(crate) time: f64,
    pub(crate) dt: f64,
    pub(crate) floor_z: f64,
    /// What the domain's predicates and actions mean here (`motions.json`).
    pub(crate) motions: Arc<Motions>,
    pub(crate) regions: Vec<Region>,
    pub(crate) bodies: Vec<Body>,
    pub(crate) arms: Vec<Arm>,
    pub(crate) params: WorldParams,
}
