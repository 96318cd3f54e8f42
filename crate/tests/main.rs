//! Integration tests (one binary, one sub-module per area).

mod ground;
mod multigoal;
mod search;
mod sim;
