//! Integration tests (one binary, one sub-module per area).

mod ground;
mod multigoal;
mod pddl;
mod search;
mod validate;
mod lqt;
