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
use tsify::Tsify;
use wasm_bindgen::prelude::*;

mod class;
mod diagnostics;
mod input;
mod query;

use diagnostics::{location_message, options_diag, LogicLfdDiagnostic};
use input::{
    count_option, files_option, known_keys, object_fields, optional_text, search_options, texts,
    Texts, FILE_KEYS, LFD_KEYS,
};
use query::{answer, prepare, Current, Fixed, LogicLfdResult};

use super::args::type_error;
use super::convert::to_js;

// The inputs are read key by key (`input.rs`: a wrong type names the key, a bad option is an
// `options` result), not deserialised into a Rust type, and the class's error is a JS `Error`
// with two properties: their declarations are written here, naming the derived types they use.
#[wasm_bindgen(typescript_custom_section)]
const TS_LOGIC_LFD_INPUT: &'static str = r#"
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
  mode?: Mode;
  /** Default `astar`. */
  search?: Algorithm;
  /** Default `lmcut` for `astar`, `hff` otherwise. */
  heuristic?: HeuristicKind;
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
/** What the `LogicLfd` class throws for bad input: `message` is `file:line:col: message`. */
export interface LogicLfdError extends Error {
  kind: 'parse' | 'demo' | 'state' | 'options';
  diagnostics: LogicLfdDiagnostic[];
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
"#;

/// The longest random walk of [`logic_lfd_perturb`] when `maxSteps` is not given.
pub const DEFAULT_PERTURB_STEPS: usize = 8;

/// One drawn state: its fluents, the demonstration state its walk started from, the walk's
/// length.
#[derive(Debug, Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
#[tsify(missing_as_null)]
struct LogicLfdPerturbed {
    /// The state's fluents.
    facts: Vec<String>,
    /// The demonstration state L_k the walk started from.
    from_k: usize,
    /// Random actions taken.
    steps: usize,
}

/// What `logicLfdPerturb` drew.
#[derive(Debug, Default, Serialize, Tsify)]
#[tsify(missing_as_null)]
struct LogicLfdPerturbResult {
    /// `true` iff the inputs were read.
    ok: bool,
    /// One line for people (`''` when ok).
    message: String,
    /// Located errors (empty when ok).
    diagnostics: Vec<LogicLfdDiagnostic>,
    /// The states drawn.
    states: Vec<LogicLfdPerturbed>,
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
        Err(e) => return to_js(&LogicLfdResult::options_failure(e)),
    };
    match prepare(&files, &texts) {
        Ok(lfd) => to_js(&answer(&lfd, &files, current, &o).with(&Fixed::of(&lfd))),
        Err((kind, d)) => to_js(&LogicLfdResult::input_failure(kind, d)),
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

fn perturb_impl(m: &Map<String, Value>, texts: &Texts) -> LogicLfdPerturbResult {
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
            return LogicLfdPerturbResult {
                message: e.clone(),
                diagnostics: vec![options_diag(e)],
                ..LogicLfdPerturbResult::default()
            }
        }
    };
    match prepare(&files, texts) {
        Ok(lfd) => LogicLfdPerturbResult {
            ok: true,
            message: String::new(),
            diagnostics: vec![],
            states: lfd
                .perturb(count, seed, max_steps)
                .into_iter()
                .map(|p| LogicLfdPerturbed {
                    facts: lfd.names(&p.state),
                    from_k: p.from_k,
                    steps: p.steps,
                })
                .collect(),
        },
        Err((_, d)) => LogicLfdPerturbResult {
            message: location_message(&d),
            diagnostics: vec![d],
            ..LogicLfdPerturbResult::default()
        },
    }
}
