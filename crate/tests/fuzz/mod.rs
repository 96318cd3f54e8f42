//! Input hardening: seeded, bounded property-based mutation tests for every input parser of the
//! library. The mutators and the guarantees (the oracle) live in the library,
//! `logic_lfd::experiments::fuzz`, shared with `logic-lfd fuzz` (longer runs, saved corpus); here
//! each target runs a bounded number of cases from a fixed seed. Each case asserts
//!
//! * no panic (every call runs under `std::panic::catch_unwind`),
//! * an error carries a location (`line:col` for text, a JSON key path or `line L column C` for
//!   JSON),
//! * nothing is partially applied (a refused world operation leaves the world's snapshot
//!   byte-identical).
//!
//! Case counts are sized so that the whole set runs ≥ 10 000 inputs in well under a minute in
//! the test profile (`opt-level = 1`); `FUZZ_CASES_SCALE=N` multiplies them for longer runs.
//! Every crash found by `logic-lfd fuzz` becomes a regression test in `regressions.rs`, named
//! after the behaviour it protects.

mod episode;
mod lqt_case;
mod pddl;
mod plan_file;
mod regressions;
mod scene;
mod world_ops;

use std::panic::{catch_unwind, AssertUnwindSafe};

use logic_lfd::experiments::fuzz::{self, FuzzTarget, Verdict};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// Multiplier of every case count (environment `FUZZ_CASES_SCALE`, default 1).
fn scale() -> u32 {
    std::env::var("FUZZ_CASES_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1)
}

/// A deterministic runner: `cases` × scale cases from a fixed seed, no persistence files, no
/// shrinking beyond a few steps (a failure prints its input).
pub(crate) fn runner(cases: u32, seed: u8) -> TestRunner {
    TestRunner::new_with_rng(
        Config {
            cases: cases * scale(),
            failure_persistence: None,
            max_shrink_iters: 64,
            ..Config::default()
        },
        TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]),
    )
}

/// Runs `f`, turning a panic into a test failure that names the input.
pub(crate) fn no_panic<T>(what: &str, f: impl FnOnce() -> T) -> Result<T, TestCaseError> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|p| {
        let msg = logic_lfd::experiments::panic_message(p.as_ref());
        TestCaseError::fail(format!("{what}: panicked: {msg}"))
    })
}

/// `cases` inputs of `target` (the library's mutator, `max_edits` edits at most, case seeds
/// drawn by proptest), each through the library's oracle. Returns (accepted, refused).
pub(crate) fn run_target(target: FuzzTarget, cases: u32, seed: u8, max_edits: usize) -> (u32, u32) {
    let bases = fuzz::base_inputs(target).unwrap();
    let counts = std::cell::Cell::new((0u32, 0u32));
    runner(cases, seed)
        .run(&any::<u64>(), |s| {
            let input = fuzz::generate(target, &bases, s, 0, max_edits);
            match no_panic(target.as_str(), || fuzz::check(target, &input))? {
                Ok(v) => {
                    let (a, r) = counts.get();
                    counts.set(if v == Verdict::Accepted {
                        (a + 1, r)
                    } else {
                        (a, r + 1)
                    });
                    Ok(())
                }
                Err(m) => Err(TestCaseError::fail(format!(
                    "{}: {m}\ninput: {input:.2000}",
                    target.as_str()
                ))),
            }
        })
        .unwrap();
    counts.get()
}
