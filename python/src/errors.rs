//! The exceptions: one base class and one class per kind of failure, each with the fields a
//! program needs (where, what), so no caller parses a message.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

use logic_lfd::lfd::LfdError;
use logic_lfd::pddl::PddlError as CorePddlError;
use logic_lfd::plan::Budget;

create_exception!(
    logic_lfd,
    LogicLfdError,
    PyException,
    "Base class of every error logic_lfd raises."
);
create_exception!(
    logic_lfd,
    PddlError,
    LogicLfdError,
    "Bad PDDL, plan or state text: `.file`, `.line`, `.col` (1-based; 0 when unknown), `.message`."
);
create_exception!(
    logic_lfd,
    DemoError,
    PddlError,
    "A demonstration that does not apply or does not reach the goal (fields as PddlError)."
);
create_exception!(
    logic_lfd,
    LoadError,
    LogicLfdError,
    "A file or folder that could not be read or is not what was expected: `.path`, `.message`."
);
create_exception!(
    logic_lfd,
    NoPlanError,
    LogicLfdError,
    "No plan: `.reason` is 'unsolvable' (proved) or 'budget' (stopped at `.budget`, 'nodes' or 'time'); `.stats`."
);
create_exception!(
    logic_lfd,
    DragRefused,
    LogicLfdError,
    "A drag the world refuses (the world unchanged): `.body`, `.reason`."
);
create_exception!(
    logic_lfd,
    OptionError,
    LogicLfdError,
    "An option the call does not know or whose value is out of range: `.option`, `.message`."
);

/// Adds the exception classes to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("LogicLfdError", py.get_type::<LogicLfdError>())?;
    m.add("PddlError", py.get_type::<PddlError>())?;
    m.add("DemoError", py.get_type::<DemoError>())?;
    m.add("LoadError", py.get_type::<LoadError>())?;
    m.add("NoPlanError", py.get_type::<NoPlanError>())?;
    m.add("OptionError", py.get_type::<OptionError>())?;
    m.add("DragRefused", py.get_type::<DragRefused>())?;
    Ok(())
}

/// Sets the attribute `name` of `err`'s instance (cannot fail on a fresh exception).
fn set<'py>(py: Python<'py>, err: &PyErr, name: &str, value: impl IntoPyObject<'py>) {
    let _ = err.value(py).setattr(name, value);
}

/// A located PDDL error (`kind` is PddlError or DemoError).
pub(crate) fn located<E: pyo3::PyTypeInfo>(
    py: Python<'_>,
    file: &str,
    line: usize,
    col: usize,
    message: &str,
) -> PyErr {
    let text = if line > 0 {
        format!("{file}:{line}:{col}: {message}")
    } else if file.is_empty() {
        message.to_string()
    } else {
        format!("{file}: {message}")
    };
    let err = PyErr::from_type(py.get_type::<E>(), (text,));
    set(py, &err, "file", file);
    set(py, &err, "line", line);
    set(py, &err, "col", col);
    set(py, &err, "message", message);
    err
}

/// A core PDDL error as `PddlError`.
pub(crate) fn pddl_error(py: Python<'_>, e: &CorePddlError) -> PyErr {
    located::<PddlError>(py, &e.file, e.line, e.col, &e.message)
}

/// `file:line:col` split, from the end (file names may hold colons).
fn split_location(location: &str) -> Option<(String, usize, usize)> {
    let mut it = location.rsplitn(3, ':');
    let col = it.next()?.parse().ok()?;
    let line = it.next()?.parse().ok()?;
    Some((it.next()?.to_string(), line, col))
}

/// A Logic-LfD error: bad PDDL as `PddlError`, a bad demonstration as `DemoError`, a state a
/// plan prefix does not reach as `PddlError` at the step, no plan as `NoPlanError`.
pub(crate) fn lfd_error(py: Python<'_>, e: &LfdError, demo_file: &str) -> PyErr {
    match e {
        LfdError::Input(p) => pddl_error(py, p),
        LfdError::DemoNotApplicable { location, .. } => {
            let (file, line, col) = location
                .as_deref()
                .and_then(split_location)
                .unwrap_or_else(|| (demo_file.to_string(), 0, 0));
            // The message without its location prefix: the fields carry it.
            let full = e.to_string();
            let message = full
                .split_once(": demonstration")
                .map_or(full.clone(), |(_, rest)| format!("demonstration{rest}"));
            located::<DemoError>(py, &file, line, col, &message)
        }
        LfdError::UnknownAction { .. } | LfdError::DemoMissesGoal { .. } => {
            located::<DemoError>(py, demo_file, 0, 0, &e.to_string())
        }
        LfdError::PrefixNotApplicable { location, .. } => {
            let (file, line, col) = split_location(location).unwrap_or_default();
            located::<PddlError>(py, &file, line, col, &e.to_string())
        }
        LfdError::Budget(which) => no_plan(py, Some(*which), &e.to_string(), None),
        LfdError::NoPlan(_) | LfdError::MergeFailed { .. } => {
            no_plan(py, None, &e.to_string(), None)
        }
        LfdError::Model(m) => LogicLfdError::new_err(m.clone()),
    }
}

/// `NoPlanError` with its reason (a budget that ran out, or none: proved unsolvable) and the
/// search's statistics.
pub(crate) fn no_plan(
    py: Python<'_>,
    budget: Option<Budget>,
    message: &str,
    stats: Option<Bound<'_, PyAny>>,
) -> PyErr {
    let err = NoPlanError::new_err(message.to_string());
    let stats = stats.unwrap_or_else(|| py.None().into_bound(py));
    let (reason, budget) = match budget {
        None => ("unsolvable", None),
        Some(Budget::Nodes) => ("budget", Some("nodes")),
        Some(Budget::Time) => ("budget", Some("time")),
    };
    set(py, &err, "reason", reason);
    set(py, &err, "budget", budget);
    set(py, &err, "message", message);
    set(py, &err, "stats", stats);
    err
}

/// `LoadError` for `path`.
pub(crate) fn load_error(py: Python<'_>, path: &str, message: &str) -> PyErr {
    let err = LoadError::new_err(format!("{path}: {message}"));
    set(py, &err, "path", path);
    set(py, &err, "message", message);
    err
}

/// `OptionError` for `option`.
pub(crate) fn option_error(py: Python<'_>, option: &str, message: &str) -> PyErr {
    let err = OptionError::new_err(format!("{option}: {message}"));
    set(py, &err, "option", option);
    set(py, &err, "message", message);
    err
}

/// `DragRefused` for `body`, with the world's reason.
pub(crate) fn drag_refused(py: Python<'_>, body: &str, reason: &str) -> PyErr {
    let err = DragRefused::new_err(format!("cannot move {body}: {reason}"));
    set(py, &err, "body", body);
    set(py, &err, "reason", reason);
    err
}
