//! The demonstration recorder: segmentation of recordings into the domain's actions, refusal of
//! recordings the PDDL model cannot explain, the quick (drag) and gripper teaching modes, undo,
//! taught tasks, and the `logic-lfd demo segment` CLI. This module holds the recordings, edits
//! and paths its test files share.

mod segmentation;
mod taught;
mod taught_folder;
mod teaching;

use std::path::PathBuf;

use logic_lfd::recorder::Edit;
use logic_lfd::recorder::GripperState;
use logic_lfd::recorder::{
    segment_recording, ArmRef, RawRecording, RecorderError, RecorderParams, Taught,
};
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::{geometry, World};

fn quick_params() -> RecorderParams {
    RecorderParams {
        learn_skills: false,
        ..RecorderParams::default()
    }
}

fn segment(rec: &RawRecording, b: Benchmark) -> Result<Taught, RecorderError> {
    segment_recording(rec, b.domain_pddl(), "domain.pddl", None, quick_params())
}

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/recordings")
        .join(name)
}

fn domain_file(b: Benchmark) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../domains")
        .join(b.dir_name())
        .join("domain.pddl")
}

fn drag(body: &str, onto: &str) -> Edit {
    Edit::Drag {
        body: body.into(),
        onto: Some(onto.into()),
        position: None,
        yaw: None,
        arm: None,
    }
}

fn gripper(position: [f64; 3], yaw: f64, g: GripperState, duration: f64) -> Edit {
    Edit::Gripper {
        arm: ArmRef::Index(0),
        position,
        yaw,
        gripper: g,
        duration,
    }
}

/// The gripper yaw of the top grasp of `body` (the yaw `down_orientation` was built with).
fn grasp_yaw(world: &World, body: &str) -> ([f64; 3], f64) {
    let g = geometry::grasp_pose(world, 0, body).unwrap();
    let r = g.rotation
        * nalgebra::UnitQuaternion::from_axis_angle(
            &nalgebra::Vector3::x_axis(),
            std::f64::consts::PI,
        );
    let x = r * nalgebra::Vector3::x();
    let p = g.translation.vector;
    ([p.x, p.y, p.z], libm::atan2(x.y, x.x))
}

/// Ticks the session `s` to its outcome, checking the world's invariants every tick. With
/// `l3_after = Some(n)`, an L3 disturbance is injected once the robot has done `n` actions and is
/// between two; returns whether it was.
fn run_to_outcome(s: &mut logic_lfd::lfd::Session, l3_after: Option<usize>) -> bool {
    let mut injected = false;
    for _ in 0..40_000 {
        if s.outcome().is_some() {
            break;
        }
        if let Some(n) = l3_after {
            if !injected && !s.is_executing() && s.actions_done() >= n {
                injected = s.inject("l3").is_ok();
            }
        }
        s.tick_once(&logic_lfd::plan::NoClock);
        let v = crate::support::invariants::broken(s.world());
        assert!(v.is_empty(), "tick {}: {v:?}", s.tick());
    }
    injected
}
