//! The motion skills the executor runs for each segment of an action (paper §III-B, Algorithm 1
//! line 14: τ = LQT-CP(a)): one skill per demonstrated action primitive.
//!
//! Every demonstrated action is split into segments, each in the frame of the action's anchor
//! object (`sim::demo`): a grasp or a release at its gripper event into an *approach* (start →
//! grasp or release point) and a *retreat* (after the event); a pull into its *stroke* (from the
//! hook's descent behind the block to the end of the drag, `skill/stroke.rs`). One skill is
//! learned per action schema and segment, keyed `action/segment` by the names the domain's
//! `motions.json` declares (`pick/approach`, `place-on-shelf/retreat`, `pull/stroke`, …), with
//! `@hook` appended when the action's object is a hook (it is grasped at its handle, not at its
//! centre). Where a schema occurs several times in the demo, its first occurrence with a usable
//! segment is learned (a retreat only when it stays near the object). A schema the demo never
//! shows borrows the skill of the first demonstrated schema with the same declared motion
//! (`unstack` moves as `pick` does).
//!
//! A skill is LQT-CP (`lqt::Skill`, DMP mode: track the demo's acceleration profile, reach the
//! goal with high precision, pass the via-points with the goal's precision) or a classic DMP
//! (`lqt::Dmp`, no via-points). At execution a segment is planned from the current TCP to the
//! anchor's *current* pose and run through its feedback controller (u_t = −K̃_t x̃_t); when the
//! anchor moves the controller is re-targeted to the new frame. Segments without a learned skill
//! (custom demonstrations without trajectories) follow the minimum-jerk profile
//! x(s) = x_0 + (x_T − x_0)(10 s³ − 15 s⁴ + 6 s⁵), s = t/T.

mod kind;
mod library;
mod stroke;
mod stroke_plan;

pub use kind::SkillKind;
pub use library::{skill_key, LearnedSkill, SegmentKind, SkillLibrary, SkillSegment};
pub use stroke::{stroke_frame, StrokePlan, StrokeViaPoint};
