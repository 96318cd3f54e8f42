//! What a robot episode runs on, read from Python arguments: the catalogue's names (benchmark,
//! method, mode, level, skill), a task folder on disk, robots, and the core's results as plain
//! Python data (through JSON, as the npm package and the CLI write them).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use pyo3::prelude::*;

use logic_lfd::lfd::{Level, Listed, SessionError, SkillKind};
use logic_lfd::sim::{ArmModel, BenchmarkSources, TaskFolder};

use crate::errors::{lfd_error, load_error, option_error, LogicLfdError};

/// A catalogue name (`benchmark`, `method`, `mode`) parsed as the CLI does, or `OptionError`
/// listing the names it takes.
pub(crate) fn listed<T: Listed>(py: Python<'_>, option: &str, name: &str) -> PyResult<T> {
    T::from_id(name).map_err(|e| option_error(py, option, &e.to_string()))
}

/// A disturbance level: `l1`..`l4` (any case) or the page's words for them (`nudge`,
/// `set-back`, `scramble`, `new-block`, the catalogue's labels with `-` or `_` for spaces).
pub(crate) fn level(py: Python<'_>, name: &str) -> PyResult<Level> {
    if let Some(l) = Level::parse_id(name) {
        return Ok(l);
    }
    let words = name.replace(['-', '_'], " ");
    Level::all()
        .iter()
        .copied()
        .find(|l| l.label().eq_ignore_ascii_case(&words))
        .ok_or_else(|| {
            let labels: Vec<String> = Level::all()
                .iter()
                .map(|l| {
                    format!(
                        "{} ({})",
                        l.id(),
                        l.label().to_lowercase().replace(' ', "-")
                    )
                })
                .collect();
            option_error(
                py,
                "level",
                &format!(
                    "unknown disturbance level `{name}` (expected {})",
                    labels.join(", ")
                ),
            )
        })
}

/// The motion skill family `lqt` or `dmp`, or `OptionError`.
pub(crate) fn skill(py: Python<'_>, name: &str) -> PyResult<SkillKind> {
    serde_json::from_value(serde_json::Value::String(name.to_string())).map_err(|_| {
        option_error(
            py,
            "skill",
            &format!("unknown skill `{name}` (expected lqt|dmp)"),
        )
    })
}

/// Checks the task arguments of `Session` and `run_episode`: a benchmark or a folder, not both,
/// and `blocks` only with a benchmark; else `OptionError`.
pub(crate) fn one_task(
    py: Python<'_>,
    benchmark: Option<&str>,
    folder: bool,
    blocks: Option<usize>,
) -> PyResult<()> {
    if let (Some(b), true) = (benchmark, folder) {
        return Err(option_error(
            py,
            "benchmark",
            &format!(
                "benchmark `{b}` and a folder: a task folder is the task (its own scene and \
                 demonstration); give one of them"
            ),
        ));
    }
    if let (Some(_), true) = (blocks, folder) {
        return Err(option_error(
            py,
            "blocks",
            "blocks are for a benchmark's generated task, not a folder",
        ));
    }
    Ok(())
}

/// A filesystem path argument (`str` or `os.PathLike`).
pub(crate) fn path_arg(option: &str, v: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    v.extract::<PathBuf>().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{option} must be a path (str or os.PathLike), got {}",
            v.get_type()
                .name()
                .map_or("an object".into(), |n| n.to_string())
        ))
    })
}

/// Reads the task folder `dir` with the core's reader (a bare name reads as `./NAME`, as the
/// CLI's `--domain` does); a missing or unreadable folder or file is `LoadError` naming it.
/// Its files are checked when its task is read ([`sources`]).
pub(crate) fn read_folder(py: Python<'_>, dir: &Path) -> PyResult<TaskFolder> {
    let mut parts = dir.components();
    let bare = matches!(
        (parts.next(), parts.next()),
        (Some(std::path::Component::Normal(_)), None)
    );
    let dir = if bare {
        Path::new(".").join(dir)
    } else {
        dir.to_path_buf()
    };
    py.detach(|| TaskFolder::read(&dir))
        .map_err(|e| load_error(py, &e.path, &e.message))
}

/// The task of `folder`: its files, every required one present, and its demonstration
/// (recorded from `expert.json` by the scripted expert when the folder has no `demo.json`);
/// `LoadError` naming the file at fault. Releases the GIL.
pub(crate) fn sources(py: Python<'_>, folder: &TaskFolder) -> PyResult<BenchmarkSources> {
    py.detach(|| folder.sources())
        .map_err(|e| load_error(py, &e.path, &e.message))
}

/// The robots `robot` names: `None`, one robot, or a list (one per arm). A robot is a shipped
/// robot's name (`panda`, `ur5`) unless a file of that name exists, else a robot file
/// (`robot.json` beside its URDF); one that does not load is `LoadError` naming the file.
pub(crate) fn robots(
    py: Python<'_>,
    robot: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<Arc<ArmModel>>> {
    let Some(robot) = robot.filter(|r| !r.is_none()) else {
        return Ok(vec![]);
    };
    let paths: Vec<PathBuf> = if robot.extract::<PathBuf>().is_ok() {
        vec![path_arg("robot", robot)?]
    } else {
        let items: Vec<Bound<'_, PyAny>> = robot.try_iter()?.collect::<PyResult<_>>()?;
        if items.is_empty() {
            return Err(option_error(py, "robot", "name at least one robot"));
        }
        items
            .iter()
            .map(|i| path_arg("robot", i))
            .collect::<PyResult<_>>()?
    };
    paths
        .iter()
        .map(|p| {
            py.detach(|| ArmModel::load(p))
                .map_err(|e| load_error(py, &e.at, &e.message))
        })
        .collect()
}

/// An error setting an episode up as an exception: bad PDDL as `PddlError`, an unusable file (a folder's, the
/// scene, the motions) as `LoadError` naming it, the rest as `LogicLfdError`.
///
/// On a task folder, a scene or demonstration error names the folder's file, as the CLI's
/// `--domain` does (`DIR/scene.json: …`, `DIR/demo.json: actions[2]…`).
pub(crate) fn episode_error(py: Python<'_>, folder: Option<&TaskFolder>, e: SessionError) -> PyErr {
    let message = e.to_string();
    if let Some(f) = folder {
        let demo = if f.files.contains_key("demo.json") {
            "demo.json"
        } else {
            "expert.json"
        };
        for (prefix, name) in [("demo: ", demo), ("scene: ", "scene.json")] {
            if let Some(rest) = message.strip_prefix(prefix) {
                return load_error(py, &f.path(name), rest);
            }
        }
    }
    match e {
        SessionError::Lfd(l) => lfd_error(py, &l, "demo.json"),
        SessionError::Folder(f) => load_error(py, &f.path, &f.message),
        SessionError::Scene(s) => load_error(py, "scene", &s.to_string()),
        SessionError::Motions(m) => load_error(
            py,
            &format!("{}:{}:{}", m.file, m.line, m.column),
            &format!("{}: {}", m.path, m.message),
        ),
        _ => LogicLfdError::new_err(message),
    }
}

/// Plain Python data (dicts, lists, floats) of a serde value, through its JSON text and
/// `json.loads`: the same keys and numbers the CLI's `--json` and the npm package give.
pub(crate) fn to_py<'py, T: serde::Serialize>(
    py: Python<'py>,
    v: &T,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(v).map_err(|e| LogicLfdError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// `numpy.asarray(v, dtype=float64)`.
pub(crate) fn array<'py>(v: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let py = v.py();
    let np = py.import("numpy")?;
    let kwargs = pyo3::types::PyDict::new(py);
    kwargs.set_item("dtype", np.getattr("float64")?)?;
    np.call_method("asarray", (v,), Some(&kwargs))
}
