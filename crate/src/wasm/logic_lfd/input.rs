//! Reading the inputs of `logicLfd`, `logicLfdPerturb` and the `LogicLfd` class: the texts (a
//! non-string throws a `TypeError` naming the key), the options (a bad one is an `options`
//! error), the file names.

use serde_json::{Map, Value};
use wasm_bindgen::prelude::*;

use super::super::args::{json_type_name, type_error, type_name};
use super::super::convert::from_js;
use crate::lfd::Mode;
use crate::plan::{Algorithm, HeuristicKind, SearchConfig};

/// File names used in diagnostics.
pub(super) struct Files {
    pub(super) domain: String,
    pub(super) problem: String,
    pub(super) demo: String,
    pub(super) state: String,
}

impl Files {
    /// Which input a located error is about, by its file name.
    pub(super) fn source_of(&self, file: &str) -> &'static str {
        if file == self.domain {
            "domain"
        } else if file == self.problem {
            "problem"
        } else if file == self.demo {
            "demo"
        } else {
            "state"
        }
    }

    /// The file name of an input.
    pub(super) fn of(&self, source: &str) -> String {
        match source {
            "domain" => self.domain.clone(),
            "problem" => self.problem.clone(),
            "demo" => self.demo.clone(),
            "state" => self.state.clone(),
            _ => String::new(),
        }
    }
}

/// The input object's fields, or the `TypeError` for a non-object.
pub(super) fn object_fields(func: &str, input: &JsValue) -> Result<Map<String, Value>, JsValue> {
    let not_object = || {
        type_error(&format!(
            "{func}: input must be an object, got {}",
            type_name(input)
        ))
    };
    if !input.is_object() || input.is_null() || input.is_array() {
        return Err(not_object());
    }
    match from_js::<Value>(input) {
        Ok(Value::Object(m)) => Ok(m),
        Ok(_) => Err(not_object()),
        Err(e) => Err(type_error(&format!("{func}: input: {e}"))),
    }
}

/// A required text field: a string, or a `TypeError` naming it.
pub(super) fn text(func: &str, m: &Map<String, Value>, key: &str) -> Result<String, JsValue> {
    match m.get(key) {
        Some(Value::String(s)) => Ok(s.clone()),
        other => Err(type_error(&format!(
            "{func}: input.{key} must be a string, got {}",
            other.map_or("undefined", json_type_name)
        ))),
    }
}

/// The domain, problem and demonstration texts of an input.
pub(super) struct Texts {
    pub(super) domain: String,
    pub(super) problem: String,
    pub(super) demo: String,
}

/// The input's `domain`, `problem` and `demo`: strings, or a `TypeError` naming the first that
/// is not.
pub(super) fn texts(func: &str, m: &Map<String, Value>) -> Result<Texts, JsValue> {
    Ok(Texts {
        domain: text(func, m, "domain")?,
        problem: text(func, m, "problem")?,
        demo: text(func, m, "demo")?,
    })
}

/// An optional text field (`null` reads as absent): a string, or a `TypeError` naming it.
pub(super) fn optional_text(
    func: &str,
    m: &Map<String, Value>,
    key: &str,
) -> Result<Option<String>, JsValue> {
    match m.get(key) {
        None | Some(Value::Null) => Ok(None),
        _ => text(func, m, key).map(Some),
    }
}

/// Refuses keys outside `allowed` (the message names the first).
pub(super) fn known_keys(
    m: &Map<String, Value>,
    allowed: &[&str],
    what: &str,
) -> Result<(), String> {
    match m.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => Err(format!(
            "unknown {what} key `{k}` (expected one of {})",
            allowed.join(", ")
        )),
        None => Ok(()),
    }
}

/// A non-negative integer option (absent or `null`: `None`).
pub(super) fn count_option(m: &Map<String, Value>, key: &str) -> Result<Option<u64>, String> {
    match m.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::Number(n)) => match n.as_f64() {
            Some(x) if x >= 0.0 && x.fract() == 0.0 && x <= 9_007_199_254_740_991.0 => {
                Ok(Some(x as u64))
            }
            _ => Err(format!("`{key}` must be a non-negative integer, got {n}")),
        },
        Some(v) => Err(format!(
            "`{key}` must be a non-negative integer, got {}",
            json_type_name(v)
        )),
    }
}

pub(super) fn string_option<'m>(
    m: &'m Map<String, Value>,
    key: &str,
) -> Result<Option<&'m str>, String> {
    match m.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::String(s)) => Ok(Some(s)),
        Some(v) => Err(format!(
            "`{key}` must be a string, got {}",
            json_type_name(v)
        )),
    }
}

/// The `files` option: names for diagnostics.
pub(super) fn files_option(m: &Map<String, Value>, keys: &[&str]) -> Result<Files, String> {
    let mut files = Files {
        domain: "domain.pddl".into(),
        problem: "problem.pddl".into(),
        demo: "demo.plan".into(),
        state: "state".into(),
    };
    let f = match m.get("files") {
        None | Some(Value::Null) => return Ok(files),
        Some(Value::Object(f)) => f,
        Some(v) => {
            return Err(format!(
                "`files` must be an object, got {}",
                json_type_name(v)
            ))
        }
    };
    known_keys(f, keys, "files")?;
    for (key, slot) in [
        ("domain", &mut files.domain),
        ("problem", &mut files.problem),
        ("demo", &mut files.demo),
        ("state", &mut files.state),
    ] {
        if let Some(name) = string_option(f, key).map_err(|e| format!("files: {e}"))? {
            *slot = name.to_string();
        }
    }
    Ok(files)
}

/// The search options of `logicLfd`.
pub(super) struct Options {
    pub(super) mode: Mode,
    pub(super) config: SearchConfig,
    pub(super) compare: bool,
    /// Replay the merged plan on the lifted domain (`valid`); default on.
    pub(super) validate: bool,
}

pub(super) fn search_options(m: &Map<String, Value>) -> Result<Options, String> {
    let mode = match string_option(m, "mode")? {
        None => Mode::Paper,
        Some(s) => Mode::parse(s)
            .ok_or_else(|| format!("unknown mode `{s}` (expected paper|prioritised)"))?,
    };
    let algorithm = string_option(m, "search")?
        .unwrap_or("astar")
        .parse::<Algorithm>()
        .map_err(|e| e.to_string())?;
    let default_h = if algorithm == Algorithm::Astar {
        "lmcut"
    } else {
        "hff"
    };
    let heuristic = string_option(m, "heuristic")?
        .unwrap_or(default_h)
        .parse::<HeuristicKind>()
        .map_err(|e| e.to_string())?;
    let max_nodes = count_option(m, "maxExpanded")?;
    let time_ms = match m.get("timeLimitMs") {
        None | Some(Value::Null) => 30_000.0,
        Some(Value::Number(n)) => match n.as_f64() {
            Some(x) if x >= 0.0 => x,
            _ => {
                return Err(format!(
                    "`timeLimitMs` must be a non-negative number, got {n}"
                ))
            }
        },
        Some(v) => {
            return Err(format!(
                "`timeLimitMs` must be a non-negative number, got {}",
                json_type_name(v)
            ))
        }
    };
    let compare = bool_option(m, "compare", false)?;
    let validate = bool_option(m, "validate", true)?;
    Ok(Options {
        mode,
        config: SearchConfig {
            algorithm,
            heuristic,
            max_nodes,
            time_limit_secs: Some(time_ms / 1e3),
        },
        compare,
        validate,
    })
}

/// Boolean option `key` of `m`, `default` when absent or null.
fn bool_option(m: &Map<String, Value>, key: &str, default: bool) -> Result<bool, String> {
    match m.get(key) {
        None | Some(Value::Null) => Ok(default),
        Some(Value::Bool(b)) => Ok(*b),
        Some(v) => Err(format!(
            "`{key}` must be a boolean, got {}",
            json_type_name(v)
        )),
    }
}

pub(super) const LFD_KEYS: [&str; 13] = [
    "domain",
    "problem",
    "demo",
    "state",
    "after",
    "mode",
    "search",
    "heuristic",
    "maxExpanded",
    "timeLimitMs",
    "files",
    "compare",
    "validate",
];

/// The keys of the `LogicLfd` class's constructor input.
pub(super) const SETUP_KEYS: [&str; 4] = ["domain", "problem", "demo", "files"];

/// The keys of `LogicLfd.replan`'s options.
pub(super) const REPLAN_KEYS: [&str; 7] = [
    "mode",
    "search",
    "heuristic",
    "maxExpanded",
    "timeLimitMs",
    "compare",
    "validate",
];

/// The keys of the `files` option of `logicLfd` and the `LogicLfd` class.
pub(super) const FILE_KEYS: [&str; 4] = ["domain", "problem", "demo", "state"];
