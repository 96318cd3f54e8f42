//! Executing one grounded action in the simulator through its motion skill (Algorithm 1 line 14,
//! τ = LQT-CP(a)).
//!
//! What an action does physically comes from [`crate::tamp::classify`] (its effects,
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
mod state;
mod steps;
mod tick;
mod via;

use nalgebra::Vector3;

use crate::sim::BodyKind;
use crate::sim::{GripperCommand, World};
use crate::tamp::ActionKind;

use super::skill::SkillLibrary;
pub use params::ExecParams;
use phase::{action_phases, prepare_arm};
use state::Running;
pub use state::{ActionExec, ExecStatus};
use steps::{Phase, Via};

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
    /// streams certified it; `tamp::release_turns`) rather than the yaw nearest the
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
