//! The kinematic world's state: the [`World`] itself, its tunables ([`WorldParams`]) and the
//! small types its stages share (arms, regions, gripper commands, errors of calls).
//!
//! See the module header of [`crate::sim`] for the contact rules in words. Each stage lives in
//! its own file: loading and saving scenes (`load`), queries (`accessors`), path checks for
//! planners (`path_checks`), the fixed step (`step`) and the hook's pushes (`hook`), settling
//! released bodies (`settle`), user moves (`user_moves`) and the invariants (`invariants`).

mod accessors;
mod body;
mod hook;
mod invariants;
mod load;
mod path_checks;
mod settle;
mod state;
mod step;
mod user_moves;

pub(crate) use body::Body;
pub use invariants::Violation;
pub(crate) use state::{Arm, Region, LINK_TOLERANCE};
pub use state::{GripperCommand, SceneError, SimError, World, WorldParams};

pub use step::WorldEvent;
pub use user_moves::{MoveOutcome, Refused};
