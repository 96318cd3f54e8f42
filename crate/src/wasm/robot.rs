//! Robots in the npm package: the `robot` option of `new Session`, `Session.fromScene` and
//! `Session.fromFolder`, a shipped robot's name or a robot folder's files, in place of the
//! built-in Panda.

use std::sync::Arc;

use js_sys::{Array, ArrayBuffer, Object, Reflect, Uint8Array};
use wasm_bindgen::prelude::*;

use super::args::{type_error, type_name};
use super::convert::js_err;
use crate::sim::{ArmModel, Robot, SHIPPED_ROBOTS};

#[wasm_bindgen(typescript_custom_section)]
const ROBOT_TS: &'static str = r#"
/** A robot folder's files: each path in the folder (`robot.json`, `urdf/arm.urdf`,
 * `meshes/link1.stl`, …) with its text or bytes. The robot file is the folder's `robot.json`. */
export type RobotFolder = Record<string, string | Uint8Array | ArrayBuffer>;
/** A robot for the session's arms: a shipped robot (`"panda"`, the Franka Emika Panda from its
 * URDF, or `"ur5"`), a robot folder's files, or one of these per arm. */
export type RobotChoice = string | RobotFolder | (string | RobotFolder)[];
"#;

/// `options` without its `robot` key (a copy; the caller's object is left as it is) and the
/// robots that key names (none when absent).
pub(super) fn take_robots(
    func: &str,
    options: &JsValue,
) -> Result<(JsValue, Vec<Arc<ArmModel>>), JsValue> {
    if !options.is_object() || options.is_null() || options.is_array() {
        return Ok((options.clone(), vec![]));
    }
    let key = JsValue::from_str("robot");
    let value = Reflect::get(options, &key)?;
    let rest = Object::assign(&Object::new(), options.unchecked_ref());
    Reflect::delete_property(&rest, &key)?;
    let robots = if value.is_undefined() || value.is_null() {
        vec![]
    } else if value.is_array() {
        let list = Array::from(&value);
        if list.length() == 0 {
            return Err(type_error(&format!(
                "{func}: options.robot must name at least one robot"
            )));
        }
        list.iter()
            .enumerate()
            .map(|(i, v)| robot(func, &format!("options.robot[{i}]"), &v))
            .collect::<Result<Vec<_>, _>>()?
    } else {
        vec![robot(func, "options.robot", &value)?]
    };
    Ok((rest.into(), robots))
}

/// One robot: a shipped robot's name or a robot folder's files.
fn robot(func: &str, at: &str, v: &JsValue) -> Result<Arc<ArmModel>, JsValue> {
    if let Some(name) = v.as_string() {
        return ArmModel::shipped(&name).ok_or_else(|| {
            js_err(format!(
                "{at}: no shipped robot `{name}` (shipped: {}); give a robot folder's files for \
                 another robot",
                SHIPPED_ROBOTS.join(", ")
            ))
            .into()
        });
    }
    if !v.is_object() || v.is_array() {
        return Err(type_error(&format!(
            "{func}: {at} must be a robot's name or a robot folder's files, got {}",
            type_name(v)
        )));
    }
    let mut files = Vec::new();
    for entry in Object::entries(v.unchecked_ref()).iter() {
        let pair = Array::from(&entry);
        let path = pair.get(0).as_string().unwrap_or_default();
        let content = pair.get(1);
        let bytes = if let Some(text) = content.as_string() {
            text.into_bytes()
        } else if let Some(a) = content.dyn_ref::<Uint8Array>() {
            a.to_vec()
        } else if let Some(b) = content.dyn_ref::<ArrayBuffer>() {
            Uint8Array::new(b).to_vec()
        } else {
            return Err(type_error(&format!(
                "{func}: {at}[{path:?}] must be a string, a Uint8Array or an ArrayBuffer, got {}",
                type_name(&content)
            )));
        };
        files.push((path, bytes));
    }
    let robot = Robot::from_folder(files).map_err(|e| js_err(format!("{at}: {e}")))?;
    ArmModel::from_robot(&robot)
        .map(Arc::new)
        .map_err(|e| js_err(format!("{at}: {e}")).into())
}
