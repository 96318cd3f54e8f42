//! LQT-CP motion skills (paper §III-B, eqs. 1–4) and the classic DMP used for comparison.
//!
//! * [`LqtCp`]: linear quadratic tracking with control primitives — batch weights, the matrix F
//!   and the time-varying feedback gains K̃_t, on the exact conventions of `docs/formats.md`
//!   (fast structured path; [`solve_dense`] is the dense transcription kept for tests);
//! * [`build_reference`]: builds the reference μ and weights Q from via-points, goals and a tracked demo;
//! * [`run_case`]: the JSON contract of `logic-lfd lqt CASE.json`;
//! * [`Skill`]: an LQT-CP motion skill learned from one demonstrated segment in an object's frame,
//!   planned for a new start / object pose / via-points into a [`Trajectory`] executed by a
//!   [`FeedbackController`]; [`Dmp`] is the classic DMP behind the same [`MotionSkill`] trait;
//! * [`full_pipeline`]: weights, F, gains and one rollout in one call (the benchmark).

// Index loops mirror the formulas (A1[i][j], Y_t[i][k]) in this numeric code.
#![allow(clippy::needless_range_loop)]

mod basis;
mod case;
mod dmp;
mod dmp_skill;
mod dynamics;
mod error;
mod linalg;
mod reference;
mod riccati;
mod skill;
mod solver;
mod task;
mod trajectory;

pub use case::{
    run_case, CaseInput, CaseOutput, FeedbackSpec, LqtFeedback, LqtRollout, LqtTargetError,
};
pub use reference::{gains_recursive_dense, rollout_dense, solve_dense, DenseSolution};
pub use task::{
    build_reference, gradient, validate_targets, validate_tracking, Target, TargetRole, Tracking,
};

pub use basis::Basis;
pub use dmp::{Dmp, DmpParams, DmpRunner};
pub use error::LqtError;
pub use skill::{Skill, SkillParams};
pub use solver::{
    full_pipeline, BatchSolution, FeedbackGains, LqtConfig, LqtCp, Perturbation, Rollout, MAX_ORDER,
};
pub use trajectory::{FeedbackController, GripperEvent, MotionSkill, Policy, Trajectory, ViaPoint};
