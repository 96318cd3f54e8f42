//! Helpers shared by several test modules: benchmark worlds, tasks and skills (`bench`), running
//! actions with the executor (`exec`), and running the `logic-lfd` binary (`cli`).

pub(crate) mod bench;
pub(crate) mod cli;
pub(crate) mod exec;
