//! `Session`: one closed-loop episode (paper Algorithm 1) in the kinematic workcell, stepped
//! from Python, disturbed (`inject`, `drag`) and logged, as the npm package's `Session` and the
//! page do.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use logic_lfd::lfd::{Frame, Listed, Session as Core, SessionOptions, SessionParams};
use logic_lfd::sim::{Benchmark, TaskFolder};

use crate::clock::WallClock;
use crate::errors::{drag_refused, load_error, option_error, LogicLfdError};
use crate::task::{self, array, to_py};

/// One closed-loop episode (paper Algorithm 1) in a kinematic workcell: step it, read its
/// frames, disturb it, save its log.
///
/// Exactly one of `benchmark` (`"b1"`, `"b2"`, `"b3"`; `"b1"` when neither is given) and
/// `folder` (a task folder such as `domains/b1-tower`, read from disk). `method` is
/// 'logic-lfd', 'linear', 'rlds' or 'tamp'; `mode` 'paper' or 'prioritised'; `seed` seeds every
/// random choice; `skill` is 'lqt' or 'dmp'; `blocks` runs the benchmark's generated N-block
/// tower task; `scene` is a starting world (a saved scene JSON text, as `scene_json()` gives);
/// `robot` puts a robot in the arms' place: a shipped robot ('panda', 'ur5'), a robot file, or
/// a list of them (one per arm).
///
/// Raises `OptionError` for a bad option, `LoadError` (with `.path`) for a folder, robot or
/// scene that cannot be read, `PddlError` for a task whose PDDL is broken.
///
/// `step` and `run` release the GIL (the core episode is `Send`); an episode is used by one
/// thread at a time: a call while another thread steps it raises `RuntimeError` (already
/// borrowed).
#[pyclass(module = "logic_lfd")]
pub(crate) struct Session {
    inner: Core,
    /// The task folder the episode runs on (its files, for a log that carries them).
    folder: Option<TaskFolder>,
}

/// The frame as a dict: the core's frame (snake_case, as the episode log names things) plus
/// `joints` (arm name → joint angles, float64 (n_joints,)) and `poses` (body name → position
/// and quaternion `[x, y, z, qx, qy, qz, qw]`, float64 (7,)).
fn frame_dict<'py>(py: Python<'py>, f: &Frame) -> PyResult<Bound<'py, PyAny>> {
    let d = to_py(py, f)?;
    let joints = PyDict::new(py);
    for arm in &f.world.arms {
        joints.set_item(&arm.name, array(&arm.joints.clone().into_pyobject(py)?)?)?;
    }
    let poses = PyDict::new(py);
    for b in &f.world.bodies {
        let p = &b.pose;
        let v: Vec<f64> = p.position.iter().chain(&p.quaternion).copied().collect();
        poses.set_item(&b.name, array(&v.into_pyobject(py)?)?)?;
    }
    d.set_item("joints", joints)?;
    d.set_item("poses", poses)?;
    Ok(d)
}

/// `to` of `drag`: three finite numbers.
fn position(py: Python<'_>, to: &Bound<'_, PyAny>) -> PyResult<[f64; 3]> {
    let v: Vec<f64> = to
        .try_iter()
        .and_then(|it| it.map(|x| x?.extract::<f64>()).collect())
        .map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err("to must be a sequence of numbers (x, y, z)")
        })?;
    match <[f64; 3]>::try_from(v.as_slice()) {
        Ok(p) if p.iter().all(|x| x.is_finite()) => Ok(p),
        Ok(_) => Err(option_error(py, "to", "the position must be finite")),
        Err(_) if v.len() == 4 => Err(option_error(
            py,
            "to",
            "a drag keeps the block's yaw (as the page's drag does): give (x, y, z)",
        )),
        Err(_) => Err(option_error(
            py,
            "to",
            &format!("expected (x, y, z), got {} numbers", v.len()),
        )),
    }
}

#[pymethods]
impl Session {
    /// Sets the episode up (reads the task, derives L_0 … L_N, learns the skills).
    #[new]
    #[pyo3(signature = (benchmark = None, *, folder = None, method = "logic-lfd", mode = "paper",
        seed = 0, skill = "lqt", blocks = None, scene = None, robot = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        benchmark: Option<&str>,
        folder: Option<&Bound<'_, PyAny>>,
        method: &str,
        mode: &str,
        seed: u64,
        skill: &str,
        blocks: Option<usize>,
        scene: Option<String>,
        robot: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let folder = folder.filter(|f| !f.is_none());
        task::one_task(py, benchmark, folder.is_some(), blocks)?;
        let options = SessionOptions {
            benchmark: task::listed::<Benchmark>(py, "benchmark", benchmark.unwrap_or("b1"))?,
            method: task::listed(py, "method", method)?,
            mode: task::listed(py, "mode", mode)?,
            seed,
            skill: task::skill(py, skill)?,
            blocks,
        };
        let robots = task::robots(py, robot)?;
        let folder = match folder {
            Some(f) => Some(task::read_folder(py, &task::path_arg("folder", f)?)?),
            None => None,
        };
        let mut inner = match &folder {
            None => py
                .detach(|| match &scene {
                    Some(s) => Core::from_scene(options, s, None),
                    None => Core::new(options),
                })
                .map_err(|e| task::episode_error(py, None, e))?,
            Some(f) => {
                let sources = task::sources(py, f)?;
                if let Some(s) = &scene {
                    // The folder's own scene is still the demonstration's.
                    logic_lfd::sim::world_from_json(&sources.scene)
                        .map_err(|e| load_error(py, &f.path("scene.json"), &e.to_string()))?;
                    logic_lfd::sim::world_from_json(s)
                        .map_err(|e| load_error(py, "scene", &e.to_string()))?;
                }
                py.detach(|| {
                    Core::with_sources(
                        options,
                        &sources,
                        scene.as_deref(),
                        None,
                        SessionParams::default(),
                    )
                })
                .map_err(|e| task::episode_error(py, Some(f), e))?
            }
        };
        inner
            .set_robots(&robots)
            .map_err(|e| task::episode_error(py, folder.as_ref(), e))?;
        Ok(Session { inner, folder })
    }

    /// Advances the episode by `dt` simulated seconds and returns the new frame (as `frame()`).
    ///
    /// Runs the whole 10 ms ticks `dt` covers (a remainder carries over to the next call),
    /// replanning inside; stops early when the episode ends. Releases the GIL.
    fn step<'py>(&mut self, py: Python<'py>, dt: f64) -> PyResult<Bound<'py, PyAny>> {
        if !dt.is_finite() || dt < 0.0 {
            return Err(option_error(
                py,
                "dt",
                &format!("dt must be a non-negative number of seconds, got {dt}"),
            ));
        }
        let inner = &mut self.inner;
        let f = py.detach(|| inner.step(dt, &WallClock::start()));
        frame_dict(py, &f)
    }

    /// Steps until the episode ends (the goal holds, or it fails; at most 240 simulated
    /// seconds) and returns the last frame. Releases the GIL.
    fn run<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let inner = &mut self.inner;
        let f = py.detach(|| {
            let clock = WallClock::start();
            let mut f = inner.step(0.0, &clock);
            while inner.outcome().is_none() {
                f = inner.step(1.0, &clock);
            }
            f
        });
        frame_dict(py, &f)
    }

    /// The current frame, without stepping.
    ///
    /// A dict: `t` (simulated s), `tick`, `status` (`kind`: idle, planning, executing,
    /// replanning, done or failed; `message`, `step`, `of`), `plan`, `executing` (index into
    /// `plan`), `demo`, `demo_states` (L_0 … L_N), `matched_k` (the L_k the plan joins),
    /// `facts` (S_C, sorted), `facts_added`, `facts_removed` (since the previous step),
    /// `last_replan`, `replans`, `ee` (end-effector points), `world` (the scene snapshot), and
    /// numpy arrays: `joints` (arm → joint angles) and `poses` (body → x, y, z, qx, qy, qz, qw).
    fn frame<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        frame_dict(py, &self.inner.frame())
    }

    /// Injects a disturbance now and returns what it did, or `None` when it cannot apply now.
    ///
    /// `level` is 'l1' … 'l4' (any case) or the page's words: 'nudge', 'set-back', 'scramble',
    /// 'new-block'. The result is a dict (`level`, `description`, `moved`, `during`, `push`);
    /// `None` when the world offers nothing to disturb that way (`can_inject` says why). An
    /// injection after the episode ended opens it again. Raises `OptionError` for an unknown
    /// level.
    fn inject<'py>(&mut self, py: Python<'py>, level: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        let level = task::level(py, level)?;
        match self.inner.inject(level.id()) {
            Ok(inj) => to_py(py, &inj).map(Some),
            Err(_) => Ok(None),
        }
    }

    /// Why `inject(level)` would not apply now, or `None` when it would; changes nothing.
    fn can_inject(&self, py: Python<'_>, level: &str) -> PyResult<Option<String>> {
        let level = task::level(py, level)?;
        Ok(self
            .inner
            .can_inject(level.id())
            .err()
            .map(|e| e.to_string()))
    }

    /// Moves a block as a user's drag on the page does: its centre to `to` (x, y, z in m; the
    /// yaw is kept), then it settles on the highest support under it.
    ///
    /// Returns a dict: `body`, `from`, `to` (the centre after settling), `support`, `also_moved`.
    /// Logged with its tick (the episode replays it); after the end it opens the episode again.
    /// Raises `DragRefused` (`.body`, `.reason`) when the world refuses the move (a body that
    /// is unknown, fixed, lost or held; a place where it would collide or lie out of every
    /// arm's reach), the world unchanged; `OptionError` for a `to` that is not (x, y, z).
    fn drag<'py>(
        &mut self,
        py: Python<'py>,
        body: &str,
        to: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let p = position(py, to)?;
        match self.inner.perturb(body, p) {
            Ok(out) => to_py(py, &out),
            Err(r) => Err(drag_refused(py, &r.body, &r.reason)),
        }
    }

    /// Drops the current plan; the loop replans on the next step.
    fn cancel(&mut self) {
        self.inner.cancel();
    }

    /// Restarts from the initial scene, with `seed` (default: the seed it was made with).
    #[pyo3(signature = (seed = None))]
    fn reset(&mut self, seed: Option<u64>) {
        let seed = seed.unwrap_or(self.inner.options().seed);
        self.inner.reset(seed);
    }

    /// The episode ended: the goal holds, or it failed (`success` says which).
    #[getter]
    fn done(&self) -> bool {
        self.inner.outcome().is_some()
    }

    /// The episode ended with the goal holding.
    #[getter]
    fn success(&self) -> bool {
        matches!(self.inner.outcome(), Some(Ok(())))
    }

    /// 10 ms ticks run so far.
    #[getter]
    fn tick(&self) -> u64 {
        self.inner.tick()
    }

    /// The seed of the episode's random choices.
    #[getter]
    fn seed(&self) -> u64 {
        self.inner.options().seed
    }

    /// The full episode log as JSON: the CLI's format (`logic-lfd run --json`'s `log`, the npm
    /// package's `episodeJson()`), which replays exactly.
    ///
    /// With `with_files=True` a task folder's log carries the folder's files
    /// (`folder.files`), so it replays without the folder.
    #[pyo3(signature = (*, with_files = false))]
    fn episode_json(&self, with_files: bool) -> PyResult<String> {
        match (&self.folder, with_files) {
            (Some(folder), true) => {
                let mut log = self.inner.log();
                if let Some(record) = log.folder.as_mut() {
                    record.files = Some(folder.files.clone());
                }
                serde_json::to_string(&log).map_err(|e| LogicLfdError::new_err(e.to_string()))
            }
            _ => Ok(self.inner.episode_json()),
        }
    }

    /// The current world as scene JSON (a starting scene for `Session(scene=…)`).
    fn scene_json(&self) -> String {
        self.inner.world().to_json()
    }

    /// `Session(b1, logic-lfd, seed 1, tick 0, running)`.
    fn __repr__(&self) -> String {
        let o = self.inner.options();
        let task = match &self.folder {
            Some(f) => format!("folder {}", f.dir),
            None => o.benchmark.id().to_string(),
        };
        let state = match self.inner.outcome() {
            None => "running",
            Some(Ok(())) => "done",
            Some(Err(_)) => "failed",
        };
        format!(
            "Session({task}, {}, seed {}, tick {}, {state})",
            o.method.id(),
            o.seed,
            self.inner.tick()
        )
    }
}

/// Adds `Session` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Session>()?;
    Ok(())
}
