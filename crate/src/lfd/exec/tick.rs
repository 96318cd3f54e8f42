//! One tick of a running action: a short dispatch over the steps of a gripper event and of a
//! move (plan or re-anchor the segment, command the arm and step the world, undo a stuck lift,
//! fly a transit when blocked, and at the segment's end: go on, recover, or fail).

use nalgebra::{Isometry3, Point3, Translation3};

use super::recovery::{rise_by_ready, stuck_lift, unwound};
use super::steps::{no_transit, Phase, Via};
use super::via::{anchor_frame, pull_stroke, ViaPose};
use super::{ActionExec, ExecParams, ExecStatus, Running};
use crate::lfd::SkillLibrary;
use crate::sim::{GripperCommand, World, WorldEvent};
use crate::tamp::ActionKind;
use crate::tamp::{joint_recovery, transit_height, LiveArm, RecoveryRoute};

impl ActionExec {
    /// Commands the arm for this tick, steps the world once, and reports.
    pub fn tick(&mut self, world: &mut World, skills: &SkillLibrary, p: &ExecParams) -> ExecStatus {
        let dt = world.dt();
        let Some(phase) = self.phases.get(self.phase).cloned() else {
            return ExecStatus::Done;
        };
        match phase {
            Phase::Gripper(cmd) => self.tick_gripper(world, cmd, dt, p),
            Phase::Move(via) => self.tick_move(world, &via, skills, dt, p),
        }
    }

    /// A tick of a gripper event: hold the TCP, command the fingers, step; the event is over
    /// after `gripper_time`.
    fn tick_gripper(
        &mut self,
        world: &mut World,
        cmd: GripperCommand,
        dt: f64,
        p: &ExecParams,
    ) -> ExecStatus {
        let Some(tcp) = world.tcp_pose(self.arm) else {
            return ExecStatus::Failed("no such arm".into());
        };
        if self.wait == 0 {
            if let Some(failed) = self.start_gripper_event(world, cmd) {
                return failed;
            }
        }
        self.gripper = cmd;
        let _ = world.command_arm(self.arm, tcp, cmd);
        let ev = world.step();
        self.events.extend(ev.iter().cloned());
        self.wait += 1;
        if let Some(failed) = self.gripper_event_failure(world, &ev) {
            return failed;
        }
        if (self.wait as f64) * dt >= p.gripper_time {
            if let Some(s) = self.check_gripper(world, cmd) {
                return ExecStatus::Failed(s);
            }
            self.end_gripper_event(world, cmd);
            self.next_phase();
        }
        self.status()
    }

    /// The first tick of a gripper event: refuses to let go of a load that would fall or end
    /// inside another body, and records the retreat's frame.
    fn start_gripper_event(&mut self, world: &World, cmd: GripperCommand) -> Option<ExecStatus> {
        if cmd == GripperCommand::Open {
            // Never let go of a load that would fall or end inside another body.
            if let (ActionKind::Release { body, .. }, Err(why)) =
                (&self.kind, world.release_check(self.arm))
            {
                return Some(ExecStatus::Failed(format!(
                    "cannot release {body} here: {why}"
                )));
            }
        }
        // The retreat's frame: the grasped body where it was grasped; for a release the body's
        // resting pose (recorded once it has settled, in `end_gripper_event`).
        self.event_frame = world
            .held_by(self.arm)
            .and_then(|h| world.body_pose(h))
            .map(|p| anchor_frame(&p));
        None
    }

    /// Why the gripper event fails after this step's events `ev`: the fingers closed on nothing
    /// (because something stands on the body), or a body fell.
    fn gripper_event_failure(&self, world: &World, ev: &[WorldEvent]) -> Option<ExecStatus> {
        if ev
            .iter()
            .any(|e| matches!(e, WorldEvent::GraspedNothing { .. }))
        {
            if let ActionKind::Grasp { body, .. } = &self.kind {
                let above = world.resting_on(body);
                if !above.is_empty() {
                    return Some(ExecStatus::Failed(format!(
                        "cannot lift {body}: {} stands on it",
                        above.join(", ")
                    )));
                }
            }
            return Some(ExecStatus::Failed("the gripper closed on nothing".into()));
        }
        fell(ev)
    }

    /// The gripper event is over: records the released body's resting frame, or the TCP's
    /// height at the grasp.
    fn end_gripper_event(&mut self, world: &World, cmd: GripperCommand) {
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
    }

    /// A tick of a move to `via`: follow the segment one step, then handle what the step did.
    fn tick_move(
        &mut self,
        world: &mut World,
        via: &Via,
        skills: &SkillLibrary,
        dt: f64,
        p: &ExecParams,
    ) -> ExecStatus {
        if let Some(status) = self.follow_anchor(world, via, skills, p) {
            return status;
        }
        // The grasp needs the hand turned as planned: the fingers must fit around the
        // block (a release lands wherever the block is, turned or not). So does every
        // via-point of a pull: a hook turned otherwise lowers its long arm elsewhere.
        let turn_matters = match self.phases.get(self.phase) {
            Some(Phase::Move(Via::Grasp { dz, .. })) => *dz <= 0.0,
            Some(Phase::Move(Via::Pull { .. } | Via::Stroke { .. })) => true,
            _ => false,
        };
        if let Some(status) = self.step_segment(world) {
            return status;
        }
        if let Some(status) = self.undo_stuck_lift(world, via) {
            return status;
        }
        if let Some(status) = self.transit_when_blocked(world, via) {
            return status;
        }
        let Some(seg) = self.segment.as_mut() else {
            return ExecStatus::Failed("no segment".into());
        };
        seg.t += 1;
        // Once the hook is down behind the block, the block moves because the stroke drags it.
        if seg.anchor_until.is_some_and(|u| seg.t >= u) {
            seg.anchor = None;
        }
        if seg.t >= seg.traj.len() {
            if let Some(status) = self.segment_ended(world, via, turn_matters, dt, p) {
                return status;
            }
        }
        self.status()
    }

    /// Plans the segment when it starts; when its anchor object moved, re-targets the skill's
    /// controller to the new object frame (or re-plans a profile). A status when the tick ends
    /// here (a transit inserted, a failure).
    fn follow_anchor(
        &mut self,
        world: &World,
        via: &Via,
        skills: &SkillLibrary,
        p: &ExecParams,
    ) -> Option<ExecStatus> {
        let moved = match &self.segment {
            None => true,
            Some(r) => r.anchor.as_ref().is_some_and(|a| {
                world
                    .body_pose(&a.body)
                    .is_some_and(|q| (q.translation.vector - a.at).norm() > p.reanchor_tolerance)
            }),
        };
        if !moved {
            return None;
        }
        let start = world.tcp_pose(self.arm).unwrap_or_else(Isometry3::identity);
        let fresh = self.via_pose(world, via, &start);
        let retargeted = match self.segment.as_mut() {
            Some(r) => match (fresh, r.frame) {
                (
                    Ok(ViaPose {
                        goal,
                        frame: Some(new_frame),
                        anchor,
                    }),
                    Some(old),
                ) => {
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
        if retargeted {
            return None;
        }
        match self.plan_segment(world, via, skills, p) {
            Ok(r) => {
                // A carried body whose path would sweep through another goes up, over at a
                // safe height, and down instead.
                if let Some(z) = self.transit_height(world, via, &r) {
                    self.insert_transit(self.phase, via, z);
                    return Some(ExecStatus::Running);
                }
                self.segment = Some(r);
                None
            }
            Err(e) => Some(ExecStatus::Failed(e)),
        }
    }

    /// Commands the arm along the segment (or to its joint-space recovery's next goal) and steps
    /// the world once. A status when the tick ends here (no segment, a body fell).
    fn step_segment(&mut self, world: &mut World) -> Option<ExecStatus> {
        let Some(seg) = self.segment.as_mut() else {
            return Some(ExecStatus::Failed("no segment".into()));
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
        fell(&ev)
    }

    /// A lift stopped before the body has left its place (something overhangs it): puts it back
    /// down where it was, lets go and rises, then reports the failure, so the replan starts from
    /// a free hand and the body where it was.
    fn undo_stuck_lift(&mut self, world: &World, via: &Via) -> Option<ExecStatus> {
        let stuck = match self.abort {
            None => stuck_lift(world, self.arm, &self.kind, via, self.grasped_z),
            Some(_) => None,
        };
        let (Some(why), Some(z)) = (stuck, self.grasped_z) else {
            return None;
        };
        self.phases.truncate(self.phase + 1);
        self.phases.extend([
            Phase::Move(Via::Rise { z }),
            Phase::Gripper(GripperCommand::Open),
            Phase::Move(Via::Up {
                dz: self.motion.approach_height,
                skill: false,
            }),
        ]);
        self.abort = Some(why);
        self.next_phase();
        Some(ExecStatus::Running)
    }

    /// The carried body met another on the way (tracking lag or a moved obstacle), or the
    /// hand's learned approach swung a link into a table or shelf: go up, over at a safe height,
    /// and down instead, once per action.
    fn transit_when_blocked(&mut self, world: &World, via: &Via) -> Option<ExecStatus> {
        if world.arm_blocked_by(self.arm).is_some()
            && (world.held_by(self.arm).is_some() || via.is_learned_approach())
            && self.transit_at.is_none()
            && !no_transit(via)
        {
            let goal = self.segment.as_ref()?.goal;
            if let Some(z) = transit_height(world, self.arm, &goal) {
                self.insert_transit(self.phase, via, z);
                return Some(ExecStatus::Running);
            }
        }
        None
    }

    /// The segment's trajectory has run out: on to the next phase when the TCP is there (and
    /// turned, where `turn_matters`), else go on with or start a joint-space recovery, and fail
    /// once it lags too long.
    fn segment_ended(
        &mut self,
        world: &World,
        via: &Via,
        turn_matters: bool,
        dt: f64,
        p: &ExecParams,
    ) -> Option<ExecStatus> {
        let seg = self.segment.as_ref()?;
        let tcp = world.tcp_pose(self.arm).unwrap_or(seg.goal);
        let err = (tcp.translation.vector - seg.traj.goal()).norm();
        // At a grasp the hand's turn matters too: a wrist stuck at its limit leaves
        // the fingers across a block's diagonal, where they do not fit around it.
        let turn_err = (seg.goal.rotation * tcp.rotation.inverse()).angle();
        let turned = !turn_matters || turn_err <= p.orientation_tolerance;
        let miss = Miss {
            tcp,
            err,
            turn_err,
            turned,
        };
        if err <= p.reach_tolerance && turned {
            self.next_phase();
            None
        } else if let Some(&q) = seg.joint_goals.first() {
            self.continue_joint_recovery(world, q, dt, p)
        } else {
            self.lagging(world, via, &miss, dt, p)
        }
    }

    /// A joint-space recovery towards joints `q`: back to Cartesian tracking once there (or
    /// after `settle_timeout` more), to settle on the goal.
    fn continue_joint_recovery(
        &mut self,
        world: &World,
        q: [f64; crate::sim::panda::DOF],
        dt: f64,
        p: &ExecParams,
    ) -> Option<ExecStatus> {
        let seg = self.segment.as_mut()?;
        seg.joint_ticks += 1;
        let there = world.joints(self.arm).is_none_or(|j| {
            j.iter()
                .zip(&q)
                .all(|(a, b)| (a - b).abs() < JOINT_GOAL_TOLERANCE)
        });
        let stopped = world.arm_blocked_by(self.arm).is_some();
        if there && seg.rise_by_ready {
            self.next_phase();
            return Some(ExecStatus::Running);
        }
        if there && seg.joint_goals.len() > 1 {
            seg.joint_goals.remove(0);
            seg.joint_ticks = 0;
        } else if there || stopped || seg.joint_ticks as f64 * dt > p.joint_recovery_timeout() {
            seg.joint_goals.clear();
            seg.lag = 0;
        }
        None
    }

    /// The TCP lags behind the segment's end (`miss`): a joint-space recovery once it has
    /// lagged `recovery_after`, a failure (or a release from just above) after
    /// `settle_timeout`.
    fn lagging(
        &mut self,
        world: &World,
        via: &Via,
        miss: &Miss,
        dt: f64,
        p: &ExecParams,
    ) -> Option<ExecStatus> {
        let body = self.kind.body().to_string();
        let seg = self.segment.as_mut()?;
        seg.lag += 1;
        // Cartesian tracking stuck far from a goal the planning IK reaches (a local minimum of
        // the tracking IK after a large reconfiguration, or a joint at its limit): move in joint
        // space to the planning IK's solution with the most room to the limits, once per
        // segment.
        if !seg.recovered
            && (miss.err > p.recovery_distance || !miss.turned)
            && seg.lag as f64 * dt > p.recovery_after
            && world.arm_blocked_by(self.arm).is_none()
        {
            start_joint_recovery(world, self.arm, via, seg, &body);
        }
        if seg.lag as f64 * dt > p.settle_timeout {
            return Some(self.settle_timed_out(world, via, miss, p));
        }
        None
    }

    /// The arm has lagged `settle_timeout` behind the segment's end: a release point it stops
    /// just above (an elbow at its limit over a tall stack near the base) lets go there if the
    /// body comes to rest on its support from that height; anything else fails, saying why.
    fn settle_timed_out(
        &mut self,
        world: &World,
        via: &Via,
        miss: &Miss,
        p: &ExecParams,
    ) -> ExecStatus {
        let goal = self.segment.as_ref().map(|s| s.goal).unwrap_or(miss.tcp);
        let above = miss.tcp.translation.vector - goal.translation.vector;
        let drop_ok = matches!(via, Via::Place { .. })
            && matches!(self.phases.get(self.phase + 1), Some(Phase::Gripper(_)))
            && above.z >= 0.0
            && above.norm() <= RELEASE_SLACK
            && libm::hypot(above.x, above.y) <= p.reach_tolerance
            && world.release_check(self.arm).is_ok();
        if drop_ok {
            self.next_phase();
            return ExecStatus::Running;
        }
        let err = miss.err;
        ExecStatus::Failed(match world.arm_blocked_by(self.arm) {
            Some(b) => format!(
                "the {} is stopped by {b} ({:.1} mm from the via-point)",
                if world.held_by(self.arm).is_some() {
                    "held body"
                } else {
                    "arm"
                },
                err * 1e3
            ),
            None if !miss.turned && err <= p.reach_tolerance => format!(
                "the arm cannot turn its hand to the via-point ({:.0}° off)",
                miss.turn_err.to_degrees()
            ),
            None => format!(
                "the arm cannot reach its via-point ({:.1} mm away)",
                err * 1e3
            ),
        })
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
        let ViaPose {
            goal,
            frame,
            anchor,
        } = self.via_pose(world, via, &start)?;
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
        let name = self.skill_name(via);
        let (traj, anchor_until) = match via {
            Via::Stroke { body, turn } => {
                let stroke = pull_stroke(world, self.arm, body, *turn)?;
                let point = |p: &Isometry3<f64>| Point3::from(p.translation.vector);
                let (seg, _, behind) = skills
                    .stroke_segment(
                        &name,
                        &start,
                        &point(&stroke.contact),
                        &point(&stroke.pulled),
                    )
                    .ok_or_else(|| format!("the learned stroke {name} cannot be planned"))?;
                (seg, Some(behind))
            }
            _ => (
                skills.segment(&name, &start, &goal, frame.as_ref(), steps),
                None,
            ),
        };
        Ok(Running {
            traj,
            t: 0,
            goal,
            anchor,
            anchor_until,
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
}

/// How far the TCP is from a segment's end when its trajectory has run out.
struct Miss {
    /// The TCP's pose.
    tcp: Isometry3<f64>,
    /// Its distance from the trajectory's end (m).
    err: f64,
    /// Its turn from the via-point's orientation (rad).
    turn_err: f64,
    /// Whether it is turned closely enough (or the turn does not matter).
    turned: bool,
}

/// Starts the joint-space recovery of `arm` for segment `seg` (a move to `via`; `body` may be
/// touched), once per segment: to the planning IK's solution with the most room to the
/// limits by the route the streams certify ([`joint_recovery`]), or, for a rise the arm cannot make where it is, by way of
/// the ready posture ([`rise_by_ready`]).
fn start_joint_recovery(world: &World, arm: usize, via: &Via, seg: &mut Running, body: &str) {
    seg.recovered = true;
    // Where the segment is judged: the end of its trajectory (a learned skill's own, in its
    // object frame), turned as the via-point.
    let target = Isometry3::from_parts(Translation3::from(seg.traj.goal()), seg.goal.rotation);
    let mut live = LiveArm {
        world,
        arm,
        touches: body,
    };
    match joint_recovery(&mut live, &target) {
        Some(recovery) => {
            seg.joint_goals = match recovery.route {
                RecoveryRoute::Straight | RecoveryRoute::Blocked(_) => vec![recovery.goal],
                RecoveryRoute::ByReady { ready } => vec![ready, recovery.goal],
                RecoveryRoute::Near { joints, .. } => vec![joints],
            };
            seg.joint_ticks = 0;
            seg.lag = 0;
        }
        None if matches!(via, Via::Rise { .. } | Via::Up { .. }) => {
            if let Some(q) = rise_by_ready(world, arm, &target, body) {
                seg.joint_goals = vec![q];
                seg.rise_by_ready = true;
                seg.joint_ticks = 0;
                seg.lag = 0;
            }
        }
        None => {}
    }
}

/// A failure when one of a step's events `ev` says a body fell.
fn fell(ev: &[WorldEvent]) -> Option<ExecStatus> {
    match ev.iter().find(|e| matches!(e, WorldEvent::Lost { .. })) {
        Some(WorldEvent::Lost { body, reason }) => {
            Some(ExecStatus::Failed(format!("{body} fell: {reason}")))
        }
        _ => None,
    }
}

/// How far above its release point (m) a load the arm cannot bring lower may be let go, when it
/// comes to rest on its support from there.
const RELEASE_SLACK: f64 = 0.01;

/// A joint-space move has reached its joint goal when every joint is this close to it (rad).
const JOINT_GOAL_TOLERANCE: f64 = 1e-6;
