//! Integration tests (one binary, one sub-module per area).

mod any_domain;
mod circles;
mod declared_names;
mod exec;
mod fig4;
mod fuzz;
mod ground;
mod layers;
mod levels;
mod lfd;
mod lfd_cli;
mod load_errors;
mod lqt;
mod multigoal;
mod observed_states;
mod pddl;
mod recorder;
mod search;
mod sim;
mod soak;
mod standalone;
mod support;
mod sweeps;
mod tables;
mod tamp;
mod validate;
