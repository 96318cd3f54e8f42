//! Executing one grounded action in the simulator through its motion skill (Algorithm 1 line 14,
//! τ = LQT-CP(a)).
//!
//! What an action does physically comes from [`crate::tamp::action::classify`] (its effects,
//! not its name).
//!
//! The motion is a chain of segments, each a skill trajectory τ from the current end-effector
//! state to a via-point expressed in the frame of the object acted on (pre-grasp above it, the
//! grasp, the lift). Object-centric re-anchoring: while a segment runs, if its anchor object moves
//! by more than `reanchor_tolerance` (a motion-level disturbance, L1), the rest of the segment is
//! re-planned from the current state to the new pose; the skill's feedback absorbs the rest.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use crate::sim::geometry::{
    boxes_except, clear_grasp_at, quarter_turn_for_arm, raised, rest_pose, rest_pose_on,
    rise_first, tcp_for_body_pose, transit_z,
};
use crate::sim::snapshot::BodyKind;
use crate::sim::{GripperCommand, World, WorldEvent};
use crate::tamp::action::{ActionKind, Placement};
use crate::tamp::motion::NEAR_RECOVERY_FRACTIONS;

use super::skill::{SkillLibrary, SkillSegment};

/// Tunables of action execution (metres, seconds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExecParams {
    /// Height of the approach / retreat via-points above a grasp or placement (m).
    pub approach_height: f64,
    /// Height the held block is lifted to after a grasp (m).
    pub lift_height: f64,
    /// Mean Cartesian speed of the end effector along a segment (m/s).
    pub speed: f64,
    /// Shortest duration of a segment (s).
    pub min_segment: f64,
    /// The end effector is "there" when within this distance of the segment's goal (m).
    pub reach_tolerance: f64,
    /// How long the arm may lag behind a segment's end before the action fails (s).
    pub settle_timeout: f64,
    /// Time given to the fingers to open or close (s).
    pub gripper_time: f64,
    /// An anchor object moving more than this re-plans the segment (m).
    pub reanchor_tolerance: f64,
    /// Clearance left under a released block (m).
    pub release_clearance: f64,
    /// A segment whose end lags by more than `recovery_distance` (m) for `recovery_after` (s)
    /// recovers in joint space (planning IK) once. Equal to `reach_tolerance`: a tracker stuck a
    /// few mm short (a wrist at its limit) recovers too (1 cm left such arms stuck).
    pub recovery_distance: f64,
    /// See `recovery_distance` (s).
    pub recovery_after: f64,
    /// At a grasp the hand is "there" when also turned within this angle of the grasp's (rad);
    /// a larger error after `recovery_after` also recovers in joint space.
    pub orientation_tolerance: f64,
}

impl ExecParams {
    /// How long a joint-space recovery may move before Cartesian tracking takes over again (s):
    /// twice `settle_timeout`.
    pub fn joint_recovery_timeout(&self) -> f64 {
        2.0 * self.settle_timeout
    }

    /// Mean speed of a pull's stroke and of the lift after it (m/s): half `speed`.
    pub fn stroke_speed(&self) -> f64 {
        0.5 * self.speed
    }
}

impl Default for ExecParams {
    fn default() -> Self {
        ExecParams {
            approach_height: 0.10,
            lift_height: 0.12,
            speed: 0.35,
            min_segment: 0.3,
            reach_tolerance: 0.004,
            settle_timeout: 1.5,
            gripper_time: 0.15,
            reanchor_tolerance: 0.005,
            release_clearance: 0.003,
            recovery_distance: 0.004,
            recovery_after: 0.25,
            orientation_tolerance: 0.1,
        }
    }
}

/// One step of an action's motion.
#[derive(Clone, Debug, PartialEq)]
enum Phase {
    /// Move the TCP to a via-point defined relative to the anchor.
    Move(Via),
    /// Open or close the gripper and wait.
    Gripper(GripperCommand),
}

/// A via-point: where the TCP goes, computed from the world when the segment starts (and again
/// when its anchor moves).
#[derive(Clone, Debug, PartialEq)]
enum Via {
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
    /// Transit: straight up (or down) to TCP height `z`.
    Rise { z: f64 },
    /// Where the TCP is, with the joints that leave the most room to their limits: a joint-space
    /// move that unwinds an arm left with a joint at its limit ([`unwound`]; none if that move
    /// would sweep the arm through something).
    Unwind,
    /// Transit: above the goal of `inner`, at TCP height `z`.
    Over { inner: Box<Via>, z: f64 },
}

impl Via {
    /// A learned skill's approach to a grasp or a release (its shape is the demonstration's, not
    /// the straight line the streams certify).
    fn is_learned_approach(&self) -> bool {
        matches!(
            self,
            Via::Grasp { skill: true, .. } | Via::Place { skill: true, .. }
        )
    }
}

/// The running execution of one action.
#[derive(Clone, Debug)]
pub struct ActionExec {
    /// The action `(stack a b)`.
    pub action: String,
    /// What it does.
    pub kind: ActionKind,
    arm: usize,
    phases: Vec<Phase>,
    phase: usize,
    /// The segment being followed: planned TCP positions, one per tick, and its goal.
    segment: Option<Running>,
    /// Ticks spent waiting in the current phase.
    wait: usize,
    gripper: GripperCommand,
    /// Events seen during the action.
    pub events: Vec<WorldEvent>,
    /// The anchor frame at the gripper event (frame of the retreat skill).
    event_frame: Option<Isometry3<f64>>,
    /// Phase before which a transit (rise, move over, descend) was inserted.
    transit_at: Option<usize>,
    /// The body acted on is the hook (its skills are the `hook-…` ones).
    hook: bool,
    /// The approach height (m): the grasp is chosen with the hand clear up to half of it.
    approach_height: f64,
    /// The yaw of the TCP's x axis a release was certified with (`None`: the heading from the
    /// base).
    hand_yaw: Option<f64>,
    /// Why the action failed, once its remaining phases only undo it (a lift stopped at the
    /// start: the body is let go where it was grasped).
    abort: Option<String>,
    /// The TCP's height when the gripper closed on the body it grasps.
    grasped_z: Option<f64>,
}

#[derive(Clone, Debug)]
struct Running {
    traj: SkillSegment,
    t: usize,
    goal: Isometry3<f64>,
    /// Body watched for re-anchoring, where it was, and the skill frame planned for.
    anchor: Option<(String, Vector3<f64>)>,
    frame: Option<Isometry3<f64>>,
    lag: usize,
    /// Joint-space recovery: the joint goals still to reach, the first followed instead of the
    /// Cartesian command while there is one (the planning IK's joints for `goal`, perhaps by
    /// way of the ready posture first); `recovered` once tried for this segment.
    joint_goals: Vec<[f64; crate::sim::panda::DOF]>,
    recovered: bool,
    /// Ticks spent in joint-space recovery.
    joint_ticks: usize,
    /// A rise the arm could not make where it was, made by going to the ready posture instead
    /// (the segment ends there).
    rise_by_ready: bool,
}

/// Centre + yaw of a pose (the demo's anchor-frame convention).
fn anchor_frame(p: &Isometry3<f64>) -> Isometry3<f64> {
    let (_, _, yaw) = p.rotation.euler_angles();
    Isometry3::from_parts(
        p.translation,
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
    )
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

impl ActionExec {
    /// Prepares the execution of `kind` (placements must be bound).
    pub fn new(
        action: &str,
        kind: ActionKind,
        world: &World,
        skills: &SkillLibrary,
        p: &ExecParams,
    ) -> Self {
        let hook = match &kind {
            ActionKind::Grasp { body, .. } | ActionKind::Release { body, .. } => {
                world.body_kind(body) == Some(BodyKind::Hook)
            }
            ActionKind::Pull { .. } => true,
        };
        let pre = if hook { "hook-" } else { "" };
        let (arm, mut phases) = match &kind {
            ActionKind::Grasp { arm, body } if skills.has(&format!("{pre}grasp-approach")) => (
                *arm,
                vec![
                    Phase::Gripper(GripperCommand::Open),
                    Phase::Move(Via::Grasp {
                        body: body.clone(),
                        dz: 0.0,
                        skill: true,
                    }),
                    Phase::Gripper(GripperCommand::Close),
                    Phase::Move(Via::Up {
                        dz: p.lift_height,
                        skill: skills.has(&format!("{pre}grasp-retreat")),
                    }),
                ],
            ),
            ActionKind::Release { arm, placement, .. }
                if skills.has("place-approach") && skills.has("place-retreat") =>
            {
                let placement = placement.clone().unwrap_or(Placement::At {
                    x: 0.0,
                    y: 0.0,
                    yaw: 0.0,
                });
                (
                    *arm,
                    vec![
                        Phase::Move(Via::Place {
                            placement,
                            dz: p.release_clearance,
                            skill: true,
                        }),
                        Phase::Gripper(GripperCommand::Open),
                        Phase::Move(Via::Up {
                            dz: p.approach_height,
                            skill: skills.has(&format!("{pre}place-retreat")),
                        }),
                    ],
                )
            }
            ActionKind::Grasp { arm, body } => (
                *arm,
                vec![
                    Phase::Gripper(GripperCommand::Open),
                    Phase::Move(Via::Grasp {
                        body: body.clone(),
                        dz: p.approach_height,
                        skill: false,
                    }),
                    Phase::Move(Via::Grasp {
                        body: body.clone(),
                        dz: 0.0,
                        skill: false,
                    }),
                    Phase::Gripper(GripperCommand::Close),
                    Phase::Move(Via::Up {
                        dz: p.lift_height,
                        skill: false,
                    }),
                ],
            ),
            ActionKind::Release { arm, placement, .. } => {
                let placement = placement.clone().unwrap_or(Placement::At {
                    x: 0.0,
                    y: 0.0,
                    yaw: 0.0,
                });
                (
                    *arm,
                    vec![
                        Phase::Move(Via::Place {
                            placement: placement.clone(),
                            dz: p.approach_height,
                            skill: false,
                        }),
                        Phase::Move(Via::Place {
                            placement,
                            dz: p.release_clearance,
                            skill: false,
                        }),
                        Phase::Gripper(GripperCommand::Open),
                        Phase::Move(Via::Up {
                            dz: p.approach_height,
                            skill: false,
                        }),
                    ],
                )
            }
            ActionKind::Pull {
                arm, body, turn, ..
            } => (
                *arm,
                (0..4)
                    .map(|stage| {
                        Phase::Move(Via::Pull {
                            body: body.clone(),
                            stage,
                            turn: *turn,
                        })
                    })
                    .collect(),
            ),
        };
        // An empty hand left down among bodies (the last action was interrupted at its
        // gripper event) first rises straight up, clear of them.
        if let Some(up) = rise_first(world, arm, p.approach_height) {
            phases.insert(
                0,
                Phase::Move(Via::Rise {
                    z: up.translation.z,
                }),
            );
        }
        // An arm the last action left with a joint at its limit (a recovery that failed, a
        // tracker wound up against a shelf) unwinds first, up there: from such a posture the
        // tracker comes down the same way and fails the same way again.
        if world
            .joints(arm)
            .is_some_and(|q| crate::sim::panda::limit_margin(&q) < UNWIND_MARGIN)
        {
            let at = usize::from(matches!(
                phases.first(),
                Some(Phase::Move(Via::Rise { .. }))
            ));
            phases.insert(at, Phase::Move(Via::Unwind));
        }
        let gripper = world
            .arm_command(arm)
            .map(|c| c.1)
            .unwrap_or(GripperCommand::Open);
        ActionExec {
            action: action.to_string(),
            kind,
            arm,
            phases,
            phase: 0,
            segment: None,
            wait: 0,
            gripper,
            events: vec![],
            event_frame: None,
            transit_at: None,
            hook,
            approach_height: p.approach_height,
            hand_yaw: None,
            abort: None,
            grasped_z: None,
        }
    }

    /// Puts a released square block down with the hand at yaw `yaw` (of the TCP's x axis, as the
    /// streams certified it; [`quarter_turn_for_arm`]) rather than the yaw nearest the heading
    /// from the base. `None` keeps the heading.
    pub fn with_hand_yaw(mut self, yaw: Option<f64>) -> Self {
        self.hand_yaw = yaw;
        self
    }

    /// Makes the action's first approach a transit at TCP height `z` (a stream found the
    /// straight approach blocked and certified this one instead, see `tamp::streams`): straight
    /// up to `z`, across above the approach's goal, straight down to it.
    pub fn with_transit(mut self, z: f64) -> Self {
        let first = self.phases.iter().position(
            |ph| matches!(ph, Phase::Move(v) if !matches!(v, Via::Rise { .. } | Via::Unwind)),
        );
        if let Some(i) = first {
            if let Phase::Move(via) = self.phases[i].clone() {
                self.insert_transit(i, &via, z);
            }
        }
        self
    }

    /// The arm executing the action.
    pub fn arm(&self) -> usize {
        self.arm
    }

    /// The current commanded target of the TCP, if moving.
    pub fn target(&self) -> Option<Vector3<f64>> {
        self.segment.as_ref().map(|s| s.traj.current(s.t))
    }

    /// Index of the phase being executed and the number of phases.
    pub fn progress(&self) -> (usize, usize) {
        (self.phase, self.phases.len())
    }

    /// Commands the arm for this tick, steps the world once, and reports.
    pub fn tick(&mut self, world: &mut World, skills: &SkillLibrary, p: &ExecParams) -> ExecStatus {
        let dt = world.dt();
        let Some(phase) = self.phases.get(self.phase).cloned() else {
            return ExecStatus::Done;
        };
        match phase {
            Phase::Gripper(cmd) => {
                let Some(tcp) = world.tcp_pose(self.arm) else {
                    return ExecStatus::Failed("no such arm".into());
                };
                if self.wait == 0 && cmd == GripperCommand::Open {
                    // Never let go of a load that would fall or end inside another body.
                    if let (ActionKind::Release { body, .. }, Err(why)) =
                        (&self.kind, world.release_check(self.arm))
                    {
                        return ExecStatus::Failed(format!("cannot release {body} here: {why}"));
                    }
                }
                if self.wait == 0 {
                    // The retreat's frame: the grasped body where it was grasped; for a release
                    // the body's resting pose (recorded once it has settled, below).
                    self.event_frame = world
                        .held_by(self.arm)
                        .and_then(|h| world.body_pose(h))
                        .map(|p| anchor_frame(&p));
                }
                self.gripper = cmd;
                let _ = world.command_arm(self.arm, tcp, cmd);
                let ev = world.step();
                self.events.extend(ev.iter().cloned());
                self.wait += 1;
                if ev
                    .iter()
                    .any(|e| matches!(e, WorldEvent::GraspedNothing { .. }))
                {
                    if let ActionKind::Grasp { body, .. } = &self.kind {
                        let above = world.resting_on(body);
                        if !above.is_empty() {
                            return ExecStatus::Failed(format!(
                                "cannot lift {body}: {} stands on it",
                                above.join(", ")
                            ));
                        }
                    }
                    return ExecStatus::Failed("the gripper closed on nothing".into());
                }
                if let Some(WorldEvent::Lost { body, reason }) =
                    ev.iter().find(|e| matches!(e, WorldEvent::Lost { .. }))
                {
                    return ExecStatus::Failed(format!("{body} fell: {reason}"));
                }
                if (self.wait as f64) * dt >= p.gripper_time {
                    if let Some(s) = self.check_gripper(world, cmd) {
                        return ExecStatus::Failed(s);
                    }
                    match &self.kind {
                        ActionKind::Release { body, .. } => {
                            self.event_frame = world.body_pose(body).map(|p| anchor_frame(&p));
                        }
                        ActionKind::Grasp { body, .. } if cmd == GripperCommand::Close => {
                            self.grasped_z = world
                                .held_by(self.arm)
                                .filter(|h| h == body)
                                .and(world.tcp_pose(self.arm))
                                .map(|p| p.translation.z);
                        }
                        _ => {}
                    }
                    self.next_phase();
                }
                self.status()
            }
            Phase::Move(via) => {
                // Plan the segment when it starts; when its anchor object moved, re-target the
                // skill's controller to the new object frame (or re-plan a profile).
                let moved = match &self.segment {
                    None => true,
                    Some(r) => r.anchor.as_ref().is_some_and(|(name, at)| {
                        world.body_pose(name).is_some_and(|q| {
                            (q.translation.vector - at).norm() > p.reanchor_tolerance
                        })
                    }),
                };
                if moved {
                    let start = world.tcp_pose(self.arm).unwrap_or_else(Isometry3::identity);
                    let fresh = self.via_pose(world, &via, &start);
                    let retargeted = match self.segment.as_mut() {
                        Some(r) => match (fresh, r.frame) {
                            (Ok((goal, Some(new_frame), anchor)), Some(old)) => {
                                let ok = r.traj.retarget(&old, &new_frame);
                                if ok {
                                    r.goal = goal;
                                    r.frame = Some(new_frame);
                                    r.anchor = anchor;
                                    r.lag = 0;
                                }
                                ok
                            }
                            _ => false,
                        },
                        None => false,
                    };
                    if !retargeted {
                        match self.plan_segment(world, &via, skills, p) {
                            Ok(r) => {
                                // A carried body whose path would sweep through another goes
                                // up, over at a safe height, and down instead.
                                if let Some(z) = self.transit_height(world, &via, &r) {
                                    self.insert_transit(self.phase, &via, z);
                                    return ExecStatus::Running;
                                }
                                self.segment = Some(r);
                            }
                            Err(e) => return ExecStatus::Failed(e),
                        }
                    }
                }
                // The grasp needs the hand turned as planned: the fingers must fit around the
                // block (a release lands wherever the block is, turned or not). So does every
                // via-point of a pull: a hook turned otherwise lowers its long arm elsewhere.
                let turn_matters = match self.phases.get(self.phase) {
                    Some(Phase::Move(Via::Grasp { dz, .. })) => *dz <= 0.0,
                    Some(Phase::Move(Via::Pull { .. })) => true,
                    _ => false,
                };
                let Some(seg) = self.segment.as_mut() else {
                    return ExecStatus::Failed("no segment".into());
                };
                let i = seg.t.min(seg.traj.len() - 1);
                let measured = world
                    .tcp_pose(self.arm)
                    .map(|q| q.translation.vector)
                    .unwrap_or_default();
                let cmd_pos = seg.traj.command(seg.t, &measured);
                let s = (i as f64 / (seg.traj.len().max(2) - 1) as f64).clamp(0.0, 1.0);
                let rot = seg.traj.start_rotation().slerp(&seg.goal.rotation, s);
                let target = Isometry3::from_parts(Translation3::from(cmd_pos), rot);
                match seg.joint_goals.first() {
                    Some(&q) => {
                        let _ = world.command_joints(self.arm, q, self.gripper);
                    }
                    None => {
                        let _ = world.command_arm(self.arm, target, self.gripper);
                    }
                }
                let ev = world.step();
                self.events.extend(ev.iter().cloned());
                if let Some(WorldEvent::Lost { body, reason }) =
                    ev.iter().find(|e| matches!(e, WorldEvent::Lost { .. }))
                {
                    return ExecStatus::Failed(format!("{body} fell: {reason}"));
                }
                // A lift stopped before the body has left its place (something overhangs it):
                // put it back down where it was, let go and rise, then report the failure, so
                // the replan starts from a free hand and the body where it was.
                let stuck = match self.abort {
                    None => stuck_lift(world, self.arm, &self.kind, &via, self.grasped_z),
                    Some(_) => None,
                };
                if let (Some(why), Some(z)) = (stuck, self.grasped_z) {
                    self.phases.truncate(self.phase + 1);
                    self.phases.extend([
                        Phase::Move(Via::Rise { z }),
                        Phase::Gripper(GripperCommand::Open),
                        Phase::Move(Via::Up {
                            dz: self.approach_height,
                            skill: false,
                        }),
                    ]);
                    self.abort = Some(why);
                    self.next_phase();
                    return ExecStatus::Running;
                }
                // The carried body met another on the way (tracking lag or a moved obstacle),
                // or the hand's learned approach swung a link into a table or shelf: go up,
                // over at a safe height, and down instead, once per action.
                if world.arm_blocked_by(self.arm).is_some()
                    && (world.held_by(self.arm).is_some() || via.is_learned_approach())
                    && self.transit_at.is_none()
                    && !no_transit(&via)
                {
                    let goal = seg.goal;
                    if let Some(z) = safe_transit_z(world, self.arm, &goal) {
                        self.insert_transit(self.phase, &via, z);
                        return ExecStatus::Running;
                    }
                }
                seg.t += 1;
                if seg.t >= seg.traj.len() {
                    let tcp = world.tcp_pose(self.arm).unwrap_or(seg.goal);
                    let err = (tcp.translation.vector - seg.traj.goal()).norm();
                    // At a grasp the hand's turn matters too: a wrist stuck at its limit leaves
                    // the fingers across a block's diagonal, where they do not fit around it.
                    let turn_err = (seg.goal.rotation * tcp.rotation.inverse()).angle();
                    let turned = !turn_matters || turn_err <= p.orientation_tolerance;
                    if err <= p.reach_tolerance && turned {
                        self.next_phase();
                    } else if let Some(&q) = seg.joint_goals.first() {
                        // Joint-space recovery: back to Cartesian tracking once there (or after
                        // `settle_timeout` more), to settle on the goal.
                        seg.joint_ticks += 1;
                        let there = world.joints(self.arm).is_none_or(|j| {
                            j.iter()
                                .zip(&q)
                                .all(|(a, b)| (a - b).abs() < JOINT_GOAL_TOLERANCE)
                        });
                        let stopped = world.arm_blocked_by(self.arm).is_some();
                        if there && seg.rise_by_ready {
                            self.next_phase();
                            return ExecStatus::Running;
                        }
                        if there && seg.joint_goals.len() > 1 {
                            seg.joint_goals.remove(0);
                            seg.joint_ticks = 0;
                        } else if there
                            || stopped
                            || seg.joint_ticks as f64 * dt > p.joint_recovery_timeout()
                        {
                            seg.joint_goals.clear();
                            seg.lag = 0;
                        }
                    } else {
                        seg.lag += 1;
                        // Cartesian tracking stuck far from a goal the planning IK reaches (a
                        // local minimum of the tracking IK after a large reconfiguration, or a
                        // joint at its limit): move in joint space to the planning IK's
                        // solution with the most room to the limits, once per segment.
                        if !seg.recovered
                            && (err > p.recovery_distance || !turned)
                            && seg.lag as f64 * dt > p.recovery_after
                            && world.arm_blocked_by(self.arm).is_none()
                        {
                            seg.recovered = true;
                            // Where the segment is judged: the end of its trajectory (a learned
                            // skill's own, in its object frame), turned as the via-point.
                            let target = Isometry3::from_parts(
                                Translation3::from(seg.traj.goal()),
                                seg.goal.rotation,
                            );
                            let body = self.kind.body();
                            match world.reachable_with_room(self.arm, &target) {
                                Ok(sol) => {
                                    seg.joint_goals = joint_recovery_route(
                                        world, self.arm, &target, sol.joints, body,
                                    );
                                    seg.joint_ticks = 0;
                                    seg.lag = 0;
                                }
                                Err(_) if matches!(via, Via::Rise { .. } | Via::Up { .. }) => {
                                    if let Some(q) = rise_by_ready(world, self.arm, &target, body) {
                                        seg.joint_goals = vec![q];
                                        seg.rise_by_ready = true;
                                        seg.joint_ticks = 0;
                                        seg.lag = 0;
                                    }
                                }
                                Err(_) => {}
                            }
                        }
                        if seg.lag as f64 * dt > p.settle_timeout {
                            // A release point the arm stops just above (an elbow at its limit
                            // over a tall stack near the base): let go there if the body comes
                            // to rest on its support from that height.
                            let above = tcp.translation.vector - seg.goal.translation.vector;
                            let drop_ok = matches!(via, Via::Place { .. })
                                && matches!(
                                    self.phases.get(self.phase + 1),
                                    Some(Phase::Gripper(_))
                                )
                                && above.z >= 0.0
                                && above.norm() <= RELEASE_SLACK
                                && libm::hypot(above.x, above.y) <= p.reach_tolerance
                                && world.release_check(self.arm).is_ok();
                            if drop_ok {
                                self.next_phase();
                                return ExecStatus::Running;
                            }
                            return ExecStatus::Failed(match world.arm_blocked_by(self.arm) {
                                Some(b) => format!(
                                    "the {} is stopped by {b} ({:.1} mm from the via-point)",
                                    if world.held_by(self.arm).is_some() {
                                        "held body"
                                    } else {
                                        "arm"
                                    },
                                    err * 1e3
                                ),
                                None if !turned && err <= p.reach_tolerance => format!(
                                    "the arm cannot turn its hand to the via-point ({:.0}° off)",
                                    turn_err.to_degrees()
                                ),
                                None => format!(
                                    "the arm cannot reach its via-point ({:.1} mm away)",
                                    err * 1e3
                                ),
                            });
                        }
                    }
                }
                self.status()
            }
        }
    }

    fn status(&self) -> ExecStatus {
        if self.phase >= self.phases.len() {
            match &self.abort {
                Some(why) => ExecStatus::Failed(why.clone()),
                None => ExecStatus::Done,
            }
        } else {
            ExecStatus::Running
        }
    }

    fn next_phase(&mut self) {
        self.phase += 1;
        self.segment = None;
        self.wait = 0;
    }

    fn check_gripper(&self, world: &World, cmd: GripperCommand) -> Option<String> {
        let held = world.held_by(self.arm);
        match (&self.kind, cmd) {
            (ActionKind::Grasp { body, .. }, GripperCommand::Close) => match held {
                Some(h) if h == body => None,
                Some(h) => Some(format!("grasped {h} instead of {body}")),
                None => Some(format!("could not grasp {body}")),
            },
            (_, GripperCommand::Open) if held.is_some() => Some("could not release".into()),
            _ => None,
        }
    }

    fn plan_segment(
        &self,
        world: &World,
        via: &Via,
        skills: &SkillLibrary,
        p: &ExecParams,
    ) -> Result<Running, String> {
        let start = world
            .tcp_pose(self.arm)
            .ok_or_else(|| "no such arm".to_string())?;
        let (goal, frame, anchor) = self.via_pose(world, via, &start)?;
        let dist = (goal.translation.vector - start.translation.vector).norm();
        // The stroke and the lift after it go at half speed: the stroke folds the arm towards
        // its base, where the joint tracker falls behind at full speed (the lagging hand lifts
        // the blade over the block, or drifts into it as it rises).
        let speed = match via {
            Via::Pull { stage: 2.., .. } => p.stroke_speed(),
            _ => p.speed,
        };
        let duration = (dist / speed).max(p.min_segment);
        let steps = ((duration / world.dt()).round() as usize).max(2);
        let traj = skills.segment(&self.skill_name(via), &start, &goal, frame.as_ref(), steps);
        Ok(Running {
            traj,
            t: 0,
            goal,
            anchor,
            frame,
            lag: 0,
            joint_goals: match via {
                Via::Unwind => unwound(world, self.arm, &start, self.kind.body())
                    .into_iter()
                    .collect(),
                _ => vec![],
            },
            recovered: false,
            joint_ticks: 0,
            rise_by_ready: false,
        })
    }

    /// When the planned segment `r` would sweep a carried body into another body, or a learned
    /// approach's path (the skill's shape, not the straight line the streams certify) would
    /// sweep the hand through a block, the TCP height of a safe transit (the held body's bottom,
    /// or the hand, 3 cm above every top between start and goal); `None` when the path is
    /// clear, the via is a pull stroke or a transit itself, or a transit was already inserted
    /// for this phase.
    fn transit_height(&self, world: &World, via: &Via, r: &Running) -> Option<f64> {
        if no_transit(via) || self.transit_at.is_some() {
            return None;
        }
        let n = r.traj.len();
        let path: Vec<Isometry3<f64>> = (0..n)
            .step_by(4)
            .chain(std::iter::once(n - 1))
            .map(|t| {
                let s = (t as f64 / (n.max(2) - 1) as f64).clamp(0.0, 1.0);
                let rot = r.traj.start_rotation().slerp(&r.goal.rotation, s);
                Isometry3::from_parts(Translation3::from(r.traj.planned(t)), rot)
            })
            .collect();
        let held = world.held_by(self.arm).map(str::to_string);
        let load_hits = held.as_ref().is_some_and(|held| {
            let tol = world.params().penetration_tolerance;
            world.grasp_transform(self.arm).is_some_and(|g| {
                path.iter().any(|tcp| {
                    world
                        .overlap_at(held, &(tcp * g))
                        .is_some_and(|(d, _)| d > LOAD_OVERLAP_OF_TOLERANCE * tol)
                })
            })
        });
        if load_hits {
            return safe_transit_z(world, self.arm, &r.goal);
        }
        if !via.is_learned_approach() || world.hand_path_hits(&path, &[self.kind.body()]).is_none()
        {
            return None;
        }
        // The hand's transit only where the arm reaches above the goal (near the base, the
        // learned path may reach a goal the transit's corner cannot).
        let z = safe_transit_z(world, self.arm, &r.goal)?;
        let mut over = r.goal;
        over.translation.z = z;
        world.reachable(self.arm, &over).is_ok().then_some(z)
    }

    /// Inserts a transit (rise, over at height `z`) before phase `at` (whose move is `via`); that
    /// phase then descends straight (the learned approach's shape would swing the load back into
    /// what the transit avoids).
    fn insert_transit(&mut self, at: usize, via: &Via, z: f64) {
        self.transit_at = Some(at);
        if let Some(Phase::Move(Via::Grasp { skill, .. } | Via::Place { skill, .. })) =
            self.phases.get_mut(at)
        {
            *skill = false;
        }
        self.phases.splice(
            at..at,
            [
                Phase::Move(Via::Rise { z }),
                Phase::Move(Via::Over {
                    inner: Box::new(via.clone()),
                    z,
                }),
            ],
        );
        self.segment = None;
    }

    fn skill_name(&self, via: &Via) -> String {
        let grasping = matches!(self.kind, ActionKind::Grasp { .. });
        let base = match via {
            Via::Grasp { skill: true, .. } => "grasp-approach",
            Via::Place { skill: true, .. } => "place-approach",
            Via::Up { skill: true, .. } if grasping => "grasp-retreat",
            Via::Up { skill: true, .. } => "place-retreat",
            _ => return "profile".into(),
        };
        if self.hook {
            format!("hook-{base}")
        } else {
            base.to_string()
        }
    }

    /// The TCP goal of a via-point, the skill's object frame (centre + yaw) and the body it
    /// follows (name, position) for re-anchoring.
    #[allow(clippy::type_complexity)]
    fn via_pose(
        &self,
        world: &World,
        via: &Via,
        start: &Isometry3<f64>,
    ) -> Result<
        (
            Isometry3<f64>,
            Option<Isometry3<f64>>,
            Option<(String, Vector3<f64>)>,
        ),
        String,
    > {
        match via {
            Via::Grasp { body, dz, .. } => {
                let bp = world.body_pose(body);
                let g = bp
                    .and_then(|at| {
                        let boxes = boxes_except(world, &[body]);
                        clear_grasp_at(world, self.arm, body, &at, &boxes, self.approach_height)
                    })
                    .ok_or_else(|| format!("{body} cannot be grasped"))?;
                let at = bp.map(|q| q.translation.vector);
                Ok((
                    raised(&g, *dz),
                    bp.map(|q| anchor_frame(&q)),
                    at.map(|a| (body.clone(), a)),
                ))
            }
            Via::Place { placement, dz, .. } => {
                let body = match &self.kind {
                    ActionKind::Release { body, .. } => body.clone(),
                    _ => return Err("not a release".into()),
                };
                let (pose, anchor) = placement_pose(world, &body, placement)?;
                let pose = quarter_turn_for_arm(world, self.arm, &body, &pose, self.hand_yaw);
                let tcp = tcp_for_body_pose(world, self.arm, &pose);
                Ok((raised(&tcp, *dz), Some(anchor_frame(&pose)), anchor))
            }
            Via::Up { dz, .. } => {
                let mut g = *start;
                g.translation.vector.z += dz;
                Ok((g, self.event_frame, None))
            }
            Via::Rise { z } => {
                let mut g = *start;
                g.translation.vector.z = *z;
                Ok((g, None, None))
            }
            Via::Unwind => Ok((*start, None, None)),
            Via::Over { inner, z } => {
                let (mut g, _, anchor) = self.via_pose(world, inner, start)?;
                g.translation.vector.z = *z;
                Ok((g, None, anchor))
            }
            Via::Pull { body, stage, turn } => {
                let g = pull_via(world, self.arm, body, *stage, *turn)?;
                let at = world.body_pose(body).map(|q| q.translation.vector);
                Ok((
                    g,
                    None,
                    if *stage == 0 {
                        at.map(|a| (body.clone(), a))
                    } else {
                        None
                    },
                ))
            }
        }
    }
}

/// A body followed for re-anchoring: its name and where it was.
pub(crate) type Anchor = Option<(String, Vector3<f64>)>;

/// The resting pose of `body` at a placement, and the anchor it follows (the block below).
pub(crate) fn placement_pose(
    world: &World,
    body: &str,
    placement: &Placement,
) -> Result<(Isometry3<f64>, Anchor), String> {
    match placement {
        Placement::OnBlock(y) => {
            let pose = rest_pose_on(world, body, y, 0.0)
                .ok_or_else(|| format!("nothing to put {body} on at {y}"))?;
            let at = world.body_pose(y).map(|q| q.translation.vector);
            Ok((pose, at.map(|a| (y.clone(), a))))
        }
        Placement::At { x, y, yaw } => {
            let pose = rest_pose(world, body, *x, *y, *yaw)
                .ok_or_else(|| format!("no support under ({x:.3}, {y:.3})"))?;
            Ok((pose, None))
        }
        Placement::Stroke(_) => Err(format!("a pull stroke is not a placement of {body}")),
    }
}

/// Via-points of a pull stroke (the simulator's hook geometry, `sim::demo::pull_hook_poses`):
/// 0 above the contact pose (blade behind the block), 1 the contact pose, 2 the pulled pose
/// (block at `PULL_TARGET_RADIUS` from the base), 3 lifted from there.
fn pull_via(
    world: &World,
    arm: usize,
    body: &str,
    stage: u8,
    turn: f64,
) -> Result<Isometry3<f64>, String> {
    let base = world.arm_base(arm).ok_or("no such arm")?;
    let bp = world
        .body_pose(body)
        .ok_or_else(|| format!("no body {body}"))?;
    let reach = crate::sim::demo::PULL_TARGET_RADIUS;
    let (contact, pulled) = crate::sim::demo::pull_hook_poses_turned(&base, &bp, reach, turn)
        .ok_or_else(|| format!("no stroke turned by {turn:.2} rad pulls {body} into reach"))?;
    let lift = |iso: Isometry3<f64>| raised(&iso, crate::sim::demo::PULL_LIFT);
    let tc = tcp_for_body_pose(world, arm, &contact);
    let tp = tcp_for_body_pose(world, arm, &pulled);
    Ok(match stage {
        0 => lift(tc),
        1 => tc,
        2 => tp,
        _ => lift(tp),
    })
}

/// Whether a segment to `via` must not be replaced by a transit: the hook's stroke itself (from
/// its contact pose on), and transits.
fn no_transit(via: &Via) -> bool {
    matches!(via, Via::Rise { .. } | Via::Over { .. } | Via::Unwind)
        || matches!(via, Via::Pull { stage, .. } if *stage > 0)
}

/// The TCP height of a safe transit of arm `arm` from where it is to `goal`
/// ([`transit_z`]): a held body's bottom, or the empty hand, clears every top between them,
/// "between" widened by how far the held body (at least 8 cm) or the hand reaches around the
/// TCP.
pub(crate) fn safe_transit_z(world: &World, arm: usize, goal: &Isometry3<f64>) -> Option<f64> {
    let a = world.tcp_pose(arm)?.translation.vector;
    let held = world.held_by(arm).map(str::to_string);
    let load = match &held {
        Some(h) => Some(world.body_aabb(h)?),
        None => None,
    };
    let except = held.unwrap_or_default();
    Some(transit_z(&a, &goal.translation.vector, load, |lo, hi| {
        world.highest_top_in(lo, hi, &except)
    }))
}

/// Why the lift of the body that `arm` just grasped (action `kind`, move `via`, the TCP's height
/// `grasped_z` at the grasp) is stuck: the simulator stopped it at another body before it rose
/// [`STUCK_LIFT`] above where it was grasped. `None` if it is not.
fn stuck_lift(
    world: &World,
    arm: usize,
    kind: &ActionKind,
    via: &Via,
    grasped_z: Option<f64>,
) -> Option<String> {
    let (ActionKind::Grasp { body, .. }, Via::Up { .. }) = (kind, via) else {
        return None;
    };
    if world.held_by(arm) != Some(body.as_str()) {
        return None;
    }
    let by = world.arm_blocked_by(arm)?;
    let at = grasped_z?;
    let z = world.tcp_pose(arm)?.translation.z;
    (z - at < STUCK_LIFT).then(|| format!("cannot lift {body}: {by} is in its way"))
}

/// How far above its release point (m) a load the arm cannot bring lower may be let go, when it
/// comes to rest on its support from there.
const RELEASE_SLACK: f64 = 0.01;

/// How far a body must have risen from where it was grasped for a stopped lift to be carried
/// on (by a transit) rather than undone (m).
const STUCK_LIFT: f64 = 0.01;

/// A joint-space move has reached its joint goal when every joint is this close to it (rad).
const JOINT_GOAL_TOLERANCE: f64 = 1e-6;

/// A planned path of a carried body counts as hitting another body where it goes deeper into it
/// than this fraction of the world's penetration tolerance.
const LOAD_OVERLAP_OF_TOLERANCE: f64 = 0.5;

/// How much more room to its joint limits ([`panda::limit_margin`]) an unwound posture must
/// leave than the arm's posture now.
///
/// [`panda::limit_margin`]: crate::sim::panda::limit_margin
const UNWIND_GAIN: f64 = 1e-3;

/// Below this [`panda::limit_margin`] (of a joint's range) an action starts by unwinding the
/// arm ([`Via::Unwind`]).
///
/// [`panda::limit_margin`]: crate::sim::panda::limit_margin
const UNWIND_MARGIN: f64 = 0.01;

/// The joints that reach arm `arm`'s TCP pose `tcp` with the most room to their limits, if they
/// leave more room than the arm's joints now and the straight joint-space move there is clear
/// ([`World::joint_move_hits`]; `touches` may be touched).
fn unwound(
    world: &World,
    arm: usize,
    tcp: &Isometry3<f64>,
    touches: &str,
) -> Option<[f64; crate::sim::panda::DOF]> {
    use crate::sim::panda::limit_margin;
    let now = world.joints(arm)?;
    let sol = world.reachable_with_room(arm, tcp).ok()?.joints;
    (limit_margin(&sol) > limit_margin(&now) + UNWIND_GAIN
        && world.joint_move_hits(arm, &now, &sol, &[touches]).is_none())
    .then_some(sol)
}

/// The ready posture, as a way for arm `arm` to rise to `goal`'s height when it cannot rise
/// where it is (a hand folded inside the minimum reach, a wrist at its limit): if the ready TCP
/// is at least that high and the joint-space move there is clear ([`World::joint_move_hits`];
/// `touches` may be touched). The transit's next leg, across and down to its goal, starts from
/// there, higher than the height it needs.
fn rise_by_ready(
    world: &World,
    arm: usize,
    goal: &Isometry3<f64>,
    touches: &str,
) -> Option<[f64; crate::sim::panda::DOF]> {
    let ready = crate::sim::panda::READY;
    let now = world.joints(arm)?;
    let base = world.arm_base(arm)?;
    let high = crate::sim::panda::forward_kinematics(&base, &ready)
        .translation
        .z
        >= goal.translation.z;
    (high
        && world
            .joint_move_hits(arm, &now, &ready, &[touches])
            .is_none())
    .then_some(ready)
}

/// The joint goals of a joint-space recovery of `arm` to the TCP pose `pose`, whose solution
/// with the most room to the limits is `goal`: straight there, or, when that move would sweep
/// the arm or its load through something ([`World::joint_move_hits`]) and the way by the ready
/// posture would not, by way of [`panda::READY`]; failing both, straight to the solution
/// nearest the arm's joints ([`World::reachable_near`]) for the goal, or for a point on the
/// way to it ([`NEAR_RECOVERY_FRACTIONS`]), if that move is clear. The streams certify the same
/// choice. `touches`: the body the action grasps, releases or pulls, which the hand may touch.
///
/// [`panda::READY`]: crate::sim::panda::READY
fn joint_recovery_route(
    world: &World,
    arm: usize,
    pose: &Isometry3<f64>,
    goal: [f64; crate::sim::panda::DOF],
    touches: &str,
) -> Vec<[f64; crate::sim::panda::DOF]> {
    let ready = crate::sim::panda::READY;
    let Some(now) = world.joints(arm) else {
        return vec![goal];
    };
    let except = [touches];
    if world.joint_move_hits(arm, &now, &goal, &except).is_none() {
        return vec![goal];
    }
    if world.joint_move_hits(arm, &now, &ready, &except).is_none()
        && world.joint_move_hits(arm, &ready, &goal, &except).is_none()
    {
        return vec![ready, goal];
    }
    let Some(tcp) = world.tcp_pose(arm) else {
        return vec![goal];
    };
    for s in NEAR_RECOVERY_FRACTIONS {
        let mut part = *pose;
        part.translation.vector = tcp.translation.vector.lerp(&pose.translation.vector, s);
        match world.reachable_near(arm, &part) {
            Ok(near)
                if world
                    .joint_move_hits(arm, &now, &near.joints, &except)
                    .is_none() =>
            {
                return vec![near.joints];
            }
            _ => {}
        }
    }
    vec![goal]
}
