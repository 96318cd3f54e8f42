//! Helpers shared by several test modules: benchmark worlds, tasks and skills (`bench`), running
//! actions with the executor (`exec`), the invariants the closed-loop tests hold
//! (`invariants`), running the `logic-lfd` binary (`cli`), and the library's source files
//! (`source`).

pub(crate) mod bench;
pub(crate) mod cli;
pub(crate) mod exec;
pub(crate) mod invariants;
pub(crate) mod source;
