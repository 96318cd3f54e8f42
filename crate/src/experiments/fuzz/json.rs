//! The JSON formats — scene, LQT-CP case, episode — under fuzzing: one mutator for all three
//! (seeded edits of the document's tree, then of its text) and one oracle per format.

use rand::Rng;
use rand_pcg::Pcg64Mcg;
use serde_json::{json, Value};

use super::common::{ensure, idx, Verdict};
use crate::lfd::{EpisodeLog, Session, SessionError, SessionOptions};
use crate::lqt::LqtError;
use crate::lqt::{run_case, CaseInput};
use crate::plan::NoClock;
use crate::sim::Benchmark;
use crate::sim::{SceneGraph, Violation, World};

// ------------------------------------------------------------------------------ base inputs

/// An LQT-CP case with every key of the contract (2-D, via-point and goal, RBF basis, feedback).
pub(super) fn base_case() -> String {
    let n = 40;
    let mu: Vec<Value> = (0..n).map(|_| json!([0.0, 0.0, 0.0, 0.0])).collect();
    let q_diag = mu.clone();
    json!({
        "dim": 2, "order": 2, "dt": 0.02, "n_steps": n, "r": 1e-6,
        "basis": {"type": "rbf", "n_fct": 6, "centers": [0.0, 0.2, 0.4, 0.6, 0.8, 1.0], "lambda": 40.0},
        "x0": [0.0, 0.0, 0.0, 0.0],
        "targets": [
            {"t": 19, "role": "via", "pos": [0.3, 0.5], "w_pos": 1.0},
            {"t": 39, "role": "goal", "pos": [1.0, 0.0], "w_pos": 1.0, "vel": [0.0, 0.0], "w_vel": 1.0}
        ],
        "tracking": null,
        "reference": {"mu": mu, "q_diag": q_diag},
        "feedback": {"x_init": [0.0, 0.0, 0.0, 0.0], "perturbation": {"after_step": 15, "delta": [0.1, -0.1, 0.0, 0.0]}}
    })
    .to_string()
}

/// A short B1 episode (a drag and an injection) as JSON.
pub(super) fn base_episode() -> Result<String, String> {
    let mut s = Session::new(SessionOptions {
        benchmark: Benchmark::B1,
        method: Default::default(),
        mode: Default::default(),
        seed: 11,
        skill: Default::default(),
        blocks: None,
    })
    .map_err(|e| e.to_string())?;
    s.run_to_end(120, &NoClock);
    let _ = s.inject("l1");
    s.run_to_end(120, &NoClock);
    let _ = s.perturb("a", [0.40, -0.20, 0.1]);
    s.run_to_end(60, &NoClock);
    Ok(s.episode_json())
}

// ------------------------------------------------------------------------------ mutator

/// A value that a hostile or careless user could put anywhere in a JSON document.
pub fn hostile_value(rng: &mut Pcg64Mcg) -> Value {
    match rng.random_range(0..27) {
        0 => Value::Null,
        1 => json!(true),
        2 => json!(0),
        3 => json!(-1),
        4 => json!(1),
        5 => json!(2),
        6 => json!(0.5),
        7 => json!(-0.0),
        8 => json!(1e308),
        9 => json!(-1e308),
        10 => json!(5e-324),
        11 => json!(u64::MAX),
        12 => json!(i64::MIN),
        13 => json!(4_000_000_000u64),
        14 => json!(""),
        15 => json!("x"),
        16 => json!("A"),
        17 => json!("<script>alert(1)</script>"),
        18 => json!("\u{202e}\u{0}é"),
        19 => json!("1"),
        20 => json!([]),
        21 => json!({}),
        22 => json!([1, 2, 3]),
        23 => json!([0.0, 0.0, 0.0, 0.0]),
        24 => json!({"type": "cuboid"}),
        25 => Value::String("z".repeat(10_000)),
        _ => {
            let mut v = json!(0);
            for _ in 0..200 {
                v = json!([v]);
            }
            v
        }
    }
}

/// One edit of a JSON document: on its tree (by pre-order node index) or on its text.
#[derive(Clone, Debug, PartialEq)]
pub enum JsonEdit {
    /// Replace node `i` by a value.
    Replace(usize, Value),
    /// Remove node `i` from its object or array.
    Remove(usize),
    /// Duplicate array element `i` (or set object key `i` to a copy of node `j`).
    Duplicate(usize, usize),
    /// Scale the `i`-th number node by a factor.
    Scale(usize, f64),
    /// Cut the text at a byte.
    Truncate(usize),
    /// Overwrite a byte of the text.
    Byte(usize, u8),
    /// Insert a fragment into the text.
    Insert(usize, &'static str),
}

impl JsonEdit {
    /// A random edit (weights 4 replace, 2 remove, 1 duplicate, 3 scale, 1 each text edit).
    pub fn random(rng: &mut Pcg64Mcg) -> JsonEdit {
        let i = idx(rng);
        match rng.random_range(0..13) {
            0..=3 => JsonEdit::Replace(i, hostile_value(rng)),
            4..=5 => JsonEdit::Remove(i),
            6 => JsonEdit::Duplicate(i, idx(rng)),
            7..=9 => {
                const F: [f64; 7] = [-1.0, 0.0, 0.001, 1.01, 10.0, 1e6, 1e300];
                JsonEdit::Scale(i, F[rng.random_range(0..F.len())])
            }
            10 => JsonEdit::Truncate(i),
            11 => JsonEdit::Byte(i, rng.random()),
            _ => {
                const S: [&str; 11] = [
                    "{", "}", "[", "]", ",", ":", "\"", "1e999", "-", "null", "\\u",
                ];
                JsonEdit::Insert(i, S[rng.random_range(0..S.len())])
            }
        }
    }
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

/// Applies `edits` to the JSON document `text` (tree edits first, then text edits). A `text`
/// that is not JSON only gets the text edits.
pub fn mutate_json(text: &str, edits: &[JsonEdit]) -> Vec<u8> {
    let mut bytes = match serde_json::from_str::<Value>(text) {
        Ok(mut v) => {
            edit_tree(&mut v, edits);
            serde_json::to_vec(&v).unwrap_or_default()
        }
        Err(_) => text.as_bytes().to_vec(),
    };
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

fn edit_tree(v: &mut Value, edits: &[JsonEdit]) {
    for e in edits {
        let ptrs = pointers(v);
        if ptrs.len() < 2 {
            break;
        }
        // Leave the root alone (index 0 would replace the whole document).
        let pick = |i: usize| ptrs[1 + i % (ptrs.len() - 1)].clone();
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
                        Some(Value::Array(a)) if !a.is_empty() => {
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
                let nums: Vec<&String> = ptrs
                    .iter()
                    .filter(|p| v.pointer(p).is_some_and(Value::is_number))
                    .collect();
                if !nums.is_empty() {
                    let p = nums[i % nums.len()].clone();
                    if let Some(n) = v.pointer_mut(&p) {
                        let x = n.as_f64().unwrap_or(0.0) * f;
                        *n = serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number);
                    }
                }
            }
            _ => {}
        }
    }
}

// ------------------------------------------------------------------------------ oracles

/// `line L column C` (serde_json's syntax-error location) with L ≥ 1 and C within line L.
pub fn is_line_col_within(loc: &str, text: &str) -> bool {
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

/// Relative tolerance of the scene round trip: re-normalising a quaternion on load may move its
/// last bit.
const ROUND_TRIP_TOLERANCE: f64 = 1e-12;

/// Numbers equal up to [`ROUND_TRIP_TOLERANCE`] (relative), everything else exactly.
fn approx_eq(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap_or(0.0), y.as_f64().unwrap_or(0.0));
            (x - y).abs() <= ROUND_TRIP_TOLERANCE * (1.0 + x.abs().max(y.abs()))
        }
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(x, y)| approx_eq(x, y))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len()
                && x.iter()
                    .all(|(k, v)| y.get(k).is_some_and(|w| approx_eq(v, w)))
        }
        _ => a == b,
    }
}

const SCENE_KEYS: [&str; 8] = [
    "version", "name", "time", "dt", "floor_z", "regions", "bodies", "arms",
];

const CASE_KEYS: [&str; 12] = [
    "dim",
    "order",
    "dt",
    "n_steps",
    "r",
    "basis",
    "x0",
    "targets",
    "tracking",
    "reference",
    "feedback",
    "(root)",
];

/// Longest episode (ticks) the `episode` oracle replays; longer logs are only parsed.
pub const MAX_REPLAY_TICKS: u64 = 2_000;

pub(super) fn check_scene(input: &str) -> Result<Verdict, String> {
    match World::from_json(input) {
        Err(e) => {
            ensure(!e.message.is_empty(), || "empty scene error".into())?;
            ensure(
                is_line_col_within(&e.path, input)
                    || SCENE_KEYS.iter().any(|k| e.path.starts_with(k)),
                || format!("unlocated scene error: {e}"),
            )?;
            Ok(Verdict::Refused)
        }
        Ok(world) => {
            let v = world.check_invariants().err().unwrap_or_default();
            ensure(
                v.iter().all(|v| matches!(v, Violation::Lost { .. })),
                || format!("an accepted scene breaks the invariants: {v:?}"),
            )?;
            let _ = SceneGraph::from_world(&world);
            let again = World::from_json(&world.to_json())
                .map_err(|e| format!("an accepted scene does not round-trip: {e}"))?;
            let a = serde_json::to_value(again.snapshot()).map_err(|e| e.to_string())?;
            let b = serde_json::to_value(world.snapshot()).map_err(|e| e.to_string())?;
            ensure(approx_eq(&a, &b), || {
                "the round trip changed the scene".into()
            })?;
            Ok(Verdict::Accepted)
        }
    }
}

pub(super) fn check_case(input: &str) -> Result<Verdict, String> {
    match CaseInput::from_json_str(input) {
        Err(LqtError::Input { key, message }) => {
            ensure(
                key.is_empty() || CASE_KEYS.iter().any(|k| key.starts_with(k)),
                || format!("unlocated key {key:?}: {message}"),
            )?;
            ensure(!message.is_empty(), || "empty case error".into())?;
            Ok(Verdict::Refused)
        }
        Err(LqtError::Json { line, .. }) => {
            let lines = input.split('\n').count();
            ensure(line >= 1 && line <= lines, || {
                format!("syntax error at line {line} of {lines}")
            })?;
            Ok(Verdict::Refused)
        }
        Err(e) => Err(format!("a parse returned a solver error: {e}")),
        Ok(case) => match run_case(&case) {
            Ok(_) => Ok(Verdict::Accepted),
            Err(LqtError::Singular(_)) | Err(LqtError::NonFinite(_)) => Ok(Verdict::Refused),
            Err(e) => Err(format!("a parsed case failed as input: {e}")),
        },
    }
}

pub(super) fn check_episode(input: &str) -> Result<Verdict, String> {
    let log = match serde_json::from_str::<EpisodeLog>(input) {
        Err(e) => {
            ensure(e.line() >= 1, || format!("unlocated episode error: {e}"))?;
            return Ok(Verdict::Refused);
        }
        Ok(l) => l,
    };
    if log.ticks > MAX_REPLAY_TICKS {
        return Ok(Verdict::Accepted);
    }
    match Session::replay(input) {
        Err(SessionError::Scene(e)) => {
            ensure(!e.path.is_empty(), || format!("unlocated scene error: {e}"))?;
            Ok(Verdict::Refused)
        }
        Err(e) => {
            ensure(!e.to_string().is_empty(), || "empty replay error".into())?;
            Ok(Verdict::Refused)
        }
        Ok(s) => {
            let _ = s.episode_json();
            Ok(Verdict::Accepted)
        }
    }
}
