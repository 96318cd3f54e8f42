//! The wall clock search budgets run on: the core takes its clock from the caller.

use std::time::Instant;

use logic_lfd::plan::Clock;

/// Seconds since the call began.
pub(crate) struct WallClock(Instant);

impl WallClock {
    /// A clock whose origin is now.
    pub(crate) fn start() -> Self {
        WallClock(Instant::now())
    }
}

impl Clock for WallClock {
    fn now_secs(&self) -> f64 {
        self.0.elapsed().as_secs_f64()
    }
}
