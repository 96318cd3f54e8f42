//! The `LogicLfd` class: the domain, the problem and the demonstration read, grounded and turned
//! into L_0 … L_N once, then any number of queries (LogicIn, replanning, validation) on states.
//!
//! A replan's result is `logicLfd`'s, built by the same code; its `demo`, `statics` and
//! `fluents` are serialised once and shared (frozen) by every result, since they are the bulk of
//! the result and do not depend on the state.

use js_sys::{Object, Reflect};
use wasm_bindgen::prelude::*;

use super::super::args::{json_type_name, type_error, type_name};
use super::super::convert::{from_js, to_js};
use super::super::pddl::Validation;
use super::diagnostics::{located_error, options_diag};
use super::input::{
    files_option, known_keys, object_fields, search_options, texts, Files, FILE_KEYS, REPLAN_KEYS,
    SETUP_KEYS,
};
use super::query::{answer, prepare, Current, Fixed, LogicLfdResult};
use crate::lfd::{LogicLfd, Observed};

#[wasm_bindgen]
extern "C" {
    /// S_C as a parameter: PDDL atoms (a text, or one atom an entry); absent or `null`: the
    /// problem's initial state.
    #[wasm_bindgen(typescript_type = "string | string[]")]
    pub type StateArg;

    /// `LogicLfd.replan`'s options.
    #[wasm_bindgen(typescript_type = "LogicLfdOptions")]
    pub type OptionsArg;
}

/// Logic-LfD on one PDDL task: reads the domain, the problem and one demonstration once, then
/// answers LogicIn, replanning and validation queries on any number of states.
///
/// Bad input throws an `Error` whose message is `file:line:col: message` and whose `kind` and
/// `diagnostics` are those `logicLfd` would report. Call `free()` when done; any call after it
/// throws an `Error` saying so.
#[wasm_bindgen(js_name = LogicLfd)]
pub struct LogicLfdClass {
    /// `None` once `free()` was called.
    task: Option<Box<Task>>,
}

/// What the class holds until `free()`.
struct Task {
    lfd: LogicLfd,
    files: Files,
    /// The demonstration, static facts and fluents as JS values (frozen), shared by results.
    demo: JsValue,
    statics: JsValue,
    fluents: JsValue,
}

/// The state parameter: atoms text, an array of atoms (one a line), or nothing for `:init`.
fn current(func: &str, state: Option<StateArg>) -> Result<Current, JsValue> {
    match state.map(JsValue::from) {
        Some(v) if !v.is_undefined() && !v.is_null() => {
            text_or_lines(func, "state", "an array of strings, null or undefined", &v)
                .map(Current::Atoms)
        }
        _ => Ok(Current::Init),
    }
}

/// A string, or an array of strings joined one a line; else a `TypeError` saying `param` must
/// be a string or `others`.
fn text_or_lines(func: &str, param: &str, others: &str, v: &JsValue) -> Result<String, JsValue> {
    if let Some(text) = v.as_string() {
        return Ok(text);
    }
    let wrong = |got: &str| {
        type_error(&format!(
            "{func}: {param} must be a string or {others}, got {got}"
        ))
    };
    if !v.is_array() {
        return Err(wrong(&type_name(v)));
    }
    let items: Vec<serde_json::Value> = from_js(v).map_err(|e| wrong(&e))?;
    let lines = items
        .iter()
        .map(|a| {
            a.as_str()
                .ok_or_else(|| wrong(&format!("an array holding a {}", json_type_name(a))))
        })
        .collect::<Result<Vec<&str>, JsValue>>()?;
    Ok(lines.join("\n"))
}

/// `value` frozen, and every object inside it (results share it).
fn deep_freeze(value: &JsValue) {
    if let Some(object) = value.dyn_ref::<Object>() {
        for v in Object::values(object).iter() {
            deep_freeze(&v);
        }
        Object::freeze(object);
    }
}

fn frozen<T: serde::Serialize>(value: &T) -> Result<JsValue, JsValue> {
    let js = to_js(value)?;
    deep_freeze(&js);
    Ok(js)
}

#[wasm_bindgen(js_class = LogicLfd)]
impl LogicLfdClass {
    /// Reads, grounds and derives L_0 … L_N from `{ domain, problem, demo, files? }`.
    ///
    /// Throws a `TypeError` when `input` is not an object or a text is not a string, and an
    /// `Error` with located `diagnostics` for bad PDDL, a bad demonstration or a bad option.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "LogicLfdSetup")] input: JsValue,
    ) -> Result<LogicLfdClass, JsValue> {
        const F: &str = "LogicLfd";
        let m = object_fields(F, &input)?;
        let texts = texts(F, &m)?;
        let files = known_keys(&m, &SETUP_KEYS, "input")
            .and_then(|()| files_option(&m, &FILE_KEYS))
            .map_err(|e| located_error("options", options_diag(e)))?;
        let lfd = prepare(&files, &texts).map_err(|(k, d)| located_error(k, d))?;
        let fixed = Fixed::of(&lfd);
        let task = Task {
            demo: frozen(&fixed.demo)?,
            statics: frozen(&fixed.statics)?,
            fluents: frozen(&fixed.fluents)?,
            lfd,
            files,
        };
        Ok(LogicLfdClass {
            task: Some(Box::new(task)),
        })
    }

    /// Releases the task (the grounded operators, the demonstration states); any later call
    /// on this instance throws. Calling it again does nothing.
    //
    // Replaces the `free()` wasm-bindgen writes, which would leave later calls to fail with
    // its "null pointer passed to rust"; the emptied handle itself goes with garbage collection.
    #[wasm_bindgen(js_name = free)]
    pub fn release(&mut self) {
        self.task = None;
    }

    /// The demonstration: its actions a_1 … a_N, its states L_0 … L_N and the costs c_k
    /// (frozen: every result of `replan` shares it).
    #[wasm_bindgen(getter, unchecked_return_type = "LogicLfdDemo")]
    pub fn demo(&self) -> Result<JsValue, JsValue> {
        Ok(self.live("LogicLfd.demo")?.demo.clone())
    }

    /// LogicIn(S_C): the largest k with L_k ⊆ S_C from which the rest of the demonstration
    /// applies, or `null`. `state`: PDDL atoms (a string, or an array of atoms), or `null` for
    /// the problem's initial state; a bad atom throws an `Error` with located `diagnostics`.
    #[wasm_bindgen(js_name = logicIn, unchecked_return_type = "number | null")]
    pub fn logic_in(&self, state: Option<StateArg>) -> Result<JsValue, JsValue> {
        let s = self.observe("LogicLfd.logicIn", state)?;
        Ok(s.logic_in()
            .map_or(JsValue::NULL, |k| JsValue::from(k as u32)))
    }

    /// Logic-LfD from `state` (as in `logicIn`): the same result as `logicLfd` with this task
    /// and the same options, without reading the texts again. Never throws for a bad state or
    /// option (`ok: false` with located diagnostics).
    #[wasm_bindgen(unchecked_return_type = "LogicLfdResult")]
    pub fn replan(
        &self,
        state: Option<StateArg>,
        options: Option<OptionsArg>,
    ) -> Result<JsValue, JsValue> {
        const F: &str = "LogicLfd.replan";
        let task = self.live(F)?;
        let current = current(F, state)?;
        let m = match options.map(JsValue::from) {
            Some(o) if !o.is_undefined() && !o.is_null() => object_fields(F, &o).map_err(|_| {
                type_error(&format!(
                    "{F}: options must be an object, got {}",
                    type_name(&o)
                ))
            })?,
            _ => serde_json::Map::new(),
        };
        let o = match known_keys(&m, &REPLAN_KEYS, "options").and_then(|()| search_options(&m)) {
            Ok(o) => o,
            Err(e) => return to_js(&LogicLfdResult::options_failure(e)),
        };
        let out = to_js(&answer(&task.lfd, &task.files, current, &o))?;
        // An answer leaves the fixed parts empty: the shared ones go in at the same keys.
        for (key, value) in [
            ("demo", &task.demo),
            ("statics", &task.statics),
            ("fluents", &task.fluents),
        ] {
            Reflect::set(&out, &key.into(), value)?;
        }
        Ok(out)
    }

    /// Replays `plan` (IPC plan text, or an array of steps) from `state` (as in `logicIn`) on
    /// the lifted domain: valid, or the first failing step and why. A bad state throws; a
    /// malformed step is reported in the result's `diagnostics`.
    #[wasm_bindgen(unchecked_return_type = "Validation")]
    pub fn validate(
        &self,
        #[wasm_bindgen(unchecked_param_type = "string | string[] | null | undefined")]
        state: JsValue,
        #[wasm_bindgen(unchecked_param_type = "string | string[]")] plan: JsValue,
    ) -> Result<JsValue, JsValue> {
        const F: &str = "LogicLfd.validate";
        let plan = text_or_lines(F, "plan", "an array of strings", &plan)?;
        let s = self.observe(F, Some(state.unchecked_into()))?;
        let report = s
            .validate(std::slice::from_ref(&plan))
            .map_err(|e| JsValue::from(js_sys::Error::new(&e.to_string())))?;
        to_js(&Validation::of(&report))
    }
}

impl LogicLfdClass {
    /// The task, or the `Error` a call after `free()` throws.
    fn live(&self, func: &str) -> Result<&Task, JsValue> {
        self.task.as_deref().ok_or_else(|| {
            js_sys::Error::new(&format!(
                "{func}: this LogicLfd was freed (free() was called); create a new one"
            ))
            .into()
        })
    }

    /// S_C read from the `state` parameter, or the `Error` to throw.
    fn observe(&self, func: &str, state: Option<StateArg>) -> Result<Observed<'_>, JsValue> {
        let task = self.live(func)?;
        current(func, state)?
            .read(&task.lfd, &task.files)
            .map_err(|(kind, d)| located_error(kind, d))
    }
}
