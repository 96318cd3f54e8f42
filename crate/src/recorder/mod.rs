//! Teach it yourself: record a demonstration in the simulator and segment it into the symbolic
//! actions of a PDDL domain, producing a `demo.json` like `domains/*/demo.json`.
//!
//! # What the recorder does
//!
//! A recording is a stream of *edits* of a world (a [`WorldSnapshot`](crate::sim::WorldSnapshot)): gripper samples (the user
//! moves the gripper — a 3-D handle with a position, a yaw and open/close — and the arm follows by
//! IK), hand moves of a block (the user displaces a block directly), or, in the quicker mode, block
//! drags and hook pulls for which the recorder synthesises the arm motion ([`recording_from_demo`], [`drag_samples`]). Each edit is
//! replayed in the simulator ([`World::step`](crate::sim::World::step): the arm follows by IK, a
//! closing gripper grasps, an opening one releases and the body settles) and after **every** step
//! the scene graph's facts `S_C` are compared with the current logical state `S`:
//!
//! ```text
//!   S_C = S                      nothing to explain
//!   S_C ≠ S                      find the operators o of the grounded task with
//!                                  pre(o) ⊆ S,  pre⁻(o) ∩ S = ∅,  (S \ del(o)) ∪ add(o) = S_C
//!                                exactly one  → the action a_k = o is recorded at this time,
//!                                               L_k = S_C and S ← S_C
//!                                none         → error: the time and the unexplained facts
//!                                               (added +f, removed −f) and the closest operator
//! ```
//!
//! so the demo states `L_0..L_N` are the states the model passes through (fluents only), every
//! recorded action is a valid step of the domain, and the taught goal `G` defaults to `L_N` (the
//! user may replace it by any subset of `L_N`). Physical implausibility is refused too: a release
//! more than [`RecorderParams::max_release_drop`] above the support (a release in mid-air), a body
//! that falls off, and any broken world invariant (interpenetration, unsupported body).
//!
//! # Segmenting the motion
//!
//! Action `a_k` happens at step `e_k` (its fact change) and is carried out by arm `r_k` (its first
//! argument that names an arm). The samples between two actions are split at a boundary
//! `b_k ∈ [e_k, e_{k+1})`:
//! * same arm: the end of the lift after a grasp or a release — once the TCP has risen
//!   [`RecorderParams::lift_height`] above its height at `e_k`, the first local minimum of its speed
//!   after the speed has come down from its peak (not the first sample where the speed rises: the
//!   lift height is often passed while still accelerating, and a cut there starts the next action
//!   at full speed, which no skill learned from it can fit); without such a lift, the highest TCP
//!   point in between;
//! * different arms: where `r_k` stops moving, or just before `r_{k+1}` starts if that is earlier.
//!
//! Action `k` owns the samples `(b_{k−1}, b_k]` of its arm (the first from the recording's start,
//! the last to its end), expressed in the frame of its *anchor* object exactly as
//! [`crate::sim::demo`] documents (pick/unstack/pull: the object at the action's start; placing
//! actions: the carried object's resting pose at the action's end), with its gripper commands and
//! key points (`grasp`, `release`, `contact`, `pulled`). The LQT-CP skills the loop will use are
//! learned from every action's motion — its approach (to the grasp or release) and its retreat
//! ([`crate::lqt::Skill::learn`], [`taught::skill_fits`]) — and their reproduction errors reported
//! ([`SkillFit`]): within about 2 mm RMS for taught B1 demos, as for the scripted ones.
//!
//! Nothing is saved half-made: an edit that fails leaves the recorder exactly as before it, and
//! [`Recorder::finish`] either returns a complete demonstration or an error.

mod engine;
mod recording;
mod synth;
pub mod taught;
mod types;

pub use recording::{
    ArmRef, GripperPose, GripperState, HandMove, RawRecording, RawSample, RecordingScene,
};
pub use synth::{drag_samples, pull_samples, recording_from_demo, Edit, HookGrip, SynthParams};

use crate::pddl::Source;
pub use engine::{GripperHandle, Recorder, RecorderOptions};
pub(crate) use types::change_text;
pub use types::{
    RecorderError, RecorderEvent, RecorderParams, Segment, SkillFit, Taught, TaughtDemo,
};

/// Segments a whole raw recording against a PDDL domain (the CLI's `demo segment`): replays every
/// sample, checks every fact change, and returns the demonstration or the first error.
/// `problem_pddl` (optional) supplies static facts (e.g. B3's `reaches`); without it they come
/// from the benchmark named by the recording or the scene.
pub fn segment_recording(
    recording: &RawRecording,
    domain_pddl: &str,
    domain_file: &str,
    problem: Option<&Source>,
    params: RecorderParams,
) -> Result<Taught, RecorderError> {
    let options = RecorderOptions {
        domain_file: domain_file.to_string(),
        problem_pddl: problem.cloned(),
        motions_json: None,
        params,
    };
    segment_recording_with(recording, domain_pddl, options)
}

/// [`segment_recording`] with every option given: a task folder's `motions.json` tells what the
/// domain's names mean when the recording's scene is no benchmark's or the names are not its.
pub fn segment_recording_with(
    recording: &RawRecording,
    domain_pddl: &str,
    options: RecorderOptions,
) -> Result<Taught, RecorderError> {
    let scene = recording.scene.snapshot()?;
    let mut rec = Recorder::new(&scene, domain_pddl, options)?;
    rec.set_seed(recording.seed);
    for (i, s) in recording.samples.iter().enumerate() {
        rec.push_sample(s).map_err(|e| match e {
            RecorderError::Input { path, message } => RecorderError::Input {
                path: format!("samples[{i}].{path}"),
                message,
            },
            other => other,
        })?;
    }
    if let Some(goal) = &recording.goal {
        rec.set_goal(goal.clone()).map_err(|e| match e {
            RecorderError::Input { path, message } => RecorderError::Input {
                path: format!("goal{path}"),
                message,
            },
            other => other,
        })?;
    }
    rec.finish()
}
