//! The PDDL bindings: `plan`, `check` and `validate` (feature `wasm`: the page's PDDL tab calls
//! them, after its first load). Bad PDDL is reported as data with `line:col` diagnostics; a
//! parameter of the wrong JS type throws a `TypeError`.

use super::args::{object_arg, optional_string_arg, string_arg, StringArg};
use super::convert::{from_js, js_err, to_js, PerformanceClock};
use crate::pddl::{self, PddlError};
use crate::plan::{self, Algorithm, Clock, HeuristicKind, SearchConfig, SearchOutcome};
use serde::{Deserialize, Serialize};
use tsify::Tsify;
use wasm_bindgen::prelude::*;

/// Options of [`plan()`]; every field is optional, unknown keys are refused. Names are
/// camelCase; the snake_case names of 0.1 are read too, for one release.
#[derive(Debug, Default, Deserialize, Tsify)]
#[serde(default, deny_unknown_fields, rename_all = "camelCase")]
#[tsify(missing_as_null)]
pub struct PlanOptions {
    /// Default `astar`.
    #[tsify(type = "Algorithm")]
    pub search: Option<String>,
    /// Default `lmcut` for `astar`, `hff` otherwise.
    #[tsify(type = "HeuristicKind")]
    pub heuristic: Option<String>,
    /// Stop after this many expanded states (default: unbounded).
    pub max_expanded: Option<u64>,
    /// Stop after this many milliseconds (default 30 000).
    pub time_limit_ms: Option<f64>,
    /// File name of the domain in diagnostics (default `domain.pddl`).
    pub domain_file: Option<String>,
    /// File name of the problem in diagnostics (default `problem.pddl`).
    pub problem_file: Option<String>,
    /// @deprecated Use `maxExpanded`; the snake_case name is removed in the next release.
    #[serde(rename = "max_expanded")]
    pub old_max_expanded: Option<u64>,
    /// @deprecated Use `timeLimitMs`; the snake_case name is removed in the next release.
    #[serde(rename = "time_limit_ms")]
    pub old_time_limit_ms: Option<f64>,
    /// @deprecated Use `domainFile`; the snake_case name is removed in the next release.
    #[serde(rename = "domain_file")]
    pub old_domain_file: Option<String>,
    /// @deprecated Use `problemFile`; the snake_case name is removed in the next release.
    #[serde(rename = "problem_file")]
    pub old_problem_file: Option<String>,
}

impl PlanOptions {
    /// The options with each snake_case name of 0.1 moved to its camelCase one; both names
    /// given is an error, as a repeated key is.
    fn current(self) -> Result<PlanOptions, String> {
        fn one<T>(new: Option<T>, old: Option<T>, name: &str) -> Result<Option<T>, String> {
            match (new, old) {
                (Some(_), Some(_)) => Err(format!("duplicate field `{name}`")),
                (new, old) => Ok(new.or(old)),
            }
        }
        Ok(PlanOptions {
            search: self.search,
            heuristic: self.heuristic,
            max_expanded: one(self.max_expanded, self.old_max_expanded, "maxExpanded")?,
            time_limit_ms: one(self.time_limit_ms, self.old_time_limit_ms, "timeLimitMs")?,
            domain_file: one(self.domain_file, self.old_domain_file, "domainFile")?,
            problem_file: one(self.problem_file, self.old_problem_file, "problemFile")?,
            ..PlanOptions::default()
        })
    }
}

/// A located message about one of the inputs.
#[derive(Debug, Clone, Serialize, Tsify)]
pub struct Diagnostic {
    /// Which input: `domain`, `problem`, `plan` or `options`.
    #[tsify(type = "\"domain\" | \"problem\" | \"plan\" | \"options\"")]
    pub source: &'static str,
    /// The file name used in the message.
    pub file: String,
    /// 1-based line (0 when the message is not about a place in the text).
    pub line: usize,
    /// 1-based column in characters (0 when `line` is 0).
    pub col: usize,
    /// What is wrong.
    pub message: String,
}

/// A plan found by [`plan()`].
#[derive(Debug, Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
pub struct PlanFound {
    /// Always `true`.
    #[tsify(type = "true")]
    pub ok: bool,
    /// The actions, `(stack a b)`, in order.
    pub plan: Vec<String>,
    /// The plan's cost (its length without `:action-costs`).
    pub cost: u64,
    /// Whether the configuration guarantees an optimal plan.
    pub optimal: bool,
    /// States expanded.
    pub expanded: u64,
    /// States generated.
    pub generated: u64,
    /// Search time in milliseconds (grounding excluded).
    pub time_ms: f64,
    /// Grounding time in milliseconds.
    pub ground_ms: f64,
    /// The fluent facts of the initial state and after each action (`plan.length + 1` entries).
    pub states: Vec<Vec<String>>,
}

/// Why [`plan()`] found no plan.
#[derive(Debug, Serialize, Tsify)]
pub struct PlanFailed {
    /// Always `false`.
    #[tsify(type = "false")]
    pub ok: bool,
    /// `parse` (or grounding) errors, `options`, `unsolvable` (proved), or `budget` (ran out).
    #[tsify(type = "\"parse\" | \"options\" | \"unsolvable\" | \"budget\"")]
    pub kind: &'static str,
    /// One line for people.
    pub message: String,
    /// Located errors (empty for `unsolvable` and `budget`).
    pub diagnostics: Vec<Diagnostic>,
}

/// The result of [`plan()`]: test `ok` to tell them apart.
#[derive(Debug, Serialize, Tsify)]
#[serde(untagged)]
pub enum PlanOutcome {
    /// A plan was found.
    Found(PlanFound),
    /// No plan: why.
    Failed(PlanFailed),
}

fn diagnostic(e: &PddlError, domain_file: &str) -> Diagnostic {
    Diagnostic {
        source: if e.file == domain_file {
            "domain"
        } else {
            "problem"
        },
        file: e.file.clone(),
        line: e.line,
        col: e.col,
        message: e.message.clone(),
    }
}

fn failed(kind: &'static str, message: String, diagnostics: Vec<Diagnostic>) -> PlanOutcome {
    PlanOutcome::Failed(PlanFailed {
        ok: false,
        kind,
        message,
        diagnostics,
    })
}

/// Parses and grounds both texts; `Err` carries the failure to report.
fn parse_and_ground(
    domain_text: &str,
    problem_text: &str,
    domain_file: &str,
    problem_file: &str,
) -> Result<plan::Task, PlanOutcome> {
    let parse_err =
        |e: PddlError| failed("parse", e.to_string(), vec![diagnostic(&e, domain_file)]);
    let domain = pddl::parse_domain(domain_text, domain_file).map_err(parse_err)?;
    let problem = pddl::parse_problem(problem_text, problem_file, &domain).map_err(parse_err)?;
    plan::ground(&domain, &problem).map_err(|e| match e {
        plan::GroundError::Located(p) => parse_err(p),
        other => failed(
            "parse",
            other.to_string(),
            vec![Diagnostic {
                source: "problem",
                file: problem_file.to_string(),
                line: 0,
                col: 0,
                message: other.to_string(),
            }],
        ),
    })
}

fn options_error(message: String) -> PlanOutcome {
    failed(
        "options",
        message.clone(),
        vec![Diagnostic {
            source: "options",
            file: String::new(),
            line: 0,
            col: 0,
            message,
        }],
    )
}

fn plan_impl(domain_text: &str, problem_text: &str, o: PlanOptions) -> PlanOutcome {
    let domain_file = o.domain_file.as_deref().unwrap_or("domain.pddl");
    let problem_file = o.problem_file.as_deref().unwrap_or("problem.pddl");
    let algorithm = match o.search.as_deref().unwrap_or("astar").parse::<Algorithm>() {
        Ok(a) => a,
        Err(e) => return options_error(e.to_string()),
    };
    let default_h = if algorithm == Algorithm::Astar {
        "lmcut"
    } else {
        "hff"
    };
    let heuristic = match o
        .heuristic
        .as_deref()
        .unwrap_or(default_h)
        .parse::<HeuristicKind>()
    {
        Ok(h) => h,
        Err(e) => return options_error(e.to_string()),
    };
    let clock = PerformanceClock;
    let t0 = clock.now_secs();
    let task = match parse_and_ground(domain_text, problem_text, domain_file, problem_file) {
        Ok(t) => t,
        Err(out) => return out,
    };
    let ground_ms = (clock.now_secs() - t0) * 1e3;
    let config = SearchConfig {
        algorithm,
        heuristic,
        max_nodes: o.max_expanded,
        time_limit_secs: Some(o.time_limit_ms.unwrap_or(30_000.0).max(0.0) / 1e3),
    };
    let r = plan::search(&task, &config, &clock);
    match r.outcome {
        SearchOutcome::Plan(p) => {
            let names = |s: &plan::State| -> Vec<String> {
                s.facts().map(|f| task.facts[f as usize].clone()).collect()
            };
            let mut s = task.init.clone();
            let mut states = vec![names(&s)];
            for &op in &p.operators {
                s = task.operators[op].apply(&s);
                states.push(names(&s));
            }
            PlanOutcome::Found(PlanFound {
                ok: true,
                plan: p.names(&task).into_iter().map(str::to_string).collect(),
                cost: p.cost,
                optimal: config.is_optimal(),
                expanded: r.stats.expanded,
                generated: r.stats.generated,
                time_ms: r.stats.time_secs * 1e3,
                ground_ms,
                states,
            })
        }
        SearchOutcome::Unsolvable => failed(
            "unsolvable",
            format!(
                "the problem is unsolvable: no goal state among {} reachable states",
                r.stats.states
            ),
            vec![],
        ),
        SearchOutcome::BudgetExhausted { which } => failed(
            "budget",
            format!(
                "no plan within the {which} ({} states expanded)",
                r.stats.expanded
            ),
            vec![],
        ),
    }
}

/// Plans a PDDL problem: parses both texts (errors at `line:col`), grounds, and searches.
///
/// Never throws for bad PDDL or an unsolvable problem: the outcome says `ok: false` with the
/// reason and the located diagnostics. It rejects only when `options` is not an options object.
#[wasm_bindgen(unchecked_return_type = "PlanOutcome")]
pub fn plan(
    #[wasm_bindgen(unchecked_param_type = "string")] domain: JsValue,
    #[wasm_bindgen(unchecked_param_type = "string")] problem: JsValue,
    #[wasm_bindgen(unchecked_param_type = "PlanOptions | undefined")] options: JsValue,
) -> Result<JsValue, JsValue> {
    let domain = string_arg("plan", "domain", &domain)?;
    let problem = string_arg("plan", "problem", &problem)?;
    object_arg("plan", "options", &options, true)?;
    let o: PlanOptions = if options.is_undefined() || options.is_null() {
        PlanOptions::default()
    } else {
        // Misspelt keys are refused (deny_unknown_fields).
        from_js::<PlanOptions>(&options)
            .and_then(PlanOptions::current)
            .map_err(|e| js_err(format!("options: {e}")))?
    };
    to_js(&plan_impl(&domain, &problem, o))
}

/// Parses and grounds a domain and a problem without searching: the located errors, if any
/// (what an editor shows as you type). File names as in [`PlanOptions`].
#[wasm_bindgen(js_name = check, unchecked_return_type = "Diagnostic[]")]
pub fn check(
    #[wasm_bindgen(unchecked_param_type = "string")] domain: JsValue,
    #[wasm_bindgen(unchecked_param_type = "string")] problem: JsValue,
    #[wasm_bindgen(js_name = "domainFile")] domain_file: Option<StringArg>,
    #[wasm_bindgen(js_name = "problemFile")] problem_file: Option<StringArg>,
) -> Result<JsValue, JsValue> {
    let domain = string_arg("check", "domain", &domain)?;
    let problem = string_arg("check", "problem", &problem)?;
    let domain_file = optional_string_arg("check", "domainFile", domain_file)?;
    let problem_file = optional_string_arg("check", "problemFile", problem_file)?;
    let d = domain_file.as_deref().unwrap_or("domain.pddl");
    let p = problem_file.as_deref().unwrap_or("problem.pddl");
    let diags = match parse_and_ground(&domain, &problem, d, p) {
        Ok(_) => vec![],
        Err(PlanOutcome::Failed(f)) => f.diagnostics,
        Err(PlanOutcome::Found(_)) => vec![],
    };
    to_js(&diags)
}

/// The verdict of [`validate()`].
#[derive(Debug, Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
#[tsify(missing_as_null)]
pub struct Validation {
    /// Every step applied and the goal holds.
    pub valid: bool,
    /// One line for people (`Plan valid, cost 6`, or the first failing step and why).
    pub message: String,
    /// Steps applied before the verdict.
    pub steps_applied: usize,
    /// Cost of the applied steps.
    pub cost: u64,
    /// The 1-based step whose precondition is false, if that is the verdict.
    pub failed_step: Option<usize>,
    /// The false precondition or goal literals.
    pub false_literals: Vec<String>,
    /// Located errors in the domain, problem or plan text.
    pub diagnostics: Vec<Diagnostic>,
}

/// Replays a plan (IPC format, one `(action arg …)` per line, `;` comments) on a problem and
/// says whether it is valid, or the first failing step and why. Bad PDDL or a malformed plan is
/// reported with `line:col` diagnostics, not thrown.
#[wasm_bindgen(unchecked_return_type = "Validation")]
pub fn validate(
    #[wasm_bindgen(unchecked_param_type = "string")] domain: JsValue,
    #[wasm_bindgen(unchecked_param_type = "string")] problem: JsValue,
    #[wasm_bindgen(js_name = "plan", unchecked_param_type = "string")] plan_text: JsValue,
) -> Result<JsValue, JsValue> {
    let domain = string_arg("validate", "domain", &domain)?;
    let problem = string_arg("validate", "problem", &problem)?;
    let plan_text = string_arg("validate", "plan", &plan_text)?;
    let (domain, problem, plan_text) = (domain.as_str(), problem.as_str(), plan_text.as_str());
    let (df, pf, planf) = ("domain.pddl", "problem.pddl", "plan");
    let bad = |d: Diagnostic| Validation {
        valid: false,
        message: format!("{}:{}:{}: {}", d.file, d.line, d.col, d.message),
        steps_applied: 0,
        cost: 0,
        failed_step: None,
        false_literals: vec![],
        diagnostics: vec![d],
    };
    let d = match pddl::parse_domain(domain, df) {
        Ok(d) => d,
        Err(e) => return to_js(&bad(diagnostic(&e, df))),
    };
    let p = match pddl::parse_problem(problem, pf, &d) {
        Ok(p) => p,
        Err(e) => return to_js(&bad(diagnostic(&e, df))),
    };
    let steps = match plan::parse_plan(plan_text, planf) {
        Ok(s) => s,
        Err(e) => return to_js(&bad(Diagnostic::of_plan(&e))),
    };
    to_js(&Validation::of(&plan::validate(&d, &p, &steps)))
}

impl Diagnostic {
    /// A located error in a plan text.
    pub(crate) fn of_plan(e: &PddlError) -> Self {
        Diagnostic {
            source: "plan",
            file: e.file.clone(),
            line: e.line,
            col: e.col,
            message: e.message.clone(),
        }
    }
}

impl Validation {
    /// The verdict of a replay (a malformed step as a `plan` diagnostic).
    pub(crate) fn of(r: &plan::ValidationReport) -> Self {
        let diagnostics = match &r.outcome {
            plan::Outcome::Malformed(e) => vec![Diagnostic::of_plan(e)],
            _ => vec![],
        };
        Validation {
            valid: r.is_valid(),
            message: r.to_string(),
            steps_applied: r.steps_applied,
            cost: r.cost,
            failed_step: r.failed_step(),
            false_literals: r.false_literals().to_vec(),
            diagnostics,
        }
    }
}
