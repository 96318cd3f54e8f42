//! The fixed step: arm commands, then per step and arm the gripper (grasp, release), the joints
//! following their target within the velocity limits, the stops at furniture and at contacts,
//! and the held body carried along.

use super::state::DEPTH_EPSILON;
use super::{Body, GripperCommand, SimError, World, LINK_TOLERANCE};
use crate::sim::collide;
use crate::sim::fast_math::norm3;
use crate::sim::panda::DOF;
use crate::sim::BodyKind;
use nalgebra::{Isometry3, Point3};
use serde::{Deserialize, Serialize};
use std::fmt;

/// Something that happened during a step or a user move (for logs and the page).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
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

/// An arm is at its joint target when every joint is within this of it (rad).
const JOINT_TARGET_REACHED: f64 = 1e-9;

/// An arm is at its TCP target when its TCP is within this of it (m) and turned from it by
/// less than [`TCP_TARGET_TURNED`].
const TCP_TARGET_REACHED: f64 = 1e-5;

/// The turn (rad) below which a TCP at [`TCP_TARGET_REACHED`] is at its target.
const TCP_TARGET_TURNED: f64 = 1e-4;

/// Only the parts of a held body whose centres lie within this of the TCP (m) are between the
/// fingers (the hook's handle, not its blade).
const FINGER_REACH: f64 = 0.05;

impl World {
    /// Sets the joint angles of an arm directly (clamped to the limits); a held body follows.
    pub fn set_joints(&mut self, arm: usize, joints: [f64; DOF]) -> Result<(), SimError> {
        let a = self.arms.get_mut(arm).ok_or(SimError::NoSuchArm(arm))?;
        a.joints = joints;
        a.model.clamp(&mut a.joints);
        a.target = None;
        self.carry_held(arm);
        Ok(())
    }

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
                let fits = grasp.filter(|(bi, g)| self.finger_width(ai, *bi, g) < opening);
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
                    .map(|(bi, g)| self.finger_width(ai, bi, &g))
                    .unwrap_or(0.0);
                let a = &mut self.arms[ai];
                a.gripper_opening =
                    (a.gripper_opening - self.params.finger_speed * self.dt).max(width);
            }
            (GripperCommand::Close, Some((bi, g))) => {
                let width = self.finger_width(ai, bi, &g);
                let a = &mut self.arms[ai];
                a.gripper_opening =
                    (a.gripper_opening - self.params.finger_speed * self.dt).max(width);
            }
            (GripperCommand::Open, Some((bi, _))) => {
                self.arms[ai].holding = None;
                self.release(ai, bi, events);
                let a = &mut self.arms[ai];
                a.gripper_opening = (a.gripper_opening + self.params.finger_speed * self.dt)
                    .min(a.model.max_opening());
            }
            (GripperCommand::Open, None) => {
                let a = &mut self.arms[ai];
                a.gripper_opening = (a.gripper_opening + self.params.finger_speed * self.dt)
                    .min(a.model.max_opening());
            }
            (GripperCommand::Close, None) => {}
        }
    }

    /// Width of a held body across arm `ai`'s fingers (along the TCP `y` axis), at most their
    /// opening.
    fn finger_width(&self, ai: usize, bi: usize, grasp: &Isometry3<f64>) -> f64 {
        let b = &self.bodies[bi];
        let mut w: f64 = 0.0;
        for (p, c) in &b.parts {
            let iso = grasp * p;
            if iso.translation.vector.norm() > FINGER_REACH {
                continue;
            }
            let m = iso.rotation.to_rotation_matrix().matrix().abs();
            w = w.max(2.0 * (m * c.half_extents).y);
        }
        w.min(self.arms[ai].model.max_opening())
    }

    fn step_arm(&mut self, ai: usize, events: &mut Vec<WorldEvent>) {
        let Some(desired) = self.desired_joints(ai) else {
            return;
        };
        // Contact stop: what the held body overlaps now (it may only get shallower).
        let held = self.arms[ai].holding.map(|(bi, _)| bi);
        let depth_before = held.map_or(0.0, |bi| self.held_penetration(bi).0);
        let saved = held.map(|_| (self.arms[ai].joints, self.bodies.clone(), events.len()));
        let before = self.arms[ai].joints;
        self.move_joints_towards(ai, &desired);
        // The links stop at a table or shelf they would press into (deeper than
        // LINK_TOLERANCE and deeper than before): the arm cannot reach through furniture.
        let after = self.arms[ai].joints;
        let (depth, with) = self.link_penetration(ai, &after);
        if depth > LINK_TOLERANCE && depth > self.link_penetration(ai, &before).0 + DEPTH_EPSILON {
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
            if let Some(with) =
                self.carried_stop(bi, depth_before, &mut bodies, &events[n_events..])
            {
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

    /// The joints arm `ai` heads for this step: its joint target, or the IK solution (or best
    /// attempt) for its TCP target; `None` when it has no target or is already there.
    fn desired_joints(&self, ai: usize) -> Option<[f64; DOF]> {
        let a = &self.arms[ai];
        if let Some(q) = a.joint_target {
            if (0..DOF).all(|k| (q[k] - a.joints[k]).abs() < JOINT_TARGET_REACHED) {
                return None;
            }
            Some(q)
        } else {
            let target = a.target?;
            let current = a.tcp();
            let pos_err = norm3(&(target.translation.vector - current.translation.vector));
            let rot_err = (target.rotation * current.rotation.inverse()).angle();
            if pos_err < TCP_TARGET_REACHED && rot_err < TCP_TARGET_TURNED {
                return None;
            }
            Some(
                match a.model.inverse_kinematics(
                    &a.base,
                    &target,
                    &a.joints,
                    &self.params.tracking_ik,
                ) {
                    Ok(s) => s.joints,
                    Err(u) => u.best_joints,
                },
            )
        }
    }

    /// Moves arm `ai`'s joints one step towards `desired` within the joint velocity limits and
    /// the joint ranges.
    fn move_joints_towards(&mut self, ai: usize, desired: &[f64; DOF]) {
        let dt = self.dt;
        let a = &mut self.arms[ai];
        // Within the joint velocity limits, the whole step scaled down alike: the hand lags
        // along its path instead of leaving it (clamping each joint alone turns the step: the
        // shoulder pitching on while the saturated elbow lags drops a stretched-out hand).
        let scale = (0..DOF)
            .map(|k| {
                let d = (desired[k] - a.joints[k]).abs();
                let max = a.model.velocity[k] * dt;
                if d > max {
                    max / d
                } else {
                    1.0
                }
            })
            .fold(1.0, f64::min);
        for k in 0..DOF {
            let d = scale * (desired[k] - a.joints[k]);
            a.joints[k] = (a.joints[k] + d).clamp(a.model.lower[k], a.model.upper[k]);
        }
    }

    /// Whether the step just taken must be undone because the carried body `bi` now presses
    /// into another body (deeper than [`super::WorldParams::carried_stop_depth`] and than
    /// `depth_before`), or a block the carried hook pushed in `new_events` is driven into
    /// another body or off its support: `Some(the body touched)`, else `None`. `before` holds
    /// the bodies as they were before the step.
    fn carried_stop(
        &mut self,
        bi: usize,
        depth_before: f64,
        before: &mut Vec<Body>,
        new_events: &[WorldEvent],
    ) -> Option<Option<usize>> {
        let limit = self.params.carried_stop_depth();
        let (depth, with) = self.held_penetration(bi);
        if depth > limit.max(depth_before + DEPTH_EPSILON) {
            return Some(with);
        }
        // A block the carried hook pushed may not be driven into another body, nor off its
        // support.
        for e in new_events {
            let (pushed, lost) = match e {
                WorldEvent::Pushed { body, .. } => (self.body_index(body), None),
                WorldEvent::Lost { body, .. } => (None, self.body_index(body)),
                _ => (None, None),
            };
            if let Some(j) = lost {
                return Some(Some(j));
            }
            if let Some(pi) = pushed {
                let (d, w) = self.held_penetration(pi);
                if d > limit {
                    // Its depth before this step (the saved bodies, swapped in).
                    std::mem::swap(&mut self.bodies, before);
                    let was = self.held_penetration(pi).0;
                    std::mem::swap(&mut self.bodies, before);
                    if d > was + DEPTH_EPSILON {
                        return Some(w.or(Some(pi)));
                    }
                }
            }
        }
        None
    }

    /// Deepest overlap of arm `ai`'s solids at joints `q` (the base's excepted) with a table or
    /// shelf, and which one.
    pub(super) fn link_penetration(&self, ai: usize, q: &[f64; DOF]) -> (f64, Option<usize>) {
        let mut best = (0.0, None);
        let (parts, base) = self.arm_parts(ai, q);
        for part in parts.iter().skip(base) {
            for (j, body) in self.bodies.iter().enumerate() {
                if body.lost || !matches!(body.kind, BodyKind::Table | BodyKind::Shelf) {
                    continue;
                }
                let (blo, bhi) = body.aabb();
                if !part.near(&blo, &bhi) {
                    continue;
                }
                for (iso, c) in body.world_parts() {
                    if let Some(k) = collide::contact(&part.iso, &part.shape, &iso, c, 0.0) {
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

    /// Moves the body held by `ai` rigidly with its TCP.
    fn carry_held(&mut self, ai: usize) {
        if let Some((bi, g)) = self.arms[ai].holding {
            self.bodies[bi].pose = self.arms[ai].tcp() * g;
        }
    }
}
