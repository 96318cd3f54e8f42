//! Input hardening (issue 8, item 1): seeded, bounded property-based mutation tests for every
//! input parser of the library. Each target asserts
//!
//! * no panic (every call runs under `std::panic::catch_unwind`),
//! * an error carries a location (`line:col` for text, a JSON key path or `line L column C` for
//!   JSON),
//! * nothing is partially applied (a refused world operation leaves the world's snapshot
//!   byte-identical).
//!
//! Case counts are sized so that the whole set runs ≥ 10 000 inputs in well under a minute in
//! the test profile (`opt-level = 1`); `FUZZ_CASES_SCALE=N` multiplies them for longer runs
//! (`FUZZ_CASES_SCALE=20 cargo test --release --test integration fuzz::`). The PDDL parser already
//! has token-level mutation tests in `tests/pddl`; `fuzz::pddl` extends them with structural
//! edits over the benchmark domains.

mod episode;
mod lqt_case;
mod pddl;
mod plan_file;
mod scene;
mod world_ops;

use std::panic::{catch_unwind, AssertUnwindSafe};

use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use serde_json::Value;

/// Path of a file in the repository's `domains/`.
pub(crate) fn domain_file(bench: &str, file: &str) -> String {
    let p = concat!(env!("CARGO_MANIFEST_DIR"), "/../domains");
    std::fs::read_to_string(format!("{p}/{bench}/{file}")).unwrap()
}

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
        let msg = p
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        TestCaseError::fail(format!("{what}: panicked: {msg}"))
    })
}

/// A value that a hostile or careless user could put anywhere in a JSON document.
pub(crate) fn hostile_value() -> impl Strategy<Value = Value> {
    use serde_json::json;
    let deep = {
        let mut v = json!(0);
        for _ in 0..200 {
            v = json!([v]);
        }
        v
    };
    prop::sample::select(vec![
        Value::Null,
        json!(true),
        json!(0),
        json!(-1),
        json!(1),
        json!(2),
        json!(0.5),
        json!(-0.0),
        json!(1e308),
        json!(-1e308),
        json!(5e-324),
        json!(u64::MAX),
        json!(i64::MIN),
        json!(4_000_000_000u64),
        json!(""),
        json!("x"),
        json!("A"),
        json!("<script>alert(1)</script>"),
        json!("\u{202e}\u{0}é"),
        json!("1"),
        json!([]),
        json!({}),
        json!([1, 2, 3]),
        json!([0.0, 0.0, 0.0, 0.0]),
        json!({"type": "cuboid"}),
        Value::String("z".repeat(10_000)),
        deep,
    ])
}

/// One edit of a JSON document: on its tree (by pre-order node index) or on its text.
#[derive(Clone, Debug)]
pub(crate) enum JsonEdit {
    /// Replace node `i` by a value.
    Replace(usize, Value),
    /// Remove node `i` from its object or array.
    Remove(usize),
    /// Duplicate array element `i` (or replace the node by a copy of another node).
    Duplicate(usize, usize),
    /// Scale a number node by a factor.
    Scale(usize, f64),
    /// Cut the text at a byte.
    Truncate(usize),
    /// Overwrite a byte of the text.
    Byte(usize, u8),
    /// Insert a string into the text.
    Insert(usize, &'static str),
}

pub(crate) fn json_edit() -> impl Strategy<Value = JsonEdit> {
    prop_oneof![
        4 => (any::<usize>(), hostile_value()).prop_map(|(i, v)| JsonEdit::Replace(i, v)),
        2 => any::<usize>().prop_map(JsonEdit::Remove),
        1 => (any::<usize>(), any::<usize>()).prop_map(|(i, j)| JsonEdit::Duplicate(i, j)),
        3 => (any::<usize>(), prop::sample::select(vec![-1.0, 0.0, 0.001, 1.01, 10.0, 1e6, 1e300]))
            .prop_map(|(i, f)| JsonEdit::Scale(i, f)),
        1 => any::<usize>().prop_map(JsonEdit::Truncate),
        1 => (any::<usize>(), any::<u8>()).prop_map(|(i, b)| JsonEdit::Byte(i, b)),
        1 => (any::<usize>(), prop::sample::select(vec!["{", "}", "[", "]", ",", ":", "\"", "1e999", "-", "null", "\\u"]))
            .prop_map(|(i, s)| JsonEdit::Insert(i, s)),
    ]
}

/// JSON pointers of every node, in pre-order (the root is `""`).
fn pointers(v: &Value) -> Vec<String> {
    fn walk(v: &Value, at: String, out: &mut Vec<String>) {
        out.push(at.clone());
        match v {
            Value::Object(m) => {
                for (k, c) in m {
                    let k = k.replace('~', "~0").replace('/', "~1");
                    walk(c, format!("{at}/{k}"), out);
                }
            }
            Value::Array(a) => {
                for (i, c) in a.iter().enumerate() {
                    walk(c, format!("{at}/{i}"), out);
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(v, String::new(), &mut out);
    out
}

fn split_pointer(p: &str) -> Option<(&str, String)> {
    let i = p.rfind('/')?;
    Some((&p[..i], p[i + 1..].replace("~1", "/").replace("~0", "~")))
}

/// Applies `edits` to the document `text` (tree edits first, then text edits) and returns the
/// mutated text.
pub(crate) fn mutate_json(text: &str, edits: &[JsonEdit]) -> Vec<u8> {
    let mut v: Value = serde_json::from_str(text).unwrap();
    for e in edits {
        let ptrs = pointers(&v);
        // Leave the root alone for node edits (index 0 would replace the whole document).
        let pick = |i: usize| ptrs[1 + i % (ptrs.len() - 1).max(1)].clone();
        if ptrs.len() < 2 {
            break;
        }
        match e {
            JsonEdit::Replace(i, new) => {
                if let Some(n) = v.pointer_mut(&pick(*i)) {
                    *n = new.clone();
                }
            }
            JsonEdit::Remove(i) => {
                let p = pick(*i);
                if let Some((parent, key)) = split_pointer(&p) {
                    match v.pointer_mut(parent) {
                        Some(Value::Object(m)) => {
                            m.remove(&key);
                        }
                        Some(Value::Array(a)) => {
                            if let Ok(k) = key.parse::<usize>() {
                                if k < a.len() {
                                    a.remove(k);
                                }
                            }
                        }
                        _ => {}
                    }
                }
            }
            JsonEdit::Duplicate(i, j) => {
                let (p, q) = (pick(*i), pick(*j));
                let copy = v.pointer(&q).cloned();
                if let (Some((parent, key)), Some(copy)) = (split_pointer(&p), copy) {
                    match v.pointer_mut(parent) {
                        Some(Value::Array(a)) => {
                            if let Ok(k) = key.parse::<usize>() {
                                let c = a[k.min(a.len() - 1)].clone();
                                a.insert(k.min(a.len()), c);
                            }
                        }
                        Some(Value::Object(m)) => {
                            m.insert(key, copy);
                        }
                        _ => {}
                    }
                }
            }
            JsonEdit::Scale(i, f) => {
                // The i-th number node.
                let nums: Vec<String> = ptrs
                    .iter()
                    .filter(|p| v.pointer(p).is_some_and(Value::is_number))
                    .cloned()
                    .collect();
                if !nums.is_empty() {
                    let p = &nums[i % nums.len()];
                    if let Some(n) = v.pointer_mut(p) {
                        let x = n.as_f64().unwrap_or(0.0) * f;
                        *n = serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number);
                    }
                }
            }
            _ => {}
        }
    }
    let mut bytes = serde_json::to_vec(&v).unwrap();
    for e in edits {
        let n = bytes.len();
        match e {
            JsonEdit::Truncate(i) => bytes.truncate(i % (n + 1)),
            JsonEdit::Byte(i, b) if n > 0 => bytes[i % n] = *b,
            JsonEdit::Insert(i, s) => {
                let at = i % (n + 1);
                bytes.splice(at..at, s.bytes());
            }
            _ => {}
        }
    }
    bytes
}

/// `line L column C` (serde_json's syntax-error location) with L, C ≥ 1 within `text`.
pub(crate) fn is_line_col_within(loc: &str, text: &str) -> bool {
    let parts: Vec<&str> = loc.split_whitespace().collect();
    let [_, l, _, c] = parts[..] else {
        return false;
    };
    if !(loc.starts_with("line ") && loc.contains(" column ")) {
        return false;
    }
    let (Ok(l), Ok(c)) = (l.parse::<usize>(), c.parse::<usize>()) else {
        return false;
    };
    let lines: Vec<&str> = text.split('\n').collect();
    // serde_json reports column 0 for an error at the very start of a line / empty input.
    l >= 1 && l <= lines.len() && c <= lines[l - 1].len() + 1
}
