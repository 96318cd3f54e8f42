//! `run_episode`: one closed-loop episode with one disturbance injected at a seeded moment, run
//! to its end; the report of `logic-lfd run --json` and of the npm package's `runEpisode`.

use pyo3::prelude::*;

use logic_lfd::experiments::{run_episode_with, run_episode_with_blocks, EpisodeSpec};
use logic_lfd::lfd::SessionParams;
use logic_lfd::sim::Benchmark;

use crate::clock::WallClock;
use crate::task::{self, to_py};

/// Runs one closed-loop episode to its end and returns its report as a dict: the JSON of
/// `logic-lfd run --json` (and of the npm package's `runEpisode`), key for key.
///
/// Exactly one of `benchmark` (`"b1"` when neither is given) and `folder` (a task folder read
/// from disk: its own scene and the disturbances drawn in it). `level` is the disturbance
/// injected at a seeded moment: 'l1' … 'l4' (or the page's words), or `None` / 'none'.
/// `method`, `mode`, `seed`, `blocks`, `scene` (a starting scene's JSON text) and `robot` are
/// the CLI's flags. With `canonical=True` the wall-clock planning times (`planning_ms`,
/// `log.replans[].time_ms` and `bind_ms`) are 0, so two runs give equal reports; with
/// `with_files=True` a folder episode's log carries the folder's files.
///
/// The report: `success`, `reason`, `actions_executed`, `replans`, `planning_ms`,
/// `execution_s`, `injection`, `not_injected`, `time_lost_s`, `motion`, `log` (the episode log,
/// as `Session.episode_json()`). Releases the GIL; raises as `Session` does.
#[pyfunction]
#[pyo3(signature = (benchmark = None, *, folder = None, level = None, method = "logic-lfd",
    mode = "paper", seed = 0, blocks = None, scene = None, robot = None, canonical = false,
    with_files = false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn run_episode<'py>(
    py: Python<'py>,
    benchmark: Option<&str>,
    folder: Option<&Bound<'py, PyAny>>,
    level: Option<&str>,
    method: &str,
    mode: &str,
    seed: u64,
    blocks: Option<usize>,
    scene: Option<String>,
    robot: Option<&Bound<'py, PyAny>>,
    canonical: bool,
    with_files: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let folder = folder.filter(|f| !f.is_none());
    task::one_task(py, benchmark, folder.is_some(), blocks)?;
    let level = match level {
        None => None,
        Some(l) if l.eq_ignore_ascii_case("none") => None,
        Some(l) => Some(task::level(py, l)?),
    };
    let spec = EpisodeSpec {
        benchmark: task::listed::<Benchmark>(py, "benchmark", benchmark.unwrap_or("b1"))?,
        level,
        method: task::listed(py, "method", method)?,
        mode: task::listed(py, "mode", mode)?,
        seed,
        scene,
        robots: task::robots(py, robot)?,
    };
    let folder = match folder {
        Some(f) => Some(task::read_folder(py, &task::path_arg("folder", f)?)?),
        None => None,
    };
    let sources = match &folder {
        Some(f) => Some(task::sources(py, f)?),
        None => None,
    };
    let result = py.detach(|| {
        let clock = WallClock::start();
        match &sources {
            Some(files) => run_episode_with(&spec, files, SessionParams::default(), &clock),
            None => run_episode_with_blocks(&spec, blocks, SessionParams::default(), &clock),
        }
    });
    // A scene given as an argument is named `scene`, as the CLI names its file.
    let named = folder.as_ref().filter(|_| spec.scene.is_none());
    let mut report = result.map_err(|e| task::episode_error(py, named, e))?;
    if let (Some(f), true) = (&folder, with_files) {
        if let Some(record) = report.log.folder.as_mut() {
            record.files = Some(f.files.clone());
        }
    }
    if canonical {
        report.planning_ms.iter_mut().for_each(|t| *t = 0.0);
        report.log = report.log.canonical();
    }
    to_py(py, &report)
}

/// Adds `run_episode` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(run_episode, m)?)?;
    Ok(())
}
