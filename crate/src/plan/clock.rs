//! Caller-supplied time source for search time budgets.
//!
//! The planning core never reads the system clock (the standard library's monotonic clock panics
//! on wasm32). A caller that wants a time limit passes a [`Clock`]: the CLI one wraps that clock,
//! the browser one wraps `performance.now()`. Only differences of [`Clock::now_secs`] are used.

/// How many expansions a search makes between two [`Clock::progress`] calls.
pub const PROGRESS_EVERY: u64 = 1024;

/// A monotonic time source in seconds (any origin), and the listener of a long search.
pub trait Clock {
    /// Current time in seconds since an arbitrary, fixed origin.
    fn now_secs(&self) -> f64;

    /// Called by a running search every [`PROGRESS_EVERY`] expansions with its count so far, so
    /// a caller can show a long search while it runs. The default ignores it.
    fn progress(&self, _expanded: u64) {}
}

/// A clock that never advances: time limits never trigger and reported times are 0.
///
/// For callers that only use node budgets (tests, deterministic replays).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoClock;

impl Clock for NoClock {
    fn now_secs(&self) -> f64 {
        0.0
    }
}

impl<C: Clock + ?Sized> Clock for &C {
    fn now_secs(&self) -> f64 {
        (**self).now_secs()
    }

    fn progress(&self, expanded: u64) {
        (**self).progress(expanded);
    }
}
