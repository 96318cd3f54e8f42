//! The kinematic world: bodies, arms, the fixed-step update and the contact rules.
//!
//! See the module header of [`crate::sim`] for the rules in words.

use super::panda::{self, IkParams, IkSolution, Unreachable, DOF};
use super::snapshot::*;
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::query;
use parry3d_f64::shape::{Capsule, Cuboid};
use serde::{Deserialize, Serialize};
use std::fmt;

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

/// One body: a union of boxes at a pose.
#[derive(Clone, Debug)]
pub(crate) struct Body {
    pub name: String,
    pub kind: BodyKind,
    /// Boxes in the body frame.
    pub parts: Vec<(Isometry3<f64>, Cuboid)>,
    pub pose: Isometry3<f64>,
    pub color: String,
    pub lost: bool,
}

impl Body {
    pub(crate) fn is_movable(&self) -> bool {
        matches!(self.kind, BodyKind::Block | BodyKind::Hook)
    }

    /// World poses of the parts.
    pub(crate) fn world_parts(&self) -> impl Iterator<Item = (Isometry3<f64>, &Cuboid)> + '_ {
        self.parts.iter().map(move |(p, c)| (self.pose * p, c))
    }

    /// World-frame axis-aligned bounds `(min, max)`.
    pub(crate) fn aabb(&self) -> (Vector3<f64>, Vector3<f64>) {
        self.aabb_at(&self.pose)
    }

    pub(crate) fn aabb_at(&self, pose: &Isometry3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = Vector3::repeat(f64::NEG_INFINITY);
        for (p, c) in &self.parts {
            let iso = pose * p;
            let r = iso.rotation.to_rotation_matrix();
            let m = r.matrix().abs();
            let ext = m * c.half_extents;
            let t = iso.translation.vector;
            lo = lo.inf(&(t - ext));
            hi = hi.sup(&(t + ext));
        }
        (lo, hi)
    }

    /// Volume-weighted centroid of the parts, world frame.
    pub(crate) fn centroid_at(&self, pose: &Isometry3<f64>) -> Vector3<f64> {
        let mut acc = Vector3::zeros();
        let mut vol = 0.0;
        for (p, c) in &self.parts {
            let v = c.half_extents.x * c.half_extents.y * c.half_extents.z;
            acc += (pose * p).translation.vector * v;
            vol += v;
        }
        acc / vol
    }

    /// Whether the world point lies inside some part grown by `margin`.
    pub(crate) fn contains_point(&self, pt: &Point3<f64>, margin: f64) -> bool {
        self.world_parts().any(|(iso, c)| {
            let l = iso.inverse_transform_point(pt);
            l.x.abs() <= c.half_extents.x + margin
                && l.y.abs() <= c.half_extents.y + margin
                && l.z.abs() <= c.half_extents.z + margin
        })
    }

    /// The highest top-face height of a part whose horizontal footprint contains `(x, y)`.
    pub(crate) fn top_under(&self, x: f64, y: f64, margin: f64) -> Option<f64> {
        let mut best: Option<f64> = None;
        for (iso, c) in self.world_parts() {
            let l = iso.inverse_transform_point(&Point3::new(x, y, iso.translation.vector.z));
            if l.x.abs() <= c.half_extents.x + margin && l.y.abs() <= c.half_extents.y + margin {
                let m = iso.rotation.to_rotation_matrix();
                let top = iso.translation.vector.z + (m.matrix().abs() * c.half_extents).z;
                best = Some(best.map_or(top, |b: f64| b.max(top)));
            }
        }
        best
    }

    /// Penetration depth with another body (≥ 0; 0 when apart or touching).
    pub(crate) fn penetration(&self, other: &Body) -> f64 {
        let (alo, ahi) = self.aabb();
        let (blo, bhi) = other.aabb();
        if (0..3).any(|i| alo[i] > bhi[i] || blo[i] > ahi[i]) {
            return 0.0;
        }
        let mut depth: f64 = 0.0;
        for (ia, ca) in self.world_parts() {
            for (ib, cb) in other.world_parts() {
                if let Ok(Some(c)) = query::contact(&ia, ca, &ib, cb, 0.0) {
                    depth = depth.max(-c.dist);
                }
            }
        }
        depth
    }
}

/// Yaw (rotation about world `z`) of a pose's rotation.
pub(crate) fn yaw_of(rot: &UnitQuaternion<f64>) -> f64 {
    let x = rot * Vector3::x();
    libm::atan2(x.y, x.x)
}

/// An inverse kinematics of [`panda`]: (base, target, seed joints, parameters).
type IkSolver =
    fn(&Isometry3<f64>, &Isometry3<f64>, &[f64; DOF], &IkParams) -> Result<IkSolution, Unreachable>;

/// How deep an arm link may press into a table or shelf before the arm stops (m): the link
/// capsules are rounded stand-ins for the real links.
pub(crate) const LINK_TOLERANCE: f64 = 0.01;

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
}

impl Arm {
    pub(crate) fn tcp(&self) -> Isometry3<f64> {
        panda::forward_kinematics(&self.base, &self.joints)
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

/// Something that happened during a step or a user move (for logs and the page).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum WorldEvent {
    /// An arm closed its gripper around a body.
    Grasped {
        /// Arm name.
        arm: String,
        /// Body name.
        body: String,
    },
    /// An arm closed its gripper on nothing.
    GraspedNothing {
        /// Arm name.
        arm: String,
    },
    /// An arm opened its gripper and the body settled on a support.
    Released {
        /// Arm name.
        arm: String,
        /// Body name.
        body: String,
        /// Name of the body it came to rest on.
        support: String,
        /// Height it dropped (m).
        drop: f64,
    },
    /// A body was pushed by the hook's blade.
    Pushed {
        /// Body name.
        body: String,
        /// Pushing body (the hook).
        by: String,
        /// Horizontal displacement `[dx, dy]` (m).
        displacement: [f64; 2],
    },
    /// A body lost its support and fell to the floor.
    Lost {
        /// Body name.
        body: String,
        /// Why, in words.
        reason: String,
    },
}

impl fmt::Display for WorldEvent {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WorldEvent::Grasped { arm, body } => write!(f, "{arm} grasped {body}"),
            WorldEvent::GraspedNothing { arm } => write!(f, "{arm} closed on nothing"),
            WorldEvent::Released {
                arm,
                body,
                support,
                drop,
            } => write!(
                f,
                "{arm} released {body}; it dropped {:.1} mm onto {support}",
                drop * 1000.0
            ),
            WorldEvent::Pushed {
                body,
                by,
                displacement,
            } => write!(
                f,
                "{by} pushed {body} by ({:.1}, {:.1}) mm",
                displacement[0] * 1000.0,
                displacement[1] * 1000.0
            ),
            WorldEvent::Lost { body, reason } => write!(f, "{body} fell: {reason}"),
        }
    }
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

fn scene_err(path: impl Into<String>, message: impl Into<String>) -> SceneError {
    SceneError {
        path: path.into(),
        message: message.into(),
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

/// A user move refused, with the reason (the world is unchanged).
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize, Deserialize)]
#[error("cannot move {body}: {reason}")]
pub struct Refused {
    /// The body the user tried to move.
    pub body: String,
    /// Why, in words (shown on the page).
    pub reason: String,
}

/// The result of an accepted [`World::move_block`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MoveOutcome {
    /// The moved body.
    pub body: String,
    /// Its previous centre (m).
    pub from: [f64; 3],
    /// Its new centre after settling (m).
    pub to: [f64; 3],
    /// What it rests on now.
    pub support: String,
    /// Bodies that were standing on it and settled down after it left, with their new centres.
    pub also_moved: Vec<(String, [f64; 3])>,
}

/// A broken invariant found by [`World::check_invariants`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "violation", rename_all = "snake_case")]
pub enum Violation {
    /// Two bodies overlap deeper than the tolerance.
    Interpenetration {
        /// First body.
        a: String,
        /// Second body.
        b: String,
        /// Penetration depth (m).
        depth: f64,
    },
    /// A free body does not rest on anything.
    Unsupported {
        /// The body.
        body: String,
        /// Height of its bottom above the nearest support under its centre (m; infinite if none).
        gap: f64,
    },
    /// A body fell off every support.
    Lost {
        /// The body.
        body: String,
    },
    /// A joint is outside its limits.
    JointLimit {
        /// The arm.
        arm: String,
        /// Joint index 0..7.
        joint: usize,
        /// Its value (rad).
        value: f64,
    },
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Violation::Interpenetration { a, b, depth } => {
                write!(f, "{a} and {b} interpenetrate by {:.2} mm", depth * 1000.0)
            }
            Violation::Unsupported { body, gap } => {
                write!(
                    f,
                    "{body} is in the air ({:.1} mm above any support)",
                    gap * 1000.0
                )
            }
            Violation::Lost { body } => write!(f, "{body} is lost (fell off)"),
            Violation::JointLimit { arm, joint, value } => {
                write!(
                    f,
                    "{arm} joint {} = {value:.4} rad is outside its limits",
                    joint + 1
                )
            }
        }
    }
}

/// Where a released or moved body would come to rest.
enum Settle {
    /// On `support` (body index) with its centre lowered by `drop`.
    On { support: usize, drop: f64 },
    /// Nothing under it, or its centre is not above the surface it would touch.
    Falls(String),
    /// It overlaps a body already at its start height.
    Blocked(usize),
}

/// The kinematic world (see the module documentation of [`crate::sim`] for the rules).
#[derive(Clone, Debug)]
pub struct World {
    pub(crate) name: String,
    pub(crate) time: f64,
    pub(crate) dt: f64,
    pub(crate) floor_z: f64,
    pub(crate) predicates: Vec<String>,
    pub(crate) regions: Vec<Region>,
    pub(crate) bodies: Vec<Body>,
    pub(crate) arms: Vec<Arm>,
    pub(crate) params: WorldParams,
}

/// The predicates a scene may ask the scene graph for.
pub const KNOWN_PREDICATES: [&str; 8] = [
    "on",
    "ontable",
    "onshelf",
    "clear",
    "holding",
    "handempty",
    "inreach",
    "at",
];

fn pose_to_snapshot(p: &Isometry3<f64>) -> PoseSnapshot {
    let q = p.rotation.coords;
    PoseSnapshot {
        position: [p.translation.x, p.translation.y, p.translation.z],
        quaternion: [q.x, q.y, q.z, q.w],
    }
}

fn pose_from_snapshot(p: &PoseSnapshot, path: &str) -> Result<Isometry3<f64>, SceneError> {
    if p.position.iter().any(|v| !v.is_finite()) {
        return Err(scene_err(
            format!("{path}.position"),
            "must be finite numbers",
        ));
    }
    let [x, y, z, w] = p.quaternion;
    let q = nalgebra::Quaternion::new(w, x, y, z);
    let n = q.norm();
    if !n.is_finite() || n < 1e-9 {
        return Err(scene_err(
            format!("{path}.quaternion"),
            "must be a non-zero quaternion [x, y, z, w]",
        ));
    }
    Ok(Isometry3::from_parts(
        Translation3::new(p.position[0], p.position[1], p.position[2]),
        UnitQuaternion::from_quaternion(q),
    ))
}

fn check_half_extents(h: &[f64; 3], path: &str) -> Result<Cuboid, SceneError> {
    if h.iter().any(|v| !v.is_finite() || *v <= 0.0 || *v > 10.0) {
        return Err(scene_err(
            format!("{path}.half_extents"),
            "must be three numbers in (0, 10] metres",
        ));
    }
    Ok(Cuboid::new(Vector3::new(h[0], h[1], h[2])))
}

fn check_color(c: &str, path: &str) -> Result<(), SceneError> {
    let ok = c.len() == 7 && c.starts_with('#') && c[1..].chars().all(|ch| ch.is_ascii_hexdigit());
    if ok {
        Ok(())
    } else {
        Err(scene_err(
            format!("{path}.color"),
            format!("{c:?} is not #rrggbb"),
        ))
    }
}

fn check_name(n: &str, path: &str) -> Result<(), SceneError> {
    let ok = !n.is_empty()
        && n.chars().next().is_some_and(|c| c.is_ascii_lowercase())
        && n.chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-' || c == '_');
    if ok {
        Ok(())
    } else {
        Err(scene_err(
            format!("{path}.name"),
            format!("{n:?} is not a lower-case PDDL name ([a-z][a-z0-9_-]*)"),
        ))
    }
}

fn round6(v: f64) -> f64 {
    (v * 1e6).round() / 1e6
}

impl World {
    // ----------------------------------------------------------------- snapshots

    /// The world as a JSON-ready snapshot (with the derived drawing fields filled in).
    pub fn snapshot(&self) -> WorldSnapshot {
        WorldSnapshot {
            version: SNAPSHOT_VERSION,
            name: self.name.clone(),
            time: self.time,
            dt: self.dt,
            floor_z: self.floor_z,
            predicates: self.predicates.clone(),
            regions: self
                .regions
                .iter()
                .map(|r| RegionSnapshot {
                    name: r.name.clone(),
                    min: r.min,
                    max: r.max,
                    color: r.color.clone(),
                })
                .collect(),
            bodies: self
                .bodies
                .iter()
                .map(|b| BodySnapshot {
                    name: b.name.clone(),
                    kind: b.kind,
                    shape: if b.parts.len() == 1 && b.parts[0].0 == Isometry3::identity() {
                        let h = b.parts[0].1.half_extents;
                        ShapeSnapshot::Cuboid {
                            half_extents: [h.x, h.y, h.z],
                        }
                    } else {
                        ShapeSnapshot::Compound {
                            parts: b
                                .parts
                                .iter()
                                .map(|(p, c)| PartSnapshot {
                                    pose: pose_to_snapshot(p),
                                    half_extents: [
                                        c.half_extents.x,
                                        c.half_extents.y,
                                        c.half_extents.z,
                                    ],
                                })
                                .collect(),
                        }
                    },
                    pose: pose_to_snapshot(&b.pose),
                    color: b.color.clone(),
                    lost: b.lost,
                })
                .collect(),
            arms: self
                .arms
                .iter()
                .map(|a| {
                    let (links, fingers) = super::geometry::arm_drawing(a);
                    ArmSnapshot {
                        name: a.name.clone(),
                        base: pose_to_snapshot(&a.base),
                        joints: a.joints.to_vec(),
                        gripper_opening: a.gripper_opening,
                        holding: a.holding.map(|(i, _)| self.bodies[i].name.clone()),
                        reach: a.reach.clone(),
                        tcp: pose_to_snapshot(&a.tcp()),
                        links: links
                            .iter()
                            .map(|c| CapsuleSnapshot {
                                a: c.0.into(),
                                b: c.1.into(),
                                radius: c.2,
                            })
                            .collect(),
                        fingers: fingers
                            .iter()
                            .map(|(p, h)| CuboidSnapshot {
                                pose: pose_to_snapshot(p),
                                half_extents: (*h).into(),
                            })
                            .collect(),
                    }
                })
                .collect(),
        }
    }

    /// The snapshot as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(&self.snapshot()).unwrap_or_default()
    }

    /// Parses and validates a JSON scene (see [`World::from_snapshot`]).
    pub fn from_json(text: &str) -> Result<World, SceneError> {
        let snap: WorldSnapshot = serde_json::from_str(text).map_err(|e| {
            let msg = e.to_string();
            let suffix = format!(" at line {} column {}", e.line(), e.column());
            scene_err(
                format!("line {} column {}", e.line(), e.column()),
                msg.strip_suffix(&suffix).unwrap_or(&msg),
            )
        })?;
        World::from_snapshot(&snap)
    }

    /// Builds a world from a snapshot, validating every field and the geometry: unique lower-case
    /// names, known predicates, positive sizes, non-zero quaternions, joints within limits, held
    /// bodies that exist and sit in the gripper, no interpenetrating bodies, no free body in the air.
    pub fn from_snapshot(s: &WorldSnapshot) -> Result<World, SceneError> {
        if s.version != SNAPSHOT_VERSION {
            return Err(scene_err(
                "version",
                format!(
                    "unsupported version {} (expected {SNAPSHOT_VERSION})",
                    s.version
                ),
            ));
        }
        if !(s.dt.is_finite() && s.dt > 0.0 && s.dt <= 0.1) {
            return Err(scene_err("dt", "must be in (0, 0.1] seconds"));
        }
        if !s.time.is_finite() || s.time < 0.0 {
            return Err(scene_err("time", "must be a finite number ≥ 0"));
        }
        if !s.floor_z.is_finite() {
            return Err(scene_err("floor_z", "must be finite"));
        }
        for (i, p) in s.predicates.iter().enumerate() {
            if !KNOWN_PREDICATES.contains(&p.as_str()) {
                return Err(scene_err(
                    format!("predicates[{i}]"),
                    format!(
                        "unknown predicate {p:?} (known: {})",
                        KNOWN_PREDICATES.join(", ")
                    ),
                ));
            }
        }
        let mut names: Vec<(String, String)> = Vec::new();
        let mut claim = |name: &str, path: &str| -> Result<(), SceneError> {
            if let Some((_, first)) = names.iter().find(|(n, _)| n == name) {
                return Err(scene_err(
                    format!("{path}.name"),
                    format!("{name:?} is already used by {first}"),
                ));
            }
            names.push((name.to_string(), path.to_string()));
            Ok(())
        };
        let mut regions = Vec::new();
        for (i, r) in s.regions.iter().enumerate() {
            let path = format!("regions[{i}] {:?}", r.name);
            check_name(&r.name, &path)?;
            claim(&r.name, &path)?;
            check_color(&r.color, &path)?;
            if !(r.min.iter().chain(r.max.iter()).all(|v| v.is_finite())
                && r.min[0] < r.max[0]
                && r.min[1] < r.max[1])
            {
                return Err(scene_err(
                    format!("{path}.max"),
                    "min and max must be finite with min < max on x and y",
                ));
            }
            regions.push(Region {
                name: r.name.clone(),
                min: r.min,
                max: r.max,
                color: r.color.clone(),
            });
        }
        let mut bodies = Vec::new();
        for (i, b) in s.bodies.iter().enumerate() {
            let path = format!("bodies[{i}] {:?}", b.name);
            check_name(&b.name, &path)?;
            claim(&b.name, &path)?;
            check_color(&b.color, &path)?;
            let pose = pose_from_snapshot(&b.pose, &format!("{path}.pose"))?;
            let parts = match &b.shape {
                ShapeSnapshot::Cuboid { half_extents } => {
                    vec![(
                        Isometry3::identity(),
                        check_half_extents(half_extents, &format!("{path}.shape"))?,
                    )]
                }
                ShapeSnapshot::Compound { parts } => {
                    if parts.is_empty() {
                        return Err(scene_err(
                            format!("{path}.shape.parts"),
                            "a compound needs at least one part",
                        ));
                    }
                    let mut v = Vec::new();
                    for (k, p) in parts.iter().enumerate() {
                        let pp = format!("{path}.shape.parts[{k}]");
                        v.push((
                            pose_from_snapshot(&p.pose, &format!("{pp}.pose"))?,
                            check_half_extents(&p.half_extents, &pp)?,
                        ));
                    }
                    v
                }
            };
            if b.lost && !matches!(b.kind, BodyKind::Block | BodyKind::Hook) {
                return Err(scene_err(
                    format!("{path}.lost"),
                    "only blocks and the hook can be lost",
                ));
            }
            bodies.push(Body {
                name: b.name.clone(),
                kind: b.kind,
                parts,
                pose,
                color: b.color.clone(),
                lost: b.lost,
            });
        }
        let mut arms = Vec::new();
        for (i, a) in s.arms.iter().enumerate() {
            let path = format!("arms[{i}] {:?}", a.name);
            check_name(&a.name, &path)?;
            claim(&a.name, &path)?;
            let base = pose_from_snapshot(&a.base, &format!("{path}.base"))?;
            if a.joints.len() != DOF {
                return Err(scene_err(
                    format!("{path}.joints"),
                    format!("needs {DOF} joint angles, got {}", a.joints.len()),
                ));
            }
            let mut joints = [0.0; DOF];
            for (k, v) in a.joints.iter().enumerate() {
                if !v.is_finite()
                    || *v < panda::JOINT_LOWER[k] - 1e-9
                    || *v > panda::JOINT_UPPER[k] + 1e-9
                {
                    return Err(scene_err(
                        format!("{path}.joints[{k}]"),
                        format!(
                            "{v} rad is outside the joint limits [{}, {}]",
                            panda::JOINT_LOWER[k],
                            panda::JOINT_UPPER[k]
                        ),
                    ));
                }
                joints[k] = *v;
            }
            if !(a.gripper_opening.is_finite()
                && (0.0..=panda::GRIPPER_MAX_OPENING + 1e-9).contains(&a.gripper_opening))
            {
                return Err(scene_err(
                    format!("{path}.gripper_opening"),
                    "must be in [0, 0.08] m",
                ));
            }
            let r = &a.reach;
            if !(r.min_radius.is_finite()
                && r.max_radius.is_finite()
                && 0.0 <= r.min_radius
                && r.min_radius < r.max_radius)
            {
                return Err(scene_err(
                    format!("{path}.reach"),
                    "needs 0 ≤ min_radius < max_radius",
                ));
            }
            let mut arm = Arm {
                name: a.name.clone(),
                base,
                joints,
                gripper_opening: a.gripper_opening,
                holding: None,
                reach: a.reach.clone(),
                target: None,
                gripper: GripperCommand::Open,
                last_gripper: GripperCommand::Open,
                blocked_by: None,
                joint_target: None,
            };
            if let Some(h) = &a.holding {
                let Some(bi) = bodies.iter().position(|b: &Body| &b.name == h) else {
                    return Err(scene_err(
                        format!("{path}.holding"),
                        format!("unknown body {h:?}"),
                    ));
                };
                let b = &bodies[bi];
                if !b.is_movable() || b.lost {
                    return Err(scene_err(
                        format!("{path}.holding"),
                        format!("{h:?} is not a block or hook that can be held"),
                    ));
                }
                if arms
                    .iter()
                    .any(|o: &Arm| o.holding.is_some_and(|(j, _)| j == bi))
                {
                    return Err(scene_err(
                        format!("{path}.holding"),
                        format!("{h:?} is already held by another arm"),
                    ));
                }
                let tcp = arm.tcp();
                if !b.contains_point(&Point3::from(tcp.translation.vector), 0.01) {
                    return Err(scene_err(
                        format!("{path}.holding"),
                        format!("{h:?} is not between the fingers of {}", a.name),
                    ));
                }
                arm.holding = Some((bi, tcp.inverse() * b.pose));
                arm.gripper = GripperCommand::Close;
                arm.last_gripper = GripperCommand::Close;
            }
            arms.push(arm);
        }
        let world = World {
            name: s.name.clone(),
            time: s.time,
            dt: s.dt,
            floor_z: s.floor_z,
            predicates: s.predicates.clone(),
            regions,
            bodies,
            arms,
            params: WorldParams::default(),
        };
        for v in world.check_invariants_list() {
            let (name, field) = match &v {
                Violation::Interpenetration { a, .. } => (a.clone(), "pose"),
                Violation::Unsupported { body, .. } => (body.clone(), "pose"),
                Violation::Lost { .. } => continue,
                Violation::JointLimit { arm, .. } => (arm.clone(), "joints"),
            };
            let path = if let Some(i) = world.bodies.iter().position(|b| b.name == name) {
                format!("bodies[{i}] {name:?}.{field}")
            } else if let Some(i) = world.arms.iter().position(|a| a.name == name) {
                format!("arms[{i}] {name:?}.{field}")
            } else {
                name.clone()
            };
            return Err(scene_err(path, v.to_string()));
        }
        Ok(world)
    }

    // ----------------------------------------------------------------- queries

    /// Scene name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The fixed step (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The tunables.
    pub fn params(&self) -> &WorldParams {
        &self.params
    }

    /// Mutable tunables.
    pub fn params_mut(&mut self) -> &mut WorldParams {
        &mut self.params
    }

    /// Arm names in order (the index used by [`World::command_arm`]).
    pub fn arm_names(&self) -> Vec<&str> {
        self.arms.iter().map(|a| a.name.as_str()).collect()
    }

    /// Index of the arm called `name`.
    pub fn arm_index(&self, name: &str) -> Option<usize> {
        self.arms.iter().position(|a| a.name == name)
    }

    /// Names of the blocks (kind [`BodyKind::Block`]), in body order.
    pub fn block_names(&self) -> Vec<&str> {
        self.bodies
            .iter()
            .filter(|b| b.kind == BodyKind::Block)
            .map(|b| b.name.as_str())
            .collect()
    }

    /// Names of the table regions.
    pub fn region_names(&self) -> Vec<&str> {
        self.regions.iter().map(|r| r.name.as_str()).collect()
    }

    pub(crate) fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// Pose of the body called `name`.
    pub fn body_pose(&self, name: &str) -> Option<Isometry3<f64>> {
        self.body_index(name).map(|i| self.bodies[i].pose)
    }

    /// Kind of the body called `name`.
    pub fn body_kind(&self, name: &str) -> Option<BodyKind> {
        self.body_index(name).map(|i| self.bodies[i].kind)
    }

    /// World-frame bounding box `(min, max)` of the body called `name`.
    pub fn body_aabb(&self, name: &str) -> Option<(Vector3<f64>, Vector3<f64>)> {
        self.body_index(name).map(|i| self.bodies[i].aabb())
    }

    /// Whether the body fell off (lost).
    pub fn is_lost(&self, name: &str) -> bool {
        self.body_index(name).is_some_and(|i| self.bodies[i].lost)
    }

    /// The body held by arm `arm`, if any.
    pub fn held_by(&self, arm: usize) -> Option<&str> {
        self.arms
            .get(arm)
            .and_then(|a| a.holding.map(|(i, _)| self.bodies[i].name.as_str()))
    }

    /// The held body's pose in the TCP frame of arm `arm` (the grasp), if holding.
    pub fn grasp_transform(&self, arm: usize) -> Option<Isometry3<f64>> {
        self.arms.get(arm).and_then(|a| a.holding.map(|(_, g)| g))
    }

    /// The arm's current joint angles.
    pub fn joints(&self, arm: usize) -> Option<[f64; DOF]> {
        self.arms.get(arm).map(|a| a.joints)
    }

    /// The arm's base pose.
    pub fn arm_base(&self, arm: usize) -> Option<Isometry3<f64>> {
        self.arms.get(arm).map(|a| a.base)
    }

    /// The arm's current tool-centre-point pose (between the fingertips).
    pub fn tcp_pose(&self, arm: usize) -> Option<Isometry3<f64>> {
        self.arms.get(arm).map(|a| a.tcp())
    }

    /// The arm's finger opening (m).
    pub fn gripper_opening(&self, arm: usize) -> Option<f64> {
        self.arms.get(arm).map(|a| a.gripper_opening)
    }

    /// The arm's link capsules `(a, b, radius)` in the world frame (for collision checks).
    pub fn arm_capsules(&self, arm: usize) -> Vec<Capsule> {
        self.arms
            .get(arm)
            .map(|a| {
                super::geometry::arm_drawing(a)
                    .0
                    .iter()
                    .map(|(p, q, r)| Capsule::new(Point3::from(*p), Point3::from(*q), *r))
                    .collect()
            })
            .unwrap_or_default()
    }

    /// The parry boxes of the body called `name`, posed in the world (for collision checks).
    pub fn body_shapes(&self, name: &str) -> Vec<(Isometry3<f64>, Cuboid)> {
        self.body_index(name)
            .map(|i| self.bodies[i].world_parts().map(|(p, c)| (p, *c)).collect())
            .unwrap_or_default()
    }

    /// Inverse kinematics for a TCP pose of arm `arm`, warm-started from its current joints, with
    /// seeded restarts: `Ok` with the joint angles, or `Err` with the best residual.
    pub fn reachable(&self, arm: usize, pose: &Isometry3<f64>) -> Result<IkSolution, Unreachable> {
        let Some(a) = self.arms.get(arm) else {
            return Err(Unreachable {
                best_joints: panda::READY,
                position_error: f64::INFINITY,
                orientation_error: f64::INFINITY,
            });
        };
        panda::inverse_kinematics(&a.base, pose, &a.joints, &self.params.planning_ik)
    }

    /// Like [`World::reachable`], the solution with the most room to the joint limits
    /// ([`panda::inverse_kinematics_with_room`] from the arm's joints; the executor's joint-space
    /// recovery).
    pub fn reachable_with_room(
        &self,
        arm: usize,
        pose: &Isometry3<f64>,
    ) -> Result<IkSolution, Unreachable> {
        self.solve_from_joints(arm, pose, panda::inverse_kinematics_with_room)
    }

    /// The solution nearest the arm's joints ([`panda::inverse_kinematics_near`]: from them
    /// alone, a joint at a limit held there while the others reach the pose).
    pub fn reachable_near(
        &self,
        arm: usize,
        pose: &Isometry3<f64>,
    ) -> Result<IkSolution, Unreachable> {
        self.solve_from_joints(arm, pose, panda::inverse_kinematics_near)
    }

    /// `solve` (an IK of [`panda`]) for arm `arm` from its joints, with the planning IK's
    /// parameters; [`World::reachable`] for an unknown arm.
    fn solve_from_joints(
        &self,
        arm: usize,
        pose: &Isometry3<f64>,
        solve: IkSolver,
    ) -> Result<IkSolution, Unreachable> {
        let Some(a) = self.arms.get(arm) else {
            return self.reachable(arm, pose);
        };
        solve(&a.base, pose, &a.joints, &self.params.planning_ik)
    }

    /// The world boxes of the bodies (not lost) that `keep` accepts (index, body), each with its
    /// body's index, shrunk by 2 mm so that touching faces and resting contacts do not count.
    fn parts_shrunk(
        &self,
        keep: impl Fn(usize, &Body) -> bool,
    ) -> Vec<(usize, Isometry3<f64>, Cuboid)> {
        self.bodies
            .iter()
            .enumerate()
            .filter(|(j, b)| !b.lost && keep(*j, b))
            .flat_map(|(j, b)| {
                b.world_parts()
                    .map(move |(iso, c)| (j, iso, super::geometry::shrunk(c, 0.002)))
            })
            .collect()
    }

    /// The first block or hook (`except` and held bodies excepted) that the hand's capsule
    /// ([`super::geometry::hand_capsule`]) overlaps, by more than 2 mm, at one of the TCP poses
    /// `path` and did not already overlap at the first; `None` if none. The simulator stops the
    /// links only at tables and shelves, so the executor asks this of a learned approach's
    /// planned path before it follows it (a hand swept through a block would knock it over).
    pub(crate) fn hand_path_hits(
        &self,
        path: &[Isometry3<f64>],
        except: &[&str],
    ) -> Option<String> {
        let others = self.parts_shrunk(|j, b| {
            matches!(b.kind, BodyKind::Block | BodyKind::Hook)
                && !self.is_held(j)
                && !except.contains(&b.name.as_str())
        });
        let touching = |tcp: &Isometry3<f64>| -> Vec<usize> {
            let cap = super::geometry::hand_shape(tcp, 0.0);
            others
                .iter()
                .filter(|(_, iso, c)| {
                    query::intersection_test(&Isometry3::identity(), &cap, iso, c).unwrap_or(true)
                })
                .map(|(j, _, _)| *j)
                .collect()
        };
        let at_start = path.first().map(touching).unwrap_or_default();
        path.iter().skip(1).find_map(|tcp| {
            touching(tcp)
                .into_iter()
                .find(|j| !at_start.contains(j))
                .map(|j| self.bodies[j].name.clone())
        })
    }

    /// What arm `arm` would sweep through on a straight joint-space move from `from` to `to`
    /// (sampled at most 0.05 rad apart in every joint, as the streams sample it), carrying what
    /// it holds: the name of the first body (`except` excepted) its links (the base link
    /// excepted) or its load overlap, by more than 2 mm, that they did not already overlap at
    /// `from`, or the table or shelf its links would stop at (pressing deeper than the simulator
    /// lets them); `None` if nothing. The executor's joint-space recovery asks this before it
    /// moves (a link passing through a block would knock it over).
    pub fn joint_move_hits(
        &self,
        arm: usize,
        from: &[f64; DOF],
        to: &[f64; DOF],
        except: &[&str],
    ) -> Option<String> {
        let a = self.arms.get(arm)?;
        let held = a.holding;
        // The load's boxes in the TCP frame.
        let load: Vec<(Isometry3<f64>, Cuboid)> = held
            .map(|(bi, g)| {
                self.bodies[bi]
                    .parts
                    .iter()
                    .map(|(p, c)| (g * p, *c))
                    .collect()
            })
            .unwrap_or_default();
        let others = self.parts_shrunk(|j, b| {
            held.is_none_or(|(bi, _)| bi != j) && !except.contains(&b.name.as_str())
        });
        // (part, other) pairs overlapping at q; parts: link capsules, then load boxes.
        let overlapping = |q: &[f64; DOF]| -> Vec<(usize, usize)> {
            let mut out = vec![];
            let caps = super::geometry::link_capsules(self, arm, q);
            for (pi, (p0, p1, r)) in caps.iter().enumerate().skip(1) {
                let cap = Capsule::new(Point3::from(*p0), Point3::from(*p1), *r);
                for (oi, (_, iso, c)) in others.iter().enumerate() {
                    if query::intersection_test(&Isometry3::identity(), &cap, iso, c)
                        .unwrap_or(true)
                    {
                        out.push((pi, oi));
                    }
                }
            }
            let tcp = panda::forward_kinematics(&a.base, q);
            for (li, (off, lc)) in load.iter().enumerate() {
                let liso = tcp * off;
                for (oi, (_, iso, c)) in others.iter().enumerate() {
                    if query::intersection_test(&liso, lc, iso, c).unwrap_or(true) {
                        out.push((caps.len() + li, oi));
                    }
                }
            }
            out
        };
        let at_start = overlapping(from);
        // The links' stop at furniture, as in `step_arm`: deeper than LINK_TOLERANCE and deeper
        // than the step before.
        let mut furniture_depth = self.link_penetration(arm, from).0;
        panda::joint_line(from, to).find_map(|q| {
            let (depth, with) = self.link_penetration(arm, &q);
            if depth > LINK_TOLERANCE && depth > furniture_depth + 1e-9 {
                if let Some(j) = with {
                    return Some(self.bodies[j].name.clone());
                }
            }
            furniture_depth = depth;
            overlapping(&q)
                .into_iter()
                .find(|pair| !at_start.contains(pair))
                .map(|(_, oi)| self.bodies[others[oi].0].name.clone())
        })
    }

    /// Sets the joint angles of an arm directly (clamped to the limits); a held body follows.
    pub fn set_joints(&mut self, arm: usize, joints: [f64; DOF]) -> Result<(), SimError> {
        let a = self.arms.get_mut(arm).ok_or(SimError::NoSuchArm(arm))?;
        a.joints = joints;
        panda::clamp_joints(&mut a.joints);
        a.target = None;
        self.carry_held(arm);
        Ok(())
    }

    // ----------------------------------------------------------------- commands and stepping

    /// Commands arm `arm`: its TCP follows `target` (through IK, within joint velocity limits) from
    /// the next [`World::step`] on, and its gripper opens or closes. A change of the gripper
    /// command takes effect (grasp / release) at the next step.
    pub fn command_arm(
        &mut self,
        arm: usize,
        target: Isometry3<f64>,
        gripper: GripperCommand,
    ) -> Result<(), SimError> {
        let a = self.arms.get_mut(arm).ok_or(SimError::NoSuchArm(arm))?;
        a.target = Some(target);
        a.joint_target = None;
        a.gripper = gripper;
        Ok(())
    }

    /// Commands arm `arm` to move in joint space to `joints` (each joint at its velocity limit,
    /// clamped to its range), replacing any TCP target until the next [`World::command_arm`].
    /// Used to recover when Cartesian tracking is stuck far from a reachable goal.
    pub fn command_joints(
        &mut self,
        arm: usize,
        joints: [f64; DOF],
        gripper: GripperCommand,
    ) -> Result<(), SimError> {
        if joints.iter().any(|j| !j.is_finite()) {
            return Err(SimError::NonFinite);
        }
        let a = self.arms.get_mut(arm).ok_or(SimError::NoSuchArm(arm))?;
        a.joint_target = Some(joints);
        a.target = None;
        a.gripper = gripper;
        Ok(())
    }

    /// The command an arm is following: target TCP pose (if any) and gripper command.
    pub fn arm_command(&self, arm: usize) -> Option<(Option<Isometry3<f64>>, GripperCommand)> {
        self.arms.get(arm).map(|a| (a.target, a.gripper))
    }

    /// Advances the world by one fixed step [`World::dt`]: grasps/releases on gripper changes,
    /// moves every commanded arm towards its target (IK, joint velocity limits), carries held
    /// bodies, lets the hook push blocks its blade sweeps into. Returns what happened.
    pub fn step(&mut self) -> Vec<WorldEvent> {
        let mut events = Vec::new();
        for ai in 0..self.arms.len() {
            self.step_gripper(ai, &mut events);
            self.arms[ai].last_gripper = self.arms[ai].gripper;
            self.step_arm(ai, &mut events);
        }
        self.time += self.dt;
        events
    }

    fn step_gripper(&mut self, ai: usize, events: &mut Vec<WorldEvent>) {
        let cmd = self.arms[ai].gripper;
        match (cmd, self.arms[ai].holding) {
            (GripperCommand::Close, None) if self.arms[ai].gripper_opening > 0.0 => {
                // Closing: grasp the first free movable body whose inside holds the TCP.
                let tcp = self.arms[ai].tcp();
                let pt = Point3::from(tcp.translation.vector);
                let found = (0..self.bodies.len()).find(|&i| {
                    let b = &self.bodies[i];
                    b.is_movable()
                        && !b.lost
                        && !self
                            .arms
                            .iter()
                            .any(|a| a.holding.is_some_and(|(j, _)| j == i))
                        && b.contains_point(&pt, self.params.grasp_tolerance)
                });
                // Grasp when the fingers are still wider than the body across them.
                let opening = self.arms[ai].gripper_opening;
                let grasp = found.map(|bi| (bi, tcp.inverse() * self.bodies[bi].pose));
                let fits = grasp.filter(|(bi, g)| self.finger_width(*bi, g) < opening);
                if let Some((bi, grasp)) = fits {
                    self.arms[ai].holding = Some((bi, grasp));
                    events.push(WorldEvent::Grasped {
                        arm: self.arms[ai].name.clone(),
                        body: self.bodies[bi].name.clone(),
                    });
                } else if self.arms[ai].last_gripper == GripperCommand::Open {
                    events.push(WorldEvent::GraspedNothing {
                        arm: self.arms[ai].name.clone(),
                    });
                }
                let width = self.arms[ai]
                    .holding
                    .map(|(bi, g)| self.finger_width(bi, &g))
                    .unwrap_or(0.0);
                let a = &mut self.arms[ai];
                a.gripper_opening =
                    (a.gripper_opening - self.params.finger_speed * self.dt).max(width);
            }
            (GripperCommand::Close, Some((bi, g))) => {
                let width = self.finger_width(bi, &g);
                let a = &mut self.arms[ai];
                a.gripper_opening =
                    (a.gripper_opening - self.params.finger_speed * self.dt).max(width);
            }
            (GripperCommand::Open, Some((bi, _))) => {
                self.arms[ai].holding = None;
                self.release(ai, bi, events);
                let a = &mut self.arms[ai];
                a.gripper_opening = (a.gripper_opening + self.params.finger_speed * self.dt)
                    .min(panda::GRIPPER_MAX_OPENING);
            }
            (GripperCommand::Open, None) => {
                let a = &mut self.arms[ai];
                a.gripper_opening = (a.gripper_opening + self.params.finger_speed * self.dt)
                    .min(panda::GRIPPER_MAX_OPENING);
            }
            (GripperCommand::Close, None) => {}
        }
    }

    /// Width of a held body across the fingers (along the TCP `y` axis).
    fn finger_width(&self, bi: usize, grasp: &Isometry3<f64>) -> f64 {
        let b = &self.bodies[bi];
        let mut w: f64 = 0.0;
        for (p, c) in &b.parts {
            let iso = grasp * p;
            if iso.translation.vector.norm() > 0.05 {
                continue;
            }
            let m = iso.rotation.to_rotation_matrix().matrix().abs();
            w = w.max(2.0 * (m * c.half_extents).y);
        }
        w.min(panda::GRIPPER_MAX_OPENING)
    }

    fn step_arm(&mut self, ai: usize, events: &mut Vec<WorldEvent>) {
        let a = &self.arms[ai];
        let desired = if let Some(q) = a.joint_target {
            if (0..DOF).all(|k| (q[k] - a.joints[k]).abs() < 1e-9) {
                return;
            }
            q
        } else {
            let Some(target) = a.target else {
                return;
            };
            let current = a.tcp();
            let pos_err = (target.translation.vector - current.translation.vector).norm();
            let rot_err = (target.rotation * current.rotation.inverse()).angle();
            if pos_err < 1e-5 && rot_err < 1e-4 {
                return;
            }
            match panda::inverse_kinematics(&a.base, &target, &a.joints, &self.params.tracking_ik) {
                Ok(s) => s.joints,
                Err(u) => u.best_joints,
            }
        };
        let dt = self.dt;
        // Contact stop: what the held body overlaps now (it may only get shallower).
        let held = self.arms[ai].holding.map(|(bi, _)| bi);
        let depth_before = held.map_or(0.0, |bi| self.held_penetration(bi).0);
        let saved = held.map(|_| (self.arms[ai].joints, self.bodies.clone(), events.len()));
        let before = self.arms[ai].joints;
        let a = &mut self.arms[ai];
        // Within the joint velocity limits, the whole step scaled down alike: the hand lags
        // along its path instead of leaving it (clamping each joint alone turns the step: the
        // shoulder pitching on while the saturated elbow lags drops a stretched-out hand).
        let scale = (0..DOF)
            .map(|k| {
                let d = (desired[k] - a.joints[k]).abs();
                let max = panda::JOINT_VELOCITY[k] * dt;
                if d > max {
                    max / d
                } else {
                    1.0
                }
            })
            .fold(1.0, f64::min);
        for k in 0..DOF {
            let d = scale * (desired[k] - a.joints[k]);
            a.joints[k] = (a.joints[k] + d).clamp(panda::JOINT_LOWER[k], panda::JOINT_UPPER[k]);
        }
        // The links stop at a table or shelf they would press into (deeper than
        // LINK_TOLERANCE and deeper than before): the arm cannot reach through furniture.
        let after = self.arms[ai].joints;
        let (depth, with) = self.link_penetration(ai, &after);
        if depth > LINK_TOLERANCE && depth > self.link_penetration(ai, &before).0 + 1e-9 {
            self.arms[ai].joints = before;
            self.arms[ai].blocked_by = with.map(|j| self.bodies[j].name.clone());
            return;
        }
        let hook_before = self.arms[ai].holding.and_then(|(bi, _)| {
            (self.bodies[bi].kind == BodyKind::Hook).then_some((bi, self.bodies[bi].pose))
        });
        self.carry_held(ai);
        if let Some((hi, before)) = hook_before {
            self.hook_push(hi, &before, events);
        }
        self.arms[ai].blocked_by = None;
        if let (Some(bi), Some((joints, mut bodies, n_events))) = (held, saved) {
            let limit = self.params.carried_stop_depth();
            let (depth, with) = self.held_penetration(bi);
            let mut stop = (depth > limit.max(depth_before + 1e-9)).then_some(with);
            if stop.is_none() {
                // A block the carried hook pushed may not be driven into another body, nor off
                // its support.
                for e in &events[n_events..] {
                    let (pushed, lost) = match e {
                        WorldEvent::Pushed { body, .. } => (self.body_index(body), None),
                        WorldEvent::Lost { body, .. } => (None, self.body_index(body)),
                        _ => (None, None),
                    };
                    if let Some(j) = lost {
                        stop = Some(Some(j));
                        break;
                    }
                    if let Some(pi) = pushed {
                        let (d, w) = self.held_penetration(pi);
                        if d > limit {
                            // Its depth before this step (the saved bodies, swapped in).
                            std::mem::swap(&mut self.bodies, &mut bodies);
                            let was = self.held_penetration(pi).0;
                            std::mem::swap(&mut self.bodies, &mut bodies);
                            if d > was + 1e-9 {
                                stop = Some(w.or(Some(pi)));
                                break;
                            }
                        }
                    }
                }
            }
            if let Some(with) = stop {
                // The carried body would press into another (or push one into another or off
                // its support): the arm stops at the contact (the step is undone, pushes
                // included), as a compliant controller would.
                self.arms[ai].joints = joints;
                self.bodies = bodies;
                events.truncate(n_events);
                self.arms[ai].blocked_by = with.map(|j| self.bodies[j].name.clone());
            }
        }
    }

    /// Deepest overlap of arm `ai`'s link capsules at joints `q` (the base link excepted) with a
    /// table or shelf, and which one.
    fn link_penetration(&self, ai: usize, q: &[f64; DOF]) -> (f64, Option<usize>) {
        let mut best = (0.0, None);
        let caps = super::geometry::link_capsules(self, ai, q);
        for (a, b, r) in caps.into_iter().skip(1) {
            let lo = a.inf(&b) - Vector3::repeat(r);
            let hi = a.sup(&b) + Vector3::repeat(r);
            let cap = parry3d_f64::shape::Capsule::new(Point3::from(a), Point3::from(b), r);
            for (j, body) in self.bodies.iter().enumerate() {
                if body.lost || !matches!(body.kind, BodyKind::Table | BodyKind::Shelf) {
                    continue;
                }
                let (blo, bhi) = body.aabb();
                if (0..3).any(|i| lo[i] > bhi[i] || blo[i] > hi[i]) {
                    continue;
                }
                for (iso, c) in body.world_parts() {
                    if let Ok(Some(k)) = query::contact(&Isometry3::identity(), &cap, &iso, c, 0.0)
                    {
                        if -k.dist > best.0 {
                            best = (-k.dist, Some(j));
                        }
                    }
                }
            }
        }
        best
    }

    /// Deepest overlap of body `bi` with any other body that is not lost (bodies the other arms
    /// hold included), and with which one.
    fn held_penetration(&self, bi: usize) -> (f64, Option<usize>) {
        let mut best = (0.0, None);
        for j in 0..self.bodies.len() {
            if j == bi || self.bodies[j].lost {
                continue;
            }
            let d = self.bodies[bi].penetration(&self.bodies[j]);
            if d > best.0 {
                best = (d, Some(j));
            }
        }
        best
    }

    /// The deepest overlap (m) body `name` would have at `pose` with another body that is not
    /// lost (bodies held by arms included), and that body's name; `None` when it would touch
    /// nothing.
    pub fn overlap_at(&self, name: &str, pose: &Isometry3<f64>) -> Option<(f64, String)> {
        let bi = self.body_index(name)?;
        let mut probe = self.bodies[bi].clone();
        probe.pose = *pose;
        let mut best: Option<(f64, String)> = None;
        for (j, o) in self.bodies.iter().enumerate() {
            if j == bi || o.lost {
                continue;
            }
            let d = probe.penetration(o);
            if d > 0.0 && best.as_ref().is_none_or(|(b, _)| d > *b) {
                best = Some((d, o.name.clone()));
            }
        }
        best
    }

    /// The highest top face (m) of the bodies (not lost, `except` left out) whose
    /// horizontal bounds meet the rectangle `[lo, hi]` (x, y); the floor height if none.
    pub fn highest_top_in(&self, lo: [f64; 2], hi: [f64; 2], except: &str) -> f64 {
        let mut top = self.floor_z;
        for b in &self.bodies {
            if b.lost || b.name == except {
                continue;
            }
            let (blo, bhi) = b.aabb();
            if blo.x <= hi[0] && bhi.x >= lo[0] && blo.y <= hi[1] && bhi.y >= lo[1] {
                top = top.max(bhi.z);
            }
        }
        top
    }

    /// Names of the bodies standing (directly or through others) on body `name`, bottom first.
    pub fn resting_on(&self, name: &str) -> Vec<String> {
        self.body_index(name)
            .map(|bi| {
                self.stack_above(bi)
                    .into_iter()
                    .map(|j| self.bodies[j].name.clone())
                    .collect()
            })
            .unwrap_or_default()
    }

    /// The body that stopped the body held by `arm` at the last step (contact stop), if any.
    pub fn arm_blocked_by(&self, arm: usize) -> Option<&str> {
        self.arms.get(arm).and_then(|a| a.blocked_by.as_deref())
    }

    /// Moves the body held by `ai` rigidly with its TCP.
    fn carry_held(&mut self, ai: usize) {
        if let Some((bi, g)) = self.arms[ai].holding {
            self.bodies[bi].pose = self.arms[ai].tcp() * g;
        }
    }

    fn is_held(&self, bi: usize) -> bool {
        self.arms
            .iter()
            .any(|a| a.holding.is_some_and(|(j, _)| j == bi))
    }

    /// The hook (body `hi`) moved from `before` to its current pose: blocks hit by the swept blade
    /// are pushed horizontally by the remaining part of the motion (with what stands on them).
    fn hook_push(&mut self, hi: usize, before: &Isometry3<f64>, events: &mut Vec<WorldEvent>) {
        let after = self.bodies[hi].pose;
        let d = after.translation.vector - before.translation.vector;
        let horiz = Vector3::new(d.x, d.y, 0.0);
        if horiz.norm() < 1e-9 {
            return;
        }
        for bi in 0..self.bodies.len() {
            let b = &self.bodies[bi];
            if b.kind != BodyKind::Block || b.lost || self.is_held(bi) {
                continue;
            }
            // Swept test: the hook's boxes translate along d from `before` (parry shape cast).
            let mut toi = f64::INFINITY;
            for (hp, hc) in &self.bodies[hi].parts {
                let hiso = before * hp;
                for (bp, bc) in b.world_parts() {
                    let opts = query::ShapeCastOptions {
                        max_time_of_impact: 1.0,
                        target_distance: 0.0,
                        stop_at_penetration: false,
                        compute_impact_geometry_on_penetration: false,
                    };
                    if let Ok(Some(hit)) =
                        query::cast_shapes(&hiso, &d, hc, &bp, &Vector3::zeros(), bc, opts)
                    {
                        // Separating contacts at time 0 are discarded by parry
                        // (`stop_at_penetration: false`), so a hit is a blade driving into it.
                        toi = toi.min(hit.time_of_impact);
                    }
                }
            }
            let mut push = if toi > 1.0 {
                Vector3::zeros()
            } else {
                horiz * (1.0 - toi)
            };
            // The hook also turns a little as the arm tracks its stroke, which a translation
            // alone does not cover: a blade still inside the block after the push drives it
            // further along the contact's (horizontal) normal.
            push += self.hook_overlap_push(hi, bi, &push);
            if push.norm() < 1e-12 {
                continue;
            }
            let stack = self.stack_above(bi);
            for &si in std::iter::once(&bi).chain(stack.iter()) {
                self.bodies[si].pose.translation.vector += push;
            }
            events.push(WorldEvent::Pushed {
                body: self.bodies[bi].name.clone(),
                by: self.bodies[hi].name.clone(),
                displacement: [push.x, push.y],
            });
            // Pushed off its support? Then it (and its stack) falls.
            for si in std::iter::once(bi).chain(stack) {
                if let Settle::Falls(reason) =
                    self.settle_probe(si, &self.bodies[si].pose.clone(), &[hi])
                {
                    self.make_lost(si, reason, events);
                }
            }
        }
    }

    /// How far block `bi`, already moved by `push`, must move further so that the hook `hi` (at
    /// its pose) no longer overlaps it sideways: the horizontal part of the deepest contact's
    /// normal times its depth (zero when they do not overlap, or the contact is vertical: a hook
    /// resting on a block does not push it).
    fn hook_overlap_push(&self, hi: usize, bi: usize, push: &Vector3<f64>) -> Vector3<f64> {
        let mut best = Vector3::zeros();
        // Runs every step the hook is carried: apart (AABBs disjoint) means no overlap.
        let (hlo, hhi) = self.bodies[hi].aabb();
        let (blo, bhi) = self.bodies[bi].aabb();
        if (0..3).any(|i| hlo[i] > bhi[i] + push[i] || blo[i] + push[i] > hhi[i]) {
            return best;
        }
        let shift = Isometry3::translation(push.x, push.y, push.z);
        for (hiso, hc) in self.bodies[hi].world_parts() {
            for (biso, bc) in self.bodies[bi].world_parts() {
                let Ok(Some(k)) = query::contact(&hiso, hc, &(shift * biso), bc, 0.0) else {
                    continue;
                };
                let n = k.normal1.into_inner();
                let side = Vector3::new(n.x, n.y, 0.0);
                if k.dist >= 0.0 || side.norm() < 0.7 {
                    continue;
                }
                let step = side.normalize() * (-k.dist + 1e-4);
                if step.norm() > best.norm() {
                    best = step;
                }
            }
        }
        best
    }

    /// Blocks resting (transitively) on body `bi`, bottom to top.
    pub(crate) fn stack_above(&self, bi: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut frontier = vec![bi];
        while let Some(cur) = frontier.pop() {
            let (lo, hi) = self.bodies[cur].aabb();
            for (j, b) in self.bodies.iter().enumerate() {
                if j == bi || out.contains(&j) || !b.is_movable() || b.lost || self.is_held(j) {
                    continue;
                }
                let c = b.centroid_at(&b.pose);
                let (blo, _) = b.aabb();
                if (blo.z - hi.z).abs() <= self.params.support_tolerance
                    && c.x >= lo.x
                    && c.x <= hi.x
                    && c.y >= lo.y
                    && c.y <= hi.y
                    && self.bodies[cur].top_under(c.x, c.y, 0.0).is_some()
                {
                    out.push(j);
                    frontier.push(j);
                }
            }
        }
        out.sort_by(|&a, &b| {
            self.bodies[a]
                .pose
                .translation
                .z
                .total_cmp(&self.bodies[b].pose.translation.z)
        });
        out
    }

    /// Where body `bi` would come to rest if let go at `pose` (tilt removed, yaw kept); `ignore`
    /// lists bodies that are not obstacles.
    fn settle_probe(&self, bi: usize, pose: &Isometry3<f64>, ignore: &[usize]) -> Settle {
        self.settle_probe_among(bi, pose, ignore, false)
    }

    /// [`World::settle_probe`]; with `held_obstacles`, bodies held by a gripper are obstacles
    /// too (a dragged block must not fall through a carried one).
    fn settle_probe_among(
        &self,
        bi: usize,
        pose: &Isometry3<f64>,
        ignore: &[usize],
        held_obstacles: bool,
    ) -> Settle {
        match self.settle_probe_once(bi, pose, ignore, held_obstacles) {
            Settle::Blocked(j) => {
                // Wedged under an overhang (a block pushed over its edge): what lies above its
                // centre cannot hold it up; it rests on what is below, if that holds it.
                let centre = pose.translation.z;
                let mut above: Vec<usize> = ignore.to_vec();
                above.extend(
                    (0..self.bodies.len())
                        .filter(|&k| k != bi && self.bodies[k].aabb().0.z > centre),
                );
                let tol = self.params.penetration_tolerance;
                match self.settle_probe_once(bi, pose, &above, held_obstacles) {
                    Settle::On { support, drop } => {
                        // Only if, at rest, it presses into none of them beyond the tolerance.
                        let mut rest = self.bodies[bi].clone();
                        rest.pose = *pose;
                        rest.pose.translation.z -= drop;
                        let clear = above[ignore.len()..].iter().all(|&k| {
                            self.bodies[k].lost || rest.penetration(&self.bodies[k]) <= 0.9 * tol
                        });
                        if clear {
                            Settle::On { support, drop }
                        } else {
                            Settle::Blocked(j)
                        }
                    }
                    _ => Settle::Blocked(j),
                }
            }
            settle => settle,
        }
    }

    /// One probe of [`World::settle_probe_among`], `ignore` excepted.
    fn settle_probe_once(
        &self,
        bi: usize,
        pose: &Isometry3<f64>,
        ignore: &[usize],
        held_obstacles: bool,
    ) -> Settle {
        let b = &self.bodies[bi];
        let lift = 0.005;
        let start = Isometry3::from_parts(
            Translation3::from(pose.translation.vector + Vector3::new(0.0, 0.0, lift)),
            pose.rotation,
        );
        let (lo, _) = b.aabb_at(&start);
        let max_fall = (lo.z - self.floor_z).max(0.0);
        let down = Vector3::new(0.0, 0.0, -1.0);
        let mut best: Option<(f64, usize)> = None;
        for (j, o) in self.bodies.iter().enumerate() {
            if j == bi || o.lost || ignore.contains(&j) || (!held_obstacles && self.is_held(j)) {
                continue;
            }
            for (bp, bc) in &b.parts {
                let biso = start * bp;
                for (op, oc) in o.world_parts() {
                    let opts = query::ShapeCastOptions {
                        max_time_of_impact: max_fall,
                        target_distance: 0.0,
                        stop_at_penetration: true,
                        compute_impact_geometry_on_penetration: false,
                    };
                    if let Ok(Some(hit)) =
                        query::cast_shapes(&biso, &down, bc, &op, &Vector3::zeros(), oc, opts)
                    {
                        if best.is_none_or(|(t, _)| hit.time_of_impact < t) {
                            best = Some((hit.time_of_impact, j));
                        }
                    }
                }
            }
        }
        let Some((toi, j)) = best else {
            return Settle::Falls("nothing is under it".into());
        };
        if toi <= 0.0 {
            // Overlapping something even when lifted: only acceptable if that body is below.
            let (olo, ohi) = self.bodies[j].aabb();
            let _ = olo;
            if ohi.z > lo.z + 0.003 {
                return Settle::Blocked(j);
            }
        }
        let rest = Isometry3::from_parts(
            Translation3::from(start.translation.vector + down * toi),
            start.rotation,
        );
        let c = b.centroid_at(&rest);
        let (rlo, _) = b.aabb_at(&rest);
        // Supported if some body whose top is at the contact height lies under the centroid.
        let supported = self.bodies.iter().enumerate().any(|(k, o)| {
            k != bi
                && !o.lost
                && !ignore.contains(&k)
                && !self.is_held(k)
                && o.top_under(c.x, c.y, 0.0)
                    .is_some_and(|t| (t - rlo.z).abs() <= self.params.support_tolerance)
        });
        if !supported {
            return Settle::Falls(format!(
                "its centre is not above {} (it would tip over)",
                self.bodies[j].name
            ));
        }
        Settle::On {
            support: j,
            drop: pose.translation.z - rest.translation.z,
        }
    }

    /// Why a dragged or released body may not come to rest on body `support`, if it may not: a body held by
    /// a gripper, the hook, or a block in a scene whose vocabulary has no `on` (the scene graph
    /// could not say where it is, and lifting the block below would leave it in the air).
    fn support_refusal(&self, support: usize) -> Option<String> {
        let s = &self.bodies[support];
        if self.is_held(support) {
            return Some(format!(
                "it would land on {}, which a gripper holds",
                s.name
            ));
        }
        match s.kind {
            BodyKind::Hook => Some(format!("it would rest on the hook {}", s.name)),
            BodyKind::Block if !self.predicates.iter().any(|p| p == "on") => Some(format!(
                "it would rest on the block {} and this scene cannot stack blocks (no `on` predicate)",
                s.name
            )),
            _ => None,
        }
    }

    /// Pose with the tilt removed (yaw about `z` kept).
    pub(crate) fn upright(pose: &Isometry3<f64>) -> Isometry3<f64> {
        let yaw = yaw_of(&pose.rotation);
        Isometry3::from_parts(
            pose.translation,
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
        )
    }

    /// What opening arm `arm`'s gripper now would do to its load: `Err(why)` if the load would
    /// fall, end inside another body, or come to rest where a drag may not leave a body (on a
    /// held body, on the hook, on a block in a scene without `on`: the scene graph could not say
    /// where it is). Nothing held, or an unknown arm: `Ok`.
    pub fn release_check(&self, arm: usize) -> Result<(), String> {
        let Some((bi, _)) = self.arms.get(arm).and_then(|a| a.holding) else {
            return Ok(());
        };
        let pose = Self::upright(&self.bodies[bi].pose);
        match self.settle_probe(bi, &pose, &[]) {
            Settle::On { support, .. } => self.support_refusal(support).map_or(Ok(()), Err),
            Settle::Falls(reason) => Err(reason),
            Settle::Blocked(j) => Err(format!("it would be inside {}", self.bodies[j].name)),
        }
    }

    fn release(&mut self, ai: usize, bi: usize, events: &mut Vec<WorldEvent>) {
        let pose = Self::upright(&self.bodies[bi].pose);
        self.bodies[bi].pose = pose;
        match self.settle_probe(bi, &pose, &[]) {
            Settle::On { support, drop } => {
                self.bodies[bi].pose.translation.z -= drop;
                events.push(WorldEvent::Released {
                    arm: self.arms[ai].name.clone(),
                    body: self.bodies[bi].name.clone(),
                    support: self.bodies[support].name.clone(),
                    drop,
                });
            }
            Settle::Falls(reason) => self.make_lost(bi, reason, events),
            Settle::Blocked(j) => {
                let reason = format!("released inside {}", self.bodies[j].name);
                self.make_lost(bi, reason, events)
            }
        }
    }

    fn make_lost(&mut self, bi: usize, reason: String, events: &mut Vec<WorldEvent>) {
        let b = &mut self.bodies[bi];
        let (lo, _) = b.aabb();
        b.pose.translation.z += self.floor_z - lo.z;
        b.lost = true;
        events.push(WorldEvent::Lost {
            body: b.name.clone(),
            reason,
        });
    }

    // ----------------------------------------------------------------- user moves

    /// Moves a block (or the hook) as a user drag does: its centre goes to `position` (yaw kept),
    /// then it settles straight down onto the highest support under it. Bodies that stood on it
    /// settle down in turn. Refused, with the world unchanged, if the body is unknown, fixed, held
    /// or lost, if it would interpenetrate another body or an arm, or if nothing would support it.
    pub fn move_block(
        &mut self,
        name: &str,
        position: Vector3<f64>,
    ) -> Result<MoveOutcome, Refused> {
        let yaw = self
            .body_pose(name)
            .map(|p| yaw_of(&p.rotation))
            .unwrap_or(0.0);
        self.move_block_to(name, position, yaw)
    }

    /// Like [`World::move_block`] with a new yaw (rad about world `z`).
    pub fn move_block_to(
        &mut self,
        name: &str,
        position: Vector3<f64>,
        yaw: f64,
    ) -> Result<MoveOutcome, Refused> {
        let refuse = |reason: String| Refused {
            body: name.to_string(),
            reason,
        };
        let Some(bi) = self.body_index(name) else {
            return Err(refuse("there is no such body".into()));
        };
        if !self.bodies[bi].is_movable() {
            return Err(refuse("it is fixed (only blocks and the hook move)".into()));
        }
        if self.bodies[bi].lost {
            return Err(refuse("it is lost".into()));
        }
        if self.is_held(bi) {
            return Err(refuse("it is held by a gripper".into()));
        }
        if !(position.iter().all(|v| v.is_finite()) && yaw.is_finite()) {
            return Err(refuse("the position is not finite".into()));
        }
        let from = self.bodies[bi].pose.translation.vector;
        let mut trial = self.clone();
        let above = trial.stack_above(bi);
        let pose = Isometry3::from_parts(
            Translation3::from(position),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
        );
        trial.bodies[bi].pose = pose;
        // Interpenetration at the requested place (ignoring what stood on it: it stays behind).
        for (j, o) in trial.bodies.iter().enumerate() {
            if j == bi || o.lost || above.contains(&j) {
                continue;
            }
            let depth = trial.bodies[bi].penetration(o);
            if depth > trial.params.penetration_tolerance {
                return Err(refuse(format!(
                    "it would interpenetrate {} by {:.1} mm",
                    o.name,
                    depth * 1000.0
                )));
            }
        }
        let settle = trial.settle_probe_among(bi, &pose, &above, true);
        let support = match settle {
            Settle::On { support, drop } => {
                if let Some(why) = trial.support_refusal(support) {
                    return Err(refuse(why));
                }
                trial.bodies[bi].pose.translation.z -= drop;
                support
            }
            Settle::Falls(reason) => return Err(refuse(format!("it would fall: {reason}"))),
            Settle::Blocked(j) => {
                return Err(refuse(format!(
                    "it would interpenetrate {}",
                    trial.bodies[j].name
                )))
            }
        };
        // Arms: the moved body must not hit a link.
        for ai in 0..trial.arms.len() {
            for cap in trial.arm_capsules(ai) {
                for (iso, c) in trial.bodies[bi].world_parts() {
                    if query::intersection_test(&Isometry3::identity(), &cap, &iso, c)
                        .unwrap_or(false)
                    {
                        return Err(refuse(format!(
                            "it would hit the arm {}",
                            trial.arms[ai].name
                        )));
                    }
                }
            }
        }
        // What stood on it settles down, bottom first.
        let mut also = Vec::new();
        let mut events = Vec::new();
        for &j in &above {
            let p = trial.bodies[j].pose;
            match trial.settle_probe_among(j, &p, &[], true) {
                Settle::On { support, drop } => {
                    if let Some(why) = trial.support_refusal(support) {
                        return Err(refuse(format!(
                            "{} standing on it would settle badly: {why}",
                            trial.bodies[j].name
                        )));
                    }
                    trial.bodies[j].pose.translation.z -= drop
                }
                Settle::Falls(reason) => trial.make_lost(j, reason, &mut events),
                Settle::Blocked(k) => {
                    return Err(refuse(format!(
                        "{} standing on it would end inside {}",
                        trial.bodies[j].name, trial.bodies[k].name
                    )))
                }
            }
            if trial.bodies[j].lost {
                return Err(refuse(format!(
                    "{} standing on it would fall off",
                    trial.bodies[j].name
                )));
            }
            let t = trial.bodies[j].pose.translation.vector;
            also.push((
                trial.bodies[j].name.clone(),
                [round6(t.x), round6(t.y), round6(t.z)],
            ));
        }
        let to = trial.bodies[bi].pose.translation.vector;
        let support = trial.bodies[support].name.clone();
        *self = trial;
        Ok(MoveOutcome {
            body: name.to_string(),
            from: from.into(),
            to: to.into(),
            support,
            also_moved: also,
        })
    }

    /// Adds a new 6 cm block called `name` (colour `#rrggbb`) and drops it at `position` with yaw
    /// `yaw` as [`World::move_block`] does. Refused (world unchanged) for a bad or taken name, a
    /// bad colour, or a place where it cannot rest.
    pub fn add_block(
        &mut self,
        name: &str,
        color: &str,
        position: Vector3<f64>,
        yaw: f64,
    ) -> Result<MoveOutcome, Refused> {
        let refuse = |reason: String| Refused {
            body: name.to_string(),
            reason,
        };
        check_name(name, "block").map_err(|e| refuse(e.message))?;
        check_color(color, "block").map_err(|e| refuse(e.message))?;
        if self.body_index(name).is_some()
            || self.arm_index(name).is_some()
            || self.regions.iter().any(|r| r.name == name)
        {
            return Err(refuse("the name is taken".into()));
        }
        let h = 0.5 * super::benchmark::BLOCK_SIZE;
        let mut trial = self.clone();
        trial.bodies.push(Body {
            name: name.to_string(),
            kind: BodyKind::Block,
            parts: vec![(Isometry3::identity(), Cuboid::new(Vector3::repeat(h)))],
            // Far above everything until it is moved into place.
            pose: Isometry3::translation(0.0, 0.0, 100.0),
            color: color.to_string(),
            lost: false,
        });
        let out = trial.move_block_to(name, position, yaw)?;
        *self = trial;
        Ok(out)
    }

    // ----------------------------------------------------------------- invariants

    /// Checks the world's invariants: no two bodies interpenetrate deeper than
    /// [`WorldParams::penetration_tolerance`] (parry contact test on every pair of boxes), every free
    /// block and the hook rest on a support (bottom within [`WorldParams::support_tolerance`] of a
    /// top face under its centre), no body is lost, every joint is within its limits.
    pub fn check_invariants(&self) -> Result<(), Vec<Violation>> {
        let v = self.check_invariants_list();
        if v.is_empty() {
            Ok(())
        } else {
            Err(v)
        }
    }

    fn check_invariants_list(&self) -> Vec<Violation> {
        let mut out = Vec::new();
        let tol = self.params.penetration_tolerance;
        for i in 0..self.bodies.len() {
            if self.bodies[i].lost {
                out.push(Violation::Lost {
                    body: self.bodies[i].name.clone(),
                });
                continue;
            }
            for j in i + 1..self.bodies.len() {
                if self.bodies[j].lost {
                    continue;
                }
                // Fixed bodies may touch each other as built (a shelf on a table).
                if !self.bodies[i].is_movable() && !self.bodies[j].is_movable() {
                    continue;
                }
                let depth = self.bodies[i].penetration(&self.bodies[j]);
                if depth > tol {
                    out.push(Violation::Interpenetration {
                        a: self.bodies[i].name.clone(),
                        b: self.bodies[j].name.clone(),
                        depth,
                    });
                }
            }
        }
        for (i, b) in self.bodies.iter().enumerate() {
            if !b.is_movable() || b.lost || self.is_held(i) {
                continue;
            }
            let gap = self.support_gap(i);
            if gap > self.params.support_tolerance {
                out.push(Violation::Unsupported {
                    body: b.name.clone(),
                    gap,
                });
            }
        }
        for a in &self.arms {
            for k in 0..DOF {
                let v = a.joints[k];
                if !(panda::JOINT_LOWER[k] - 1e-9..=panda::JOINT_UPPER[k] + 1e-9).contains(&v) {
                    out.push(Violation::JointLimit {
                        arm: a.name.clone(),
                        joint: k,
                        value: v,
                    });
                }
            }
        }
        out
    }

    /// Height of body `bi`'s bottom above the highest top face under its centroid (∞ if none).
    fn support_gap(&self, bi: usize) -> f64 {
        let b = &self.bodies[bi];
        let c = b.centroid_at(&b.pose);
        let (lo, _) = b.aabb();
        let mut best = f64::INFINITY;
        for (j, o) in self.bodies.iter().enumerate() {
            if j == bi || o.lost || self.is_held(j) {
                continue;
            }
            if let Some(t) = o.top_under(c.x, c.y, 0.0) {
                let gap = lo.z - t;
                if gap >= -self.params.support_tolerance && gap.abs() < best.abs() {
                    best = gap;
                }
            }
        }
        best.abs()
    }

    /// The support body under `bi` (top within tolerance under its centroid), if any.
    pub(crate) fn support_of(&self, bi: usize) -> Option<usize> {
        let b = &self.bodies[bi];
        let c = b.centroid_at(&b.pose);
        let (lo, _) = b.aabb();
        let mut best: Option<(f64, usize)> = None;
        for (j, o) in self.bodies.iter().enumerate() {
            if j == bi || o.lost || self.is_held(j) {
                continue;
            }
            if let Some(t) = o.top_under(c.x, c.y, 0.0) {
                let gap = (lo.z - t).abs();
                if gap <= self.params.support_tolerance && best.is_none_or(|(g, _)| gap < g) {
                    best = Some((gap, j));
                }
            }
        }
        best.map(|(_, j)| j)
    }
}
