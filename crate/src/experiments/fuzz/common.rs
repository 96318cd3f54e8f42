//! What every fuzz target shares: the verdict, the guarantee check, random indices and the
//! benchmark an input's header names.

use rand::Rng;
use rand_pcg::Pcg64Mcg;

use crate::sim::Benchmark;

/// What the parser under test did with an input that kept every guarantee.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Accepted (and, where it applies, the accepted value behaved).
    Accepted,
    /// Refused with a located error.
    Refused,
}

/// The benchmark folders whose files are base inputs, with the benchmark each one holds.
pub(super) const BENCH_DIRS: [(&str, Benchmark); 3] = [
    ("b1-tower", Benchmark::B1),
    ("b2-workspace-reach", Benchmark::B2),
    ("b3-dual-arm", Benchmark::B3),
];

/// A random index (edits take it modulo what they index).
pub(super) fn idx(rng: &mut Pcg64Mcg) -> usize {
    rng.random::<u32>() as usize
}

/// `Ok` when `ok`, else the broken guarantee `msg()`.
pub(super) fn ensure(ok: bool, msg: impl FnOnce() -> String) -> Result<(), String> {
    if ok {
        Ok(())
    } else {
        Err(msg())
    }
}

/// The benchmark a `; fuzz <dir> …` header names (B1 without a header), and the header's words.
pub(super) fn header(input: &str) -> (Benchmark, Vec<String>) {
    let first = input.lines().next().unwrap_or("");
    let words: Vec<String> = first
        .strip_prefix("; fuzz ")
        .map(|r| r.split_whitespace().map(str::to_string).collect())
        .unwrap_or_default();
    let b = words
        .first()
        .and_then(|d| BENCH_DIRS.iter().find(|(n, _)| n == d))
        .map(|(_, b)| *b)
        .unwrap_or(Benchmark::B1);
    (b, words)
}
