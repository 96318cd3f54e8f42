//! The arm a world moves: its kinematics, joint limits and speeds, ready posture, gripper width
//! and link capsules, for the built-in Panda ([`ArmModel::panda`]) or a robot read from its URDF
//! ([`ArmModel::from_robot`]).
//!
//! # Joint vectors
//! - Always `[f64; DOF]` (7 entries): a 6-joint arm leaves the last entry at 0 with the range
//!   `[0, 0]`, so the world, the executor and the streams handle both alike.
//! - A URDF joint without limits (continuous) gets the range `[−2π, 2π]`.
//!
//! # Solids
//! The world, its path checks and the streams test an arm with its solids
//! ([`ArmModel::arm_parts`], base first, the hand's capsule last): the built-in Panda's link
//! capsules, or a URDF arm's own `<collision>` shapes (mesh hulls, boxes, cylinders, spheres).
//! Capsules fitted once to a URDF arm's shapes (one per moving joint's frame, along the longest
//! side of their bounding box, as small as covers them) are what a frame draws.

mod arm;
#[cfg(not(first_load))]
mod chain_arm;
mod ik;
mod parts;

pub(crate) use arm::joint_line;
pub use arm::{ArmModel, Joints};
pub use ik::{IkParams, IkSolution, Unreachable};
pub(crate) use parts::{ArmPart, ArmShape};
