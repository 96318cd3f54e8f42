//! `logicLfd` and `logicLfdPerturb`: Logic-LfD on any PDDL domain (`lfd::LogicLfd`), stateless,
//! text in and plain data out.
//!
//! Bad PDDL, a bad demonstration, a bad state or a bad option never throws: the result says
//! `ok: false` with a `kind` and located diagnostics. Only a non-object input or a non-string
//! text throws, a `TypeError` naming the parameter.

use serde::Serialize;
use serde_json::{Map, Value};
use wasm_bindgen::prelude::*;

mod input;

use input::{
    count_option, files_option, known_keys, object_fields, optional_text, search_options, text,
    Files, LFD_KEYS,
};

use super::args::type_error;
use super::{to_js, PerformanceClock};
use crate::lfd::{LfdError, LfdPlan, LogicLfd, PlanSource};
use crate::pddl::PddlError;
use crate::plan::{Clock, SearchConfig, SearchOutcome, SearchStats, State};

#[wasm_bindgen(typescript_custom_section)]
const TS_LOGIC_LFD: &'static str = r#"
/** What `logicLfd` reads: a domain, a problem, one demonstration and the current state S_C. */
export interface LogicLfdInput {
  /** PDDL domain text. */
  domain: string;
  /** PDDL problem text. */
  problem: string;
  /** The demonstration: IPC plan text, one `(action args)` a line, `;` comments. */
  demo: string;
  /** S_C as PDDL atoms (one a line or space separated; static facts optional). */
  state?: string;
  /** Or: S_C is the state after this plan prefix from the problem's init. Neither: the problem's
   *  initial state. Both given: `TypeError`. */
  after?: string;
  /** `paper` (default: the first demonstration state reached) or `prioritised` (the cheapest
   *  prefix + demonstration left). */
  mode?: 'paper' | 'prioritised';
  /** Default `astar`. */
  search?: 'bfs' | 'ucs' | 'astar' | 'gbfs' | 'lazy-gbfs';
  /** Default `lmcut` for `astar`, `hff` otherwise. */
  heuristic?: 'blind' | 'hmax' | 'hadd' | 'hff' | 'lmcut';
  /** Node budget (default unbounded). */
  maxExpanded?: number;
  /** Time budget in ms (default 30000). */
  timeLimitMs?: number;
  /** File names used in diagnostics (default `domain.pddl`, `problem.pddl`, `demo.plan`, `state`). */
  files?: { domain?: string; problem?: string; demo?: string; state?: string };
  /** Also plan from scratch to G with the same search (the result's `scratch`). */
  compare?: boolean;
}
/** A located message about one of the inputs. */
export interface LogicLfdDiagnostic {
  source: 'domain' | 'problem' | 'demo' | 'state' | 'options';
  /** The file name used in the message. */
  file: string;
  /** 1-based line and column (0/0 when the message is not about a place). */
  line: number; col: number;
  message: string;
}
/** The demonstration as Logic-LfD reads it. */
export interface LogicLfdDemo {
  /** a_1 … a_N. */
  actions: string[];
  /** L_0 … L_N: the fluents before a_1, after a_1, …, after a_N (sorted names). */
  states: string[][];
  /** c_0 … c_N: the cost of the demonstration left after L_k. */
  costs: number[];
}
/** Search statistics; `timeMs` is the search time (parsing and grounding excluded). */
export interface LogicLfdStats { expanded: number; generated: number; evaluated: number; timeMs: number; }
/** What `logicLfd` found. */
export interface LogicLfdResult {
  /** `true` iff a plan was produced. */
  ok: boolean;
  kind: 'plan' | 'parse' | 'demo' | 'state' | 'options' | 'unsolvable' | 'budget';
  /** One line for people (`''` when ok). */
  message: string;
  /** Located errors (empty when ok). */
  diagnostics: LogicLfdDiagnostic[];
  /** `null` when the inputs did not parse. */
  demo: LogicLfdDemo | null;
  /** The problem's static facts. */
  statics: string[];
  /** Every fluent atom of the grounded task. */
  fluents: string[];
  /** S_C's fluents, sorted. */
  state: string[];
  /** The actions applicable in S_C. */
  applicable: string[];
  /** LogicIn(S_C): the largest k with L_k ⊆ S_C. */
  logicIn: number | null;
  /** The demonstration state joined (`null`: G directly, or no plan). */
  k: number | null;
  source: 'goal-holds' | 'logic-in' | 'multi-goal' | null;
  /** New actions to L_k. */
  prefix: string[];
  /** The demonstration's actions after L_k. */
  suffix: string[];
  /** `prefix` then `suffix`. */
  plan: string[];
  cost: number | null;
  /** The lifted validator replayed `plan` from S_C to the goal. */
  valid: boolean;
  stats: LogicLfdStats;
  /** With `compare`: classical planning from S_C to G with the same search. */
  scratch: { ok: boolean; plan: string[]; cost: number | null; stats: LogicLfdStats } | null;
}
/** What `logicLfdPerturb` reads. */
export interface LogicLfdPerturbInput {
  domain: string; problem: string; demo: string;
  /** How many states. */
  count: number;
  /** The same seed gives the same states, natively and in wasm. */
  seed: number;
  /** Random actions per walk, at most (default 8, as `logic-lfd lfd --perturb`). */
  maxSteps?: number;
  /** File names used in diagnostics. */
  files?: { domain?: string; problem?: string; demo?: string };
}
/** One drawn state: its fluents, the demonstration state its walk started from, the walk's length. */
export interface LogicLfdPerturbed { facts: string[]; fromK: number; steps: number; }
/** What `logicLfdPerturb` drew. */
export interface LogicLfdPerturbResult {
  ok: boolean; message: string; diagnostics: LogicLfdDiagnostic[]; states: LogicLfdPerturbed[];
}
"#;

/// The longest random walk of [`logic_lfd_perturb`] when `maxSteps` is not given.
pub const DEFAULT_PERTURB_STEPS: usize = 8;

#[derive(Debug, Clone, Serialize)]
struct Diag {
    source: &'static str,
    file: String,
    line: usize,
    col: usize,
    message: String,
}

#[derive(Debug, Default, Serialize)]
struct Demo {
    actions: Vec<String>,
    states: Vec<Vec<String>>,
    costs: Vec<u64>,
}

#[derive(Debug, Default, Serialize)]
#[serde(rename_all = "camelCase")]
struct Stats {
    expanded: u64,
    generated: u64,
    evaluated: u64,
    time_ms: f64,
}

impl Stats {
    fn of(s: &SearchStats) -> Self {
        Stats {
            expanded: s.expanded,
            generated: s.generated,
            evaluated: s.evaluated,
            time_ms: s.time_secs * 1e3,
        }
    }
}

#[derive(Debug, Serialize)]
struct Scratch {
    ok: bool,
    plan: Vec<String>,
    cost: Option<u64>,
    stats: Stats,
}

#[derive(Debug, Default, Serialize)]
#[serde(rename_all = "camelCase")]
struct LfdResult {
    ok: bool,
    kind: &'static str,
    message: String,
    diagnostics: Vec<Diag>,
    demo: Option<Demo>,
    statics: Vec<String>,
    fluents: Vec<String>,
    state: Vec<String>,
    applicable: Vec<String>,
    logic_in: Option<usize>,
    k: Option<usize>,
    source: Option<&'static str>,
    prefix: Vec<String>,
    suffix: Vec<String>,
    plan: Vec<String>,
    cost: Option<u64>,
    valid: bool,
    stats: Stats,
    scratch: Option<Scratch>,
}

#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
struct PerturbedOut {
    facts: Vec<String>,
    from_k: usize,
    steps: usize,
}

#[derive(Debug, Default, Serialize)]
struct PerturbResult {
    ok: bool,
    message: String,
    diagnostics: Vec<Diag>,
    states: Vec<PerturbedOut>,
}

fn options_diag(message: String) -> Diag {
    Diag {
        source: "options",
        file: String::new(),
        line: 0,
        col: 0,
        message,
    }
}

/// `file:line:col` split from the end (a file name may hold `:`).
fn split_location(location: &str) -> Option<(String, usize, usize)> {
    let mut it = location.rsplitn(3, ':');
    let col = it.next()?.parse().ok()?;
    let line = it.next()?.parse().ok()?;
    Some((it.next()?.to_string(), line, col))
}

/// The result kind and the diagnostics of an error from reading the inputs.
fn input_error(e: &LfdError, files: &Files, default_source: &'static str) -> (&'static str, Diag) {
    let kind_of = |source: &str| match source {
        "domain" | "problem" => "parse",
        "demo" => "demo",
        _ => "state",
    };
    let located = |source: &'static str, location: Option<&str>, message: String| {
        let (file, line, col) = location
            .and_then(split_location)
            .unwrap_or_else(|| (files.of(source), 0, 0));
        Diag {
            source,
            file,
            line,
            col,
            message,
        }
    };
    match e {
        LfdError::Input(PddlError {
            file,
            line,
            col,
            message,
        }) => {
            let source = files.source_of(file);
            (
                kind_of(source),
                Diag {
                    source,
                    file: file.clone(),
                    line: *line,
                    col: *col,
                    message: message.clone(),
                },
            )
        }
        LfdError::DemoNotApplicable {
            index,
            action,
            false_literals,
            location,
        } => (
            "demo",
            located(
                "demo",
                location.as_deref(),
                format!(
                    "demonstration step {} `{action}` is not applicable: {}",
                    index + 1,
                    false_precondition(false_literals)
                ),
            ),
        ),
        LfdError::UnknownAction { .. } | LfdError::DemoMissesGoal { .. } => {
            ("demo", located("demo", None, e.to_string()))
        }
        LfdError::PrefixNotApplicable {
            step,
            action,
            location,
            false_literals,
        } => (
            "state",
            located(
                "state",
                Some(location),
                format!(
                    "step {step} `{action}` is not applicable: {}",
                    false_precondition(false_literals)
                ),
            ),
        ),
        other => (
            kind_of(default_source),
            located(default_source, None, other.to_string()),
        ),
    }
}

fn false_precondition(literals: &[String]) -> String {
    if literals.is_empty() {
        "a precondition is false".into()
    } else {
        format!("false precondition {}", literals.join(" "))
    }
}

/// Logic-LfD on any PDDL domain: reads the domain, the problem, one demonstration and the
/// current state S_C (atoms, a plan prefix, or the problem's initial state), then LogicIn or one
/// multi-goal search to a demonstration state L_k, merged with the rest of the demonstration.
///
/// Never throws for bad PDDL, demonstration, state or options (`ok: false`, a `kind` and located
/// diagnostics); throws a `TypeError` when `input` is not an object or a text is not a string.
#[wasm_bindgen(js_name = logicLfd, unchecked_return_type = "LogicLfdResult")]
pub fn logic_lfd(
    #[wasm_bindgen(unchecked_param_type = "LogicLfdInput")] input: JsValue,
) -> Result<JsValue, JsValue> {
    const F: &str = "logicLfd";
    let m = object_fields(F, &input)?;
    let domain = text(F, &m, "domain")?;
    let problem = text(F, &m, "problem")?;
    let demo = text(F, &m, "demo")?;
    let state = optional_text(F, &m, "state")?;
    let after = optional_text(F, &m, "after")?;
    if state.is_some() && after.is_some() {
        return Err(type_error(&format!(
            "{F}: input.state and input.after are exclusive: give one"
        )));
    }
    let out = lfd_impl(&m, &domain, &problem, &demo, state, after);
    to_js(&out)
}

fn options_failure(message: String) -> LfdResult {
    LfdResult {
        kind: "options",
        message: message.clone(),
        diagnostics: vec![options_diag(message)],
        ..LfdResult::default()
    }
}

fn lfd_impl(
    m: &Map<String, Value>,
    domain: &str,
    problem: &str,
    demo: &str,
    state: Option<String>,
    after: Option<String>,
) -> LfdResult {
    let (files, o) = match known_keys(m, &LFD_KEYS, "input")
        .and_then(|()| files_option(m, &["domain", "problem", "demo", "state"]))
        .and_then(|f| Ok((f, search_options(m)?)))
    {
        Ok(x) => x,
        Err(e) => return options_failure(e),
    };
    let lfd = match LogicLfd::named(
        (&files.domain, domain),
        (&files.problem, problem),
        (&files.demo, demo),
    ) {
        Ok(l) => l,
        Err(e) => {
            let (kind, d) = input_error(&e, &files, "problem");
            return LfdResult {
                kind,
                message: location_message(&d),
                diagnostics: vec![d],
                ..LfdResult::default()
            };
        }
    };
    let task = lfd.task();
    let mut out = LfdResult {
        demo: Some(demo_of(&lfd)),
        statics: lfd.static_facts().to_vec(),
        fluents: task.facts.clone(),
        ..LfdResult::default()
    };
    let s = match (state, after) {
        (Some(text), _) => lfd.state_in(&files.state, &text),
        (None, Some(text)) => lfd.state_after(&files.state, &text),
        (None, None) => Ok(task.init.clone()),
    };
    let s = match s {
        Ok(s) => s,
        Err(e) => {
            let (kind, d) = input_error(&e, &files, "state");
            out.kind = kind;
            out.message = location_message(&d);
            out.diagnostics = vec![d];
            return out;
        }
    };
    out.state = lfd.names(&s);
    out.applicable = task
        .operators
        .iter()
        .filter(|op| op.applicable(&s))
        .map(|op| op.name.clone())
        .collect();
    out.logic_in = lfd.logic_in(&s);
    let clock = PerformanceClock;
    let t0 = clock.now_secs();
    match lfd.replan(&s, o.mode, &o.config, &clock) {
        Ok(p) => found(&lfd, &s, p, &mut out),
        Err(e) => {
            out.kind = match e {
                LfdError::Budget(_) => "budget",
                _ => "unsolvable",
            };
            out.message = e.to_string();
            out.stats.time_ms = (clock.now_secs() - t0) * 1e3;
        }
    }
    if o.compare {
        out.scratch = Some(scratch(&lfd, &s, &o.config, &clock));
    }
    out
}

fn found(lfd: &LogicLfd, s: &State, p: LfdPlan, out: &mut LfdResult) {
    out.valid = lfd.validate(s, &p.names).is_ok_and(|r| r.is_valid());
    out.ok = true;
    out.kind = "plan";
    out.k = p.k;
    out.source = Some(match p.source {
        PlanSource::GoalHolds => "goal-holds",
        PlanSource::LogicIn => "logic-in",
        PlanSource::MultiGoal => "multi-goal",
    });
    out.prefix = p.prefix().to_vec();
    out.suffix = p.suffix().to_vec();
    out.cost = Some(p.cost);
    out.stats = Stats::of(&p.stats);
    out.plan = p.names;
}

fn scratch(lfd: &LogicLfd, s: &State, config: &SearchConfig, clock: &dyn Clock) -> Scratch {
    let r = lfd.plan_from_scratch(s, config, clock);
    let stats = Stats::of(&r.stats);
    match r.outcome {
        SearchOutcome::Plan(p) => Scratch {
            ok: true,
            plan: p
                .names(lfd.task())
                .into_iter()
                .map(str::to_string)
                .collect(),
            cost: Some(p.cost),
            stats,
        },
        _ => Scratch {
            ok: false,
            plan: vec![],
            cost: None,
            stats,
        },
    }
}

fn demo_of(lfd: &LogicLfd) -> Demo {
    Demo {
        actions: lfd.demo_actions().to_vec(),
        states: lfd
            .demo_states()
            .iter()
            .map(|l| l.iter().cloned().collect())
            .collect(),
        costs: lfd
            .spec()
            .goals
            .iter()
            .take(lfd.demo_states().len())
            .map(|g| g.terminal_cost)
            .collect(),
    }
}

fn location_message(d: &Diag) -> String {
    if d.line == 0 {
        d.message.clone()
    } else {
        format!("{}:{}:{}: {}", d.file, d.line, d.col, d.message)
    }
}

const PERTURB_KEYS: [&str; 7] = [
    "domain", "problem", "demo", "count", "seed", "maxSteps", "files",
];

/// States for experiments: `count` seeded random walks with the domain's own actions (even draws
/// from L_0, odd ones from a random L_k), as fluent lists. The same seed draws the same states,
/// natively and in wasm. Bad inputs: `ok: false` with located diagnostics; a non-object input or
/// a non-string text throws a `TypeError`.
#[wasm_bindgen(js_name = logicLfdPerturb, unchecked_return_type = "LogicLfdPerturbResult")]
pub fn logic_lfd_perturb(
    #[wasm_bindgen(unchecked_param_type = "LogicLfdPerturbInput")] input: JsValue,
) -> Result<JsValue, JsValue> {
    const F: &str = "logicLfdPerturb";
    let m = object_fields(F, &input)?;
    let domain = text(F, &m, "domain")?;
    let problem = text(F, &m, "problem")?;
    let demo = text(F, &m, "demo")?;
    to_js(&perturb_impl(&m, &domain, &problem, &demo))
}

fn perturb_impl(m: &Map<String, Value>, domain: &str, problem: &str, demo: &str) -> PerturbResult {
    let options = known_keys(m, &PERTURB_KEYS, "input").and_then(|()| {
        let files = files_option(m, &["domain", "problem", "demo"])?;
        let count = count_option(m, "count")?.ok_or("`count` is required")?;
        let seed = count_option(m, "seed")?.ok_or("`seed` is required")?;
        let steps = count_option(m, "maxSteps")?.map_or(DEFAULT_PERTURB_STEPS, |n| n as usize);
        Ok((files, count as usize, seed, steps))
    });
    let (files, count, seed, max_steps) = match options {
        Ok(o) => o,
        Err(e) => {
            return PerturbResult {
                message: e.clone(),
                diagnostics: vec![options_diag(e)],
                ..PerturbResult::default()
            }
        }
    };
    match LogicLfd::named(
        (&files.domain, domain),
        (&files.problem, problem),
        (&files.demo, demo),
    ) {
        Ok(lfd) => PerturbResult {
            ok: true,
            message: String::new(),
            diagnostics: vec![],
            states: lfd
                .perturb(count, seed, max_steps)
                .into_iter()
                .map(|p| PerturbedOut {
                    facts: lfd.names(&p.state),
                    from_k: p.from_k,
                    steps: p.steps,
                })
                .collect(),
        },
        Err(e) => {
            let (_, d) = input_error(&e, &files, "problem");
            PerturbResult {
                message: location_message(&d),
                diagnostics: vec![d],
                ..PerturbResult::default()
            }
        }
    }
}
