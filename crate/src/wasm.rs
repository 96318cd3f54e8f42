//! WebAssembly bindings (feature `wasm`): the only module that touches `wasm-bindgen`.
//!
//! Everything crosses the boundary as plain JSON-compatible data (serde through JSON text and
//! `JSON.parse` / `JSON.stringify`, so that one serde_json (de)serialiser serves every type;
//! TypeScript declarations from `tsify` or hand-written custom sections); every fallible call
//! returns a rejected value carrying a message instead of panicking.
//!
//! Feature `wasm-core` builds the page's first-load module: everything but Teach mode
//! (`Teacher`, taught tasks), `Session.replay` and the npm-only `lqt`, `validate` and
//! `runEpisode`; `wasm` adds them (the npm package, and the module the page loads when Teach mode
//! opens).

use crate::pddl::{self, PddlError};
use crate::plan::{self, Algorithm, Clock, HeuristicKind, SearchConfig, SearchOutcome};
use serde::{Deserialize, Serialize};
use tsify::Tsify;
use wasm_bindgen::prelude::*;

mod args;
mod logic_lfd;
#[cfg(feature = "wasm")]
pub mod reliability;
#[cfg(feature = "wasm")]
mod teach;

#[wasm_bindgen]
extern "C" {
    /// `performance.now()` (ms): exists in windows, workers and node ≥ 16.
    #[wasm_bindgen(js_namespace = performance, js_name = now)]
    fn performance_now() -> f64;
}

#[wasm_bindgen]
extern "C" {
    /// `console.error(message)`.
    #[wasm_bindgen(js_namespace = console, js_name = error)]
    fn console_error(message: &str);
}

/// The message of the last panic (a bug: user input never panics), for [`last_panic`].
static LAST_PANIC: std::sync::Mutex<String> = std::sync::Mutex::new(String::new());

/// Runs when the module is instantiated: a panic (which aborts the module) is logged to the
/// console with its location and kept for [`last_panic`], so the page can say what happened.
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        let message = format!("logic-lfd panicked: {info}");
        console_error(&message);
        if let Ok(mut last) = LAST_PANIC.lock() {
            *last = message;
        }
    }));
}

/// The message of the last panic inside the module, or `""`. After a panic the module is dead
/// (it aborts); load it again to continue.
#[wasm_bindgen(js_name = lastPanic)]
pub fn last_panic() -> String {
    LAST_PANIC.lock().map(|s| s.clone()).unwrap_or_default()
}

/// The JS high-resolution clock, for search time limits and reported times.
struct PerformanceClock;

impl Clock for PerformanceClock {
    fn now_secs(&self) -> f64 {
        performance_now() / 1000.0
    }
}

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
export interface Replan { reason: string; time_ms: number; k?: number | null; plan: string[]; tick: number; new_actions?: number; }
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
/** An accepted drag: where the block went, what it rests on, what settled after it left. */
export interface PerturbOutcome {
  body: string; from: [number, number, number]; to: [number, number, number]; support: string;
  also_moved: [string, [number, number, number]][];
}
/** What an injected disturbance (l1..l4) did. */
export interface Injection { level: string; description: string; moved: [string, [number, number, number]][]; }
"#;

/// Converts any displayable error into a rejected value (a JS `Error` with the message).
fn js_err(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

#[wasm_bindgen]
extern "C" {
    /// `JSON.parse(text)`.
    #[wasm_bindgen(js_namespace = JSON, js_name = parse, catch)]
    fn json_parse(text: &str) -> Result<JsValue, JsValue>;

    /// `JSON.stringify(value)`: `None` for `undefined`, a function or a symbol; throws for a
    /// BigInt or a cycle.
    #[wasm_bindgen(js_namespace = JSON, js_name = stringify, catch)]
    fn json_stringify(value: &JsValue) -> Result<Option<String>, JsValue>;
}

/// Reads plain data from JS through its JSON text, so that one deserialiser (serde_json's, which
/// the core uses for JSON text) serves every type. `undefined` reads as `null`, and an object's
/// `undefined` fields as absent (JSON has no `undefined`). Errors are the serde messages, without
/// a position in the text.
fn from_js<T: serde::de::DeserializeOwned>(v: &JsValue) -> Result<T, String> {
    let text = json_stringify(v)
        .map_err(|_| "not JSON data (a BigInt, or a cycle)".to_string())?
        .unwrap_or_else(|| "null".into());
    serde_json::from_str(&text).map_err(|e| json_message(&e))
}

/// A serde_json error without its ` at line L column C` suffix.
fn json_message(e: &serde_json::Error) -> String {
    let s = e.to_string();
    let at = format!(" at line {} column {}", e.line(), e.column());
    match s.strip_suffix(&at) {
        Some(m) if e.line() != 0 => m.to_string(),
        _ => s,
    }
}

/// Serialises plain data for JS (objects, not `Map`s; numbers for `u64`) through serde_json's
/// compact text and `JSON.parse`: floats are written shortest-round-trip, so JS gets the same
/// numbers; a non-finite one would come out as `null`, as in the CLI's JSON.
fn to_js<T: serde::Serialize>(v: &T) -> Result<JsValue, JsError> {
    let text = serde_json::to_string(v).map_err(js_err)?;
    json_parse(&text).map_err(|_| js_err("JSON.parse failed"))
}

/// Solves one LQT-CP case (the contract of `docs/formats.md`, as `logic-lfd lqt CASE.json`).
///
/// `case` is the case object or its JSON text; the result is the output object (`A`, `B`, `phi`,
/// `w`, `u`, `x`, `pos`, `cost`, `target_errors`, `feedback`). A malformed case rejects with a
/// message naming the key.
#[cfg(feature = "wasm")]
#[wasm_bindgen(unchecked_return_type = "LqtOutput")]
pub fn lqt(
    #[wasm_bindgen(unchecked_param_type = "LqtCase | string")] case: JsValue,
) -> Result<JsValue, JsError> {
    use crate::lqt::case::{run_case, CaseInput};
    let input = match case.as_string() {
        Some(text) => CaseInput::from_json_str(&text),
        None => {
            let v: serde_json::Value = from_js(&case).map_err(js_err)?;
            CaseInput::from_value(&v)
        }
    }
    .map_err(js_err)?;
    let out = run_case(&input).map_err(js_err)?;
    to_js(&out)
}

#[cfg(feature = "wasm")]
#[wasm_bindgen(typescript_custom_section)]
const TS_LQT: &'static str = r#"
/** An LQT-CP case (docs/formats.md); unknown keys are ignored. */
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

/// Options of [`plan()`]; every field is optional.
#[derive(Debug, Default, Deserialize, Tsify)]
#[serde(default, deny_unknown_fields)]
pub struct PlanOptions {
    /// `bfs|ucs|astar|gbfs|lazy-gbfs` (default `astar`).
    #[tsify(optional)]
    pub search: Option<String>,
    /// `blind|hmax|hadd|hff|lmcut` (default `lmcut` for `astar`, `hff` otherwise).
    #[tsify(optional)]
    pub heuristic: Option<String>,
    /// Stop after this many expanded states (default: unbounded).
    #[tsify(optional)]
    pub max_expanded: Option<u64>,
    /// Stop after this many milliseconds (default 30 000).
    #[tsify(optional)]
    pub time_limit_ms: Option<f64>,
    /// File names used in diagnostics (default `domain.pddl`, `problem.pddl`).
    #[tsify(optional)]
    pub domain_file: Option<String>,
    /// See `domain_file`.
    #[tsify(optional)]
    pub problem_file: Option<String>,
}

/// A located message about one of the inputs.
#[derive(Debug, Clone, Serialize, Tsify)]
pub struct Diagnostic {
    /// Which input: `domain`, `problem`, `plan` or `options`.
    #[tsify(type = "\"domain\" | \"problem\" | \"plan\" | \"options\"")]
    pub source: &'static str,
    /// The file name used in the message.
    pub file: String,
    /// 1-based line (0 when the message is not about a place in the text).
    pub line: usize,
    /// 1-based column in characters (0 when `line` is 0).
    pub col: usize,
    /// What is wrong.
    pub message: String,
}

/// A plan found by [`plan()`].
#[derive(Debug, Serialize, Tsify)]
pub struct PlanFound {
    /// Always `true`.
    #[tsify(type = "true")]
    pub ok: bool,
    /// The actions, `(stack a b)`, in order.
    pub plan: Vec<String>,
    /// The plan's cost (its length without `:action-costs`).
    pub cost: u64,
    /// Whether the configuration guarantees an optimal plan.
    pub optimal: bool,
    /// States expanded.
    pub expanded: u64,
    /// States generated.
    pub generated: u64,
    /// Search time in milliseconds (grounding excluded).
    pub time_ms: f64,
    /// Grounding time in milliseconds.
    pub ground_ms: f64,
    /// The fluent facts of the initial state and after each action (`plan.length + 1` entries).
    pub states: Vec<Vec<String>>,
}

/// Why [`plan()`] found no plan.
#[derive(Debug, Serialize, Tsify)]
pub struct PlanFailed {
    /// Always `false`.
    #[tsify(type = "false")]
    pub ok: bool,
    /// `parse` (or grounding) errors, `options`, `unsolvable` (proved), or `budget` (ran out).
    #[tsify(type = "\"parse\" | \"options\" | \"unsolvable\" | \"budget\"")]
    pub kind: &'static str,
    /// One line for people.
    pub message: String,
    /// Located errors (empty for `unsolvable` and `budget`).
    pub diagnostics: Vec<Diagnostic>,
}

/// The result of [`plan()`]: test `ok` to tell them apart.
#[derive(Debug, Serialize, Tsify)]
#[serde(untagged)]
pub enum PlanOutcome {
    /// A plan was found.
    Found(PlanFound),
    /// No plan: why.
    Failed(PlanFailed),
}

fn diagnostic(e: &PddlError, domain_file: &str) -> Diagnostic {
    Diagnostic {
        source: if e.file == domain_file {
            "domain"
        } else {
            "problem"
        },
        file: e.file.clone(),
        line: e.line,
        col: e.col,
        message: e.message.clone(),
    }
}

fn failed(kind: &'static str, message: String, diagnostics: Vec<Diagnostic>) -> PlanOutcome {
    PlanOutcome::Failed(PlanFailed {
        ok: false,
        kind,
        message,
        diagnostics,
    })
}

/// Parses and grounds both texts; `Err` carries the failure to report.
fn parse_and_ground(
    domain_text: &str,
    problem_text: &str,
    domain_file: &str,
    problem_file: &str,
) -> Result<plan::Task, PlanOutcome> {
    let parse_err =
        |e: PddlError| failed("parse", e.to_string(), vec![diagnostic(&e, domain_file)]);
    let domain = pddl::parse_domain(domain_text, domain_file).map_err(parse_err)?;
    let problem = pddl::parse_problem(problem_text, problem_file, &domain).map_err(parse_err)?;
    plan::ground(&domain, &problem).map_err(|e| match e {
        plan::GroundError::Located(p) => parse_err(p),
        other => failed(
            "parse",
            other.to_string(),
            vec![Diagnostic {
                source: "problem",
                file: problem_file.to_string(),
                line: 0,
                col: 0,
                message: other.to_string(),
            }],
        ),
    })
}

fn options_error(message: String) -> PlanOutcome {
    failed(
        "options",
        message.clone(),
        vec![Diagnostic {
            source: "options",
            file: String::new(),
            line: 0,
            col: 0,
            message,
        }],
    )
}

fn plan_impl(domain_text: &str, problem_text: &str, o: PlanOptions) -> PlanOutcome {
    let domain_file = o.domain_file.as_deref().unwrap_or("domain.pddl");
    let problem_file = o.problem_file.as_deref().unwrap_or("problem.pddl");
    let algorithm = match o.search.as_deref().unwrap_or("astar").parse::<Algorithm>() {
        Ok(a) => a,
        Err(e) => return options_error(e.to_string()),
    };
    let default_h = if algorithm == Algorithm::Astar {
        "lmcut"
    } else {
        "hff"
    };
    let heuristic = match o
        .heuristic
        .as_deref()
        .unwrap_or(default_h)
        .parse::<HeuristicKind>()
    {
        Ok(h) => h,
        Err(e) => return options_error(e.to_string()),
    };
    let clock = PerformanceClock;
    let t0 = clock.now_secs();
    let task = match parse_and_ground(domain_text, problem_text, domain_file, problem_file) {
        Ok(t) => t,
        Err(out) => return out,
    };
    let ground_ms = (clock.now_secs() - t0) * 1e3;
    let config = SearchConfig {
        algorithm,
        heuristic,
        max_nodes: o.max_expanded,
        time_limit_secs: Some(o.time_limit_ms.unwrap_or(30_000.0).max(0.0) / 1e3),
    };
    let r = plan::search(&task, &config, &clock);
    match r.outcome {
        SearchOutcome::Plan(p) => {
            let names = |s: &plan::State| -> Vec<String> {
                s.facts().map(|f| task.facts[f as usize].clone()).collect()
            };
            let mut s = task.init.clone();
            let mut states = vec![names(&s)];
            for &op in &p.operators {
                s = task.operators[op].apply(&s);
                states.push(names(&s));
            }
            PlanOutcome::Found(PlanFound {
                ok: true,
                plan: p.names(&task).into_iter().map(str::to_string).collect(),
                cost: p.cost,
                optimal: config.is_optimal(),
                expanded: r.stats.expanded,
                generated: r.stats.generated,
                time_ms: r.stats.time_secs * 1e3,
                ground_ms,
                states,
            })
        }
        SearchOutcome::Unsolvable => failed(
            "unsolvable",
            format!(
                "the problem is unsolvable: no goal state among {} reachable states",
                r.stats.states
            ),
            vec![],
        ),
        SearchOutcome::BudgetExhausted { which } => failed(
            "budget",
            format!(
                "no plan within the {which} ({} states expanded)",
                r.stats.expanded
            ),
            vec![],
        ),
    }
}

/// Plans a PDDL problem: parses both texts (errors at `line:col`), grounds, and searches.
///
/// Never throws for bad PDDL or an unsolvable problem: the outcome says `ok: false` with the
/// reason and the located diagnostics. It rejects only when `options` is not an options object.
#[wasm_bindgen(unchecked_return_type = "PlanOutcome")]
pub fn plan(
    domain: &str,
    problem: &str,
    #[wasm_bindgen(unchecked_param_type = "PlanOptions | undefined")] options: JsValue,
) -> Result<JsValue, JsError> {
    let o: PlanOptions = if options.is_undefined() || options.is_null() {
        PlanOptions::default()
    } else {
        // Misspelt keys are refused (deny_unknown_fields).
        from_js(&options).map_err(|e| js_err(format!("options: {e}")))?
    };
    to_js(&plan_impl(domain, problem, o))
}

/// Parses and grounds a domain and a problem without searching: the located errors, if any
/// (what an editor shows as you type). File names as in [`PlanOptions`].
#[wasm_bindgen(js_name = check, unchecked_return_type = "Diagnostic[]")]
pub fn check(
    domain: &str,
    problem: &str,
    domain_file: Option<String>,
    problem_file: Option<String>,
) -> Result<JsValue, JsError> {
    let d = domain_file.as_deref().unwrap_or("domain.pddl");
    let p = problem_file.as_deref().unwrap_or("problem.pddl");
    let diags = match parse_and_ground(domain, problem, d, p) {
        Ok(_) => vec![],
        Err(PlanOutcome::Failed(f)) => f.diagnostics,
        Err(PlanOutcome::Found(_)) => vec![],
    };
    to_js(&diags)
}

/// A benchmark's initial scene and PDDL files (see [`benchmark()`]).
#[derive(Debug, Serialize, Tsify)]
pub struct BenchmarkInfo {
    /// `b1`, `b2` or `b3`.
    pub id: &'static str,
    /// The directory name, e.g. `b1-tower`.
    pub name: &'static str,
    /// The initial world, as the page draws it.
    #[tsify(type = "WorldSnapshot")]
    pub scene: crate::sim::snapshot::WorldSnapshot,
    /// `domains/<name>/domain.pddl`.
    pub domain: &'static str,
    /// `domains/<name>/problem.pddl`.
    pub problem: &'static str,
    /// The demonstration's actions (`domains/<name>/demo.json`) as an IPC plan, one a line.
    #[serde(rename = "demoPlan")]
    pub demo_plan: String,
}

/// One of the paper's benchmarks (`b1` tower, `b2` workspace reach, `b3` two arms): its initial
/// scene and its PDDL domain and problem. Rejects an unknown id.
#[wasm_bindgen(unchecked_return_type = "BenchmarkInfo")]
pub fn benchmark(id: &str) -> Result<JsValue, JsError> {
    use crate::sim::benchmark::Benchmark;
    let b = Benchmark::parse(id)
        .ok_or_else(|| js_err(format!("unknown benchmark `{id}` (expected b1, b2 or b3)")))?;
    to_js(&BenchmarkInfo {
        id: b.as_str(),
        name: b.dir_name(),
        scene: b.scene_snapshot(),
        domain: b.domain_pddl(),
        problem: b.problem_pddl(),
        demo_plan: crate::lfd::session::demo_actions(b.demo_json())
            .map_err(js_err)?
            .iter()
            .map(|a| format!("{a}\n"))
            .collect(),
    })
}

/// The verdict of [`validate()`].
#[cfg(feature = "wasm")]
#[derive(Debug, Serialize, Tsify)]
pub struct Validation {
    /// Every step applied and the goal holds.
    pub valid: bool,
    /// One line for people (`Plan valid, cost 6`, or the first failing step and why).
    pub message: String,
    /// Steps applied before the verdict.
    pub steps_applied: usize,
    /// Cost of the applied steps.
    pub cost: u64,
    /// The 1-based step whose precondition is false, if that is the verdict.
    #[tsify(optional)]
    pub failed_step: Option<usize>,
    /// The false precondition or goal literals.
    pub false_literals: Vec<String>,
    /// Located errors in the domain, problem or plan text.
    pub diagnostics: Vec<Diagnostic>,
}

/// Replays a plan (IPC format, one `(action arg …)` per line, `;` comments) on a problem and
/// says whether it is valid, or the first failing step and why. Bad PDDL or a malformed plan is
/// reported with `line:col` diagnostics, not thrown.
#[cfg(feature = "wasm")]
#[wasm_bindgen(unchecked_return_type = "Validation")]
pub fn validate(domain: &str, problem: &str, plan_text: &str) -> Result<JsValue, JsError> {
    use crate::plan::Outcome;
    let (df, pf, planf) = ("domain.pddl", "problem.pddl", "plan");
    let bad = |d: Diagnostic| Validation {
        valid: false,
        message: format!("{}:{}:{}: {}", d.file, d.line, d.col, d.message),
        steps_applied: 0,
        cost: 0,
        failed_step: None,
        false_literals: vec![],
        diagnostics: vec![d],
    };
    let d = match pddl::parse_domain(domain, df) {
        Ok(d) => d,
        Err(e) => return to_js(&bad(diagnostic(&e, df))),
    };
    let p = match pddl::parse_problem(problem, pf, &d) {
        Ok(p) => p,
        Err(e) => return to_js(&bad(diagnostic(&e, df))),
    };
    let plan_diag = |e: &PddlError| Diagnostic {
        source: "plan",
        ..diagnostic(e, df)
    };
    let steps = match plan::parse_plan(plan_text, planf) {
        Ok(s) => s,
        Err(e) => return to_js(&bad(plan_diag(&e))),
    };
    let r = plan::validate(&d, &p, &steps);
    let message = r.to_string();
    let (failed_step, false_literals, diagnostics) = match &r.outcome {
        Outcome::Valid => (None, vec![], vec![]),
        Outcome::Malformed(e) => (None, vec![], vec![plan_diag(e)]),
        Outcome::PreconditionFalse {
            step,
            false_literals,
            ..
        } => (Some(*step), false_literals.clone(), vec![]),
        Outcome::GoalNotReached { false_literals } => (None, false_literals.clone(), vec![]),
    };
    to_js(&Validation {
        valid: r.is_valid(),
        message,
        steps_applied: r.steps_applied,
        cost: r.cost,
        failed_step,
        false_literals,
        diagnostics,
    })
}

/// Converts a JS number to a seed (a non-negative integer below 2^53).
fn seed_of(seed: f64) -> Result<u64, JsError> {
    if seed.is_finite() && seed >= 0.0 && seed.fract() == 0.0 && seed <= 9_007_199_254_740_991.0 {
        Ok(seed as u64)
    } else {
        Err(js_err(format!(
            "seed must be a non-negative integer, got {seed}"
        )))
    }
}

fn session_options(options: JsValue) -> Result<crate::lfd::session::SessionOptions, JsError> {
    from_js(&options).map_err(|e| js_err(format!("options: {e}")))
}

/// One closed-loop episode (paper Algorithm 1) in a kinematic workcell: step it, draw its frames,
/// disturb it. Wraps `lfd::Session` 1:1; every method returns plain data (see `Frame`).
#[wasm_bindgen(js_name = Session)]
pub struct WasmSession {
    inner: crate::lfd::session::Session,
}

#[wasm_bindgen(js_class = Session)]
impl WasmSession {
    /// A session on one of the benchmarks (`{ benchmark: "b1", method: "logic-lfd", mode: "paper",
    /// seed: 1 }`). Rejects unknown options with a message.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "SessionOptions")] options: JsValue,
    ) -> Result<WasmSession, JsError> {
        let o = session_options(options)?;
        let inner = crate::lfd::session::Session::new(o).map_err(js_err)?;
        Ok(WasmSession { inner })
    }

    /// A session on a benchmark's task in a different starting scene (a saved `WorldSnapshot`
    /// JSON), optionally with another demonstration (`demo.json` text).
    #[wasm_bindgen(js_name = fromScene)]
    pub fn from_scene(
        #[wasm_bindgen(unchecked_param_type = "SessionOptions")] options: JsValue,
        scene: &str,
        demo: Option<String>,
    ) -> Result<WasmSession, JsError> {
        let o = session_options(options)?;
        let inner =
            crate::lfd::session::Session::from_scene(o, scene, demo.as_deref()).map_err(js_err)?;
        Ok(WasmSession { inner })
    }

    /// Re-runs a logged episode (from `episodeJson()`) and returns the session at its end.
    #[cfg(feature = "wasm")]
    pub fn replay(episode: &str) -> Result<WasmSession, JsError> {
        let inner = crate::lfd::session::Session::replay(episode).map_err(js_err)?;
        Ok(WasmSession { inner })
    }

    /// Advances the episode by `dt` simulated seconds (whole 10 ms ticks; replans happen inside)
    /// and returns the new frame.
    #[wasm_bindgen(unchecked_return_type = "Frame")]
    pub fn step(&mut self, dt: f64) -> Result<JsValue, JsError> {
        if !dt.is_finite() || dt < 0.0 {
            return Err(js_err(format!(
                "dt must be a non-negative number of seconds, got {dt}"
            )));
        }
        let f = self.inner.step(dt, &PerformanceClock);
        to_js(&f)
    }

    /// The current frame, without stepping.
    #[wasm_bindgen(unchecked_return_type = "Frame")]
    pub fn frame(&self) -> Result<JsValue, JsError> {
        to_js(&self.inner.frame())
    }

    /// Moves a block as a user's drag does: to `position` (m), then it settles. Rejects with the
    /// reason when the world refuses (the block would float, collide, …).
    #[wasm_bindgen(unchecked_return_type = "PerturbOutcome")]
    pub fn perturb(
        &mut self,
        body: &str,
        #[wasm_bindgen(unchecked_param_type = "[number, number, number]")] position: Vec<f64>,
    ) -> Result<JsValue, JsError> {
        let p: [f64; 3] = position
            .try_into()
            .map_err(|_| js_err("position must be [x, y, z]"))?;
        if p.iter().any(|v| !v.is_finite()) {
            return Err(js_err("position must be finite"));
        }
        let out = self
            .inner
            .perturb(body, p)
            .map_err(|r| js_err(format!("cannot move {}: {}", r.body, r.reason)))?;
        to_js(&out)
    }

    /// Injects a disturbance of level `l1`..`l4` and says what it did.
    #[wasm_bindgen(unchecked_return_type = "Injection")]
    pub fn inject(&mut self, level: &str) -> Result<JsValue, JsError> {
        let out = self.inner.inject(level).map_err(js_err)?;
        to_js(&out)
    }

    /// Restarts from the initial scene with another seed.
    pub fn reset(&mut self, seed: f64) -> Result<(), JsError> {
        self.inner.reset(seed_of(seed)?);
        Ok(())
    }

    /// Drops the current plan; the loop replans on the next step.
    pub fn cancel(&mut self) {
        self.inner.cancel();
    }

    /// The full episode log as JSON; `Session.replay` reproduces it exactly.
    #[wasm_bindgen(js_name = episodeJson)]
    pub fn episode_json(&self) -> String {
        self.inner.episode_json()
    }

    /// The current world as scene JSON (loadable with `Session.fromScene`).
    #[wasm_bindgen(js_name = sceneJson)]
    pub fn scene_json(&self) -> String {
        self.inner.world().to_json()
    }
}
