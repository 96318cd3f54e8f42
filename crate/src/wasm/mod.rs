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
//! `check`, `logicLfd` and `logicLfdPerturb`, task folders (`Session.fromFolder`,
//! `Session.taskFiles`), the Compare tab's `table1Task`, `table1Report` and `table1Episode`, and the
//! npm-only `lqt`, `validate`, `runEpisode` and `LogicLfd` class;
//! `wasm` adds them (the npm package, and the module the page loads after its first frame).

#[cfg(feature = "wasm")]
use convert::{from_js, js_err, to_js};
use wasm_bindgen::prelude::*;

mod args;
#[cfg(feature = "wasm")]
mod bench;
mod benchmark_info;
mod catalogue;
mod convert;
#[cfg(feature = "wasm")]
mod folder;
#[cfg(feature = "wasm")]
mod logic_lfd;
#[cfg(feature = "wasm")]
mod pddl;
#[cfg(feature = "wasm")]
mod progress;
#[cfg(feature = "wasm")]
mod reliability;
#[cfg(not(first_load))]
mod robot;
mod session;
#[cfg(feature = "wasm")]
mod table1;
#[cfg(feature = "wasm")]
mod teach;

pub use benchmark_info::BenchmarkInfo;
#[cfg(feature = "wasm")]
pub use pddl::{Diagnostic, PlanFailed, PlanFound, PlanOptions, PlanOutcome, Validation};
pub use session::WasmSession;

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

/// The crate version, e.g. `"0.1.0"`.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
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
    use crate::lqt::{run_case, CaseInput};
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
