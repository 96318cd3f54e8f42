//! The recorder's shared types: its tunables and errors, recognised segments and events,
//! skill fits and the taught demonstration.

use crate::sim::demo::Demonstration;
use crate::sim::WorldEvent;
use crate::sim::WorldSnapshot;
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

/// The result of [`Recorder::finish`](super::Recorder::finish).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Taught {
    /// The demonstration to save as `demo.json`.
    pub demo: TaughtDemo,
    /// L_0..L_N (fluents, sorted), derived by applying the actions.
    pub states: Vec<Vec<String>>,
    /// One fit per skill the loop learns from the demo — the approach and the retreat of every
    /// action ([`taught::skill_fits`](super::taught::skill_fits)); empty when [`RecorderParams::learn_skills`] is off.
    pub skills: Vec<SkillFit>,
}
