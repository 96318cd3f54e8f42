//! LQT-CP: the fast path against the dense reference and the contract's invariants, the CLI on
//! the shared example and on bad input, skills and the classic DMP. This module holds the shared
//! example and the error measure its test files compare with.

mod cli;
mod pinned;
mod skills;
mod solver;

use nalgebra::DMatrix;

const EXAMPLE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/data/lqt/lqt-cp-example.json"
);

/// `max |got - exp| / max |exp|` (absolute when `exp` is zero).
fn rel_err(got: &DMatrix<f64>, exp: &DMatrix<f64>) -> f64 {
    assert_eq!(got.shape(), exp.shape(), "shapes differ");
    let scale = exp.amax();
    let diff = (got - exp).amax();
    if scale > 0.0 {
        diff / scale
    } else {
        diff
    }
}
