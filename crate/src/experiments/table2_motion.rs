//! Table II's report of the mid-motion disturbances (L1 hitting a moving arm): the pushes, the
//! TCP's deviation from the undisturbed path, the time lost, and the trials a level could not
//! be injected into (`docs/levels.md`).

use super::tables::{summary, Table2};
use crate::lfd::Level;

/// `mean ± sd` with `digits` decimals, or `—`.
fn fmt_mean_sd(v: &[f64], digits: usize) -> String {
    match summary(v) {
        Some(s) => format!("{:.digits$} ± {:.digits$}", s.mean, s.sd),
        None => "—".into(),
    }
}

impl Table2 {
    /// Markdown of the mid-motion disturbances (L1): how many hit a moving arm, the pushes, the
    /// TCP's deviation from the undisturbed path and the time lost, per method × benchmark.
    pub fn motion_markdown(&self) -> String {
        let mut out = String::from(
            "\nL1 during motion — per cell: trials whose disturbance hit a moving arm, the pushes of the hand among them and their size (mm), the TCP's largest distance from the undisturbed run's path of the action hit (mm), and the simulated time lost against the undisturbed run (s, successful trials), mean ± sd:\n\n| method | benchmark | mid-motion | pushes: push, mm | TCP deviation, mm | time lost, s |\n|---|---|---|---|---|---|\n",
        );
        for c in self.cells.iter().filter(|c| c.level == Level::L1) {
            out.push_str(&format!(
                "| {} | {} | {}/{} | {}: {} | {} | {} |\n",
                c.method.as_str(),
                c.benchmark.as_str().to_uppercase(),
                c.mid_motion,
                c.trials,
                c.push_mm.len(),
                fmt_mean_sd(&c.push_mm, 1),
                fmt_mean_sd(&c.deviation_mm, 1),
                fmt_mean_sd(&c.time_lost_s, 2),
            ));
        }
        let skipped: Vec<String> = self
            .cells
            .iter()
            .filter(|c| c.not_injected > 0)
            .map(|c| {
                format!(
                    "{} {} {} ×{}",
                    c.level.as_str().to_uppercase(),
                    c.method.as_str(),
                    c.benchmark.as_str().to_uppercase(),
                    c.not_injected
                )
            })
            .collect();
        if !skipped.is_empty() {
            out.push_str(&format!(
                "\nTrials the level could not be injected into (not counted above): {}.\n",
                skipped.join(", ")
            ));
        }
        out
    }
}
