//! The motion policy the executor follows and the streams certify: one source for the choices
//! both make, so what the streams certify is what the arm does.
//!
//! ```text
//!   heights      approach h above a grasp or placement, lift l after a grasp, release r above
//!                the rest pose                                               (MotionParams)
//!   grasp        the top grasp whose hand keeps clear of every other body    (grasp_pose)
//!   release turn the quarter turn of a square block that puts the hand nearest a yaw
//!                                                                            (release_turns)
//!   transit      straight up to z = transit_z(tcp, goal, load, tops), across, down
//!                                                                            (transit_height)
//!   recovery     the planning IK's roomiest solution q*: straight there, else by way of READY,
//!                else the solution nearest q for the goal or a point on the way (joint_recovery)
//! ```
//!
//! Each decision is generic over what it asks of the scene: the executor asks the live
//! [`World`], the streams their predicted state of a skeleton rolled forward. The geometry both
//! rest on (`transit_z`, `clear_grasp_at`, `quarter_turns`, `rise_first`) is
//! `sim::geometry`'s.

use nalgebra::{Isometry3, Vector3};
use parry3d_f64::shape::Cuboid;

use crate::sim::geometry::{boxes_except, clear_grasp_at, quarter_turns, rise_first, transit_z};
use crate::sim::panda::DOF;
use crate::sim::World;

/// The heights of an action's motion, read by both the executor and the streams (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionParams {
    /// Height of the approach pose above grasps and placements, and of the retreat after a
    /// release (m).
    pub approach_height: f64,
    /// Height the held body is lifted to after a grasp (m).
    pub lift_height: f64,
    /// Height above its rest pose at which a released body is let go (m).
    pub release_clearance: f64,
}

impl Default for MotionParams {
    fn default() -> Self {
        MotionParams {
            approach_height: 0.10,
            lift_height: 0.12,
            release_clearance: 0.003,
        }
    }
}

/// Where a joint-space recovery that can take neither of its ways to the roomy solution goes
/// instead: the solution nearest the arm's joints for the first of these fractions of the way
/// from the TCP to the goal that a clear move reaches (the tracker takes it from there).
pub(crate) const NEAR_RECOVERY_FRACTIONS: [f64; 3] = [1.0, 0.5, 0.25];

/// What the policy's transit and grasp choices ask of a scene.
pub(crate) trait Scene {
    /// The TCP pose of arm `arm` (`None`: no such arm).
    fn tcp(&self, arm: usize) -> Option<Isometry3<f64>>;
    /// The world AABB of what arm `arm` carries: `Some(None)` for an empty hand, `None` when
    /// the load's extent is unknown.
    fn load_aabb(&self, arm: usize) -> Option<Option<(Vector3<f64>, Vector3<f64>)>>;
    /// The highest top (m) of the bodies but what arm `arm` carries whose horizontal bounds
    /// meet the rectangle `lo`..`hi` (x, y).
    fn highest_top_in(&self, arm: usize, lo: [f64; 2], hi: [f64; 2]) -> f64;
    /// The boxes (world frame) of every body but `body` and the held ones.
    fn boxes_except(&self, body: &str) -> Vec<(Isometry3<f64>, Cuboid)>;
}

impl Scene for World {
    fn tcp(&self, arm: usize) -> Option<Isometry3<f64>> {
        self.tcp_pose(arm)
    }

    fn load_aabb(&self, arm: usize) -> Option<Option<(Vector3<f64>, Vector3<f64>)>> {
        match self.held_by(arm) {
            Some(h) => Some(Some(self.body_aabb(h)?)),
            None => Some(None),
        }
    }

    fn highest_top_in(&self, arm: usize, lo: [f64; 2], hi: [f64; 2]) -> f64 {
        World::highest_top_in(self, lo, hi, self.held_by(arm).unwrap_or_default())
    }

    fn boxes_except(&self, body: &str) -> Vec<(Isometry3<f64>, Cuboid)> {
        boxes_except(self, &[body])
    }
}

/// The TCP height of a transit of arm `arm` from where `scene` has its TCP to `goal`
/// ([`transit_z`]): what the arm carries (or its empty hand) passes above every top between
/// the two. `None` for an unknown arm or load.
pub(crate) fn transit_height(scene: &impl Scene, arm: usize, goal: &Isometry3<f64>) -> Option<f64> {
    let a = scene.tcp(arm)?.translation.vector;
    let load = scene.load_aabb(arm)?;
    Some(transit_z(&a, &goal.translation.vector, load, |lo, hi| {
        scene.highest_top_in(arm, lo, hi)
    }))
}

/// The TCP pose with which arm `arm` grasps `body` resting at `pose` in `scene`: the top grasp
/// nearest the arm's heading whose hand keeps clear of the other bodies up to half the approach
/// height ([`clear_grasp_at`]). `world` gives the bodies' and arms' shapes.
pub(crate) fn grasp_pose(
    scene: &impl Scene,
    world: &World,
    arm: usize,
    body: &str,
    pose: &Isometry3<f64>,
    motion: &MotionParams,
) -> Option<Isometry3<f64>> {
    let boxes = scene.boxes_except(body);
    clear_grasp_at(world, arm, body, pose, &boxes, motion.approach_height)
}

/// `body_pose` of the body arm `arm` holds with grasp `grasp` (its pose in the TCP frame),
/// turned by the quarter turns of a square block, the hand's yaw nearest `toward` first
/// (`None`: the heading from the arm's base): the executor puts a body down with the first, the
/// streams certify the first few.
pub(crate) fn release_turns(
    world: &World,
    arm: usize,
    body: &str,
    body_pose: &Isometry3<f64>,
    grasp: &Isometry3<f64>,
    toward: Option<f64>,
) -> Vec<Isometry3<f64>> {
    quarter_turns(world, arm, body, body_pose, grasp, toward)
}

/// Where arm `arm`'s empty hand, left down among bodies, rises to before its next action
/// ([`rise_first`], by the approach height).
pub(crate) fn rise_before_action(
    world: &World,
    arm: usize,
    motion: &MotionParams,
) -> Option<Isometry3<f64>> {
    rise_first(world, arm, motion.approach_height)
}

/// What a joint-space recovery asks of one arm in a scene.
pub(crate) trait JointMoves {
    /// What a straight joint-space move hits.
    type Hit;
    /// The arm's joints now (`None`: no such arm).
    fn joints(&self) -> Option<[f64; DOF]>;
    /// The TCP's position now (`None`: no such arm).
    fn tcp_position(&self) -> Option<Vector3<f64>>;
    /// The planning IK's solution for `pose` with the most room to the joint limits, from the
    /// joints now.
    fn solve_with_room(&self, pose: &Isometry3<f64>) -> Option<[f64; DOF]>;
    /// The planning IK's solution for `pose` nearest the joints now.
    fn solve_near(&self, pose: &Isometry3<f64>) -> Option<[f64; DOF]>;
    /// The arm's ready posture (`None`: no such arm).
    fn ready(&self) -> Option<[f64; DOF]>;
    /// What the arm (with its load) hits on the straight joint-space move from `from` to `to`;
    /// `None` if nothing.
    fn joint_move_hits(&mut self, from: &[f64; DOF], to: &[f64; DOF]) -> Option<Self::Hit>;
}

/// Arm `arm` of the live world in a joint-space recovery; `touches`: the body the action
/// grasps, releases or pulls, which the hand may touch.
pub(crate) struct LiveArm<'a> {
    /// The world.
    pub(crate) world: &'a World,
    /// The arm.
    pub(crate) arm: usize,
    /// The body the moves may touch.
    pub(crate) touches: &'a str,
}

impl JointMoves for LiveArm<'_> {
    type Hit = String;

    fn joints(&self) -> Option<[f64; DOF]> {
        self.world.joints(self.arm)
    }

    fn ready(&self) -> Option<[f64; DOF]> {
        self.world.arm_model(self.arm).map(|m| m.ready())
    }

    fn tcp_position(&self) -> Option<Vector3<f64>> {
        self.world.tcp_pose(self.arm).map(|p| p.translation.vector)
    }

    fn solve_with_room(&self, pose: &Isometry3<f64>) -> Option<[f64; DOF]> {
        self.world
            .reachable_with_room(self.arm, pose)
            .ok()
            .map(|s| s.joints)
    }

    fn solve_near(&self, pose: &Isometry3<f64>) -> Option<[f64; DOF]> {
        self.world
            .reachable_near(self.arm, pose)
            .ok()
            .map(|s| s.joints)
    }

    fn joint_move_hits(&mut self, from: &[f64; DOF], to: &[f64; DOF]) -> Option<String> {
        self.world
            .joint_move_hits(self.arm, from, to, &[self.touches])
    }
}

/// How a joint-space recovery reaches its goal joints.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum RecoveryRoute<H> {
    /// Straight there in joint space.
    Straight,
    /// By way of the ready posture `ready`, then straight there.
    ByReady {
        /// The arm's ready posture.
        ready: [f64; DOF],
    },
    /// Straight to `joints`, the solution nearest the arm's for `pose` (the goal or a point on
    /// the way to it); the tracker follows the rest of the way. `hit`: what the straight move
    /// to the goal joints hits.
    Near {
        /// The joints to move to.
        joints: [f64; DOF],
        /// The TCP pose they reach.
        pose: Isometry3<f64>,
        /// What the straight move to the goal joints hits.
        hit: H,
    },
    /// No clear way: what the straight move to the goal joints hits.
    Blocked(H),
}

/// A joint-space recovery: the goal joints and the way there.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointRecovery<H> {
    /// The planning IK's solution with the most room to the joint limits.
    pub(crate) goal: [f64; DOF],
    /// How to get there.
    pub(crate) route: RecoveryRoute<H>,
}

/// The joint-space recovery of an arm to the TCP pose `pose`: the planning IK's solution with
/// the most room to the joint limits, straight there, or, when that move sweeps the arm or its
/// load through something and the way by the ready posture does not, by way of
/// the ready posture; failing both, straight to the solution nearest the arm's joints for the
/// goal or for a point on the way to it ([`NEAR_RECOVERY_FRACTIONS`]), if that move is clear.
/// `None` if the planning IK finds no solution.
pub(crate) fn joint_recovery<M: JointMoves>(
    arm: &mut M,
    pose: &Isometry3<f64>,
) -> Option<JointRecovery<M::Hit>> {
    let goal = arm.solve_with_room(pose)?;
    let route = recovery_route(arm, pose, &goal);
    Some(JointRecovery { goal, route })
}

/// The way of [`joint_recovery`] to `goal`, the joints for `pose`.
fn recovery_route<M: JointMoves>(
    arm: &mut M,
    pose: &Isometry3<f64>,
    goal: &[f64; DOF],
) -> RecoveryRoute<M::Hit> {
    let Some(now) = arm.joints() else {
        return RecoveryRoute::Straight;
    };
    let Some(hit) = arm.joint_move_hits(&now, goal) else {
        return RecoveryRoute::Straight;
    };
    if let Some(ready) = arm.ready() {
        if arm.joint_move_hits(&now, &ready).is_none()
            && arm.joint_move_hits(&ready, goal).is_none()
        {
            return RecoveryRoute::ByReady { ready };
        }
    }
    let Some(tcp) = arm.tcp_position() else {
        return RecoveryRoute::Blocked(hit);
    };
    for s in NEAR_RECOVERY_FRACTIONS {
        let mut part = *pose;
        part.translation.vector = tcp.lerp(&pose.translation.vector, s);
        let Some(near) = arm.solve_near(&part) else {
            continue;
        };
        if arm.joint_move_hits(&now, &near).is_some() {
            continue;
        }
        return RecoveryRoute::Near {
            joints: near,
            pose: part,
            hit,
        };
    }
    RecoveryRoute::Blocked(hit)
}
