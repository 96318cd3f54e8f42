//! WebAssembly bindings (feature `wasm`): the only module that touches `wasm-bindgen`.
//!
//! Everything crosses the boundary as plain JSON-compatible data (serde through
//! `serde-wasm-bindgen`, TypeScript declarations from `tsify` or hand-written custom sections);
//! every fallible call returns a rejected value carrying a message instead of panicking.

use wasm_bindgen::prelude::*;

/// The crate version, e.g. `"0.1.0"`.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}
