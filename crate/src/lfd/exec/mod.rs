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
//!
//! One file per job: `params` (the tunables), `phase` (the phases of each action kind and the
//! via-points they move to), `via` (each via-point's pose), `recovery` (transits and the
//! arm's recoveries), `tick` (one tick of the running action).

mod params;
mod phase;
mod recovery;
mod tick;
mod via;

use nalgebra::{Isometry3, Vector3};

use crate::sim::snapshot::BodyKind;
use crate::sim::{GripperCommand, World, WorldEvent};
use crate::tamp::action::ActionKind;
use crate::tamp::motion::MotionParams;

use super::skill::{SkillLibrary, SkillSegment};
pub use params::ExecParams;
use phase::{action_phases, prepare_arm, Phase, Via};
use via::Anchor;

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
    /// The body acted on is the hook (its skills are the `…@hook` ones).
    hook: bool,
    /// The motion's heights: the grasp is chosen with the hand clear up to half the approach
    /// height.
    motion: MotionParams,
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
    anchor: Option<Anchor>,
    /// The step from which the anchor is no longer followed (a stroke's: the hook is behind the
    /// block, which moves because the hook drags it).
    anchor_until: Option<usize>,
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
        let (arm, mut phases) = action_phases(action, &kind, skills, p, hook);
        prepare_arm(world, arm, p, &mut phases);
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
            motion: p.motion,
            hand_yaw: None,
            abort: None,
            grasped_z: None,
        }
    }

    /// Puts a released square block down with the hand at yaw `yaw` (of the TCP's x axis, as the
    /// streams certified it; `tamp::motion::release_turns`) rather than the yaw nearest the
    /// heading from the base. `None` keeps the heading.
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
}
