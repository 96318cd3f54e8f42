//! `logicLfd`, `logicLfdPerturb` and the `LogicLfd` class: Logic-LfD on any PDDL domain
//! (`lfd::LogicLfd`), text in and plain data out. The functions read the domain, the problem and
//! the demonstration on every call; the class reads them once and answers many queries.
//!
//! Bad PDDL, a bad demonstration, a bad state or a bad option never throws from the functions or
//! `LogicLfd.replan`: the result says `ok: false` with a `kind` and located diagnostics. Only a
//! non-object input or a non-string text throws, a `TypeError` naming the parameter. The class's
//! constructor, `logicIn` and `validate` throw an `Error` carrying the same diagnostics.

use serde::Serialize;
use serde_json::{Map, Value};
use wasm_bindgen::prelude::*;

mod class;
mod diagnostics;
mod input;
mod query;

use diagnostics::{location_message, options_diag, Diag};
use input::{
    count_option, files_option, known_keys, object_fields, optional_text, search_options, texts,
    Texts, FILE_KEYS, LFD_KEYS,
};
use query::{answer, prepare, Current, Fixed, LfdResult};

use super::args::type_error;
use super::to_js;

#[wasm_bindgen(typescript_custom_section)]
const TS_LOGIC_LFD: &'static str = r#"
/** A Logic-LfD task: a domain, a problem and one demonstration (what the `LogicLfd` class reads). */
export interface LogicLfdSetup {
  /** PDDL domain text. */
  domain: string;
  /** PDDL problem text. */
  problem: string;
  /** The demonstration: IPC plan text, one `(action args)` a line, `;` comments. */
  demo: string;
  /** File names used in diagnostics (default `domain.pddl`, `problem.pddl`, `demo.plan`, `state`). */
  files?: { domain?: string; problem?: string; demo?: string; state?: string };
}
/** How to plan (`logicLfd`'s options, and `LogicLfd.replan`'s). */
export interface LogicLfdOptions {
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
  /** Also plan from scratch to G with the same search (the result's `scratch`). */
  compare?: boolean;
  /** Replay the merged plan on the lifted domain (the result's `valid`; default `true`). The
   *  replay costs several times the search on small tasks; `false` skips it (`valid: null`). */
  validate?: boolean;
}
/** What `logicLfd` reads: a task, the options and the current state S_C. */
export interface LogicLfdInput extends LogicLfdSetup, LogicLfdOptions {
  /** S_C as PDDL atoms (one a line or space separated; static facts optional). Any atoms over
   *  the problem's objects and the domain's predicates: facts no action adds and static facts
   *  that differ from the problem's are kept (the problem is grounded again from S_C). */
  state?: string;
  /** Or: S_C is the state after this plan prefix from the problem's init. Neither: the problem's
   *  initial state. Both given: `TypeError`. */
  after?: string;
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
/** What the `LogicLfd` class throws for bad input: `message` is `file:line:col: message`. */
export interface LogicLfdError extends Error {
  kind: 'parse' | 'demo' | 'state' | 'options';
  diagnostics: LogicLfdDiagnostic[];
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
  /** S_C's atoms without the problem's static facts, sorted. */
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
  /** The lifted validator replayed `plan` from S_C to the goal; `null` without a plan or with
   *  `validate: false`. */
  valid: boolean | null;
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
    let texts = texts(F, &m)?;
    let current = match (
        optional_text(F, &m, "state")?,
        optional_text(F, &m, "after")?,
    ) {
        (Some(_), Some(_)) => {
            return Err(type_error(&format!(
                "{F}: input.state and input.after are exclusive: give one"
            )))
        }
        (Some(atoms), None) => Current::Atoms(atoms),
        (None, Some(prefix)) => Current::After(prefix),
        (None, None) => Current::Init,
    };
    let options = known_keys(&m, &LFD_KEYS, "input")
        .and_then(|()| files_option(&m, &FILE_KEYS))
        .and_then(|f| Ok((f, search_options(&m)?)));
    let (files, o) = match options {
        Ok(x) => x,
        Err(e) => return to_js(&LfdResult::options_failure(e)),
    };
    match prepare(&files, &texts) {
        Ok(lfd) => to_js(&answer(&lfd, &files, current, &o).with(&Fixed::of(&lfd))),
        Err((kind, d)) => to_js(&LfdResult::input_failure(kind, d)),
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
    let texts = texts(F, &m)?;
    to_js(&perturb_impl(&m, &texts))
}

fn perturb_impl(m: &Map<String, Value>, texts: &Texts) -> PerturbResult {
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
    match prepare(&files, texts) {
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
        Err((_, d)) => PerturbResult {
            message: location_message(&d),
            diagnostics: vec![d],
            ..PerturbResult::default()
        },
    }
}
