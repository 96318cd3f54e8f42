//! Helpers shared by several test modules: benchmark worlds, tasks and skills (`bench`), and
//! running actions with the executor (`exec`).

pub(crate) mod bench;
pub(crate) mod exec;
