//! # logic-lfd
//!
//! Learn a multi-step manipulation task from ONE demonstration and keep finishing it while the
//! world is disturbed — the method of *Logic-LfD* (RA-L 2024), written from the paper:
//!
//! * [`pddl`] reads typed STRIPS PDDL (with negative preconditions, equality, or-conditions and
//!   action costs) with line:column errors;
//! * [`plan`] grounds it into a bitset [`plan::Task`] and searches it (BFS, uniform cost, A*, greedy
//!   best-first; blind, h_max, h_add, h_FF, LM-cut), including the multi-goal search that plans to
//!   *any* state of the demonstration;
//! * [`lqt`] is LQT-CP (linear quadratic tracking with control primitives): motion skills with
//!   time-varying feedback gains that reject perturbations;
//! * [`sim`] is a small deterministic kinematic world (tables, shelf, blocks, hook, 7-DoF arms) with
//!   a scene graph of PDDL facts;
//! * `lfd` is the reactive loop (paper Algorithm 1) and its baselines; `experiments` reproduces
//!   the paper's Tables I and II.
//!
//! The core is plain `std` Rust: no clocks (time budgets come from the caller), every random
//! choice takes a seed. The same code runs natively and in WebAssembly (feature `wasm`).
#![warn(missing_docs)]

pub mod experiments;
pub mod lfd;
pub mod lqt;
pub mod pddl;
pub mod plan;
pub mod recorder;
pub mod sim;
pub mod tamp;
#[cfg(feature = "wasm-core")]
pub mod wasm;

/// What most programs need: Logic-LfD on a PDDL domain, the planner's configuration, and the
/// clock a search budget runs on.
///
/// ```
/// use logic_lfd::prelude::*;
/// let cfg = SearchConfig::new(Algorithm::LazyGbfs, HeuristicKind::HFf);
/// assert_eq!(Mode::default(), Mode::Paper);
/// # let _ = cfg;
/// ```
pub mod prelude {
    pub use crate::lfd::{LfdError, LfdPlan, LogicLfd, Mode, Observed, Perturbed, PlanSource};
    pub use crate::pddl::Source;
    pub use crate::plan::{
        Algorithm, Clock, HeuristicKind, NoClock, SearchConfig, SearchOutcome, SearchStats, State,
        ValidationReport,
    };
}
