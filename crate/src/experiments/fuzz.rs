//! Mutation fuzzing of every input the library takes from users (issue 8, item 1), shared by the
//! CI property tests (`crate/tests/fuzz`) and the `logic-lfd fuzz` command, so both run the same
//! mutators against the same guarantees.
//!
//! A [`Target`] names an input format. Each has *base inputs* (the benchmarks' own files, built
//! into the library), a *mutator* (seeded edits: structural ones on the parsed form, then
//! byte-level ones on the text) and an *oracle* ([`check`]) that states the guarantees:
//!
//! | target      | parser under test                                  | guarantee besides "no panic"                                  |
//! |-------------|----------------------------------------------------|---------------------------------------------------------------|
//! | `pddl`      | `parse_domain`, `parse_problem`, `ground`          | an error names its file and a `line:col` inside the text      |
//! | `plan`      | `parse_plan`, `validate`                           | errors located; a failing step exists; counts agree           |
//! | `scene`     | `World::from_json`                                 | refusal names a key path or `line L column C`; an accepted scene is a valid world that round-trips |
//! | `case`      | `CaseInput::from_json_str`, `run_case`             | refusal names the key; an accepted case solves or fails numerically |
//! | `episode`   | `EpisodeLog` parse, `Session::replay`              | parse errors located; an accepted log replays                 |
//! | `world-ops` | `World::move_block(_to)`, `World::add_block`       | a refused operation changes nothing; an accepted one keeps the invariants |
//!
//! Every input is text, so a failing one can be saved to a corpus directory and replayed alone
//! (`logic-lfd fuzz --target T --replay FILE`). PDDL and plan inputs start with a comment line
//! `; fuzz <benchmark-dir> [domain|problem]` naming the files they stand for; world-ops inputs
//! are JSON (`{"benchmark":"b1","ops":[…]}`; coordinates may be strings `"nan"`, `"inf"`).
//!
//! Case `i` of a run with seed `S` draws everything from `Pcg64Mcg(mix(S, i))`.

use std::panic::{catch_unwind, AssertUnwindSafe};

use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};

use crate::lfd::session::{demo_actions, mix, EpisodeLog, Session, SessionError, SessionOptions};
use crate::lqt::case::{run_case, CaseInput};
use crate::lqt::LqtError;
use crate::pddl::{parse_domain, parse_problem, Domain, PddlError, Problem};
use crate::plan::{ground, parse_plan, validate, NoClock, Outcome};
use crate::sim::benchmark::Benchmark as BenchmarkId;
use crate::sim::{SceneGraph, Violation, World};

/// An input format under test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Target {
    /// PDDL domain and problem files.
    Pddl,
    /// Plan files for `validate`.
    Plan,
    /// Scene JSON.
    Scene,
    /// LQT-CP case JSON.
    Case,
    /// Episode JSON (replay).
    Episode,
    /// World operations (drags, new blocks), as the page sends them.
    WorldOps,
}

impl Target {
    /// Every target.
    pub const ALL: [Target; 6] = [
        Target::Pddl,
        Target::Plan,
        Target::Scene,
        Target::Case,
        Target::Episode,
        Target::WorldOps,
    ];

    /// `pddl`, `plan`, `scene`, `case`, `episode`, `world-ops`.
    pub fn as_str(self) -> &'static str {
        match self {
            Target::Pddl => "pddl",
            Target::Plan => "plan",
            Target::Scene => "scene",
            Target::Case => "case",
            Target::Episode => "episode",
            Target::WorldOps => "world-ops",
        }
    }

    /// Parses a target name.
    pub fn parse(s: &str) -> Option<Target> {
        Target::ALL.into_iter().find(|t| t.as_str() == s)
    }

    /// File extension of a saved input.
    pub fn extension(self) -> &'static str {
        match self {
            Target::Pddl => "pddl",
            Target::Plan => "plan",
            _ => "json",
        }
    }
}

/// What the parser under test did with an input that kept every guarantee.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Accepted (and, where it applies, the accepted value behaved).
    Accepted,
    /// Refused with a located error.
    Refused,
}

// ------------------------------------------------------------------------------ base inputs

const BENCH_DIRS: [(&str, BenchmarkId); 3] = [
    ("b1-tower", BenchmarkId::B1),
    ("b2-workspace-reach", BenchmarkId::B2),
    ("b3-dual-arm", BenchmarkId::B3),
];

/// An LQT-CP case with every key of the contract (2-D, via-point and goal, RBF basis, feedback).
fn base_case() -> String {
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
fn base_episode() -> Result<String, String> {
    let mut s = Session::new(SessionOptions {
        benchmark: BenchmarkId::B1,
        method: Default::default(),
        mode: Default::default(),
        seed: 11,
        skill: Default::default(),
    })
    .map_err(|e| e.to_string())?;
    s.run_to_end(120, &NoClock);
    let _ = s.inject("l1");
    s.run_to_end(120, &NoClock);
    let _ = s.perturb("a", [0.40, -0.20, 0.1]);
    s.run_to_end(60, &NoClock);
    Ok(s.episode_json())
}

/// The base inputs of a target (mutations start from one of them).
pub fn base_inputs(target: Target) -> Result<Vec<String>, String> {
    let mut out = Vec::new();
    for (dir, b) in BENCH_DIRS {
        let files = b.sources().map_err(|e| e.to_string())?;
        match target {
            Target::Pddl => {
                out.push(format!("; fuzz {dir} domain\n{}", files.domain));
                out.push(format!("; fuzz {dir} problem\n{}", files.problem));
            }
            Target::Plan => {
                let demo = demo_actions(&files.demo).map_err(|e| e.to_string())?;
                out.push(format!("; fuzz {dir}\n{}\n", demo.join("\n")));
            }
            Target::Scene => out.push(files.scene),
            Target::Case | Target::Episode | Target::WorldOps => {}
        }
    }
    match target {
        Target::Case => out.push(base_case()),
        Target::Episode => out.push(base_episode()?),
        Target::WorldOps => {
            for b in ["b1", "b2", "b3"] {
                out.push(json!({"benchmark": b, "ops": []}).to_string());
            }
        }
        _ => {}
    }
    Ok(out)
}

// ------------------------------------------------------------------------------ JSON mutator

/// A random index (edits take it modulo what they index).
fn idx(rng: &mut Pcg64Mcg) -> usize {
    rng.random::<u32>() as usize
}

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

// ------------------------------------------------------------------------------ PDDL mutator

/// A structural edit of a PDDL text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PddlEdit {
    /// Delete the i-th balanced list.
    DeleteList(usize),
    /// Put a copy of list j right after list i.
    CopyList(usize, usize),
    /// Swap the texts of lists i and j (when they do not overlap).
    SwapLists(usize, usize),
    /// Replace name i by name j of the same text.
    Rename(usize, usize),
    /// Wrap list i in `n` more parentheses.
    Nest(usize, u16),
    /// Delete the i-th character.
    DeleteChar(usize),
    /// Insert a fragment before the i-th character.
    Insert(usize, &'static str),
}

impl PddlEdit {
    /// A random edit (structural edits weighted over character edits).
    pub fn random(rng: &mut Pcg64Mcg) -> PddlEdit {
        let (i, j) = (idx(rng), idx(rng));
        match rng.random_range(0..10) {
            0 => PddlEdit::DeleteList(i),
            1 => PddlEdit::CopyList(i, j),
            2 => PddlEdit::SwapLists(i, j),
            3..=5 => PddlEdit::Rename(i, j),
            6 => PddlEdit::Nest(i, rng.random_range(1..300)),
            7 => PddlEdit::DeleteChar(i),
            _ => {
                const F: [&str; 14] = [
                    "(", ")", " ", "\n", ";", "?x", "-", "é", "\t", "(not ", "(or)", ":typing",
                    "(and)", "- object",
                ];
                PddlEdit::Insert(i, F[rng.random_range(0..F.len())])
            }
        }
    }
}

/// Byte ranges of every balanced `( … )` of the text.
fn lists(text: &str) -> Vec<(usize, usize)> {
    let mut open = Vec::new();
    let mut out = Vec::new();
    for (i, c) in text.char_indices() {
        match c {
            '(' => open.push(i),
            ')' => {
                if let Some(s) = open.pop() {
                    out.push((s, i + 1));
                }
            }
            _ => {}
        }
    }
    out
}

/// Byte ranges of every name (a run of non-space, non-paren characters).
fn names(text: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in text
        .char_indices()
        .chain(std::iter::once((text.len(), ' ')))
    {
        let sep = c == '(' || c == ')' || c.is_whitespace();
        match (start, sep) {
            (None, false) => start = Some(i),
            (Some(s), true) => {
                out.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// Byte offset of the `i`-th character boundary (modulo the count + 1).
fn char_boundary(t: &str, i: usize) -> usize {
    let n = t.chars().count();
    t.char_indices()
        .map(|(b, _)| b)
        .chain(std::iter::once(t.len()))
        .nth(i % (n + 1))
        .unwrap_or(t.len())
}

/// Applies PDDL edits to `text`.
pub fn mutate_pddl(text: &str, edits: &[PddlEdit]) -> String {
    let mut t = text.to_string();
    for e in edits {
        let ls = lists(&t);
        let ns = names(&t);
        match *e {
            PddlEdit::DeleteChar(i) => {
                if !t.is_empty() {
                    let at = char_boundary(&t, i % t.chars().count());
                    t.remove(at);
                }
                continue;
            }
            PddlEdit::Insert(i, f) => {
                let at = char_boundary(&t, i);
                t.insert_str(at, f);
                continue;
            }
            _ => {}
        }
        if ls.is_empty() || ns.is_empty() {
            continue;
        }
        let l = |i: usize| ls[i % ls.len()];
        let n = |i: usize| ns[i % ns.len()];
        match *e {
            PddlEdit::DeleteList(i) => {
                let (s, e) = l(i);
                t.replace_range(s..e, "");
            }
            PddlEdit::CopyList(i, j) => {
                let (_, e) = l(i);
                let (s2, e2) = l(j);
                let copy = format!(" {}", &t[s2..e2]);
                t.insert_str(e, &copy);
            }
            PddlEdit::SwapLists(i, j) => {
                let (a, b) = (l(i), l(j));
                let (first, second) = if a.0 < b.0 { (a, b) } else { (b, a) };
                if first.1 <= second.0 {
                    let x = t[first.0..first.1].to_string();
                    let y = t[second.0..second.1].to_string();
                    t.replace_range(second.0..second.1, &x);
                    t.replace_range(first.0..first.1, &y);
                }
            }
            PddlEdit::Rename(i, j) => {
                let (s, e) = n(i);
                let (s2, e2) = n(j);
                let name = t[s2..e2].to_string();
                t.replace_range(s..e, &name);
            }
            PddlEdit::Nest(i, k) => {
                let (s, e) = l(i);
                t.insert_str(e, &")".repeat(k as usize));
                t.insert_str(s, &"(".repeat(k as usize));
            }
            PddlEdit::DeleteChar(_) | PddlEdit::Insert(..) => {}
        }
    }
    t
}

// ------------------------------------------------------------------------------ plan mutator

/// An edit of a plan file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PlanEdit {
    /// Delete the i-th character.
    Delete(usize),
    /// Insert a fragment before the i-th character.
    Insert(usize, &'static str),
    /// Swap two lines.
    SwapLines(usize, usize),
    /// Duplicate a line.
    DupLine(usize),
    /// Cut the text after `i` characters.
    Truncate(usize),
}

impl PlanEdit {
    /// A random edit.
    pub fn random(rng: &mut Pcg64Mcg) -> PlanEdit {
        const F: [&str; 17] = [
            "(",
            ")",
            " ",
            "\n",
            ";",
            "x",
            "(stack a b)",
            "(pick panda zz)",
            "()",
            "((",
            "-",
            "?x",
            "é",
            "\t",
            "(unstack a a)",
            "panda",
            "; cost = 3 (general cost)",
        ];
        let (i, j) = (idx(rng), idx(rng));
        match rng.random_range(0..5) {
            0 => PlanEdit::Delete(i),
            1 => PlanEdit::Insert(i, F[rng.random_range(0..F.len())]),
            2 => PlanEdit::SwapLines(i, j),
            3 => PlanEdit::DupLine(i),
            _ => PlanEdit::Truncate(i),
        }
    }
}

/// Applies plan edits to `text`.
pub fn mutate_plan(text: &str, edits: &[PlanEdit]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for e in edits {
        let n = chars.len();
        match e {
            PlanEdit::Delete(i) if n > 0 => {
                chars.remove(i % n);
            }
            PlanEdit::Insert(i, f) => {
                let at = i % (n + 1);
                chars.splice(at..at, f.chars());
            }
            PlanEdit::Truncate(i) => chars.truncate(i % (n + 1)),
            PlanEdit::SwapLines(i, j) | PlanEdit::DupLine(i @ j) if n > 0 => {
                let s: String = chars.iter().collect();
                let mut lines: Vec<String> = s.split('\n').map(str::to_string).collect();
                let m = lines.len();
                if matches!(e, PlanEdit::DupLine(_)) {
                    let l = lines[i % m].clone();
                    lines.insert(i % m, l);
                } else {
                    lines.swap(i % m, j % m);
                }
                chars = lines.join("\n").chars().collect();
            }
            _ => {}
        }
    }
    chars.into_iter().collect()
}

// ------------------------------------------------------------------------------ world ops

/// A coordinate in a world-ops input: a number, or `"nan"`, `"inf"`, `"-inf"` (JSON has none).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Coord {
    /// A finite number.
    Num(f64),
    /// `"nan"`, `"inf"` or `"-inf"`.
    Special(SpecialFloat),
}

/// A non-finite coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SpecialFloat {
    /// Not a number.
    Nan,
    /// +∞.
    Inf,
    /// −∞.
    #[serde(rename = "-inf")]
    NegInf,
}

impl Coord {
    fn new(x: f64) -> Coord {
        if x.is_nan() {
            Coord::Special(SpecialFloat::Nan)
        } else if x == f64::INFINITY {
            Coord::Special(SpecialFloat::Inf)
        } else if x == f64::NEG_INFINITY {
            Coord::Special(SpecialFloat::NegInf)
        } else {
            Coord::Num(x)
        }
    }

    /// The value.
    pub fn value(self) -> f64 {
        match self {
            Coord::Num(x) => x,
            Coord::Special(SpecialFloat::Nan) => f64::NAN,
            Coord::Special(SpecialFloat::Inf) => f64::INFINITY,
            Coord::Special(SpecialFloat::NegInf) => f64::NEG_INFINITY,
        }
    }
}

/// One request from the page.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "op", rename_all = "snake_case")]
pub enum WorldOp {
    /// A drag (`World::move_block`).
    Move {
        /// Body name.
        body: String,
        /// Requested centre.
        to: [Coord; 3],
    },
    /// A drag with a new yaw (`World::move_block_to`).
    MoveYaw {
        /// Body name.
        body: String,
        /// Requested centre.
        to: [Coord; 3],
        /// Yaw (rad).
        yaw: Coord,
    },
    /// A new block (`World::add_block`).
    Add {
        /// New name.
        body: String,
        /// Colour `#rrggbb`.
        color: String,
        /// Requested centre.
        at: [Coord; 3],
    },
}

/// A world-ops input: a benchmark's template world and the requests applied to it in order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WorldOps {
    /// `b1`, `b2` or `b3`.
    pub benchmark: String,
    /// The requests.
    pub ops: Vec<WorldOp>,
}

const OP_NAMES: [&str; 12] = [
    "a", "b", "c", "d", "hook", "table", "shelf", "panda", "e", "", "A", "<b>",
];
const OP_COLORS: [&str; 4] = ["#123456", "red", "#12345", "#GGGGGG"];

fn random_coord(rng: &mut Pcg64Mcg, lo: f64, hi: f64) -> f64 {
    if rng.random_range(0..9) == 0 {
        const S: [f64; 6] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e12, -1e12, 0.0];
        S[rng.random_range(0..S.len())]
    } else {
        rng.random_range(lo..hi)
    }
}

fn random_point(rng: &mut Pcg64Mcg) -> [Coord; 3] {
    let z = if rng.random_range(0..4) < 3 {
        rng.random_range(0.0..0.4)
    } else {
        random_coord(rng, -0.4, 1.2)
    };
    [
        Coord::new(random_coord(rng, -0.4, 1.2)),
        Coord::new(random_coord(rng, -0.4, 1.2)),
        Coord::new(z),
    ]
}

impl WorldOp {
    /// A random request (hostile names, colours and coordinates included).
    pub fn random(rng: &mut Pcg64Mcg) -> WorldOp {
        let body = OP_NAMES[rng.random_range(0..OP_NAMES.len())].to_string();
        match rng.random_range(0..6) {
            0..=3 => WorldOp::Move {
                body,
                to: random_point(rng),
            },
            4 => WorldOp::MoveYaw {
                body,
                to: random_point(rng),
                yaw: Coord::new(random_coord(rng, -0.4, 1.2)),
            },
            _ => WorldOp::Add {
                body,
                color: OP_COLORS[rng.random_range(0..OP_COLORS.len())].to_string(),
                at: random_point(rng),
            },
        }
    }

    /// Applies the request; `Err` is the world's refusal reason.
    pub fn apply(&self, w: &mut World) -> Result<(), String> {
        let v = |p: &[Coord; 3]| Vector3::new(p[0].value(), p[1].value(), p[2].value());
        let r = match self {
            WorldOp::Move { body, to } => w.move_block(body, v(to)).map(|_| ()),
            WorldOp::MoveYaw { body, to, yaw } => {
                w.move_block_to(body, v(to), yaw.value()).map(|_| ())
            }
            WorldOp::Add { body, color, at } => w.add_block(body, color, v(at), 0.3).map(|_| ()),
        };
        r.map_err(|e| e.reason)
    }
}

// ------------------------------------------------------------------------------ mutate

/// Mutates `base` for `target` with `1..=max_edits` random edits.
pub fn mutate(target: Target, base: &str, max_edits: usize, rng: &mut Pcg64Mcg) -> String {
    let k = rng.random_range(1..=max_edits.max(1));
    let header_split = |t: &str| -> (String, String) {
        match t.split_once('\n') {
            Some((h, rest)) if h.starts_with("; fuzz ") => (format!("{h}\n"), rest.to_string()),
            _ => (String::new(), t.to_string()),
        }
    };
    match target {
        Target::Pddl => {
            let (h, body) = header_split(base);
            let edits: Vec<PddlEdit> = (0..k).map(|_| PddlEdit::random(rng)).collect();
            h + &mutate_pddl(&body, &edits)
        }
        Target::Plan => {
            let (h, body) = header_split(base);
            let edits: Vec<PlanEdit> = (0..k).map(|_| PlanEdit::random(rng)).collect();
            h + &mutate_plan(&body, &edits)
        }
        Target::Scene | Target::Case | Target::Episode => {
            let edits: Vec<JsonEdit> = (0..k).map(|_| JsonEdit::random(rng)).collect();
            String::from_utf8_lossy(&mutate_json(base, &edits)).into_owned()
        }
        Target::WorldOps => {
            let mut ops: WorldOps = serde_json::from_str(base).unwrap_or(WorldOps {
                benchmark: "b1".into(),
                ops: vec![],
            });
            let n = rng.random_range(1..=3 * max_edits.max(1));
            ops.ops.extend((0..n).map(|_| WorldOp::random(rng)));
            serde_json::to_string(&ops).unwrap_or_default()
        }
    }
}

/// Case `index` of a run with `seed`: a base input picked and mutated from
/// `Pcg64Mcg(mix(seed, index))`.
pub fn generate(
    target: Target,
    bases: &[String],
    seed: u64,
    index: u64,
    max_edits: usize,
) -> String {
    let mut rng = Pcg64Mcg::seed_from_u64(mix(seed, index));
    let base = if bases.is_empty() {
        ""
    } else {
        &bases[rng.random_range(0..bases.len())]
    };
    mutate(target, base, max_edits, &mut rng)
}

// ------------------------------------------------------------------------------ oracles

/// Whether a PDDL error lies inside `text` (1-based line and column, in characters).
pub fn pddl_error_in_bounds(text: &str, e: &PddlError) -> bool {
    let lines: Vec<&str> = text.split('\n').collect();
    e.line >= 1
        && e.line <= lines.len()
        && e.col >= 1
        && e.col <= lines[e.line - 1].chars().count() + 1
}

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

fn ensure(ok: bool, msg: impl FnOnce() -> String) -> Result<(), String> {
    if ok {
        Ok(())
    } else {
        Err(msg())
    }
}

/// The benchmark a `; fuzz <dir> …` header names (B1 without a header), and the header's words.
fn header(input: &str) -> (BenchmarkId, Vec<String>) {
    let first = input.lines().next().unwrap_or("");
    let words: Vec<String> = first
        .strip_prefix("; fuzz ")
        .map(|r| r.split_whitespace().map(str::to_string).collect())
        .unwrap_or_default();
    let b = words
        .first()
        .and_then(|d| BENCH_DIRS.iter().find(|(n, _)| n == d))
        .map(|(_, b)| *b)
        .unwrap_or(BenchmarkId::B1);
    (b, words)
}

/// Numbers equal up to 1e-12 (relative): re-normalising a quaternion on load may move its last bit.
fn approx_eq(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap_or(0.0), y.as_f64().unwrap_or(0.0));
            (x - y).abs() <= 1e-12 * (1.0 + x.abs().max(y.abs()))
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

const SCENE_KEYS: [&str; 9] = [
    "version",
    "name",
    "time",
    "dt",
    "floor_z",
    "predicates",
    "regions",
    "bodies",
    "arms",
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

/// The oracle: runs `input` through the parser(s) of `target` and checks the guarantees of the
/// module table. `Err` names a broken guarantee. It may panic (that is what fuzzing looks for):
/// [`run`] catches panics.
pub fn check(target: Target, input: &str) -> Result<Verdict, String> {
    match target {
        Target::Pddl => check_pddl(input),
        Target::Plan => check_plan(input),
        Target::Scene => check_scene(input),
        Target::Case => check_case(input),
        Target::Episode => check_episode(input),
        Target::WorldOps => check_world_ops(input),
    }
}

fn check_pddl(input: &str) -> Result<Verdict, String> {
    let (b, words) = header(input);
    let files = b.sources().map_err(|e| e.to_string())?;
    let is_problem = words.get(1).is_some_and(|w| w == "problem");
    let (dom_text, prob_text) = if is_problem {
        (files.domain.as_str(), input)
    } else {
        (input, files.problem.as_str())
    };
    let located = |text: &str, file: &str, e: &PddlError| {
        ensure(pddl_error_in_bounds(text, e) && e.file == file, || {
            format!("error outside the text: {e}")
        })?;
        ensure(e.to_string().starts_with(&format!("{file}:")), || {
            format!("error does not start with its file: {e}")
        })
    };
    let d = match parse_domain(dom_text, "domain.pddl") {
        Ok(d) => d,
        Err(e) => {
            located(dom_text, "domain.pddl", &e)?;
            return Ok(Verdict::Refused);
        }
    };
    let p = match parse_problem(prob_text, "problem.pddl", &d) {
        Ok(p) => p,
        Err(e) => {
            located(prob_text, "problem.pddl", &e)?;
            return Ok(Verdict::Refused);
        }
    };
    match ground(&d, &p) {
        Ok(_) => Ok(Verdict::Accepted),
        Err(e) => {
            ensure(!e.to_string().is_empty(), || "empty grounding error".into())?;
            Ok(Verdict::Refused)
        }
    }
}

fn check_plan(input: &str) -> Result<Verdict, String> {
    let (b, _) = header(input);
    let files = b.sources().map_err(|e| e.to_string())?;
    let d = parse_domain(&files.domain, "domain.pddl").map_err(|e| e.to_string())?;
    let p = parse_problem(&files.problem, "problem.pddl", &d).map_err(|e| e.to_string())?;
    check_plan_against(&d, &p, input)
}

/// The `plan` oracle for a plan text `input` (file name `m.plan`) against any domain and problem.
pub fn check_plan_against(d: &Domain, p: &Problem, input: &str) -> Result<Verdict, String> {
    let steps = match parse_plan(input, "m.plan") {
        Err(e) => {
            ensure(
                pddl_error_in_bounds(input, &e) && e.file == "m.plan",
                || format!("plan parse error outside the text: {e}"),
            )?;
            return Ok(Verdict::Refused);
        }
        Ok(s) => s,
    };
    let report = validate(d, p, &steps);
    match &report.outcome {
        Outcome::Valid => {
            ensure(report.steps_applied == steps.len(), || {
                format!(
                    "valid but {} of {} steps applied",
                    report.steps_applied,
                    steps.len()
                )
            })?;
            Ok(Verdict::Accepted)
        }
        Outcome::Malformed(e) => {
            ensure(pddl_error_in_bounds(input, e) && e.file == "m.plan", || {
                format!("malformed step outside the text: {e}")
            })?;
            Ok(Verdict::Refused)
        }
        Outcome::PreconditionFalse {
            step,
            location,
            false_literals,
            ..
        } => {
            ensure(*step >= 1 && *step <= steps.len(), || {
                format!("failing step {step} of {}", steps.len())
            })?;
            ensure(report.steps_applied == step - 1, || {
                format!("step {step} failed after {} applied", report.steps_applied)
            })?;
            ensure(location.starts_with("m.plan:"), || {
                format!("unlocated step: {location}")
            })?;
            ensure(!false_literals.is_empty(), || {
                "a precondition failure names no literal".into()
            })?;
            Ok(Verdict::Refused)
        }
        Outcome::GoalNotReached { false_literals } => {
            ensure(report.steps_applied == steps.len(), || {
                "goal check before the last step".into()
            })?;
            ensure(!false_literals.is_empty(), || {
                "an unreached goal names no literal".into()
            })?;
            Ok(Verdict::Refused)
        }
    }
}

fn check_scene(input: &str) -> Result<Verdict, String> {
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

fn check_case(input: &str) -> Result<Verdict, String> {
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

fn check_episode(input: &str) -> Result<Verdict, String> {
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

fn check_world_ops(input: &str) -> Result<Verdict, String> {
    let ops: WorldOps = match serde_json::from_str(input) {
        Ok(o) => o,
        Err(e) => {
            ensure(e.line() >= 1, || format!("unlocated world-ops error: {e}"))?;
            return Ok(Verdict::Refused);
        }
    };
    let Some(b) = BenchmarkId::parse(&ops.benchmark) else {
        return Ok(Verdict::Refused);
    };
    let mut w = b.scene();
    let snap = |w: &World| serde_json::to_string(&w.snapshot()).unwrap_or_default();
    let mut accepted = false;
    for (i, op) in ops.ops.iter().enumerate() {
        let before = snap(&w);
        match op.apply(&mut w) {
            Err(reason) => {
                ensure(!reason.is_empty(), || format!("op {i}: empty refusal"))?;
                ensure(snap(&w) == before, || {
                    format!("op {i} {op:?}: refused ({reason}) but changed the world")
                })?;
            }
            Ok(()) => {
                accepted = true;
                if let Err(v) = w.check_invariants() {
                    return Err(format!(
                        "op {i} {op:?}: accepted but broke invariants: {v:?}"
                    ));
                }
            }
        }
    }
    Ok(if accepted {
        Verdict::Accepted
    } else {
        Verdict::Refused
    })
}

// ------------------------------------------------------------------------------ runner

/// Tunables of a fuzz run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FuzzParams {
    /// The target.
    pub target: Target,
    /// Inputs to try.
    pub iterations: u64,
    /// Seed (case `i` draws from `mix(seed, i)`).
    pub seed: u64,
    /// Most edits per input.
    pub max_edits: usize,
}

/// An input that broke a guarantee or panicked.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FuzzFinding {
    /// Case index (regenerate with the same seed).
    pub index: u64,
    /// `panic` or `guarantee`.
    pub kind: String,
    /// The panic message or the broken guarantee.
    pub message: String,
    /// The input.
    pub input: String,
}

/// The figures of a fuzz run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FuzzReport {
    /// The parameters.
    pub params: FuzzParams,
    /// Inputs tried.
    pub inputs: u64,
    /// Inputs accepted (and checked).
    pub accepted: u64,
    /// Inputs refused with a located error.
    pub refused: u64,
    /// Every finding (inputs included).
    pub findings: Vec<FuzzFinding>,
}

impl FuzzReport {
    /// No panic and no broken guarantee.
    pub fn is_clean(&self) -> bool {
        self.findings.is_empty()
    }
}

/// Runs `input` through [`check`], turning a panic into `Err("panicked: …")`.
pub fn check_catching(target: Target, input: &str) -> Result<Verdict, (String, String)> {
    match catch_unwind(AssertUnwindSafe(|| check(target, input))) {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(m)) => Err(("guarantee".into(), m)),
        Err(p) => Err(("panic".into(), super::panic_message(p.as_ref()))),
    }
}

/// Runs a fuzz campaign; `before_each(index, input)` is called before each input runs (the CLI
/// saves it, so an input that aborts the process — a stack overflow — is not lost).
pub fn run(
    params: &FuzzParams,
    mut before_each: impl FnMut(u64, &str),
) -> Result<FuzzReport, String> {
    let bases = base_inputs(params.target)?;
    let mut report = FuzzReport {
        params: *params,
        inputs: 0,
        accepted: 0,
        refused: 0,
        findings: vec![],
    };
    for i in 0..params.iterations {
        let input = generate(params.target, &bases, params.seed, i, params.max_edits);
        before_each(i, &input);
        report.inputs += 1;
        match check_catching(params.target, &input) {
            Ok(Verdict::Accepted) => report.accepted += 1,
            Ok(Verdict::Refused) => report.refused += 1,
            Err((kind, message)) => report.findings.push(FuzzFinding {
                index: i,
                kind,
                message,
                input,
            }),
        }
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn targets_parse_their_names() {
        for t in Target::ALL {
            assert_eq!(Target::parse(t.as_str()), Some(t));
        }
        assert_eq!(Target::parse("nope"), None);
    }

    #[test]
    fn generation_is_a_function_of_seed_and_index() {
        let bases = base_inputs(Target::Pddl).unwrap();
        let a = generate(Target::Pddl, &bases, 7, 3, 4);
        assert_eq!(a, generate(Target::Pddl, &bases, 7, 3, 4));
        assert!(a.starts_with("; fuzz "), "the header is kept: {a:.40}");
        assert!((0..20).any(|i| generate(Target::Pddl, &bases, 7, i, 4) != a));
    }

    #[test]
    fn unmutated_bases_are_accepted() {
        for t in [
            Target::Pddl,
            Target::Plan,
            Target::Scene,
            Target::Case,
            Target::WorldOps,
        ] {
            for b in base_inputs(t).unwrap() {
                let v = check(t, &b);
                let want = if t == Target::WorldOps {
                    Verdict::Refused // no op: nothing accepted
                } else {
                    Verdict::Accepted
                };
                assert_eq!(v, Ok(want), "{t:?}: {b:.60}");
            }
        }
    }

    #[test]
    fn oracles_catch_what_they_promise() {
        // An unlocated PDDL error would be caught: feed the oracle a located one and check it
        // passes, then a fake out-of-bounds location fails the bound check.
        let text = "(define (domain d)\n  (:predicates (p))";
        let e = parse_domain(text, "domain.pddl").unwrap_err();
        assert!(pddl_error_in_bounds(text, &e), "{e}");
        let far = PddlError {
            line: 9,
            ..e.clone()
        };
        assert!(!pddl_error_in_bounds(text, &far));
        assert!(is_line_col_within("line 1 column 3", "abcd"));
        assert!(!is_line_col_within("line 2 column 3", "abcd"));
        // A world-ops input whose op is accepted is checked against the invariants.
        let ops = WorldOps {
            benchmark: "b1".into(),
            ops: vec![WorldOp::Move {
                body: "a".into(),
                to: [Coord::Num(0.40), Coord::Num(-0.20), Coord::Num(0.1)],
            }],
        };
        let s = serde_json::to_string(&ops).unwrap();
        assert_eq!(check(Target::WorldOps, &s), Ok(Verdict::Accepted));
        // Non-finite coordinates survive the JSON encoding.
        let nan = WorldOp::Move {
            body: "a".into(),
            to: [
                Coord::new(f64::NAN),
                Coord::new(f64::INFINITY),
                Coord::Num(0.1),
            ],
        };
        let back: WorldOp = serde_json::from_str(&serde_json::to_string(&nan).unwrap()).unwrap();
        match back {
            WorldOp::Move { to, .. } => {
                assert!(to[0].value().is_nan() && to[1].value() == f64::INFINITY)
            }
            _ => panic!("wrong op"),
        }
    }

    #[test]
    fn a_short_campaign_per_target_is_clean() {
        for t in [
            Target::Pddl,
            Target::Plan,
            Target::Scene,
            Target::Case,
            Target::WorldOps,
        ] {
            let r = run(
                &FuzzParams {
                    target: t,
                    iterations: 40,
                    seed: 1,
                    max_edits: 3,
                },
                |_, _| {},
            )
            .unwrap();
            assert_eq!(r.inputs, 40);
            assert!(r.is_clean(), "{t:?}: {:#?}", r.findings);
            assert!(r.refused > 0, "{t:?}: every mutant accepted");
        }
    }
}
