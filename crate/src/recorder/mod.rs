//! Teach it yourself: record a demonstration in the simulator and segment it into the symbolic
//! actions of a PDDL domain, producing a `demo.json` like `domains/*/demo.json`.
//!
//! # What the recorder does
//!
//! A recording is a stream of *edits* of a world (a [`WorldSnapshot`]): gripper samples (the user
//! moves the gripper — a 3-D handle with a position, a yaw and open/close — and the arm follows by
//! IK), hand moves of a block (the user displaces a block directly), or, in the quicker mode, block
//! drags and hook pulls for which the recorder synthesises the arm motion ([`synth`]). Each edit is
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
pub mod recording;
pub mod synth;
pub mod taught;

pub use engine::{GripperHandle, Recorder, RecorderOptions};
pub use recording::{ArmRef, GripperPose, RawRecording, RawSample, RecordingScene};

use crate::sim::demo::Demonstration;
use crate::sim::snapshot::WorldSnapshot;
use crate::sim::WorldEvent;
use serde::{Deserialize, Serialize};

/// Tunables of the recorder (metres, seconds).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct RecorderParams {
    /// Largest drop of a released body onto its support still counted as putting it down (m);
    /// a higher release is "a release in mid-air".
    pub max_release_drop: f64,
    /// Rise of the TCP after an action's event that ends the action's lift (m).
    pub lift_height: f64,
    /// TCP displacement per step below which an arm counts as still (m).
    pub still_per_step: f64,
    /// Most simulator steps one recording may take (bounds the work on hostile input).
    pub max_steps: usize,
    /// Learn the LQT-CP skills from each action's motion and report their fit ([`SkillFit`]).
    pub learn_skills: bool,
}

impl Default for RecorderParams {
    fn default() -> Self {
        RecorderParams {
            max_release_drop: 0.02,
            lift_height: 0.04,
            still_per_step: 2e-4,
            max_steps: 200_000,
            learn_skills: true,
        }
    }
}

/// Why a recording or an edit was refused. Display gives the whole message.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RecorderError {
    /// A malformed recording or edit: the JSON key path and what is wrong.
    #[error("{path}: {message}")]
    Input {
        /// Key path such as `samples[12].pose.position[2]`.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// The PDDL model could not be read or does not fit the scene.
    #[error("{0}")]
    Model(String),
    /// A fact change the domain's action schemas cannot explain.
    #[error("at t = {t:.2} s: the change {} is not explained by any action of the domain{hint}", change_text(.added, .removed))]
    Unexplained {
        /// Recording time of the change (s).
        t: f64,
        /// Facts that became true.
        added: Vec<String>,
        /// Facts that became false.
        removed: Vec<String>,
        /// The closest operator and why it does not fit (empty or starting with `; `).
        hint: String,
    },
    /// Something physically implausible (a release in mid-air, a body falling, interpenetration).
    #[error("at t = {t:.2} s: {message}")]
    Physics {
        /// Recording time (s).
        t: f64,
        /// What happened.
        message: String,
    },
    /// A quick-mode edit or a finishing step that cannot be done (the reason in words).
    #[error("{0}")]
    Refused(String),
}

pub(crate) fn change_text(added: &[String], removed: &[String]) -> String {
    let mut parts: Vec<String> = added.iter().map(|f| format!("+{f}")).collect();
    parts.extend(removed.iter().map(|f| format!("-{f}")));
    if parts.is_empty() {
        "(none)".into()
    } else {
        parts.join(" ")
    }
}

/// One recognised action of the recording, as the page lists it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    /// Position in the demonstration (0-based): the action a_{index+1} leading to L_{index+1}.
    pub index: usize,
    /// The grounded action, e.g. `(stack panda c b)`.
    pub action: String,
    /// The arm that carries it out.
    pub arm: String,
    /// Recording time of the segment's first sample (s).
    pub t_start: f64,
    /// Recording time of the fact change (s).
    pub t_event: f64,
    /// Recording time of the segment's last sample (s; provisional for the last segment).
    pub t_end: f64,
    /// Facts made true.
    pub added: Vec<String>,
    /// Facts made false.
    pub removed: Vec<String>,
}

/// What one accepted edit did.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RecorderEvent {
    /// Recording time after the edit (s).
    pub t: f64,
    /// Actions recognised during the edit.
    pub new_segments: Vec<Segment>,
    /// What happened in the world (grasps, releases, pushes).
    pub world_events: Vec<WorldEvent>,
    /// The current facts (fluents, sorted).
    pub facts: Vec<String>,
}

/// How well an LQT-CP skill learned from one recorded action reproduces it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SkillFit {
    /// The action.
    pub action: String,
    /// Number of samples (time steps T).
    pub steps: usize,
    /// Root-mean-square distance between the skill's plan (from the demo's start) and the
    /// recorded positions (m).
    pub rms_error: f64,
    /// Distance between the plan's end and the recorded end (m).
    pub goal_error: f64,
}

/// A taught demonstration: the `demo.json` fields of [`Demonstration`] plus what a taught task
/// needs beyond a benchmark's fixed template (older readers ignore the extra fields).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TaughtDemo {
    /// The demonstration, in the `domains/*/demo.json` format.
    #[serde(flatten)]
    pub demo: Demonstration,
    /// The PDDL domain name.
    pub domain: String,
    /// L_0: the fluents of the initial world.
    pub initial_facts: Vec<String>,
    /// The taught goal G (default: every fluent of L_N).
    pub goal: Vec<String>,
    /// The initial world (replaying the demo from it reproduces the recording).
    pub scene: WorldSnapshot,
}

/// The result of [`Recorder::finish`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Taught {
    /// The demonstration to save as `demo.json`.
    pub demo: TaughtDemo,
    /// L_0..L_N (fluents, sorted), derived by applying the actions.
    pub states: Vec<Vec<String>>,
    /// One fit per skill the loop learns from the demo — the approach and the retreat of every
    /// action ([`taught::skill_fits`]); empty when [`RecorderParams::learn_skills`] is off.
    pub skills: Vec<SkillFit>,
}

/// Segments a whole raw recording against a PDDL domain (the CLI's `demo segment`): replays every
/// sample, checks every fact change, and returns the demonstration or the first error.
/// `problem_pddl` (optional) supplies static facts (e.g. B3's `reaches`); without it they come
/// from the benchmark named by the recording or the scene.
pub fn segment_recording(
    recording: &RawRecording,
    domain_pddl: &str,
    domain_file: &str,
    problem: Option<(&str, &str)>,
    params: RecorderParams,
) -> Result<Taught, RecorderError> {
    let scene = recording.scene.snapshot()?;
    let options = RecorderOptions {
        domain_file: domain_file.to_string(),
        problem_pddl: problem.map(|(t, f)| (t.to_string(), f.to_string())),
        motions_json: None,
        params,
    };
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
