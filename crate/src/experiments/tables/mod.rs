//! Table I (generalisation) and Table II (reactivity) runners and their markdown reports, with
//! the paper's numbers beside ours.
//!
//! One file per job: `table1` (random initial states, every method from each), `feasible` (the
//! rule that redraws a task no method could solve), `table2` (disturbed episodes per level).

mod common;
mod feasible;
mod table1;
mod table2;

pub use common::{stats, MeanSd, PAPER_TABLE1, PAPER_TABLE2};
pub use feasible::infeasible;
pub use table1::{
    table1, table1_scene, table1_task_seed, Redraw, Table1, Table1Cell, Table1Run, Table1Sweep,
    Table1Task, MAX_DRAWS, TABLE1_METHODS,
};
pub use table2::{table2, Table2, Table2Cell, Table2Sweep, Table2Trial, TABLE2_METHODS};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_are_mean_sample_sd_and_median() {
        let (m, sd, med) = stats(&[1.0, 2.0, 3.0, 10.0]).unwrap();
        assert!((m - 4.0).abs() < 1e-12);
        assert!((sd - ((9.0_f64 + 4.0 + 1.0 + 36.0) / 3.0).sqrt()).abs() < 1e-12);
        assert!((med - 2.5).abs() < 1e-12);
        assert!(stats(&[]).is_none());
    }
}
