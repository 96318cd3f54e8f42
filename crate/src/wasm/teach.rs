//! WebAssembly bindings of the demonstration recorder (`Teacher`) and of taught tasks
//! (`Session.fromTaught`, `taughtInfo`): the page's Teach mode. Plain data crosses the boundary;
//! a recording the model cannot explain comes back as data (`ok: false` with the time and the
//! unexplained fact change), never as a half-applied edit.

use super::args::{
    number_arg, object_arg, optional_string_arg, string_arg, type_error, type_name, StringArg,
};
use super::convert::{from_js, js_err, seed_of, to_js};
use super::session::WasmSession;
use crate::recorder::taught::{self, TaughtRunOptions};
use crate::recorder::Edit;
use crate::recorder::{self as rec, GripperHandle, Recorder, RecorderError, RecorderEvent};
use crate::sim::{Benchmark, TaskFolder, FOLDER_FILES};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use tsify::Tsify;
use wasm_bindgen::prelude::*;

/// One recognised action of a recording (the recorder's segment with camelCase names; the
/// recorder's keeps the CLI's).
#[derive(Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
#[tsify(missing_as_null)]
struct Segment {
    /// Position in the demonstration (0-based): the action a_{index+1} leading to L_{index+1}.
    index: usize,
    /// The grounded action, e.g. `(stack panda c b)`.
    action: String,
    /// The arm that carries it out.
    arm: String,
    /// Recording time of the segment's first sample (s).
    t_start: f64,
    /// Recording time of the fact change (s).
    t_event: f64,
    /// Recording time of the segment's last sample (s; provisional for the last segment).
    t_end: f64,
    /// Facts made true.
    added: Vec<String>,
    /// Facts made false.
    removed: Vec<String>,
}

impl From<rec::Segment> for Segment {
    fn from(s: rec::Segment) -> Self {
        Segment {
            index: s.index,
            action: s.action,
            arm: s.arm,
            t_start: s.t_start,
            t_event: s.t_event,
            t_end: s.t_end,
            added: s.added,
            removed: s.removed,
        }
    }
}

/// How well an LQT-CP skill learned from a recorded motion reproduces it (the recorder's fit
/// with camelCase names).
#[derive(Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
#[tsify(missing_as_null)]
struct SkillFit {
    /// The action.
    action: String,
    /// Number of samples (time steps T).
    steps: usize,
    /// Root-mean-square distance between the skill's plan and the recorded positions (m).
    rms_error: f64,
    /// Distance between the plan's end and the recorded end (m).
    goal_error: f64,
}

impl From<rec::SkillFit> for SkillFit {
    fn from(f: rec::SkillFit) -> Self {
        SkillFit {
            action: f.action,
            steps: f.steps,
            rms_error: f.rms_error,
            goal_error: f.goal_error,
        }
    }
}

fn segments_out(segments: Vec<rec::Segment>) -> Vec<Segment> {
    segments.into_iter().map(Segment::from).collect()
}

/// Everything the Teach panel shows.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null)]
struct TeachState {
    /// Recording time (s).
    t: f64,
    /// The benchmark whose workcell and domain the recording uses (none in a task folder).
    benchmark: Option<Benchmark>,
    /// The task folder whose workcell and domain the recording uses, by its name (`./mine`).
    folder: Option<String>,
    /// The actions recognised so far.
    segments: Vec<Segment>,
    /// L_0..L_k: the fluents before the first action and after each.
    states: Vec<Vec<String>>,
    /// The current facts (fluents, sorted).
    facts: Vec<String>,
    /// The world now.
    world: crate::sim::WorldSnapshot,
    /// Each arm's gripper handle.
    handles: Vec<GripperHandle>,
    /// The taught goal, once set (default: every fact of the last state).
    goal: Option<Vec<String>>,
    /// Samples recorded.
    steps: usize,
}

/// Why an edit or the end of a recording was refused.
#[derive(Clone, Copy, Serialize, Tsify)]
#[serde(rename_all = "lowercase")]
enum TeachErrorKind {
    /// The edit is malformed.
    Input,
    /// The domain or the scene cannot be read.
    Model,
    /// A fact change no action of the domain explains.
    Unexplained,
    /// The world refused the motion (a release in mid-air, a collision).
    Physics,
    /// The recorder refused the request (nothing demonstrated, a block still held, …).
    Refused,
}

/// Why an edit or the end of a recording was refused.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null)]
struct TeachError {
    /// Which kind of refusal.
    kind: TeachErrorKind,
    /// One line for people.
    message: String,
    /// Recording time of the refused change (s), when it is about one.
    t: Option<f64>,
    /// Facts the unexplained change made true.
    added: Vec<String>,
    /// Facts the unexplained change made false.
    removed: Vec<String>,
}

/// The result of an edit: the new state, or the refusal (the recording is unchanged).
#[derive(Serialize, Tsify)]
#[serde(untagged)]
#[tsify(missing_as_null)]
enum TeachResult {
    /// The edit was applied.
    #[serde(rename_all = "camelCase")]
    Ok {
        /// Always `true`.
        #[tsify(type = "true")]
        ok: bool,
        /// The state after the edit.
        state: TeachState,
        /// Actions the edit completed.
        new_segments: Vec<Segment>,
        /// What happened in the world (grasps, releases, pushes).
        world_events: Vec<crate::sim::WorldEvent>,
        /// The action an undo removed.
        removed: Option<Segment>,
    },
    /// The edit was refused.
    Err {
        /// Always `false`.
        #[tsify(type = "false")]
        ok: bool,
        /// The state, unchanged.
        state: TeachState,
        /// Why.
        error: TeachError,
    },
}

/// The end of a recording: the `demo.json` text, its listing and the skill fits, or why not.
#[derive(Serialize, Tsify)]
#[serde(untagged)]
#[tsify(missing_as_null)]
enum TeachFinish {
    /// The demonstration.
    #[serde(rename_all = "camelCase")]
    Ok {
        /// Always `true`.
        #[tsify(type = "true")]
        ok: bool,
        /// The taught `demo.json`.
        demo_json: String,
        /// Its actions, states and goal.
        info: taught::TaughtInfo,
        /// How well each learned skill reproduces its recorded motion.
        skills: Vec<SkillFit>,
    },
    /// Why the recording cannot end here.
    Err {
        /// Always `false`.
        #[tsify(type = "false")]
        ok: bool,
        /// Why.
        error: TeachError,
    },
}

fn teach_error(e: &RecorderError) -> TeachError {
    use TeachErrorKind as K;
    let (kind, t, added, removed) = match e {
        RecorderError::Input { .. } => (K::Input, None, vec![], vec![]),
        RecorderError::Model(_) => (K::Model, None, vec![], vec![]),
        RecorderError::Unexplained {
            t, added, removed, ..
        } => (K::Unexplained, Some(*t), added.clone(), removed.clone()),
        RecorderError::Physics { t, .. } => (K::Physics, Some(*t), vec![], vec![]),
        RecorderError::Refused(_) => (K::Refused, None, vec![], vec![]),
    };
    TeachError {
        kind,
        message: e.to_string(),
        t,
        added,
        removed,
    }
}

/// A demonstration being recorded in a benchmark's workcell or a task folder's (the page's Teach
/// mode).
#[wasm_bindgen]
pub struct Teacher {
    inner: Recorder,
    benchmark: Option<Benchmark>,
    /// The task folder of the recording, which its taught demo needs.
    taught_in: Option<TaskFolder>,
}

/// The options of `Teacher.fromFolder`.
#[derive(Debug, Default, Deserialize, Tsify)]
#[serde(deny_unknown_fields)]
#[tsify(missing_as_null)]
pub struct TeachFolderOptions {
    /// The folder's name in messages (default `folder`), as `Session.fromFolder` takes it.
    #[serde(default)]
    #[tsify(optional)]
    pub dir: Option<String>,
    /// Another starting world of the folder's task (a `WorldSnapshot` JSON) than its `scene.json`.
    #[serde(default)]
    #[tsify(optional)]
    pub scene: Option<String>,
}

/// A task folder as the taught-task functions take it: its files by name, and its name.
#[derive(Debug, Deserialize, Tsify)]
#[serde(deny_unknown_fields)]
#[tsify(missing_as_null)]
pub struct TaughtFolder {
    /// The folder's files: `domain.pddl`, `problem.pddl`, `motions.json`, `scene.json`, … by name.
    #[tsify(type = "Record<string, string>")]
    pub files: BTreeMap<String, String>,
    /// The folder's name in messages (default `folder`).
    #[serde(default)]
    #[tsify(optional)]
    pub dir: Option<String>,
}

/// The optional folder argument of a taught-task function, as a [`TaskFolder`].
fn taught_folder(func: &str, folder: &JsValue) -> Result<Option<TaskFolder>, JsValue> {
    if folder.is_undefined() || folder.is_null() {
        return Ok(None);
    }
    object_arg(func, "folder", folder, false)?;
    let f: TaughtFolder = from_js(folder).map_err(|e| js_err(format!("{func}: folder: {e}")))?;
    let files = f
        .files
        .into_iter()
        .filter(|(name, _)| FOLDER_FILES.contains(&name.as_str()))
        .collect();
    Ok(Some(TaskFolder::new(
        f.dir.as_deref().unwrap_or("folder"),
        files,
    )))
}

impl Teacher {
    fn state(&self) -> TeachState {
        TeachState {
            t: self.inner.time(),
            benchmark: self.benchmark,
            folder: self.taught_in.as_ref().map(|f| f.dir.clone()),
            segments: segments_out(self.inner.segments()),
            states: self.inner.demo_states(),
            facts: self.inner.facts().to_vec(),
            world: self.inner.world().snapshot(),
            handles: self.inner.handles(),
            goal: self.inner.goal().map(<[String]>::to_vec),
            steps: self.inner.sample_count(),
        }
    }

    fn result(
        &self,
        r: Result<RecorderEvent, RecorderError>,
        removed: Option<rec::Segment>,
    ) -> TeachResult {
        match r {
            Ok(ev) => TeachResult::Ok {
                ok: true,
                state: self.state(),
                new_segments: segments_out(ev.new_segments),
                world_events: ev.world_events,
                removed: removed.map(Segment::from),
            },
            Err(e) => TeachResult::Err {
                ok: false,
                state: self.state(),
                error: teach_error(&e),
            },
        }
    }
}

#[wasm_bindgen]
impl Teacher {
    /// A recorder on benchmark `b1`, `b2` or `b3`, starting from its template scene or from
    /// `scene` (a `WorldSnapshot` JSON of that benchmark's world).
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "Benchmark")] benchmark: JsValue,
        scene: Option<StringArg>,
    ) -> Result<Teacher, JsValue> {
        let benchmark = string_arg("new Teacher", "benchmark", &benchmark)?;
        let scene = optional_string_arg("new Teacher", "scene", scene)?;
        let b = Benchmark::parse(&benchmark).ok_or_else(|| {
            js_err(format!(
                "unknown benchmark `{benchmark}` (expected b1, b2 or b3)"
            ))
        })?;
        let snapshot = match scene {
            None => b.scene_snapshot(),
            Some(text) => {
                let w = crate::sim::world_from_json(&text)
                    .map_err(js_err)?
                    .with_motions(b.motions());
                if w.name() != b.dir_name() {
                    return Err(js_err(format!(
                        "the scene is the world `{}`, not {}",
                        w.name(),
                        b.dir_name()
                    ))
                    .into());
                }
                w.snapshot()
            }
        };
        let inner = Recorder::new(
            &snapshot,
            b.domain_pddl(),
            crate::recorder::RecorderOptions {
                domain_file: format!("domains/{}/domain.pddl", b.dir_name()),
                ..Default::default()
            },
        )
        .map_err(js_err)?;
        Ok(Teacher {
            inner,
            benchmark: Some(b),
            taught_in: None,
        })
    }

    /// A recorder in a task folder's workcell (its files by name, as `Session.fromFolder` takes
    /// them), starting from its `scene.json` or `options.scene`; errors name the folder's file.
    #[wasm_bindgen(js_name = fromFolder)]
    pub fn from_folder(
        #[wasm_bindgen(unchecked_param_type = "Record<string, string>")] files: JsValue,
        #[wasm_bindgen(unchecked_param_type = "TeachFolderOptions | undefined")] options: JsValue,
    ) -> Result<Teacher, JsValue> {
        const F: &str = "Teacher.fromFolder";
        let files = super::folder::folder_files(F, &files)?;
        object_arg(F, "options", &options, true)?;
        let o: TeachFolderOptions = if options.is_undefined() || options.is_null() {
            TeachFolderOptions::default()
        } else {
            from_js(&options).map_err(|e| js_err(format!("options: {e}")))?
        };
        let folder = TaskFolder::new(o.dir.as_deref().unwrap_or("folder"), files);
        let scene = match &o.scene {
            Some(text) => Some(
                crate::sim::world_from_json(text)
                    .map_err(|e| js_err(format!("scene: {e}")))?
                    .snapshot(),
            ),
            None => None,
        };
        let inner = Recorder::for_folder(&folder, scene.as_ref()).map_err(js_err)?;
        Ok(Teacher {
            inner,
            benchmark: None,
            taught_in: Some(folder),
        })
    }

    /// The current state (segments, demo states L0..Lk, facts, world, gripper handles).
    #[wasm_bindgen(unchecked_return_type = "TeachState")]
    pub fn current(&self) -> Result<JsValue, JsValue> {
        to_js(&self.state())
    }

    /// Applies one edit, all or nothing. A refused edit (bad data, a change the domain cannot
    /// explain, a release in mid-air, …) comes back as `ok: false` with its time and fact change.
    #[wasm_bindgen(unchecked_return_type = "TeachResult")]
    pub fn push(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "TeachEdit")] edit: JsValue,
    ) -> Result<JsValue, JsValue> {
        object_arg("Teacher.push", "edit", &edit, false)?;
        let r = match from_js::<Edit>(&edit) {
            Ok(edit) => self.inner.push(&edit),
            Err(message) => Err(RecorderError::Input {
                path: "edit".into(),
                message,
            }),
        };
        to_js(&self.result(r, None))
    }

    /// Removes the last recognised action and rewinds the world to the end of the one before.
    #[wasm_bindgen(unchecked_return_type = "TeachResult")]
    pub fn undo(&mut self) -> Result<JsValue, JsValue> {
        let r = self.inner.undo_last_segment();
        let out = match r {
            Ok(removed) => self.result(
                Ok(RecorderEvent {
                    t: self.inner.time(),
                    new_segments: vec![],
                    world_events: vec![],
                    facts: self.inner.facts().to_vec(),
                }),
                removed,
            ),
            Err(e) => self.result(Err(e), None),
        };
        to_js(&out)
    }

    /// Sets the taught goal (facts that must hold at the end; default: every fact of L_N).
    #[wasm_bindgen(js_name = setGoal, unchecked_return_type = "TeachResult")]
    pub fn set_goal(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "string[]")] goal: JsValue,
    ) -> Result<JsValue, JsValue> {
        let goal: Vec<String> = match from_js(&goal) {
            Ok(g) if goal.is_array() => g,
            _ => {
                return Err(type_error(&format!(
                    "Teacher.setGoal: goal must be an array of strings, got {}",
                    type_name(&goal)
                )))
            }
        };
        let r = self.inner.set_goal(goal).map(|_| RecorderEvent {
            t: self.inner.time(),
            new_segments: vec![],
            world_events: vec![],
            facts: self.inner.facts().to_vec(),
        });
        to_js(&self.result(r, None))
    }

    /// Ends the recording: the taught `demo.json` (text), its listing and the skill fits, or why
    /// not (nothing demonstrated, a block still held, a goal fact that does not hold).
    #[wasm_bindgen(unchecked_return_type = "TeachFinish")]
    pub fn finish(&self) -> Result<JsValue, JsValue> {
        let out = match self.inner.finish().and_then(|t| {
            let json =
                serde_json::to_string(&t.demo).map_err(|e| RecorderError::Model(e.to_string()))?;
            let (_, info) = taught::load(&json, self.taught_in.as_ref())?;
            Ok((json, info, t.skills))
        }) {
            Ok((demo_json, info, skills)) => TeachFinish::Ok {
                ok: true,
                demo_json,
                info,
                skills: skills.into_iter().map(SkillFit::from).collect(),
            },
            Err(e) => TeachFinish::Err {
                ok: false,
                error: teach_error(&e),
            },
        };
        to_js(&out)
    }

    /// The raw recording so far (what `logic-lfd demo segment` reads).
    #[wasm_bindgen(js_name = recordingJson)]
    pub fn recording_json(&self) -> String {
        self.inner.recording().to_json()
    }
}

/// Checks a taught `demo.json` completely and lists its actions, states L0..LN and goal. Rejects
/// with the key and what is wrong.
#[wasm_bindgen(js_name = taughtInfo, unchecked_return_type = "TaughtInfo")]
pub fn taught_info(
    #[wasm_bindgen(js_name = "demoJson", unchecked_param_type = "string")] demo_json: JsValue,
    #[wasm_bindgen(unchecked_param_type = "TaughtFolder | undefined")] folder: JsValue,
) -> Result<JsValue, JsValue> {
    let demo_json = string_arg("taughtInfo", "demoJson", &demo_json)?;
    let folder = taught_folder("taughtInfo", &folder)?;
    let (_, info) = taught::load(&demo_json, folder.as_ref()).map_err(js_err)?;
    to_js(&info)
}

/// A seeded random initial world (scene JSON) for a taught task.
#[wasm_bindgen(js_name = taughtRandomScene)]
pub fn taught_random_scene(
    #[wasm_bindgen(js_name = "demoJson", unchecked_param_type = "string")] demo_json: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number")] seed: JsValue,
    #[wasm_bindgen(unchecked_param_type = "TaughtFolder | undefined")] folder: JsValue,
) -> Result<String, JsValue> {
    let demo_json = string_arg("taughtRandomScene", "demoJson", &demo_json)?;
    let seed = number_arg("taughtRandomScene", "seed", &seed)?;
    let folder = taught_folder("taughtRandomScene", &folder)?;
    Ok(taught::random_scene(&demo_json, seed_of(seed)?, folder.as_ref()).map_err(js_err)?)
}

#[wasm_bindgen(js_class = Session)]
impl WasmSession {
    /// A session running a taught task (`demo.json` from `Teacher.finish`) from the taught scene,
    /// a scene the user arranged (`options.scene`) or a seeded random one (`options.random`); a
    /// task taught in a folder needs that `folder`.
    #[wasm_bindgen(js_name = fromTaught)]
    pub fn from_taught(
        #[wasm_bindgen(js_name = "demoJson", unchecked_param_type = "string")] demo_json: JsValue,
        #[wasm_bindgen(unchecked_param_type = "TaughtRunOptions | undefined")] options: JsValue,
        #[wasm_bindgen(unchecked_param_type = "TaughtFolder | undefined")] folder: JsValue,
    ) -> Result<WasmSession, JsValue> {
        let demo_json = string_arg("Session.fromTaught", "demoJson", &demo_json)?;
        object_arg("Session.fromTaught", "options", &options, true)?;
        let o: TaughtRunOptions = if options.is_undefined() || options.is_null() {
            TaughtRunOptions::default()
        } else {
            from_js(&options).map_err(|e| js_err(format!("options: {e}")))?
        };
        let folder = taught_folder("Session.fromTaught", &folder)?;
        let inner = taught::session(&demo_json, &o, folder.as_ref()).map_err(js_err)?;
        Ok(WasmSession::from(inner))
    }

    /// Re-runs the logged episode of a taught task (from `episodeJson()`) exactly; a task taught
    /// in a folder needs that `folder`.
    #[wasm_bindgen(js_name = replayTaught)]
    pub fn replay_taught(
        #[wasm_bindgen(unchecked_param_type = "string")] episode: JsValue,
        #[wasm_bindgen(unchecked_param_type = "TaughtFolder | undefined")] folder: JsValue,
    ) -> Result<WasmSession, JsValue> {
        let episode = string_arg("Session.replayTaught", "episode", &episode)?;
        let folder = taught_folder("Session.replayTaught", &folder)?;
        let inner = taught::replay(&episode, folder.as_ref()).map_err(js_err)?;
        Ok(WasmSession::from(inner))
    }
}
