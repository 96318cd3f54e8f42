//! WebAssembly bindings (feature `wasm`): the only module that calls `wasm-bindgen`, `js-sys` and
//! `web-sys`.
//!
//! Everything crosses the boundary as plain JSON-compatible data (serde through JSON text and
//! `JSON.parse` / `JSON.stringify`, so that one serde_json (de)serialiser serves every type);
//! every fallible call returns a rejected value carrying a message instead of panicking. The
//! TypeScript declarations are derived with `tsify` from the types that cross (the core's behind
//! feature `wasm-core`), `Option` as `null`; only inputs read key by key rather than deserialised
//! (`LqtCase`, the `LogicLfd*` inputs) and the benchmark rows are written by hand.
//!
//! Feature `wasm-core` alone builds the page's first-load module (cfg `first_load`, set by
//! `build.rs`): the closed-loop `Session` on B1's template task, `benchmark`, `blockRange` and
//! `catalogue`, without Teach mode (`Teacher`, taught tasks), `Session.replay`,
//! `Session.fromScene`, B2, B3, N-block tasks, JSON paths in load errors, the PDDL tab's `plan`,
//! `check`, `logicLfd` and `logicLfdPerturb`, and the npm-only `lqt`, `validate`, `runEpisode` and
//! `LogicLfd` class; `wasm` adds them (the npm package, and the module the page loads after its
//! first frame).

use crate::plan::Clock;
use wasm_bindgen::prelude::*;

mod args;
#[cfg(feature = "wasm")]
mod bench;
mod benchmark_info;
mod catalogue;
#[cfg(feature = "wasm")]
mod logic_lfd;
#[cfg(feature = "wasm")]
mod pddl;
#[cfg(feature = "wasm")]
pub mod reliability;
mod session;
#[cfg(feature = "wasm")]
mod teach;

pub use benchmark_info::BenchmarkInfo;
#[cfg(feature = "wasm")]
pub use pddl::{Diagnostic, PlanFailed, PlanFound, PlanOptions, PlanOutcome, Validation};
pub use session::WasmSession;

thread_local! {
    /// The global `performance` object (windows, workers and node ≥ 16 have one), read once.
    static PERFORMANCE: Option<web_sys::Performance> =
        js_sys::Reflect::get(&js_sys::global(), &JsValue::from_str("performance"))
            .ok()
            .filter(JsValue::is_object)
            .map(JsCast::unchecked_into);
}

/// `performance.now()` (ms); 0 where the global has no `performance` (time limits then never
/// trigger and reported times are 0, as with `NoClock`).
fn performance_now() -> f64 {
    PERFORMANCE.with(|p| p.as_ref().map_or(0.0, web_sys::Performance::now))
}

/// The message of the last panic (a bug: user input never panics), for [`last_panic`].
static LAST_PANIC: std::sync::Mutex<String> = std::sync::Mutex::new(String::new());

/// Runs when the module is instantiated: a panic (which aborts the module) is logged to the
/// console with its location and kept for [`last_panic`], so the page can say what happened.
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        let message = format!("logic-lfd panicked: {info}");
        web_sys::console::error_1(&JsValue::from_str(&message));
        if let Ok(mut last) = LAST_PANIC.lock() {
            *last = message;
        }
    }));
}

/// The message of the last panic inside the module, or `""`. After a panic the module is dead
/// (it aborts); load it again to continue.
#[wasm_bindgen(js_name = lastPanic)]
pub fn last_panic() -> String {
    LAST_PANIC.lock().map(|s| s.clone()).unwrap_or_default()
}

/// The JS high-resolution clock, for search time limits and reported times.
struct PerformanceClock;

impl Clock for PerformanceClock {
    fn now_secs(&self) -> f64 {
        performance_now() / 1000.0
    }
}

/// The crate version, e.g. `"0.1.0"`.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// Converts any displayable error into a rejected value (a JS `Error` with the message).
fn js_err(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// `JSON.stringify(value)`: `None` for `undefined`, a function or a symbol; `Err` for a BigInt
/// or a cycle.
fn json_stringify(value: &JsValue) -> Result<Option<String>, JsValue> {
    js_sys::JSON::stringify(value).map(|s| JsValue::from(s).as_string())
}

/// Reads plain data from JS through its JSON text, so that one deserialiser (serde_json's, which
/// the core uses for JSON text) serves every type. `undefined` reads as `null`, and an object's
/// `undefined` fields as absent (JSON has no `undefined`). Errors are the serde messages, without
/// a position in the text.
fn from_js<T: serde::de::DeserializeOwned>(v: &JsValue) -> Result<T, String> {
    let text = json_stringify(v)
        .map_err(|_| "not JSON data (a BigInt, or a cycle)".to_string())?
        .unwrap_or_else(|| "null".into());
    serde_json::from_str(&text).map_err(|e| json_message(&e))
}

/// A serde_json error without its ` at line L column C` suffix.
fn json_message(e: &serde_json::Error) -> String {
    let s = e.to_string();
    let at = format!(" at line {} column {}", e.line(), e.column());
    match s.strip_suffix(&at) {
        Some(m) if e.line() != 0 => m.to_string(),
        _ => s,
    }
}

/// Serialises plain data for JS (objects, not `Map`s; numbers for `u64`) through serde_json's
/// compact text and `JSON.parse`: floats are written shortest-round-trip, so JS gets the same
/// numbers; a non-finite one would come out as `null`, as in the CLI's JSON.
fn to_js<T: serde::Serialize>(v: &T) -> Result<JsValue, JsValue> {
    let text = serde_json::to_string(v).map_err(js_err)?;
    js_sys::JSON::parse(&text).map_err(|_| js_err("JSON.parse failed").into())
}

/// Solves one LQT-CP case (the contract of `docs/formats.md`, as `logic-lfd lqt CASE.json`).
///
/// `case` is the case object or its JSON text; the result is the output object (`A`, `B`, `phi`,
/// `w`, `u`, `x`, `pos`, `cost`, `target_errors`, `feedback`). A malformed case rejects with a
/// message naming the key.
#[cfg(feature = "wasm")]
#[wasm_bindgen(unchecked_return_type = "LqtOutput")]
pub fn lqt(
    #[wasm_bindgen(unchecked_param_type = "LqtCase | string")] case: JsValue,
) -> Result<JsValue, JsValue> {
    use crate::lqt::case::{run_case, CaseInput};
    let input = match case.as_string() {
        Some(text) => CaseInput::from_json_str(&text),
        None => {
            args::object_arg("lqt", "case", &case, false).map_err(|_| {
                args::type_error(&format!(
                    "lqt: case must be an object or a JSON string, got {}",
                    args::type_name(&case)
                ))
            })?;
            let v: serde_json::Value = from_js(&case).map_err(js_err)?;
            CaseInput::from_value(&v)
        }
    }
    .map_err(js_err)?;
    let out = run_case(&input).map_err(js_err)?;
    to_js(&out)
}

// A case is read key by key (`lqt::case`: errors name the key path and the shape expected),
// not deserialised into a Rust type: its declaration is written here; the output is derived.
#[cfg(feature = "wasm")]
#[wasm_bindgen(typescript_custom_section)]
const TS_LQT_CASE: &'static str = r#"
/** An LQT-CP case (docs/formats.md); unknown keys are ignored. */
export interface LqtCase {
  dim: number; order: number; dt: number; n_steps: number; r: number;
  basis: { type: "rbf" | "bernstein" | "fourier" | "piecewise"; n_fct: number; centers?: number[]; lambda?: number };
  x0: number[];
  reference: { mu: number[][]; q_diag: number[][] };
  targets?: { t: number; role: TargetRole; pos: number[]; w_pos: number; vel?: number[]; w_vel?: number }[];
  tracking?: { demo_pos: number[][]; weights_per_order: number[] } | null;
  feedback?: { x_init: number[]; perturbation?: { after_step: number; delta: number[] } | null } | null;
  [key: string]: unknown;
}
"#;

/// Converts a JS number to a seed (a non-negative integer below 2^53).
fn seed_of(seed: f64) -> Result<u64, JsError> {
    if seed.is_finite() && seed >= 0.0 && seed.fract() == 0.0 && seed <= 9_007_199_254_740_991.0 {
        Ok(seed as u64)
    } else {
        Err(js_err(format!(
            "seed must be a non-negative integer, got {seed}"
        )))
    }
}
