//! Values across the boundary: plain data in and out through JSON, errors, seeds, and the
//! page's clock.

use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

use crate::plan::Clock;

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
pub(super) fn performance_now() -> f64 {
    PERFORMANCE.with(|p| p.as_ref().map_or(0.0, web_sys::Performance::now))
}

/// The JS high-resolution clock, for search time limits and reported times.
pub(super) struct PerformanceClock;

impl Clock for PerformanceClock {
    fn now_secs(&self) -> f64 {
        performance_now() / 1000.0
    }
}

/// Converts any displayable error into a rejected value (a JS `Error` with the message).
pub(super) fn js_err(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// `JSON.stringify(value)`: `None` for `undefined`, a function or a symbol; `Err` for a BigInt
/// or a cycle.
pub(super) fn json_stringify(value: &JsValue) -> Result<Option<String>, JsValue> {
    js_sys::JSON::stringify(value).map(|s| JsValue::from(s).as_string())
}

/// Reads plain data from JS through its JSON text, so that one deserialiser (serde_json's, which
/// the core uses for JSON text) serves every type. `undefined` reads as `null`, and an object's
/// `undefined` fields as absent (JSON has no `undefined`). Errors are the serde messages, without
/// a position in the text.
pub(super) fn from_js<T: serde::de::DeserializeOwned>(v: &JsValue) -> Result<T, String> {
    let text = json_stringify(v)
        .map_err(|_| "not JSON data (a BigInt, or a cycle)".to_string())?
        .unwrap_or_else(|| "null".into());
    serde_json::from_str(&text).map_err(|e| json_message(&e))
}

/// A serde_json error without its ` at line L column C` suffix.
pub(super) fn json_message(e: &serde_json::Error) -> String {
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
pub(super) fn to_js<T: serde::Serialize>(v: &T) -> Result<JsValue, JsValue> {
    let text = serde_json::to_string(v).map_err(js_err)?;
    js_sys::JSON::parse(&text).map_err(|_| js_err("JSON.parse failed").into())
}

/// Converts a JS number to a seed (a non-negative integer below 2^53).
pub(super) fn seed_of(seed: f64) -> Result<u64, JsError> {
    if seed.is_finite() && seed >= 0.0 && seed.fract() == 0.0 && seed <= 9_007_199_254_740_991.0 {
        Ok(seed as u64)
    } else {
        Err(js_err(format!(
            "seed must be a non-negative integer, got {seed}"
        )))
    }
}
