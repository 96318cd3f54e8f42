//! `LogicLfd`: a domain, a problem and one demonstration read once, then LogicIn, replanning
//! and validation on any number of states (the paper's Algorithm 1, symbolic part).

use pyo3::prelude::*;
use pyo3::types::PyDict;

use logic_lfd::lfd::{LfdError, LfdPlan, LogicLfd as Core, Mode, Observed, PlanSource};
use logic_lfd::pddl::Source;

use crate::clock::WallClock;
use crate::errors::{lfd_error, option_error};
use crate::pddl::{config, plan_text, stats_dict, Validation};

/// Logic-LfD on one PDDL task: reads the domain, the problem and the demonstration once, then
/// answers LogicIn, replanning and validation queries on states.
///
/// States are iterables of atom strings (`"(on a b)"`) or one text of atoms; `None` is the
/// problem's `:init`. Static facts may be left out of a state.
#[pyclass(module = "logic_lfd", frozen)]
pub(crate) struct LogicLfd {
    core: Core,
    /// The texts and file names it was built from, for pickling.
    texts: [String; 3],
    files: [String; 3],
}

/// A Logic-LfD plan: new actions to a demonstration state L_k, then the demonstration's rest.
#[pyclass(module = "logic_lfd", frozen, get_all)]
pub(crate) struct LfdResult {
    /// The whole plan, `prefix` then `suffix`.
    actions: Vec<String>,
    /// New actions to L_k.
    prefix: Vec<String>,
    /// The demonstration's actions after L_k.
    suffix: Vec<String>,
    /// The demonstration state joined; `None` when the plan goes to the goal directly.
    k: Option<usize>,
    /// LogicIn of the state: the largest k with L_k ⊆ S_C whose rest applies, or `None`.
    logic_in: Option<usize>,
    /// 'goal-holds', 'logic-in' or 'multi-goal'.
    source: String,
    /// The cost of the whole plan.
    cost: u64,
    /// The lifted validator replayed the plan from the state to the goal (`None` when
    /// `validate=False`).
    valid: Option<bool>,
    /// `expanded`, `generated`, `evaluated`, `search_seconds`.
    stats: Py<PyDict>,
}

#[pymethods]
impl LfdResult {
    /// A result from its parts; what pickling restores.
    #[new]
    #[pyo3(signature = (actions, prefix, suffix, k, logic_in, source, cost, valid, stats))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        actions: Vec<String>,
        prefix: Vec<String>,
        suffix: Vec<String>,
        k: Option<usize>,
        logic_in: Option<usize>,
        source: String,
        cost: u64,
        valid: Option<bool>,
        stats: Bound<'_, PyDict>,
    ) -> Self {
        LfdResult {
            actions,
            prefix,
            suffix,
            k,
            logic_in,
            source,
            cost,
            valid,
            stats: stats.unbind(),
        }
    }

    /// Pickles as `LfdResult(actions, prefix, …)`.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let py = slf.py();
        let r = slf.get();
        let args = (
            r.actions.clone(),
            r.prefix.clone(),
            r.suffix.clone(),
            r.k,
            r.logic_in,
            r.source.clone(),
            r.cost,
            r.valid,
            r.stats.clone_ref(py),
        );
        Ok((
            slf.get_type().into_any(),
            args.into_pyobject(py)?.into_any(),
        ))
    }

    fn __len__(&self) -> usize {
        self.actions.len()
    }

    fn __repr__(&self) -> String {
        let joins = self.k.map_or("the goal".into(), |k| format!("L_{k}"));
        format!(
            "LfdResult({} new + {} demonstrated actions, joins {joins}, cost {})",
            self.prefix.len(),
            self.suffix.len(),
            self.cost
        )
    }
}

/// A state argument as atom text (`None`: the initial state).
fn state_text(state: Option<&Bound<'_, PyAny>>) -> PyResult<Option<String>> {
    match state {
        None => Ok(None),
        Some(s) if s.is_none() => Ok(None),
        Some(s) => plan_text(s).map(Some).map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err(
                "state must be a string of atoms, an iterable of atom strings, or None",
            )
        }),
    }
}

/// The mode named `mode`, or `OptionError`.
pub(crate) fn mode(py: Python<'_>, mode: &str) -> PyResult<Mode> {
    Mode::parse(mode).ok_or_else(|| {
        option_error(
            py,
            "mode",
            &format!("unknown mode `{mode}` (expected paper|prioritised)"),
        )
    })
}

fn source_name(s: PlanSource) -> &'static str {
    match s {
        PlanSource::GoalHolds => "goal-holds",
        PlanSource::LogicIn => "logic-in",
        PlanSource::MultiGoal => "multi-goal",
    }
}

impl LogicLfd {
    /// S_C read from `text` (or the initial state), in the GIL-free part of a call.
    fn observe(&self, text: Option<&str>) -> Result<Observed<'_>, LfdError> {
        match text {
            Some(t) => self.core.state(t),
            None => Ok(self.core.observed(self.core.task().init.clone())),
        }
    }
}

#[pymethods]
impl LogicLfd {
    /// Reads, grounds and derives L_0 … L_N.
    ///
    /// `demo` is a plan text (IPC format) or an iterable of action strings. Raises `PddlError`
    /// for bad PDDL and `DemoError` for a demonstration that does not apply or does not reach
    /// the goal, both located.
    #[new]
    #[pyo3(signature = (domain, problem, demo, *, domain_file = "domain.pddl",
        problem_file = "problem.pddl", demo_file = "demo.plan"))]
    fn new(
        py: Python<'_>,
        domain: &str,
        problem: &str,
        demo: &Bound<'_, PyAny>,
        domain_file: &str,
        problem_file: &str,
        demo_file: &str,
    ) -> PyResult<Self> {
        let demo = plan_text(demo)?;
        let core = py
            .detach(|| {
                Core::named(
                    &Source::new(domain_file, domain),
                    &Source::new(problem_file, problem),
                    &Source::new(demo_file, demo.as_str()),
                )
            })
            .map_err(|e| lfd_error(py, &e, demo_file))?;
        Ok(LogicLfd {
            core,
            texts: [domain.to_string(), problem.to_string(), demo],
            files: [domain_file, problem_file, demo_file].map(str::to_string),
        })
    }

    /// Pickles as the texts it was read from (read again when unpickled), so a `LogicLfd`
    /// crosses process pools.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let py = slf.py();
        let this = slf.get();
        let kwargs = PyDict::new(py);
        for (key, file) in ["domain_file", "problem_file", "demo_file"]
            .iter()
            .zip(&this.files)
        {
            kwargs.set_item(key, file)?;
        }
        let partial = py
            .import("functools")?
            .getattr("partial")?
            .call((slf.get_type(),), Some(&kwargs))?;
        let [domain, problem, demo] = this.texts.clone();
        Ok((
            partial,
            (domain, problem, demo).into_pyobject(py)?.into_any(),
        ))
    }

    /// The demonstration's actions a_1 … a_N.
    #[getter]
    fn demo_actions(&self) -> Vec<String> {
        self.core.demo_actions().to_vec()
    }

    /// L_0 … L_N: the fluent atoms before a_1, after a_1, …, after a_N (sorted).
    #[getter]
    fn demo_states(&self) -> Vec<Vec<String>> {
        self.core
            .demo_states()
            .iter()
            .map(|l| l.iter().cloned().collect())
            .collect()
    }

    /// c_0 … c_N: the cost of the demonstration left after L_k.
    #[getter]
    fn demo_costs(&self) -> Vec<u64> {
        let n = self.core.demo_states().len();
        self.core
            .spec()
            .goals
            .iter()
            .take(n)
            .map(|g| g.terminal_cost)
            .collect()
    }

    /// The problem's static facts (true in every state, left out of the L_k).
    #[getter]
    fn static_facts(&self) -> Vec<String> {
        self.core.static_facts().to_vec()
    }

    /// Every fluent atom of the grounded task.
    #[getter]
    fn fluents(&self) -> Vec<String> {
        self.core.task().facts.clone()
    }

    /// LogicIn(S_C): the largest k with L_k ⊆ S_C from which the rest of the demonstration
    /// applies, or `None`. Raises `PddlError` for a bad atom.
    #[pyo3(signature = (state = None))]
    fn logic_in(
        &self,
        py: Python<'_>,
        state: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Option<usize>> {
        let text = state_text(state)?;
        py.detach(|| self.observe(text.as_deref()).map(|s| s.logic_in()))
            .map_err(|e| lfd_error(py, &e, &self.files[2]))
    }

    /// Logic-LfD from `state`: the cheapest way to any demonstration state L_k (or the goal),
    /// merged with the demonstration's rest.
    ///
    /// `mode` is 'paper' (the first L_k reached, the paper's Algorithm 1) or 'prioritised'
    /// (cost to L_k plus the demonstration left after it). Raises `NoPlanError` when there is
    /// no plan, `PddlError` for a bad atom and `OptionError` for a bad option. Releases the GIL.
    #[pyo3(signature = (state = None, mode = "paper", *, search = "astar", heuristic = None,
        max_nodes = None, time_limit = 30.0, validate = true))]
    #[allow(clippy::too_many_arguments)]
    fn replan(
        &self,
        py: Python<'_>,
        state: Option<&Bound<'_, PyAny>>,
        mode: &str,
        search: &str,
        heuristic: Option<&str>,
        max_nodes: Option<u64>,
        time_limit: Option<f64>,
        validate: bool,
    ) -> PyResult<LfdResult> {
        let mode = self::mode(py, mode)?;
        let config = config(py, search, heuristic, max_nodes, time_limit)?;
        let text = state_text(state)?;
        let found = py.detach(|| {
            let s = self.observe(text.as_deref())?;
            let clock = WallClock::start();
            let p: LfdPlan = s.replan(mode, &config, &clock)?;
            let valid = validate.then(|| s.validate(&p.names).is_ok_and(|r| r.is_valid()));
            Ok::<_, LfdError>((p, s.logic_in(), valid))
        });
        let (p, logic_in, valid) = found.map_err(|e| lfd_error(py, &e, &self.files[2]))?;
        Ok(LfdResult {
            prefix: p.prefix().to_vec(),
            suffix: p.suffix().to_vec(),
            k: p.k,
            logic_in,
            source: source_name(p.source).to_string(),
            cost: p.cost,
            valid,
            stats: stats_dict(py, &p.stats, None)?.unbind(),
            actions: p.names,
        })
    }

    /// Replays `plan` (text or iterable of action strings) from `state` on the lifted domain.
    #[pyo3(signature = (plan, state = None))]
    fn validate(
        &self,
        py: Python<'_>,
        plan: &Bound<'_, PyAny>,
        state: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Validation> {
        let text = state_text(state)?;
        // The core reads the plan text itself (comments, one action a line), as `validate` does.
        let plan = plan_text(plan)?;
        let report = py
            .detach(|| {
                self.observe(text.as_deref())?
                    .validate(std::slice::from_ref(&plan))
            })
            .map_err(|e| lfd_error(py, &e, &self.files[2]))?;
        Validation::of(py, &report)
    }

    /// Seconds each of `repeats` native calls of what `replan(state, mode)` runs takes (read
    /// the state, search, merge, validate), timed inside Rust: the yardstick of the binding's
    /// overhead (`python/benches/replan.py`).
    #[pyo3(signature = (state, repeats, mode = "paper"))]
    fn _native_replan_seconds(
        &self,
        py: Python<'_>,
        state: Option<&Bound<'_, PyAny>>,
        repeats: usize,
        mode: &str,
    ) -> PyResult<Vec<f64>> {
        let mode = self::mode(py, mode)?;
        let config = config(py, "astar", None, None, Some(30.0))?;
        let text = state_text(state)?;
        py.detach(|| {
            (0..repeats)
                .map(|_| {
                    let t0 = std::time::Instant::now();
                    let s = self.observe(text.as_deref())?;
                    let p = s.replan(mode, &config, &WallClock::start())?;
                    let valid = s.validate(&p.names).is_ok_and(|r| r.is_valid());
                    std::hint::black_box((p, valid, s.logic_in()));
                    Ok(t0.elapsed().as_secs_f64())
                })
                .collect::<Result<Vec<f64>, LfdError>>()
        })
        .map_err(|e| lfd_error(py, &e, &self.files[2]))
    }

    fn __repr__(&self) -> String {
        format!(
            "LogicLfd({} demonstrated actions, {} fluents)",
            self.core.demo_actions().len(),
            self.core.task().facts.len()
        )
    }
}

/// Adds `LogicLfd` and `LfdResult` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<LogicLfd>()?;
    m.add_class::<LfdResult>()?;
    Ok(())
}
