//! Exit codes shared by every subcommand.
#![allow(dead_code)]

/// Success.
pub const OK: u8 = 0;
/// No answer where one may not exist: `robot ik` found no joints for the pose.
pub const UNREACHABLE: u8 = 1;
/// Bad input: a file, a flag or a value.
pub const BAD_INPUT: u8 = 2;
/// The goal is proved unreachable.
pub const UNSOLVABLE: u8 = 3;
/// A budget ran out.
pub const BUDGET: u8 = 4;
/// A plan does not replay.
pub const INVALID_PLAN: u8 = 5;
