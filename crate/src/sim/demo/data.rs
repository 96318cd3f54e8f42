//! A demonstration as data: actions, key points, via-points and anchors, its errors and JSON.

use crate::sim::geometry::{gripper_yaw, wrap, yaw_of};
use crate::sim::world::{GripperCommand, Violation};
use crate::sim::Benchmark;
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// World pose of an anchor frame: position and yaw.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AnchorPose {
    /// Anchor centre, world frame (m).
    pub position: [f64; 3],
    /// Yaw about world `z` (rad).
    pub yaw: f64,
}

impl AnchorPose {
    /// As an isometry (translation + yaw).
    pub fn isometry(&self) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::from(Vector3::from(self.position)),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), self.yaw),
        )
    }

    /// The anchor frame of a world pose (tilt dropped).
    pub fn from_pose(p: &Isometry3<f64>) -> AnchorPose {
        AnchorPose {
            position: p.translation.vector.into(),
            yaw: yaw_of(&p.rotation),
        }
    }
}

/// A gripper command at a sample index.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GripperChange {
    /// Sample index (0-based, within the action).
    pub step: usize,
    /// The command from that step on.
    pub command: GripperCommand,
}

/// A named sample of an action's trajectory (a via-point for the motion skill).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct KeyPoint {
    /// Sample index (0-based, within the action).
    pub step: usize,
    /// What happens there: `grasp`, `release`, `descent` (the hook starts down behind the
    /// block), `contact` (hook behind the block), `pulled`.
    pub label: String,
}

/// A point an action's motion must pass through, recorded from the demonstration: the LQT-CP
/// via-point of its skill (a pull: where the hook's blade passed the pulled block's far edges).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DemoViaPoint {
    /// Sample index (0-based, within the action).
    pub step: usize,
    /// What the motion does there: `top-edge` (the blade's bottom passes the block's far top
    /// edge on the way down), `bottom-edge` (the blade is down behind the block's far face).
    pub label: String,
    /// The TCP in the anchor frame at that sample (m), as the sample's `[x, y, z]`.
    pub position: [f64; 3],
}

/// One demonstrated action with its motion.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DemoAction {
    /// The grounded PDDL action, e.g. `(pick panda c)`.
    pub action: String,
    /// Action name (`pick`, `place`, `stack`, `unstack`, `place-on-shelf`, `pull`).
    pub name: String,
    /// Arguments in PDDL order.
    pub args: Vec<String>,
    /// The arm executing it.
    pub arm: String,
    /// The object whose frame the samples are expressed in (see the module docs).
    pub anchor: String,
    /// The anchor frame in the world during the demonstration.
    pub anchor_pose: AnchorPose,
    /// `[x, y, z, yaw]` of the TCP in the anchor frame, one per 10 ms step (see the module docs).
    pub samples: Vec<[f64; 4]>,
    /// Gripper commands and the samples they start at.
    pub gripper: Vec<GripperChange>,
    /// Named samples (via-points).
    pub key_points: Vec<KeyPoint>,
    /// The via-points of the action's skill (a pull's; empty for the others).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub via_points: Vec<DemoViaPoint>,
}

/// A demonstration of a benchmark's template task.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Demonstration {
    /// Benchmark directory name (`b1-tower`, …).
    pub benchmark: String,
    /// Seed of the expert's variation.
    pub seed: u64,
    /// Sample period (s).
    pub dt: f64,
    /// The frame convention in words.
    pub frame_convention: String,
    /// The actions in order (the demo's states L0..LN are derived by applying them).
    pub actions: Vec<DemoAction>,
}

impl Demonstration {
    /// The grounded action strings in order.
    pub fn plan(&self) -> Vec<&str> {
        self.actions.iter().map(|a| a.action.as_str()).collect()
    }
}

/// Why recording or replaying a demonstration failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DemoError {
    /// The world broke an invariant.
    #[error("action {action} step {step}: invariant broken: {violations:?}")]
    Invariant {
        /// The action.
        action: String,
        /// Sample index.
        step: usize,
        /// What broke.
        violations: Vec<Violation>,
    },
    /// The motion did not have the intended effect or refers to unknown things.
    #[error("action {action}: {message}")]
    Failed {
        /// The action.
        action: String,
        /// What went wrong.
        message: String,
    },
    /// Malformed demo JSON.
    #[error("demo JSON: {0}")]
    Json(String),
}

pub(super) const FRAME_CONVENTION: &str =
    "samples are [x, y, z, yaw] of the gripper tool centre point in the \
anchor frame (anchor centre + its yaw about world z; pick/unstack/pull: the object at the action's \
start; place/place-on-shelf/stack: the carried object's resting pose at the action's end), every \
10 ms; gripper pointing straight down; yaw relative to the anchor's yaw";

pub(super) fn fail(action: &str, message: impl Into<String>) -> DemoError {
    DemoError::Failed {
        action: action.to_string(),
        message: message.into(),
    }
}

/// The minimum-jerk profile `10τ³ − 15τ⁴ + 6τ⁵` at `t` ∈ [0, 1] (0 to 1, at rest at both ends).
pub(crate) fn min_jerk(t: f64) -> f64 {
    t * t * t * (10.0 + t * (-15.0 + 6.0 * t))
}

/// Samples' positions are rounded to this (m): 0.1 mm.
const SAMPLE_POSITION_STEP: f64 = 1e-4;

/// Samples' yaws are rounded to this (rad): 1 mrad.
const SAMPLE_YAW_STEP: f64 = 1e-3;

/// `v` rounded to a whole multiple of `q`.
fn round_to(v: f64, q: f64) -> f64 {
    (v / q).round() * q
}

/// The sample `[x, y, z, yaw]` of TCP pose `tcp` in an anchor frame (`anchor_inv` its inverse,
/// `anchor_yaw` its yaw), rounded as the module docs say.
pub(super) fn anchor_sample(
    tcp: &Isometry3<f64>,
    anchor_inv: &Isometry3<f64>,
    anchor_yaw: f64,
) -> [f64; 4] {
    let lp = anchor_inv * Point3::from(tcp.translation.vector);
    let yaw = wrap(gripper_yaw(&tcp.rotation) - anchor_yaw);
    [
        round_to(lp.x, SAMPLE_POSITION_STEP),
        round_to(lp.y, SAMPLE_POSITION_STEP),
        round_to(lp.z, SAMPLE_POSITION_STEP),
        round_to(yaw, SAMPLE_YAW_STEP),
    ]
}

/// Parses a demo JSON text; a value of the wrong type is named by its path and position
/// (`actions[2].samples[5][1]: invalid type: …`, see [`crate::sim::parse_json`]).
pub fn from_json(text: &str) -> Result<Demonstration, DemoError> {
    parse(text).map_err(|e| DemoError::Json(e.to_string()))
}

/// [`from_json`] with the error's path and position apart. The only reader of demonstrations:
/// a second one would add its own copy of the deserialiser to the page's first-load module.
pub fn parse(text: &str) -> Result<Demonstration, crate::sim::JsonError> {
    crate::sim::parse_json(text)
}

/// The committed demonstration of a benchmark (`domains/<dir>/demo.json`).
pub fn committed(b: Benchmark) -> Result<Demonstration, DemoError> {
    b.available().map_err(|e| DemoError::Json(e.message))?;
    from_json(b.demo_json())
}
