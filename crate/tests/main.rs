//! Integration tests (one binary, one sub-module per area).

mod ground;
mod lfd;
mod lqt;
mod multigoal;
mod pddl;
mod search;
mod sim;
mod validate;
mod fuzz;
mod soak;
