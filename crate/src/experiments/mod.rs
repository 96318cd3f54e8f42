//! The paper's evaluation (§IV): closed-loop episodes, Table I (generalisation over random
//! initial states) and Table II (reactivity to disturbances L1–L4), with report writers that put
//! the measured numbers beside the paper's.
//!
//! * Table I: per benchmark, `tasks` random initial states (levels L1–L4 in turn, drawn by
//!   [`tasks`]); methods `linear`, `tamp`, `logic-lfd` (both modes) run the
//!   whole closed-loop episode from that state; success rate, and planning time of the first plan
//!   (mean ± sd and median, caller's clock).
//! * Table II: per benchmark and level, `trials` episodes from the template scene with one
//!   disturbance injected at a seeded moment, during a motion or at an idle moment
//!   ([`episode`]); methods `linear`, `rlds`, `logic-lfd`; simulated execution time mean ± sd
//!   over the successful trials (N/A if none succeeds), and what a mid-motion L1 cost
//!   ([`table2_motion`]).
//! * Fig. 4 ([`fig4`]): LQT-CP against the classic DMP picking B2's hook and pulling its block
//!   to three goals through the stroke's via-points.

pub mod episode;
pub mod fig4;
pub mod fuzz;
pub mod hot_paths;
pub mod scaling;
pub mod soak;
pub mod table2_motion;
pub mod tables;
pub mod tasks;

pub use episode::{
    run_episode, run_episode_with, run_episode_with_blocks, EpisodeReport, EpisodeSpec, Level,
};

/// The message of a caught panic (`catch_unwind`'s payload): its `String` or `&str`, else empty.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}
pub use tables::{table1, table2, Table1, Table2};
