//! `plan` and `validate`: a PDDL domain and problem (texts) in, a `Plan` or a `Validation` out.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use logic_lfd::pddl::{self, Domain, Problem};
use logic_lfd::plan::{
    self as core_plan, Algorithm, Clock, GroundError, HeuristicKind, Outcome, SearchConfig,
    SearchOutcome, SearchStats, Task, ValidationReport,
};

use crate::clock::WallClock;
use crate::errors::{located, no_plan, option_error, pddl_error, PddlError};

/// A plan: its actions `(action arg …)` in order, its cost and the search's statistics.
#[pyclass(module = "logic_lfd", frozen, get_all)]
pub(crate) struct Plan {
    /// The actions, one `(name arg …)` string each.
    actions: Vec<String>,
    /// The sum of the actions' costs (1 each without `:action-costs`).
    cost: u64,
    /// Whether the search proves the plan optimal (A* with an admissible heuristic, UCS, BFS on
    /// unit costs).
    optimal: bool,
    /// `expanded`, `generated`, `evaluated`, `search_seconds`, `ground_seconds`.
    stats: Py<PyDict>,
}

#[pymethods]
impl Plan {
    /// A plan from its parts; what pickling restores.
    #[new]
    #[pyo3(signature = (actions, cost, optimal = false, stats = None))]
    fn new(
        py: Python<'_>,
        actions: Vec<String>,
        cost: u64,
        optimal: bool,
        stats: Option<Bound<'_, PyDict>>,
    ) -> Self {
        Plan {
            actions,
            cost,
            optimal,
            stats: stats.unwrap_or_else(|| PyDict::new(py)).unbind(),
        }
    }

    /// Pickles as `Plan(actions, cost, optimal, stats)`, so plans cross process pools.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let py = slf.py();
        let p = slf.get();
        let args = (p.actions.clone(), p.cost, p.optimal, p.stats.clone_ref(py));
        Ok((
            slf.get_type().into_any(),
            args.into_pyobject(py)?.into_any(),
        ))
    }

    fn __len__(&self) -> usize {
        self.actions.len()
    }

    fn __iter__(slf: PyRef<'_, Self>) -> PyResult<Bound<'_, PyAny>> {
        let list = pyo3::types::PyList::new(slf.py(), &slf.actions)?;
        list.as_any().try_iter().map(|i| i.into_any())
    }

    fn __repr__(&self) -> String {
        format!(
            "Plan({} actions, cost {}{})",
            self.actions.len(),
            self.cost,
            if self.optimal { ", optimal" } else { "" }
        )
    }

    /// The plan in the IPC format: one action a line, then `; cost = N`.
    fn __str__(&self) -> String {
        let mut s = self.actions.join("\n");
        s.push_str(&format!("\n; cost = {}\n", self.cost));
        s
    }
}

/// The statistics dict of a search.
pub(crate) fn stats_dict<'py>(
    py: Python<'py>,
    s: &SearchStats,
    ground_seconds: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("expanded", s.expanded)?;
    d.set_item("generated", s.generated)?;
    d.set_item("evaluated", s.evaluated)?;
    d.set_item("search_seconds", s.time_secs)?;
    if let Some(g) = ground_seconds {
        d.set_item("ground_seconds", g)?;
    }
    Ok(d)
}

/// The search configuration of `search`, `heuristic` and the budgets, or `OptionError`.
pub(crate) fn config(
    py: Python<'_>,
    search: &str,
    heuristic: Option<&str>,
    max_nodes: Option<u64>,
    time_limit: Option<f64>,
) -> PyResult<SearchConfig> {
    let algorithm: Algorithm =
        search
            .parse()
            .map_err(|e: <Algorithm as std::str::FromStr>::Err| {
                option_error(py, "search", &e.to_string())
            })?;
    let default_h = if algorithm == Algorithm::Astar {
        "lmcut"
    } else {
        "hff"
    };
    let heuristic: HeuristicKind = heuristic.unwrap_or(default_h).parse().map_err(
        |e: <HeuristicKind as std::str::FromStr>::Err| {
            option_error(py, "heuristic", &e.to_string())
        },
    )?;
    if time_limit.is_some_and(|t| t.is_nan() || t < 0.0) {
        return Err(option_error(
            py,
            "time_limit",
            "expected a non-negative number of seconds",
        ));
    }
    Ok(SearchConfig {
        algorithm,
        heuristic,
        max_nodes,
        time_limit_secs: time_limit,
    })
}

/// What can go wrong reading and grounding, kept as plain data so it crosses `detach`.
enum ReadError {
    Pddl(pddl::PddlError),
    Other(String),
}

impl ReadError {
    fn into_py(self, py: Python<'_>) -> PyErr {
        match self {
            ReadError::Pddl(e) => pddl_error(py, &e),
            ReadError::Other(m) => located::<PddlError>(py, "", 0, 0, &m),
        }
    }
}

/// The domain and problem read (named `domain_file`, `problem_file` in errors).
fn read(
    domain: &str,
    problem: &str,
    domain_file: &str,
    problem_file: &str,
) -> Result<(Domain, Problem), ReadError> {
    let d = pddl::parse_domain(domain, domain_file).map_err(ReadError::Pddl)?;
    let p = pddl::parse_problem(problem, problem_file, &d).map_err(ReadError::Pddl)?;
    Ok((d, p))
}

/// The grounded task of a domain and problem.
fn ground(d: &Domain, p: &Problem) -> Result<Task, ReadError> {
    core_plan::ground(d, p).map_err(|e| match e {
        GroundError::Located(p) => ReadError::Pddl(p),
        other => ReadError::Other(other.to_string()),
    })
}

/// Plans a PDDL problem: parses both texts, grounds them and searches.
///
/// Raises `PddlError` (with `.file`, `.line`, `.col`) for bad PDDL, `OptionError` for an
/// unknown search or heuristic, and `NoPlanError` (`.reason` 'unsolvable' or 'budget') when
/// there is no plan. Releases the GIL while it works.
#[pyfunction(name = "plan")]
#[pyo3(signature = (domain, problem, search = "astar", heuristic = None, *, max_nodes = None,
    time_limit = None, domain_file = "domain.pddl", problem_file = "problem.pddl"))]
#[allow(clippy::too_many_arguments)]
fn plan_py(
    py: Python<'_>,
    domain: &str,
    problem: &str,
    search: &str,
    heuristic: Option<&str>,
    max_nodes: Option<u64>,
    time_limit: Option<f64>,
    domain_file: &str,
    problem_file: &str,
) -> PyResult<Plan> {
    let config = config(py, search, heuristic, max_nodes, time_limit)?;
    let outcome = py.detach(|| {
        let clock = WallClock::start();
        let (d, p) = read(domain, problem, domain_file, problem_file)?;
        let task = ground(&d, &p)?;
        let ground_secs = clock.now_secs();
        let r = core_plan::search(&task, &config, &clock);
        let names = match &r.outcome {
            SearchOutcome::Plan(p) => Some((
                p.names(&task).into_iter().map(str::to_string).collect(),
                p.cost,
            )),
            _ => None,
        };
        Ok::<_, ReadError>((r, names, ground_secs))
    });
    let (r, names, ground_secs) = outcome.map_err(|e| e.into_py(py))?;
    let stats = stats_dict(py, &r.stats, Some(ground_secs))?;
    match (r.outcome, names) {
        (SearchOutcome::Plan(_), Some((actions, cost))) => Ok(Plan {
            actions,
            cost,
            optimal: config.is_optimal(),
            stats: stats.unbind(),
        }),
        (SearchOutcome::BudgetExhausted { which }, _) => Err(no_plan(
            py,
            Some(which),
            &format!(
                "no plan within the {which} ({} states expanded)",
                r.stats.expanded
            ),
            Some(stats.into_any()),
        )),
        _ => Err(no_plan(
            py,
            None,
            &format!(
                "the problem is unsolvable: no goal state among {} reachable states",
                r.stats.states
            ),
            Some(stats.into_any()),
        )),
    }
}

/// The verdict of replaying a plan on a problem.
#[pyclass(module = "logic_lfd", frozen, get_all)]
pub(crate) struct Validation {
    /// Every step applied and the goal holds.
    valid: bool,
    /// One line for people: `Plan valid, cost 6`, or the first failing step and why.
    message: String,
    /// Steps applied before the verdict (all of them when valid).
    steps_applied: usize,
    /// The cost of the applied steps.
    cost: u64,
    /// The 1-based step whose precondition is false, if that is the verdict.
    failed_step: Option<usize>,
    /// The false precondition or goal literals.
    false_literals: Vec<String>,
}

#[pymethods]
impl Validation {
    /// A verdict from its parts; what pickling restores.
    #[new]
    #[pyo3(signature = (valid, message, steps_applied, cost, failed_step = None,
        false_literals = Vec::new()))]
    fn new(
        valid: bool,
        message: String,
        steps_applied: usize,
        cost: u64,
        failed_step: Option<usize>,
        false_literals: Vec<String>,
    ) -> Self {
        Validation {
            valid,
            message,
            steps_applied,
            cost,
            failed_step,
            false_literals,
        }
    }

    /// Pickles as `Validation(valid, message, …)`.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let py = slf.py();
        let v = slf.get();
        let args = (
            v.valid,
            v.message.clone(),
            v.steps_applied,
            v.cost,
            v.failed_step,
            v.false_literals.clone(),
        );
        Ok((
            slf.get_type().into_any(),
            args.into_pyobject(py)?.into_any(),
        ))
    }

    fn __bool__(&self) -> bool {
        self.valid
    }

    fn __repr__(&self) -> String {
        format!(
            "Validation(valid={}, {:?})",
            if self.valid { "True" } else { "False" },
            self.message
        )
    }
}

impl Validation {
    /// The verdict of a core report; a malformed step is raised instead (`PddlError`).
    pub(crate) fn of(py: Python<'_>, r: &ValidationReport) -> PyResult<Validation> {
        if let Outcome::Malformed(e) = &r.outcome {
            return Err(pddl_error(py, e));
        }
        Ok(Validation {
            valid: r.is_valid(),
            message: r.to_string(),
            steps_applied: r.steps_applied,
            cost: r.cost,
            failed_step: r.failed_step(),
            false_literals: r.false_literals().to_vec(),
        })
    }
}

/// A plan as text: a string (IPC format) or an iterable of action strings.
pub(crate) fn plan_text(plan: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(s) = plan.extract::<String>() {
        return Ok(s);
    }
    let mut lines = Vec::new();
    for item in plan.try_iter().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "plan must be a string or an iterable of action strings, got {}",
            plan.get_type().name().map_or("?".into(), |n| n.to_string())
        ))
    })? {
        let item = item?;
        lines.push(item.extract::<String>().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err(
                "plan must be a string or an iterable of action strings",
            )
        })?);
    }
    Ok(lines.join("\n"))
}

/// Replays `plan` (IPC text, or an iterable of `(action arg …)` strings) on the problem.
///
/// Returns a `Validation` (truthy when valid). Raises `PddlError` for bad PDDL or a malformed
/// plan step (unknown action or object, wrong arity), located in the file it is in.
#[pyfunction]
#[pyo3(signature = (domain, problem, plan, *, domain_file = "domain.pddl",
    problem_file = "problem.pddl", plan_file = "plan"))]
fn validate(
    py: Python<'_>,
    domain: &str,
    problem: &str,
    plan: &Bound<'_, PyAny>,
    domain_file: &str,
    problem_file: &str,
    plan_file: &str,
) -> PyResult<Validation> {
    let text = plan_text(plan)?;
    let report = py.detach(|| {
        let (d, p) = read(domain, problem, domain_file, problem_file)?;
        let steps = core_plan::parse_plan(&text, plan_file).map_err(ReadError::Pddl)?;
        Ok::<_, ReadError>(core_plan::validate(&d, &p, &steps))
    });
    Validation::of(py, &report.map_err(|e| e.into_py(py))?)
}

/// Adds `plan`, `validate`, `Plan` and `Validation` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Plan>()?;
    m.add_class::<Validation>()?;
    m.add_function(wrap_pyfunction!(plan_py, m)?)?;
    m.add_function(wrap_pyfunction!(validate, m)?)?;
    Ok(())
}
