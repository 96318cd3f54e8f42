//! The paper's evaluation (§IV): closed-loop episodes, Table I (generalisation over random
//! initial states) and Table II (reactivity to disturbances L1–L4), with report writers that put
//! the measured numbers beside the paper's.
//!
//! * Table I: per benchmark, `tasks` random initial states (levels L1–L4 in turn, drawn by
//!   [`initial_scene_for`]); methods `linear`, `tamp`, `logic-lfd` (both modes) run the
//!   whole closed-loop episode from that state; success rate, and planning time of the first plan
//!   (mean ± sd and median, caller's clock).
//! * Table II: per benchmark and level, `trials` episodes from the template scene with one
//!   disturbance injected at a seeded moment, during a motion or at an idle moment
//!   ([`run_episode`]); methods `linear`, `rlds`, `logic-lfd`; simulated execution time mean ± sd
//!   over the successful trials (N/A if none succeeds), and what a mid-motion L1 cost
//!   (`table2_motion.rs`).
//! * Fig. 4 ([`fig4`]): LQT-CP against the classic DMP picking B2's hook and pulling its block
//!   to three goals through the stroke's via-points.

mod episode;
pub mod fig4;
pub mod fuzz;
pub mod hot_paths;
mod panic;
pub mod scaling;
mod soak;
mod table2_motion;
mod tables;
mod tasks;

pub use episode::{
    run_episode, run_episode_with, run_episode_with_blocks, EpisodeReport, EpisodeSpec,
    MotionEffect,
};
pub use panic::panic_message;
pub use soak::{
    soak, soak_with, ExplainedFailure, SoakFinding, SoakParams, SoakReport, SoakRunner,
};
pub use tables::{
    failure_group, infeasible, table1, table1_scene, table1_task_seed, table2, wilson, MeanSd,
    Redraw, Table1, Table1Cell, Table1Run, Table1Sweep, Table1Task, Table2, Table2Cell,
    Table2Sweep, Table2Trial, MAX_DRAWS, PAPER_TABLE1, PAPER_TABLE2, TABLE1_METHODS,
    TABLE2_METHODS,
};
pub use tasks::{demo_trace, demo_trace_for, initial_scene, initial_scene_for, template_task_for};
