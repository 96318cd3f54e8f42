//! `logic_lfd._core`: the Python module of logic-lfd, built by maturin (`pip install ./python`).
//!
//! Thin bindings over the `logic-lfd` crate: texts and plain values in, classes, dicts and
//! numpy arrays out. Every long call releases the GIL; every bad input raises one of the
//! exceptions of `errors` with its fields, never a panic across the boundary. The Python
//! package `logic_lfd` re-exports this module with its docs and type stubs.

use pyo3::prelude::*;

mod clock;
mod episode;
mod errors;
mod lfd;
mod lqt;
mod pddl;
mod session;
mod sweep;
mod task;

/// The extension module (`logic_lfd._core`).
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    pddl::register(m)?;
    lfd::register(m)?;
    lqt::register(m)?;
    session::register(m)?;
    episode::register(m)?;
    sweep::register(m)?;
    Ok(())
}
