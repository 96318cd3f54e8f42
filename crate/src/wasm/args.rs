//! Argument checks at the boundary: a parameter of the wrong JS type throws a `TypeError` naming
//! the function and the parameter (`plan: domain must be a string, got number`), before any
//! wasm-bindgen conversion could read it as something else.

use wasm_bindgen::prelude::*;

#[wasm_bindgen]
extern "C" {
    /// The JS `TypeError` class.
    #[wasm_bindgen(js_name = TypeError)]
    type JsTypeError;

    /// `new TypeError(message)`.
    #[wasm_bindgen(constructor, js_class = "TypeError")]
    fn new(message: &str) -> JsTypeError;
}

#[wasm_bindgen]
extern "C" {
    /// A parameter declared `string` in TypeScript and checked here: an optional trailing
    /// `Option<StringArg>` is `name?: string | null` (a `JsValue` with an unchecked type would not
    /// be optional), and any JS value reaches the check of [`optional_string_arg`].
    #[wasm_bindgen(typescript_type = "string")]
    pub type StringArg;
}

/// A JS `TypeError` with `message`, as the value a binding throws.
pub(crate) fn type_error(message: &str) -> JsValue {
    JsTypeError::new(message).into()
}

/// The JS type of a value as people say it: `typeof`, except `null` and `array`.
pub(crate) fn type_name(v: &JsValue) -> String {
    if v.is_null() {
        "null".into()
    } else if v.is_array() {
        "array".into()
    } else {
        v.js_typeof()
            .as_string()
            .unwrap_or_else(|| "unknown".into())
    }
}

/// The type of a JSON value as its JS counterpart's `typeof` (`null` and `array` named apart).
#[cfg(feature = "wasm")]
pub(crate) fn json_type_name(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Null => "null",
        serde_json::Value::Bool(_) => "boolean",
        serde_json::Value::Number(_) => "number",
        serde_json::Value::String(_) => "string",
        serde_json::Value::Array(_) => "array",
        serde_json::Value::Object(_) => "object",
    }
}

/// `v` as a string, or a `TypeError`: `{func}: {param} must be a string, got {type}`.
pub(crate) fn string_arg(func: &str, param: &str, v: &JsValue) -> Result<String, JsValue> {
    v.as_string().ok_or_else(|| {
        type_error(&format!(
            "{func}: {param} must be a string, got {}",
            type_name(v)
        ))
    })
}

/// `v` as a string when given (`undefined` and `null` read as absent), else a `TypeError`.
#[cfg(not(first_load))]
pub(crate) fn optional_string_arg(
    func: &str,
    param: &str,
    v: Option<StringArg>,
) -> Result<Option<String>, JsValue> {
    match v.map(JsValue::from) {
        Some(v) if !v.is_undefined() && !v.is_null() => string_arg(func, param, &v).map(Some),
        _ => Ok(None),
    }
}

/// A `TypeError` unless `v` is a plain object (not `null`, not an array); `optional` also lets
/// `undefined` and `null` through.
pub(crate) fn object_arg(
    func: &str,
    param: &str,
    v: &JsValue,
    optional: bool,
) -> Result<(), JsValue> {
    if optional && (v.is_undefined() || v.is_null()) {
        return Ok(());
    }
    if v.is_object() && !v.is_array() && !v.is_null() {
        Ok(())
    } else {
        Err(type_error(&format!(
            "{func}: {param} must be an object, got {}",
            type_name(v)
        )))
    }
}

/// `v` as a number, or a `TypeError`.
pub(crate) fn number_arg(func: &str, param: &str, v: &JsValue) -> Result<f64, JsValue> {
    v.as_f64().ok_or_else(|| {
        type_error(&format!(
            "{func}: {param} must be a number, got {}",
            type_name(v)
        ))
    })
}
