//! The names of a generated task's blocks, and the generator's error.

use crate::sim::SceneError;

/// The names of an N-block task: `a`, `b`, … (N ≤ 26).
pub fn block_names(n: usize) -> Vec<String> {
    (0..n)
        .map(|i| char::from(b'a' + (i % 26) as u8).to_string())
        .collect()
}

/// A [`SceneError`] of the generator.
pub(super) fn err(message: impl Into<String>) -> SceneError {
    SceneError {
        path: "generate".into(),
        message: message.into(),
    }
}
