//! Logic-LfD: the demonstration as a multi-goal specification, LogicIn, suffix merging, the
//! reactive closed loop of the paper's Algorithm 1, its baselines, and the browser [`Session`].
//!
//! * [`DemoTrace`]: L_0..L_N from the demonstrated actions, the goals 𝒢 with terminal costs c_k;
//! * [`logic_in`], [`plan_logic_lfd`]: LogicIn, merge, Logic-LfD planning in `paper` and `prioritised` modes;
//! * [`LogicLfd`], the method on any PDDL domain (text in, merged plans out);
//! * [`catalogue()`]: every method, mode, benchmark and disturbance level by id, label and
//!   description;
//! * the reactive loop and the session ([`Controller`], [`Session`]).

mod alternatives;
mod catalogue;
mod control;
mod demo;
mod disturb;
mod error;
mod exec;
mod logic;
mod model;
mod session;
mod skill;
mod symbolic;
#[cfg(test)]
pub(crate) mod testing;

pub use alternatives::{Alternative, AlternativeStatus};
pub use catalogue::{catalogue, Catalogue, CatalogueEntry, Level, Listed, Method, Mode, UnknownId};
pub use control::{ControlParams, Controller, Decision, FailReason, Replan, TaskBuilder};
pub use demo::{normalize_action, operator_index, state_names, DemoTrace, MultiGoalSpec};
pub use disturb::motion::Moving;
pub use disturb::{inject, Injection, TcpPush};
pub use exec::{ActionExec, ExecParams, ExecStatus};
pub use logic::{
    logic_in, merge_suffix, plan_logic_lfd, plan_logic_lfd_avoiding, plan_logic_lfd_prepared,
    prepare_search, LfdPlan, PlanSource,
};
pub use model::DomainModel;
pub use session::{
    check_folder, demo_actions, demo_trace_of, mix_seed, sources_for, ActionRecord, EePoint,
    EpisodeEvent, EpisodeLog, EpisodeResult, Frame, PerturbOutcome, Session, SessionError,
    SessionOptions, SessionParams, Status, StatusKind,
};
pub use skill::{
    skill_key, stroke_frame, LearnedSkill, SegmentKind, SkillKind, SkillLibrary, SkillSegment,
    StrokePlan, StrokeViaPoint,
};
pub use symbolic::observed::Observed;
pub use symbolic::{LogicLfd, Perturbed};

pub use error::LfdError;
