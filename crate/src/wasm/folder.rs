//! Task folders in the npm package: `Session.fromFolder(files, options)`, the folder of
//! `runEpisode`, the files a folder session runs on (`Session.taskFiles`), and episode logs that
//! carry their folder's files (`episodeJson({ withFiles: true })`) so `Session.replay` needs
//! nothing else.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use tsify::Tsify;
use wasm_bindgen::prelude::*;

use super::args::{object_arg, type_error};
use super::convert::{from_js, js_err, to_js};
use super::session::WasmSession;
use crate::lfd::{Method, Mode, SessionError, SessionOptions, SessionParams, SkillKind};
use crate::sim::{Benchmark, BenchmarkSources, TaskFolder, FOLDER_FILES};

/// The options of `Session.fromFolder`: a session's options without a benchmark (the folder is
/// the task), and the folder's name in messages.
#[derive(Debug, Deserialize, Tsify)]
#[serde(deny_unknown_fields)]
#[tsify(missing_as_null)]
pub struct FolderOptions {
    /// The folder's name in messages and in the episode log (default `folder`; a name without a
    /// `/` reads `./NAME`, so messages say `./NAME/scene.json: …`).
    #[serde(default)]
    #[tsify(optional)]
    pub dir: Option<String>,
    /// The method that closes the loop (default `logic-lfd`).
    #[serde(default)]
    #[tsify(optional)]
    pub method: Method,
    /// Logic-LfD's multi-goal mode (default `paper`).
    #[serde(default)]
    #[tsify(optional)]
    pub mode: Mode,
    /// Seed of every random choice of the episode (default 0).
    #[serde(default)]
    #[tsify(optional)]
    pub seed: u64,
    /// The motion skill family (default `lqt`).
    #[serde(default)]
    #[tsify(optional)]
    pub skill: SkillKind,
    /// Another starting world (a saved `WorldSnapshot` JSON, as `Session.fromScene` takes) than
    /// the folder's `scene.json`.
    #[serde(default)]
    #[tsify(optional)]
    pub scene: Option<String>,
}

/// The texts of the task a session runs: its PDDL domain and problem, and its demonstration's
/// actions as a plan (one a line), for showing next to the run.
#[derive(Debug, Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
pub struct TaskFiles {
    /// `domain.pddl`.
    pub domain: String,
    /// `problem.pddl` (a generated N-block task's own problem, not its benchmark's template).
    pub problem: String,
    /// The demonstration's actions, one a line.
    pub demo_plan: String,
    /// Where the files come from: `domains/b1-tower`, a generated task's name, or the folder.
    pub dir: String,
}

#[wasm_bindgen]
extern "C" {
    /// `Session.fromFolder`'s optional options.
    #[wasm_bindgen(typescript_type = "FolderOptions & { robot?: RobotChoice }")]
    pub type FolderOptionsArg;
}

/// A folder's files from JS: a plain object mapping file names to their text. Names outside
/// [`FOLDER_FILES`] are ignored, as a directory's other files are.
pub(super) fn folder_files(
    func: &str,
    files: &JsValue,
) -> Result<BTreeMap<String, String>, JsValue> {
    object_arg(func, "files", files, false)?;
    let all: BTreeMap<String, serde_json::Value> =
        from_js(files).map_err(|e| js_err(format!("files: {e}")))?;
    let mut out = BTreeMap::new();
    for (name, v) in all {
        if !FOLDER_FILES.contains(&name.as_str()) {
            continue;
        }
        match v {
            serde_json::Value::String(text) => {
                out.insert(name, text);
            }
            other => {
                return Err(type_error(&format!(
                    "{func}: files[\"{name}\"] must be the file's text (a string), got {}",
                    super::args::json_type_name(&other)
                )))
            }
        }
    }
    Ok(out)
}

/// A session error on `folder`'s files, naming the file at fault: the core names PDDL and
/// `motions.json` errors by path already; a scene or demonstration error names its file here.
pub(super) fn named(folder: &TaskFolder, e: SessionError) -> String {
    match e {
        SessionError::Scene(s) => format!("{}: {s}", folder.path("scene.json")),
        SessionError::Json(m) => match m.strip_prefix("demo: ") {
            Some(rest) if folder.files.contains_key("demo.json") => {
                format!("{}: {rest}", folder.path("demo.json"))
            }
            _ => m,
        },
        e => e.to_string(),
    }
}

/// A session on `folder`'s task with `options`.
pub(super) fn session(
    folder: &TaskFolder,
    o: FolderOptions,
) -> Result<crate::lfd::Session, String> {
    let sources = folder.sources().map_err(|e| e.to_string())?;
    let scene = o.scene.clone();
    let options = SessionOptions {
        // The folder is the task; the benchmark only labels the log.
        benchmark: Benchmark::B1,
        method: o.method,
        mode: o.mode,
        seed: o.seed,
        skill: o.skill,
        blocks: None,
    };
    if let Some(scene) = &scene {
        // The folder's own scene is still the demonstration's: an error there names its file.
        crate::sim::world_from_json(&sources.scene)
            .map_err(|e| format!("{}: {e}", folder.path("scene.json")))?;
        crate::sim::world_from_json(scene).map_err(|e| format!("scene: {e}"))?;
    }
    crate::lfd::Session::with_sources(
        options,
        &sources,
        scene.as_deref(),
        None,
        SessionParams::default(),
    )
    .map_err(|e| named(folder, e))
}

/// The demonstration's actions of `demo_json` as a plan, one a line.
fn demo_plan(demo_json: &str) -> String {
    crate::lfd::demo_actions(demo_json)
        .map(|a| a.iter().map(|a| format!("{a}\n")).collect())
        .unwrap_or_default()
}

/// The texts of `sources` as [`TaskFiles`].
fn task_files(sources: &BenchmarkSources) -> TaskFiles {
    TaskFiles {
        domain: sources.domain.clone(),
        problem: sources.problem.clone(),
        demo_plan: demo_plan(&sources.demo),
        dir: sources.dir.clone(),
    }
}

#[wasm_bindgen(js_class = Session)]
impl WasmSession {
    /// A session on a task folder given as its files: an object mapping `domain.pddl`,
    /// `problem.pddl`, `motions.json`, `scene.json` and `demo.json` or `expert.json` (optionally
    /// `demo.plan`, `README.md`) to their text. Rejects a missing or broken file with an `Error`
    /// naming it (`./mine/scene.json: …`), as the CLI does.
    #[wasm_bindgen(js_name = fromFolder)]
    pub fn from_folder(
        #[wasm_bindgen(unchecked_param_type = "Record<string, string>")] files: JsValue,
        options: Option<FolderOptionsArg>,
    ) -> Result<WasmSession, JsValue> {
        const F: &str = "Session.fromFolder";
        let files = folder_files(F, &files)?;
        let options = options.map(JsValue::from).unwrap_or(JsValue::UNDEFINED);
        object_arg(F, "options", &options, true)?;
        let (options, robots) = super::robot::take_robots(F, &options)?;
        let o: FolderOptions = if options.is_undefined() || options.is_null() {
            FolderOptions::deserialize(serde_json::json!({})).map_err(js_err)?
        } else {
            from_js(&options).map_err(|e| js_err(format!("options: {e}")))?
        };
        let folder = TaskFolder::new(o.dir.as_deref().unwrap_or("folder"), files);
        let mut inner = session(&folder, o).map_err(js_err)?;
        inner
            .set_robots(&robots)
            .map_err(|e| js_err(named(&folder, e)))?;
        Ok(WasmSession {
            inner,
            folder: Some(folder),
            progress: None,
        })
    }

    /// The task the session runs: its domain, problem (a generated N-block task's own, a task
    /// folder's) and demonstration plan.
    #[wasm_bindgen(js_name = taskFiles, unchecked_return_type = "TaskFiles")]
    pub fn task_files(&self) -> Result<JsValue, JsValue> {
        let sources = match &self.folder {
            Some(folder) => folder.sources().map_err(js_err)?,
            None => {
                let o = self.inner.options();
                crate::lfd::sources_for(o.benchmark, o.blocks).map_err(js_err)?
            }
        };
        to_js(&task_files(&sources))
    }

    /// The task folder's files the session runs on, by name (`null` on a benchmark's task).
    #[wasm_bindgen(js_name = folderFiles, unchecked_return_type = "Record<string, string> | null")]
    pub fn folder_files(&self) -> Result<JsValue, JsValue> {
        to_js(&self.folder.as_ref().map(|f| &f.files))
    }
}
