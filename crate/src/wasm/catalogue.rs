//! `catalogue`: every method, multi-goal mode, benchmark and disturbance level with its id, label
//! and one-line description (`lfd::catalogue`), from which the page builds its selects, tables
//! and tooltips.

use super::convert::to_js;
use wasm_bindgen::prelude::*;

/// Every method, multi-goal mode, benchmark and disturbance level: the id that options take, a
/// short label and a one-line description, each list in the order the page shows it.
#[wasm_bindgen(unchecked_return_type = "Catalogue")]
pub fn catalogue() -> Result<JsValue, JsValue> {
    to_js(&crate::lfd::catalogue())
}
