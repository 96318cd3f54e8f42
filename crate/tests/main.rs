//! Integration tests (one binary, one sub-module per area).

mod multigoal;
mod search;
