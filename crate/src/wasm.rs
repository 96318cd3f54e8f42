//! WebAssembly bindings (feature `wasm`): the only module that touches `wasm-bindgen`.
//!
//! Everything crosses the boundary as plain JSON-compatible data (serde through
//! `serde-wasm-bindgen`, TypeScript declarations from `tsify` or hand-written custom sections);
//! every fallible call returns a rejected value carrying a message instead of panicking.

use wasm_bindgen::prelude::*;

/// The crate version, e.g. `"0.1.0"`.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// TypeScript declarations of the scene and frame shapes (`sim::snapshot`, the loop's `Frame`):
/// those types live in the core, which stays free of wasm crates, so their `.d.ts` is written here.
#[wasm_bindgen(typescript_custom_section)]
const TS_SCENE: &'static str = r#"
/** A rigid pose: position (m) and unit quaternion [x, y, z, w]. */
export interface PoseSnapshot { position: [number, number, number]; quaternion: [number, number, number, number]; }
/** One box of a compound shape, in the body frame. */
export interface PartSnapshot { pose: PoseSnapshot; half_extents: [number, number, number]; }
/** Geometry of a body in its own frame. */
export type ShapeSnapshot =
  | { type: "cuboid"; half_extents: [number, number, number] }
  | { type: "compound"; parts: PartSnapshot[] };
/** What a body is. */
export type BodyKind = "block" | "hook" | "table" | "shelf";
/** One body of the world. */
export interface BodySnapshot { name: string; kind: BodyKind; shape: ShapeSnapshot; pose: PoseSnapshot; color: string; lost?: boolean; }
/** A capsule (segment swept by a sphere), world frame. */
export interface CapsuleSnapshot { a: [number, number, number]; b: [number, number, number]; radius: number; }
/** A posed box, world frame. */
export interface CuboidSnapshot { pose: PoseSnapshot; half_extents: [number, number, number]; }
/** Horizontal workspace annulus of an arm (m). */
export interface ReachSnapshot { min_radius: number; max_radius: number; }
/** One 7-DoF arm with its gripper; `tcp`, `links` and `fingers` are derived, for drawing. */
export interface ArmSnapshot {
  name: string; base: PoseSnapshot; joints: number[]; gripper_opening: number; holding?: string | null;
  reach: ReachSnapshot; tcp: PoseSnapshot; links: CapsuleSnapshot[]; fingers: CuboidSnapshot[];
}
/** A named table region (B3). */
export interface RegionSnapshot { name: string; min: [number, number]; max: [number, number]; color: string; }
/** The whole world, as `World::snapshot` writes it and `scene.json` files hold it. */
export interface WorldSnapshot {
  version: number; name: string; time: number; dt: number; floor_z: number; predicates: string[];
  regions: RegionSnapshot[]; bodies: BodySnapshot[]; arms: ArmSnapshot[];
}
"#;

/// TypeScript declarations of the closed-loop session's data (the loop's `SessionOptions`, `Frame`
/// and friends, see `lfd::session`).
#[wasm_bindgen(typescript_custom_section)]
const TS_SESSION: &'static str = r#"
/** Which benchmark, method and mode a session runs. */
export interface SessionOptions {
  benchmark: "b1" | "b2" | "b3";
  method: "logic-lfd" | "linear" | "rlds" | "tamp";
  mode: "paper" | "prioritised";
  seed: number;
  skill?: "lqt" | "dmp";
}
/** What the loop is doing. */
export interface Status {
  kind: "idle" | "planning" | "executing" | "replanning" | "done" | "failed";
  message: string;
  step?: number | null;
  of?: number | null;
}
/** The last replan: why, how long it took (ms), which demo state it joined, the plan it made. */
export interface Replan { reason: string; time_ms: number; k?: number | null; plan: string[]; tick: number; }
/** One end-effector sample: where the arm's TCP is and where its controller aims. */
export interface EePoint { arm: number; pos: [number, number, number]; target: [number, number, number]; }
/** Everything the page draws after a step. */
export interface Frame {
  t: number;
  tick: number;
  world: WorldSnapshot;
  status: Status;
  plan: string[];
  executing?: number | null;
  demo: string[];
  demo_states: string[][];
  matched_k?: number | null;
  facts: string[];
  facts_added: string[];
  facts_removed: string[];
  last_replan?: Replan | null;
  replans: number;
  ee: EePoint[];
}
"#;

/// Converts any displayable error into a rejected value (a JS `Error` with the message).
fn js_err(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// Serialises plain data for JS: objects (not `Map`s), numbers for `u64`.
fn to_js<T: serde::Serialize>(v: &T) -> Result<JsValue, JsError> {
    v.serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(js_err)
}

/// Solves one LQT-CP case (the contract of `shared/lqt-cp-io.md`, as `logic-lfd lqt CASE.json`).
///
/// `case` is the case object or its JSON text; the result is the output object (`A`, `B`, `phi`,
/// `w`, `u`, `x`, `pos`, `cost`, `target_errors`, `feedback`). A malformed case rejects with a
/// message naming the key.
#[wasm_bindgen(unchecked_return_type = "LqtOutput")]
pub fn lqt(
    #[wasm_bindgen(unchecked_param_type = "LqtCase | string")] case: JsValue,
) -> Result<JsValue, JsError> {
    use crate::lqt::case::{run_case, CaseInput};
    let input = match case.as_string() {
        Some(text) => CaseInput::from_json_str(&text),
        None => {
            let v: serde_json::Value = serde_wasm_bindgen::from_value(case).map_err(js_err)?;
            CaseInput::from_value(&v)
        }
    }
    .map_err(js_err)?;
    let out = run_case(&input).map_err(js_err)?;
    to_js(&out)
}

#[wasm_bindgen(typescript_custom_section)]
const TS_LQT: &'static str = r#"
/** An LQT-CP case (shared/lqt-cp-io.md); unknown keys are ignored. */
export interface LqtCase {
  dim: number; order: number; dt: number; n_steps: number; r: number;
  basis: { type: "rbf" | "bernstein" | "fourier" | "piecewise"; n_fct: number; centers?: number[]; lambda?: number };
  x0: number[];
  reference: { mu: number[][]; q_diag: number[][] };
  targets?: { t: number; role: "via" | "goal"; pos: number[]; w_pos: number; vel?: number[]; w_vel?: number }[];
  tracking?: { demo_pos: number[][]; weights_per_order: number[] } | null;
  feedback?: { x_init: number[]; perturbation?: { after_step: number; delta: number[] } | null } | null;
  [key: string]: unknown;
}
/** One feedback rollout. */
export interface LqtRollout { x: number[][]; u: number[][]; pos: number[][]; final_goal_pos_dist: number | null; }
/** The output object of an LQT-CP case. */
export interface LqtOutput {
  A: number[][]; B: number[][]; phi: number[][]; w: number[][]; u: number[][]; x: number[][]; pos: number[][];
  cost: number;
  target_errors: { t: number; role: "via" | "goal"; pos_dist: number; vel_dist?: number }[];
  feedback?: { F: number[][]; gains: number[][][]; nominal: LqtRollout; perturbed?: LqtRollout };
}
"#;
