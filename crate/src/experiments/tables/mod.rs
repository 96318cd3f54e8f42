//! Table I (generalisation) and Table II (reactivity) runners and their markdown reports, with
//! the paper's numbers beside ours.
//!
//! One file per job: `table1` (random initial states, every method from each), `feasible` (the
//! rule that redraws a task no method could solve), `table2` (disturbed episodes per level).

mod common;
mod feasible;
mod table1;
mod table2;

pub(crate) use common::summary;
pub use common::{failure_group, wilson, MeanSd, PAPER_TABLE1, PAPER_TABLE2};
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
    fn a_summary_is_the_mean_sample_sd_and_median() {
        let s = summary(&[1.0, 2.0, 3.0, 10.0]).unwrap();
        assert!((s.mean - 4.0).abs() < 1e-12);
        assert!((s.sd - ((9.0_f64 + 4.0 + 1.0 + 36.0) / 3.0).sqrt()).abs() < 1e-12);
        assert!((s.median - 2.5).abs() < 1e-12);
        assert!(summary(&[]).is_none());
    }
}
