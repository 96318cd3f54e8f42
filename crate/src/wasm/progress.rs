//! A clock that also reports a long search's progress to a JS callback, at most every
//! [`REPORT_MS`] of wall time, so that the page can show a search while its worker is busy with
//! it (the worker answers no message until the step returns).

use super::convert::performance_now;
use crate::plan::Clock;
use std::cell::Cell;
use wasm_bindgen::JsValue;

/// Wall time between two reports (ms); a step shorter than this reports nothing.
const REPORT_MS: f64 = 100.0;

/// `performance.now()` as the clock, `callback(expanded, ms)` as the progress listener.
pub(super) struct ProgressClock<'a> {
    callback: &'a js_sys::Function,
    started: f64,
    last: Cell<f64>,
}

impl<'a> ProgressClock<'a> {
    /// Starts timing now (the step's start).
    pub(super) fn new(callback: &'a js_sys::Function) -> Self {
        let now = performance_now();
        ProgressClock {
            callback,
            started: now,
            last: Cell::new(now),
        }
    }
}

impl Clock for ProgressClock<'_> {
    fn now_secs(&self) -> f64 {
        performance_now() / 1000.0
    }

    fn progress(&self, expanded: u64) {
        let now = performance_now();
        if now - self.last.get() < REPORT_MS {
            return;
        }
        self.last.set(now);
        // The search goes on whatever the listener does: a throw is dropped.
        let _ = self.callback.call2(
            &JsValue::NULL,
            &JsValue::from_f64(expanded as f64),
            &JsValue::from_f64(now - self.started),
        );
    }
}
