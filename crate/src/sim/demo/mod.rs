//! Demonstrations (`domains/*/demo.json`): the template task's action sequence and, per action,
//! the end-effector trajectory expressed relative to the object it acts on; recorded by a
//! scripted expert in the simulator, replayable in it.
//!
//! **Frame convention.** Each action has an *anchor* object and an anchor frame `F` = the anchor's
//! centre with its yaw about world `z` (no tilt):
//! * `pick`, `unstack`, `pull`: the picked / pulled block (or the hook) at the start of the action;
//! * `place`, `place-on-shelf`, `stack`: the carried object at the pose where it is put down
//!   (its resting pose at the end of the action).
//!
//! A sample `[x, y, z, yaw]` is the gripper's tool centre point in `F` (metres) and the gripper's
//! yaw about `z` relative to `F`'s yaw (radians); the gripper always points straight down
//! (`panda::down_orientation`). Samples are taken every `dt` = 10 ms after each simulator step,
//! rounded to 0.1 mm / 1 mrad. A gripper event at sample `k` was commanded at the step that
//! produced sample `k`. `key_points` name the samples that matter to a motion skill (grasp,
//! release, the hook's descent and contact, the end of its stroke) and a pull's `via_points`
//! name where its hook must pass: the via-points of its LQT-CP skill.
//!
//! **Expert.** Each motion is a chain of minimum-jerk segments `p(τ) = p₀ + (p₁ − p₀)(10τ³ −
//! 15τ⁴ + 6τ⁵)` between way-points (approach above the object, the grasp / place pose, a lift),
//! with seeded human-like variation of segment durations (±15 %), approach heights (±2 cm) and
//! way-point offsets (±6 mm above, ±1.5 mm at contact).

mod data;
mod expert;
mod flight;
mod pull;
mod replay;
mod segment;
mod template;

pub(crate) use data::min_jerk;
pub use data::{
    committed, from_json, parse, AnchorPose, DemoAction, DemoError, DemoViaPoint, Demonstration,
    GripperChange, KeyPoint,
};
pub use expert::{record, record_script, ExpertParams};
pub use pull::{
    pull_hook_poses, pull_hook_poses_turned, pulled_block_position, PULL_LIFT, PULL_TARGET_RADIUS,
    PULL_TURNS,
};
pub use replay::{demo_states, replay};
pub use template::{Script, ScriptStep};
