//! The located diagnostics of `logicLfd` and the `LogicLfd` class: which input an error is
//! about (domain, problem, demonstration, state or options), at which `file:line:col`, and the
//! JS `Error` the class throws with them.

use serde::Serialize;
use tsify::Tsify;
use wasm_bindgen::prelude::*;

use super::super::convert::to_js;
use super::input::Files;
use crate::lfd::LfdError;
use crate::pddl::PddlError;

/// A located message about one of the inputs.
#[derive(Debug, Clone, Serialize, Tsify)]
#[tsify(missing_as_null)]
pub(super) struct LogicLfdDiagnostic {
    /// Which input.
    #[tsify(type = "'domain' | 'problem' | 'demo' | 'state' | 'options'")]
    pub(super) source: &'static str,
    /// The file name used in the message.
    pub(super) file: String,
    /// 1-based line (0 when the message is not about a place).
    pub(super) line: usize,
    /// 1-based column (0 when the message is not about a place).
    pub(super) col: usize,
    /// What is wrong.
    pub(super) message: String,
}

/// A diagnostic about the options (not about a place in a text).
pub(super) fn options_diag(message: String) -> LogicLfdDiagnostic {
    LogicLfdDiagnostic {
        source: "options",
        file: String::new(),
        line: 0,
        col: 0,
        message,
    }
}

/// `file:line:col` split from the end (a file name may hold `:`).
fn split_location(location: &str) -> Option<(String, usize, usize)> {
    let mut it = location.rsplitn(3, ':');
    let col = it.next()?.parse().ok()?;
    let line = it.next()?.parse().ok()?;
    Some((it.next()?.to_string(), line, col))
}

/// The result kind and the diagnostics of an error from reading the inputs.
pub(super) fn input_error(
    e: &LfdError,
    files: &Files,
    default_source: &'static str,
) -> (&'static str, LogicLfdDiagnostic) {
    let kind_of = |source: &str| match source {
        "domain" | "problem" => "parse",
        "demo" => "demo",
        _ => "state",
    };
    let located = |source: &'static str, location: Option<&str>, message: String| {
        let (file, line, col) = location
            .and_then(split_location)
            .unwrap_or_else(|| (files.of(source), 0, 0));
        LogicLfdDiagnostic {
            source,
            file,
            line,
            col,
            message,
        }
    };
    match e {
        LfdError::Input(PddlError {
            file,
            line,
            col,
            message,
        }) => {
            let source = files.source_of(file);
            (
                kind_of(source),
                LogicLfdDiagnostic {
                    source,
                    file: file.clone(),
                    line: *line,
                    col: *col,
                    message: message.clone(),
                },
            )
        }
        LfdError::DemoNotApplicable {
            index,
            action,
            false_literals,
            location,
        } => (
            "demo",
            located(
                "demo",
                location.as_deref(),
                format!(
                    "demonstration step {} `{action}` is not applicable: {}",
                    index + 1,
                    false_precondition(false_literals)
                ),
            ),
        ),
        LfdError::UnknownAction { .. } | LfdError::DemoMissesGoal { .. } => {
            ("demo", located("demo", None, e.to_string()))
        }
        LfdError::PrefixNotApplicable {
            step,
            action,
            location,
            false_literals,
        } => (
            "state",
            located(
                "state",
                Some(location),
                format!(
                    "step {step} `{action}` is not applicable: {}",
                    false_precondition(false_literals)
                ),
            ),
        ),
        other => (
            kind_of(default_source),
            located(default_source, None, other.to_string()),
        ),
    }
}

fn false_precondition(literals: &[String]) -> String {
    if literals.is_empty() {
        "a precondition is false".into()
    } else {
        format!("false precondition {}", literals.join(" "))
    }
}

/// The diagnostic as one line: `file:line:col: message` when it has a place.
pub(super) fn location_message(d: &LogicLfdDiagnostic) -> String {
    if d.line == 0 {
        d.message.clone()
    } else {
        format!("{}:{}:{}: {}", d.file, d.line, d.col, d.message)
    }
}

/// The `Error` the class throws: the one-line message, and `kind` and `diagnostics` properties
/// as `logicLfd`'s result would carry them.
pub(super) fn located_error(kind: &str, d: LogicLfdDiagnostic) -> JsValue {
    let error = js_sys::Error::new(&location_message(&d));
    let set = |key: &str, value: &JsValue| {
        // Setting a property on a fresh Error cannot fail.
        let _ = js_sys::Reflect::set(&error, &JsValue::from_str(key), value);
    };
    set("kind", &JsValue::from_str(kind));
    if let Ok(diagnostics) = to_js(&[d]) {
        set("diagnostics", &diagnostics);
    }
    error.into()
}
