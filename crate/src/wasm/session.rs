//! The closed-loop session (`Session`): one episode of paper Algorithm 1 in the kinematic
//! workcell, stepped from JS. Its frames cross the boundary with camelCase names (the world
//! snapshot inside keeps the scene file's names; the episode log keeps the CLI's).

use super::args::{number_arg, object_arg, string_arg, type_error, type_name};
use super::convert::{from_js, js_err, seed_of, to_js, PerformanceClock};
use crate::lfd::{self as core, EePoint, Status};
use crate::sim::WorldSnapshot;
use serde::Serialize;
use tsify::Tsify;
use wasm_bindgen::prelude::*;

/// Everything the page draws after a step (the session's frame, with camelCase names).
#[derive(Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
#[tsify(missing_as_null)]
struct Frame<'a> {
    /// Simulated seconds.
    t: f64,
    /// 10 ms steps so far.
    tick: u64,
    /// Every body pose, arm joints and link capsules, grippers.
    world: &'a WorldSnapshot,
    /// The status line.
    status: &'a Status,
    /// The current plan, actions as `(stack a b)`.
    plan: &'a [String],
    /// Index into `plan` of the action being executed.
    executing: Option<usize>,
    /// The demonstration's actions a_1..a_N.
    demo: &'a [String],
    /// L_0..L_N (fluents).
    demo_states: &'a [Vec<String>],
    /// Demonstration state index the current plan joins.
    matched_k: Option<usize>,
    /// S_C, sorted.
    facts: &'a [String],
    /// Facts that appeared since the previous frame.
    facts_added: &'a [String],
    /// Facts that disappeared since the previous frame.
    facts_removed: &'a [String],
    /// The last replan.
    last_replan: Option<Replan<'a>>,
    /// Number of replans so far.
    replans: usize,
    /// End effector positions and targets.
    ee: &'a [EePoint],
}

/// The last replan: why, how long it took, which demonstration state it joined, the plan it made
/// and how many of its leading actions are new (the controller's replan with camelCase names; the
/// episode log, `episodeJson()`, keeps the snake_case names of the CLI's JSON: `time_ms`,
/// `new_actions`).
#[derive(Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
#[tsify(missing_as_null)]
struct Replan<'a> {
    /// Why: `start`, `(on c d) no longer holds`, `(on e b) appeared`, …
    reason: &'a str,
    /// Planning time in milliseconds.
    time_ms: f64,
    /// The demonstration state index the plan joins.
    k: Option<usize>,
    /// The new plan.
    plan: &'a [String],
    /// Simulation tick when it happened.
    tick: u64,
    /// How many leading actions of the plan are new (not from the demonstration).
    new_actions: usize,
    /// Part of `timeMs` spent binding actions to motions.
    bind_ms: f64,
    /// States the searches expanded.
    expanded: u64,
    /// Logic-LfD planned to G from scratch (its TAMP fallback).
    fallback: bool,
    /// Logic-LfD: every candidate L_k (k null: G) with the costs its search found; empty for the
    /// other methods.
    alternatives: &'a [crate::lfd::Alternative],
}

/// An accepted drag: where the block went, what it rests on, what settled after it left (the
/// world's move outcome with camelCase names).
#[derive(Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
#[tsify(missing_as_null)]
struct PerturbOutcome<'a> {
    /// The block moved.
    body: &'a str,
    /// Its centre before (m).
    from: [f64; 3],
    /// Its centre after settling (m).
    to: [f64; 3],
    /// What it rests on.
    support: &'a str,
    /// Bodies that settled after it left: name and new centre (m).
    also_moved: &'a [(String, [f64; 3])],
}

/// A frame as plain JS data, camelCase.
fn frame_js(f: &core::Frame) -> Result<JsValue, JsValue> {
    let last_replan = f.last_replan.as_ref().map(|r: &crate::lfd::Replan| Replan {
        reason: &r.reason,
        time_ms: r.time_ms,
        k: r.k,
        plan: &r.plan,
        tick: r.tick,
        new_actions: r.new_actions,
        bind_ms: r.bind_ms,
        expanded: r.expanded,
        fallback: r.fallback,
        alternatives: &r.alternatives,
    });
    to_js(&Frame {
        t: f.t,
        tick: f.tick,
        world: &f.world,
        status: &f.status,
        plan: &f.plan,
        executing: f.executing,
        demo: &f.demo,
        demo_states: &f.demo_states,
        matched_k: f.matched_k,
        facts: &f.facts,
        facts_added: &f.facts_added,
        facts_removed: &f.facts_removed,
        last_replan,
        replans: f.replans,
        ee: &f.ee,
    })
}

fn perturb_js(o: &core::PerturbOutcome) -> Result<JsValue, JsValue> {
    to_js(&PerturbOutcome {
        body: &o.body,
        from: o.from,
        to: o.to,
        support: &o.support,
        also_moved: &o.also_moved,
    })
}

/// The session options object of `func`, or a `TypeError` / an `Error` naming the bad key.
pub(super) fn session_options(
    func: &str,
    options: &JsValue,
) -> Result<crate::lfd::SessionOptions, JsValue> {
    object_arg(func, "options", options, false)?;
    Ok(from_js(options).map_err(|e| js_err(format!("options: {e}")))?)
}

/// One closed-loop episode (paper Algorithm 1) in a kinematic workcell: step it, draw its frames,
/// disturb it. Wraps `lfd::Session` 1:1; every method returns plain data (see `Frame`).
#[wasm_bindgen(js_name = Session)]
pub struct WasmSession {
    pub(super) inner: crate::lfd::Session,
    /// The task folder the session runs on (its files, for a log that carries them).
    pub(super) folder: Option<crate::sim::TaskFolder>,
    /// `onProgress`'s listener.
    #[cfg(feature = "wasm")]
    pub(super) progress: Option<js_sys::Function>,
}

impl From<crate::lfd::Session> for WasmSession {
    fn from(inner: crate::lfd::Session) -> WasmSession {
        WasmSession {
            inner,
            folder: None,
            #[cfg(feature = "wasm")]
            progress: None,
        }
    }
}

/// The options of `Session.episodeJson`.
#[derive(Tsify)]
#[serde(rename_all = "camelCase")]
#[allow(dead_code)]
struct EpisodeJsonOptions {
    /// A task folder's episode carries the folder's files (`log.folder.files`), so
    /// `Session.replay` re-runs it without the folder; no effect on a benchmark's episode.
    #[tsify(optional)]
    with_files: bool,
}

#[wasm_bindgen]
extern "C" {
    /// `episodeJson`'s optional options (`{ withFiles: true }`).
    #[wasm_bindgen(typescript_type = "EpisodeJsonOptions")]
    pub type EpisodeJsonOptionsArg;
}

#[wasm_bindgen(js_class = Session)]
impl WasmSession {
    /// A session on one of the benchmarks (`{ benchmark: "b1", method: "logic-lfd", mode: "paper",
    /// seed: 1 }`). Rejects unknown options with a message; a non-object is a `TypeError`.
    ///
    /// `robot` (full module) puts a robot in the arms' place: `"panda"` (the Franka Emika Panda
    /// from its URDF), `"ur5"`, a robot folder's files, or one per arm.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "SessionOptions & { robot?: RobotChoice }")]
        options: JsValue,
    ) -> Result<WasmSession, JsValue> {
        #[cfg(not(first_load))]
        let (options, robots) = super::robot::take_robots("new Session", &options)?;
        let o = session_options("new Session", &options)?;
        #[allow(unused_mut)]
        let mut inner = crate::lfd::Session::new(o).map_err(js_err)?;
        #[cfg(not(first_load))]
        inner.set_robots(&robots).map_err(js_err)?;
        Ok(WasmSession::from(inner))
    }

    /// A session on a benchmark's task in a different starting scene (a saved `WorldSnapshot`
    /// JSON), optionally with another demonstration (`demo.json` text).
    // Not in the page's first-load module: the page loads files on the full module, whose errors
    // name the JSON path of the value at fault.
    #[cfg(not(first_load))]
    #[wasm_bindgen(js_name = fromScene)]
    pub fn from_scene(
        #[wasm_bindgen(unchecked_param_type = "SessionOptions & { robot?: RobotChoice }")]
        options: JsValue,
        #[wasm_bindgen(unchecked_param_type = "string")] scene: JsValue,
        demo: Option<super::args::StringArg>,
    ) -> Result<WasmSession, JsValue> {
        const F: &str = "Session.fromScene";
        let (options, robots) = super::robot::take_robots(F, &options)?;
        let o = session_options(F, &options)?;
        let scene = string_arg(F, "scene", &scene)?;
        let demo = super::args::optional_string_arg(F, "demo", demo)?;
        let mut inner =
            crate::lfd::Session::from_scene(o, &scene, demo.as_deref()).map_err(js_err)?;
        inner.set_robots(&robots).map_err(js_err)?;
        Ok(WasmSession::from(inner))
    }

    /// Re-runs a logged episode (from `episodeJson()`) and returns the session at its end.
    #[cfg(feature = "wasm")]
    pub fn replay(
        #[wasm_bindgen(unchecked_param_type = "string")] episode: JsValue,
    ) -> Result<WasmSession, JsValue> {
        let episode = string_arg("Session.replay", "episode", &episode)?;
        let inner = crate::lfd::Session::replay(&episode).map_err(js_err)?;
        // A folder episode replays on the files it carries: keep them for the next log.
        let folder = crate::sim::parse_json::<crate::lfd::EpisodeLog>(&episode)
            .ok()
            .and_then(|log| log.folder)
            .and_then(|record| crate::sim::TaskFolder::from_record(&record));
        Ok(WasmSession {
            inner,
            folder,
            progress: None,
        })
    }

    /// Advances the episode by `dt` simulated seconds (whole 10 ms ticks; replans happen inside)
    /// and returns the new frame.
    #[wasm_bindgen(unchecked_return_type = "Frame")]
    pub fn step(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "number")] dt: JsValue,
    ) -> Result<JsValue, JsValue> {
        let dt = number_arg("Session.step", "dt", &dt)?;
        if !dt.is_finite() || dt < 0.0 {
            return Err(js_err(format!(
                "dt must be a non-negative number of seconds, got {dt}"
            ))
            .into());
        }
        #[cfg(feature = "wasm")]
        let f = match &self.progress {
            Some(callback) => self
                .inner
                .step(dt, &super::progress::ProgressClock::new(callback)),
            None => self.inner.step(dt, &PerformanceClock),
        };
        #[cfg(not(feature = "wasm"))]
        let f = self.inner.step(dt, &PerformanceClock);
        frame_js(&f)
    }

    /// Calls `callback(expanded, ms)` while a search inside `step` runs: every 100 ms of wall
    /// time at most, the states the current search has expanded and the step's milliseconds so
    /// far. A step shorter than 100 ms calls nothing; `null` stops the calls.
    #[cfg(feature = "wasm")]
    #[wasm_bindgen(js_name = onProgress)]
    pub fn on_progress(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "((expanded: number, ms: number) => void) | null")]
        callback: Option<js_sys::Function>,
    ) {
        self.progress = callback;
    }

    /// The current frame, without stepping.
    #[wasm_bindgen(unchecked_return_type = "Frame")]
    pub fn frame(&self) -> Result<JsValue, JsValue> {
        frame_js(&self.inner.frame())
    }

    /// Moves a block as a user's drag does: to `position` (m), then it settles. Rejects with the
    /// reason when the world refuses (the block would float, collide, …).
    #[wasm_bindgen(unchecked_return_type = "PerturbOutcome")]
    pub fn perturb(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "string")] body: JsValue,
        #[wasm_bindgen(unchecked_param_type = "[number, number, number]")] position: JsValue,
    ) -> Result<JsValue, JsValue> {
        const F: &str = "Session.perturb";
        let body = string_arg(F, "body", &body)?;
        let bad = || {
            type_error(&format!(
                "{F}: position must be [x, y, z] (three finite numbers), got {}",
                type_name(&position)
            ))
        };
        if !position.is_array() {
            return Err(bad());
        }
        let p: [f64; 3] = from_js::<Vec<f64>>(&position)
            .ok()
            .and_then(|v| v.try_into().ok())
            .ok_or_else(bad)?;
        if p.iter().any(|v| !v.is_finite()) {
            return Err(js_err("position must be finite").into());
        }
        let out = self
            .inner
            .perturb(&body, p)
            .map_err(|r| js_err(format!("cannot move {}: {}", r.body, r.reason)))?;
        perturb_js(&out)
    }

    /// Injects a disturbance of level `l1`..`l4` and says what it did.
    #[wasm_bindgen(unchecked_return_type = "Injection")]
    pub fn inject(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Level")] level: JsValue,
    ) -> Result<JsValue, JsValue> {
        let level = string_arg("Session.inject", "level", &level)?;
        let out = self.inner.inject(&level).map_err(js_err)?;
        to_js(&out)
    }

    /// Why `inject(level)` would be refused now, or `undefined` when it would apply; changes
    /// nothing (the page enables its L1–L4 buttons with it).
    #[wasm_bindgen(js_name = canInject)]
    pub fn can_inject(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Level")] level: JsValue,
    ) -> Result<Option<String>, JsValue> {
        let level = string_arg("Session.canInject", "level", &level)?;
        Ok(self.inner.can_inject(&level).err().map(|e| e.to_string()))
    }

    /// Restarts from the initial scene with another seed.
    pub fn reset(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "number")] seed: JsValue,
    ) -> Result<(), JsValue> {
        let seed = number_arg("Session.reset", "seed", &seed)?;
        self.inner.reset(seed_of(seed)?);
        Ok(())
    }

    /// Drops the current plan; the loop replans on the next step.
    pub fn cancel(&mut self) {
        self.inner.cancel();
    }

    /// The full episode log as JSON (the CLI's format, snake_case); `Session.replay` reproduces
    /// it exactly. With `{ withFiles: true }` a task folder's log carries the folder's files
    /// (`folder.files`), so it replays without the folder.
    #[wasm_bindgen(js_name = episodeJson)]
    pub fn episode_json(&self, options: Option<EpisodeJsonOptionsArg>) -> Result<String, JsValue> {
        let with_files = match options.map(JsValue::from) {
            Some(v) if !v.is_undefined() && !v.is_null() => {
                object_arg("Session.episodeJson", "options", &v, false)?;
                let w = js_sys::Reflect::get(&v, &JsValue::from_str("withFiles"))?;
                if !w.is_undefined() && w.as_bool().is_none() {
                    return Err(type_error(&format!(
                        "Session.episodeJson: options.withFiles must be a boolean, got {}",
                        type_name(&w)
                    )));
                }
                w.as_bool().unwrap_or(false)
            }
            _ => false,
        };
        match (&self.folder, with_files) {
            (Some(folder), true) => {
                let mut log = self.inner.log();
                if let Some(record) = log.folder.as_mut() {
                    record.files = Some(folder.files.clone());
                }
                serde_json::to_string(&log).map_err(|e| js_err(e).into())
            }
            _ => Ok(self.inner.episode_json()),
        }
    }

    /// The current world as scene JSON (loadable with `Session.fromScene`).
    #[wasm_bindgen(js_name = sceneJson)]
    pub fn scene_json(&self) -> String {
        self.inner.world().to_json()
    }
}
