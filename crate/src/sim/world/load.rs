//! Scenes in and out: a [`World`] as a JSON-ready snapshot, and a snapshot (or its JSON) read
//! back into a world with every field and the geometry validated.

use super::state::{scene_err, SceneError, LIMIT_SLACK};
use super::{Arm, Body, GripperCommand, Region, Violation, World, WorldParams};
use crate::sim::panda::DOF;
use crate::sim::ArmModel;
use crate::sim::{
    ArmSnapshot, BodyKind, BodySnapshot, CapsuleSnapshot, CuboidSnapshot, PartSnapshot,
    PoseSnapshot, RegionSnapshot, ShapeSnapshot, WorldSnapshot, SNAPSHOT_VERSION,
};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::shape::Cuboid;
use std::sync::Arc;

/// A loaded quaternion shorter than this counts as zero: it has no orientation to normalise to.
const MIN_QUATERNION_NORM: f64 = 1e-9;

/// A loaded arm holds a body only if its TCP lies inside the body grown by this (m).
const HELD_TCP_MARGIN: f64 = 0.01;

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
    if !n.is_finite() || n < MIN_QUATERNION_NORM {
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

pub(super) fn check_color(c: &str, path: &str) -> Result<(), SceneError> {
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

pub(super) fn check_name(n: &str, path: &str) -> Result<(), SceneError> {
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

/// The names claimed so far while loading a scene, each with the path of the field that
/// claimed it (names are unique across regions, bodies and arms).
#[derive(Default)]
struct NameClaims(Vec<(String, String)>);

impl NameClaims {
    /// Claims `name` for the field at `path`; an error naming the first claim if it is taken.
    fn claim(&mut self, name: &str, path: &str) -> Result<(), SceneError> {
        if let Some((_, first)) = self.0.iter().find(|(n, _)| n == name) {
            return Err(scene_err(
                format!("{path}.name"),
                format!("{name:?} is already used by {first}"),
            ));
        }
        self.0.push((name.to_string(), path.to_string()));
        Ok(())
    }
}

/// The snapshot of a body (a single centred box as a cuboid, anything else as a compound).
fn body_snapshot(b: &Body) -> BodySnapshot {
    BodySnapshot {
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
                        half_extents: [c.half_extents.x, c.half_extents.y, c.half_extents.z],
                    })
                    .collect(),
            }
        },
        pose: pose_to_snapshot(&b.pose),
        color: b.color.clone(),
        lost: b.lost,
    }
}

/// Checks a snapshot's scalar fields: version, step, time and floor.
fn check_header(s: &WorldSnapshot) -> Result<(), SceneError> {
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
    Ok(())
}

/// The regions of a snapshot, validated, their names claimed.
fn load_regions(
    snaps: &[RegionSnapshot],
    names: &mut NameClaims,
) -> Result<Vec<Region>, SceneError> {
    let mut regions = Vec::new();
    for (i, r) in snaps.iter().enumerate() {
        let path = format!("regions[{i}] {:?}", r.name);
        check_name(&r.name, &path)?;
        names.claim(&r.name, &path)?;
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
    Ok(regions)
}

/// The bodies of a snapshot, validated, their names claimed.
fn load_bodies(snaps: &[BodySnapshot], names: &mut NameClaims) -> Result<Vec<Body>, SceneError> {
    let mut bodies = Vec::new();
    for (i, b) in snaps.iter().enumerate() {
        let path = format!("bodies[{i}] {:?}", b.name);
        check_name(&b.name, &path)?;
        names.claim(&b.name, &path)?;
        check_color(&b.color, &path)?;
        let pose = pose_from_snapshot(&b.pose, &format!("{path}.pose"))?;
        let parts = load_shape(&b.shape, &path)?;
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
    Ok(bodies)
}

/// The boxes of a body's shape (body frame), validated; `path` names the body.
fn load_shape(
    shape: &ShapeSnapshot,
    path: &str,
) -> Result<Vec<(Isometry3<f64>, Cuboid)>, SceneError> {
    match shape {
        ShapeSnapshot::Cuboid { half_extents } => Ok(vec![(
            Isometry3::identity(),
            check_half_extents(half_extents, &format!("{path}.shape"))?,
        )]),
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
            Ok(v)
        }
    }
}

/// The shipped robot `name`, which a scene may name without its robot file.
fn shipped(name: &str) -> Option<Arc<ArmModel>> {
    #[cfg(not(first_load))]
    return ArmModel::shipped(name);
    #[cfg(first_load)]
    return {
        let _ = name;
        None
    };
}

/// The arms of a snapshot, validated against `bodies`, their names claimed.
fn load_arms(
    snaps: &[ArmSnapshot],
    bodies: &[Body],
    names: &mut NameClaims,
) -> Result<Vec<Arm>, SceneError> {
    let mut arms = Vec::new();
    for (i, a) in snaps.iter().enumerate() {
        let path = format!("arms[{i}] {:?}", a.name);
        check_name(&a.name, &path)?;
        names.claim(&a.name, &path)?;
        let base = pose_from_snapshot(&a.base, &format!("{path}.base"))?;
        let model = match &a.robot {
            None => ArmModel::panda(),
            Some(r) => {
                let given = a.model.as_ref().filter(|m| m.name() == r).cloned();
                match given.or_else(|| shipped(r)) {
                    Some(m) => m,
                    None => {
                        return Err(scene_err(
                            format!("{path}.robot"),
                            format!(
                                "robot `{r}` is not loaded: give its robot file (--robot \
                                 ROBOT.json)"
                            ),
                        ))
                    }
                }
            }
        };
        let joints = load_joints(&a.joints, &path, &model)?;
        let max = model.max_opening();
        if !(a.gripper_opening.is_finite()
            && (0.0..=max + LIMIT_SLACK).contains(&a.gripper_opening))
        {
            return Err(scene_err(
                format!("{path}.gripper_opening"),
                format!("must be in [0, {max}] m"),
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
            model,
        };
        if let Some(h) = &a.holding {
            attach_held(&mut arm, h, &path, bodies, &arms)?;
        }
        arms.push(arm);
    }
    Ok(arms)
}

/// An arm's joint angles, validated: one per moving joint of `model`, each within its limits.
fn load_joints(values: &[f64], path: &str, model: &ArmModel) -> Result<[f64; DOF], SceneError> {
    let n = model.dof();
    if values.len() != n {
        return Err(scene_err(
            format!("{path}.joints"),
            format!(
                "needs {n} joint angles for `{}`, got {}",
                model.name(),
                values.len()
            ),
        ));
    }
    let mut joints = [0.0; DOF];
    for (k, v) in values.iter().enumerate() {
        if !v.is_finite() || *v < model.lower[k] - LIMIT_SLACK || *v > model.upper[k] + LIMIT_SLACK
        {
            return Err(scene_err(
                format!("{path}.joints[{k}]"),
                format!(
                    "{v} rad is outside the joint limits [{}, {}]",
                    model.lower[k], model.upper[k]
                ),
            ));
        }
        joints[k] = *v;
    }
    Ok(joints)
}

/// Puts body `h` in `arm`'s gripper (grasp frozen at its current pose, gripper closed) if it is
/// a free block or hook, held by none of `others`, with the TCP inside it.
fn attach_held(
    arm: &mut Arm,
    h: &str,
    path: &str,
    bodies: &[Body],
    others: &[Arm],
) -> Result<(), SceneError> {
    let Some(bi) = bodies.iter().position(|b: &Body| b.name == h) else {
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
    if others
        .iter()
        .any(|o: &Arm| o.holding.is_some_and(|(j, _)| j == bi))
    {
        return Err(scene_err(
            format!("{path}.holding"),
            format!("{h:?} is already held by another arm"),
        ));
    }
    let tcp = arm.tcp();
    if !b.contains_point(&Point3::from(tcp.translation.vector), HELD_TCP_MARGIN) {
        return Err(scene_err(
            format!("{path}.holding"),
            format!("{h:?} is not between the fingers of {}", arm.name),
        ));
    }
    arm.holding = Some((bi, tcp.inverse() * b.pose));
    arm.gripper = GripperCommand::Close;
    arm.last_gripper = GripperCommand::Close;
    Ok(())
}

impl World {
    /// The world as a JSON-ready snapshot (with the derived drawing fields filled in).
    pub fn snapshot(&self) -> WorldSnapshot {
        WorldSnapshot {
            version: SNAPSHOT_VERSION,
            name: self.name.clone(),
            time: self.time,
            dt: self.dt,
            floor_z: self.floor_z,
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
            bodies: self.bodies.iter().map(body_snapshot).collect(),
            arms: self.arms.iter().map(|a| self.arm_snapshot(a)).collect(),
        }
    }

    /// The snapshot of an arm, with its drawing (TCP, link capsules, fingers).
    fn arm_snapshot(&self, a: &Arm) -> ArmSnapshot {
        let (links, fingers) = crate::sim::geometry::arm_drawing(a);
        ArmSnapshot {
            name: a.name.clone(),
            base: pose_to_snapshot(&a.base),
            robot: (!a.model.is_builtin()).then(|| a.model.name().to_string()),
            joints: a.joints[..a.model.dof()].to_vec(),
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
            model: (!a.model.is_builtin()).then(|| Arc::clone(&a.model)),
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
    /// names, positive sizes, non-zero quaternions, joints within limits, held
    /// bodies that exist and sit in the gripper, no interpenetrating bodies, no free body in the air.
    pub fn from_snapshot(s: &WorldSnapshot) -> Result<World, SceneError> {
        check_header(s)?;
        let mut names = NameClaims::default();
        let regions = load_regions(&s.regions, &mut names)?;
        let bodies = load_bodies(&s.bodies, &mut names)?;
        let arms = load_arms(&s.arms, &bodies, &mut names)?;
        let world = World {
            name: s.name.clone(),
            time: s.time,
            dt: s.dt,
            floor_z: s.floor_z,
            // A shipped benchmark's world reads its facts through that benchmark's declaration
            // until another is installed (`World::with_motions`).
            motions: crate::sim::Benchmark::parse(&s.name)
                .map(|b| b.motions())
                .unwrap_or_default(),
            regions,
            bodies,
            arms,
            params: WorldParams::default(),
        };
        match world.first_scene_error() {
            Some(e) => Err(e),
            None => Ok(world),
        }
    }

    /// Puts robot `model` in place of arm `arm`'s, on the same base, with the fingers at most as
    /// wide as before: at its ready posture, or, when the arm holds a body, at the joints its
    /// IK finds for the TCP pose that holds it there.
    ///
    /// # Errors
    /// An unknown arm, or a held body the robot cannot hold where it is.
    pub fn set_robot(&mut self, arm: usize, model: Arc<ArmModel>) -> Result<(), SceneError> {
        let params = self.params.planning_ik.clone();
        let held = self.arms.get(arm).and_then(|a| a.holding);
        let Some(a) = self.arms.get_mut(arm) else {
            return Err(scene_err(format!("arms[{arm}]"), "no such arm"));
        };
        let joints = match held {
            None => model.ready(),
            Some((bi, _)) => {
                let tcp = a.tcp();
                model
                    .inverse_kinematics(&a.base, &tcp, &model.ready(), &params)
                    .map_err(|u| {
                        scene_err(
                            format!("arms[{arm}] {:?}.holding", a.name),
                            format!(
                                "`{}` cannot hold {} where it is: {u}",
                                model.name(),
                                self.bodies[bi].name
                            ),
                        )
                    })?
                    .joints
            }
        };
        a.joints = joints;
        a.gripper_opening = a.gripper_opening.min(model.max_opening());
        a.target = None;
        a.joint_target = None;
        a.model = model;
        Ok(())
    }

    /// The first broken invariant of a freshly loaded world (lost bodies allowed) as a scene
    /// error naming the body's or arm's field.
    fn first_scene_error(&self) -> Option<SceneError> {
        for v in self.check_invariants_list() {
            let (name, field) = match &v {
                Violation::Interpenetration { a, .. } => (a.clone(), "pose"),
                Violation::Unsupported { body, .. } => (body.clone(), "pose"),
                Violation::Lost { .. } => continue,
                Violation::JointLimit { arm, .. } => (arm.clone(), "joints"),
            };
            let path = if let Some(i) = self.bodies.iter().position(|b| b.name == name) {
                format!("bodies[{i}] {name:?}.{field}")
            } else if let Some(i) = self.arms.iter().position(|a| a.name == name) {
                format!("arms[{i}] {name:?}.{field}")
            } else {
                name.clone()
            };
            return Some(scene_err(path, v.to_string()));
        }
        None
    }
}
