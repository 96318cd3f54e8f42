//! The JSON scene format: a still picture of a [`World`](super::World).
//!
//! This is what `domains/*/scene.json` contain, what the CLI reads and what the browser page draws.
//! [`World::snapshot`](super::World::snapshot) writes it, [`World::from_snapshot`](super::World::from_snapshot)
//! reads it back with validation (unknown names, overlapping bodies, a block in the air, joints out
//! of limits: a [`SceneError`](super::SceneError) naming the body and the field).
//!
//! Conventions used by every field below:
//! * lengths in metres, angles in radians, time in seconds;
//! * the world frame is right-handed with `z` up; the table tops of the benchmarks are at `z = 0`;
//! * a pose is a position plus a unit quaternion `[x, y, z, w]` (the order three.js uses);
//! * fields marked *derived* are written for drawing and ignored when a snapshot is loaded, so a
//!   hand-written scene may leave them out.
//!
//! Round trip: `World::from_snapshot(&w.snapshot())?.snapshot() == w.snapshot()`. The snapshot does
//! not store an arm's pending end-effector command: a loaded world starts with every arm holding
//! still at its current pose.

use serde::{Deserialize, Serialize};
use std::sync::Arc;

use super::kinematics::ArmModel;

/// Version written into [`WorldSnapshot::version`]; loading refuses other versions.
pub const SNAPSHOT_VERSION: u32 = 1;

/// A rigid pose: position plus unit quaternion.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct PoseSnapshot {
    /// Position `[x, y, z]` in metres, world frame (or the parent frame where stated).
    pub position: [f64; 3],
    /// Orientation as a unit quaternion `[x, y, z, w]` (scalar last). Loading normalises it and
    /// refuses a zero quaternion.
    pub quaternion: [f64; 4],
}

/// One box of a compound shape, posed in the body's own frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct PartSnapshot {
    /// Pose of the box centre in the body frame.
    pub pose: PoseSnapshot,
    /// Half side lengths `[hx, hy, hz]` in metres (all > 0).
    pub half_extents: [f64; 3],
}

/// The geometry of a body, in its own frame (the body pose places it in the world).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum ShapeSnapshot {
    /// A box centred on the body origin.
    Cuboid {
        /// Half side lengths `[hx, hy, hz]` in metres (all > 0). A 6 cm cube has `[0.03; 3]`.
        half_extents: [f64; 3],
    },
    /// A union of boxes (the hook: an L of a long handle and a short blade).
    Compound {
        /// The boxes, each posed in the body frame (at least one).
        parts: Vec<PartSnapshot>,
    },
}

/// What a body is; decides which rules apply to it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "snake_case")]
pub enum BodyKind {
    /// A cube that can be grasped, stacked and pushed; a PDDL `block` object.
    Block,
    /// The L-shaped tool of B2: it can be grasped and pulls blocks that its blade touches.
    Hook,
    /// A fixed table top (blocks rest on its upper face).
    Table,
    /// A fixed shelf board standing on a table (blocks on it are `(onshelf x)`).
    Shelf,
}

/// One body of the world (blocks, the hook, tables, shelves).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct BodySnapshot {
    /// Unique lower-case name; for blocks and the hook it is the PDDL object name (`a`, `hook`).
    pub name: String,
    /// What the body is.
    pub kind: BodyKind,
    /// Geometry in the body frame.
    pub shape: ShapeSnapshot,
    /// Pose of the body frame in the world.
    pub pose: PoseSnapshot,
    /// Display colour as `#rrggbb`.
    pub color: String,
    /// The body fell off every support (released in the air over nothing, or tipped over) and lies
    /// on the floor; it takes no further part in contacts or facts. Default `false`.
    #[serde(default)]
    pub lost: bool,
}

/// A capsule (segment swept by a sphere), used for the arm links.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct CapsuleSnapshot {
    /// First end point of the segment, world frame, metres.
    pub a: [f64; 3],
    /// Second end point of the segment, world frame, metres.
    pub b: [f64; 3],
    /// Radius in metres.
    pub radius: f64,
}

/// A posed box in the world frame (a gripper finger).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct CuboidSnapshot {
    /// Pose of the box centre, world frame.
    pub pose: PoseSnapshot,
    /// Half side lengths in metres.
    pub half_extents: [f64; 3],
}

/// The horizontal workspace annulus used for the `(inreach arm x)` fact.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct ReachSnapshot {
    /// Smallest horizontal distance (m) from the arm's base axis to a block centre that counts as
    /// in reach.
    pub min_radius: f64,
    /// Largest horizontal distance (m) from the arm's base axis to a block centre that counts as
    /// in reach.
    pub max_radius: f64,
}

/// One arm with a parallel gripper: the built-in Panda, or a robot from its URDF.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(from = "ArmIn")]
pub struct ArmSnapshot {
    /// Unique lower-case name, the PDDL `arm` object (`panda`, `left`, `right`).
    pub name: String,
    /// Pose of the arm's base (link 0) in the world.
    pub base: PoseSnapshot,
    /// The robot's name when it is not the built-in Panda (a robot file's `name`); absent for
    /// the built-in Panda.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[cfg_attr(feature = "wasm-core", tsify(optional))]
    pub robot: Option<String>,
    /// The joint angles, one per moving joint (rad, or m for a prismatic joint), within the
    /// limits.
    pub joints: Vec<f64>,
    /// Distance between the two finger pads in metres, 0 (closed) ..= 0.08 (open).
    pub gripper_opening: f64,
    /// Name of the body in the gripper, if any (it moves rigidly with the gripper).
    pub holding: Option<String>,
    /// Workspace annulus for `(inreach arm x)`.
    pub reach: ReachSnapshot,
    /// *Derived*: the gripper's tool centre point (between the fingertips; `z` axis points out of
    /// the gripper, `y` axis joins the fingers), world frame.
    pub tcp: PoseSnapshot,
    /// *Derived*: the link capsules in the world frame, base to hand, for drawing.
    pub links: Vec<CapsuleSnapshot>,
    /// *Derived*: the two finger boxes in the world frame.
    pub fingers: Vec<CuboidSnapshot>,
    /// The robot's model, carried from a world to its snapshot and back (not saved: a saved
    /// scene names it in `robot`).
    #[serde(skip)]
    pub model: Option<Arc<ArmModel>>,
}

/// A named rectangle of table top (B3's `left-table`, `handover`, `right-table`): a PDDL `region`
/// object; a block resting on a table with its centre inside it is `(at x region)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct RegionSnapshot {
    /// Unique lower-case name (the PDDL object).
    pub name: String,
    /// Lower corner `[x, y]` (m, world frame).
    pub min: [f64; 2],
    /// Upper corner `[x, y]` (m, world frame); each coordinate > the one in `min`.
    pub max: [f64; 2],
    /// Display colour as `#rrggbb` (drawn as a translucent patch on the table).
    pub color: String,
}

/// The whole world.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(from = "WorldIn")]
pub struct WorldSnapshot {
    /// Format version, [`SNAPSHOT_VERSION`].
    pub version: u32,
    /// Scene name, e.g. `b1-tower`.
    pub name: String,
    /// Simulated time in seconds since the scene started.
    pub time: f64,
    /// Fixed step of [`World::step`](super::World::step) in seconds (default 0.01).
    pub dt: f64,
    /// Height of the floor (m); lost bodies lie on it.
    pub floor_z: f64,
    /// Named table regions (B3); empty elsewhere.
    pub regions: Vec<RegionSnapshot>,
    /// Every body, in a stable order (fixed bodies first, then the hook, then blocks by name).
    pub bodies: Vec<BodySnapshot>,
    /// Every arm, in PDDL order.
    pub arms: Vec<ArmSnapshot>,
}

/// [`ArmSnapshot`] as a scene file may give it: the derived fields can be left out.
#[derive(Deserialize)]
struct ArmIn {
    name: String,
    base: PoseSnapshot,
    #[serde(default)]
    robot: Option<String>,
    joints: Vec<f64>,
    gripper_opening: f64,
    #[serde(default)]
    holding: Option<String>,
    reach: ReachSnapshot,
    #[serde(default = "identity_pose")]
    tcp: PoseSnapshot,
    #[serde(default)]
    links: Vec<CapsuleSnapshot>,
    #[serde(default)]
    fingers: Vec<CuboidSnapshot>,
}

// The snapshot types read scene files through these input shapes, so that their TypeScript
// declarations (derived from the types themselves) say what a frame always holds.
impl From<ArmIn> for ArmSnapshot {
    fn from(a: ArmIn) -> Self {
        let ArmIn {
            name,
            base,
            robot,
            joints,
            gripper_opening,
            holding,
            reach,
            tcp,
            links,
            fingers,
        } = a;
        ArmSnapshot {
            name,
            base,
            robot,
            joints,
            gripper_opening,
            holding,
            reach,
            tcp,
            links,
            fingers,
            model: None,
        }
    }
}

/// [`WorldSnapshot`] as a scene file may give it: time, step and regions can be left out.
#[derive(Deserialize)]
struct WorldIn {
    version: u32,
    name: String,
    #[serde(default)]
    time: f64,
    #[serde(default = "default_dt")]
    dt: f64,
    floor_z: f64,
    #[serde(default)]
    regions: Vec<RegionSnapshot>,
    bodies: Vec<BodySnapshot>,
    arms: Vec<ArmSnapshot>,
}

impl From<WorldIn> for WorldSnapshot {
    fn from(w: WorldIn) -> Self {
        let WorldIn {
            version,
            name,
            time,
            dt,
            floor_z,
            regions,
            bodies,
            arms,
        } = w;
        WorldSnapshot {
            version,
            name,
            time,
            dt,
            floor_z,
            regions,
            bodies,
            arms,
        }
    }
}

fn default_dt() -> f64 {
    0.01
}

fn identity_pose() -> PoseSnapshot {
    PoseSnapshot {
        position: [0.0; 3],
        quaternion: [0.0, 0.0, 0.0, 1.0],
    }
}
