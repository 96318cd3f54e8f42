//! The raw recording format (`logic-lfd demo segment RECORDING.json`): time-stamped gripper poses
//! and gripper states, optionally hand moves of blocks, on a named benchmark scene or a scene
//! given inline.
//!
//! ```json
//! { "benchmark": "b1",                    // or "scene": { …a WorldSnapshot, scene.json… }
//!   "dt": 0.01,                           // nominal sample period (s), informative
//!   "samples": [
//!     { "t": 0.00, "arm": 0, "pose": { "position": [0.3, 0.0, 0.4], "yaw": 0.0 }, "gripper": "open" },
//!     { "t": 0.01, "arm": "panda", "pose": { … }, "gripper": "closed" },
//!     { "t": 2.50, "move": { "body": "c", "position": [0.5, 0.1, 0.03] } }
//!   ],
//!   "goal": ["(on c b)", "(on b a)"],     // optional: the taught goal (default: every final fact)
//!   "seed": 0 }                           // optional, copied into the demo
//! ```
//!
//! * `t`: seconds, non-decreasing. A sample is applied at its time: the simulator steps (every
//!   `dt` of the scene) with the previous commands until `t`, then the sample's command holds for
//!   the next step. Samples with the same `t` for different arms command them together.
//! * `arm`: index in the scene's arm list or the arm's name.
//! * `pose`: the commanded tool centre point: `position` (m, world frame) and `yaw` (rad about
//!   world `z`; the gripper always points straight down, fingers closing across the yaw direction
//!   rotated by 90°, as [`panda::down_orientation`](crate::sim::panda::down_orientation)).
//! * `gripper`: `"open"` or `"closed"` (`"close"` accepted).
//! * `move`: the user displaced a block by hand (not with the robot): it goes to `position` and
//!   settles. Allowed only if it changes no fact (a motion-level nudge); a block "teleported" to
//!   another support is an unexplained change.

use super::RecorderError;
use crate::sim::Benchmark;
use crate::sim::WorldSnapshot;
use crate::sim::{GripperCommand, World};
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// An arm by index or by name.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(untagged)]
pub enum ArmRef {
    /// Index in the scene's arm list.
    Index(usize),
    /// Arm name (`panda`, `left`, `right`).
    Name(String),
}

impl ArmRef {
    /// The arm's index in `world`, if it exists.
    pub fn resolve(&self, world: &World) -> Option<usize> {
        match self {
            ArmRef::Index(i) => (*i < world.arm_names().len()).then_some(*i),
            ArmRef::Name(n) => world.arm_index(n),
        }
    }
}

/// A gripper pose: TCP position and yaw (the gripper points straight down).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct GripperPose {
    /// TCP position, world frame (m).
    pub position: [f64; 3],
    /// Gripper yaw about world `z` (rad).
    pub yaw: f64,
}

/// Open or closed gripper.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "lowercase")]
pub enum GripperState {
    /// Fingers open (a held body is released).
    Open,
    /// Fingers closed (a body between the fingertips is grasped).
    #[serde(alias = "close")]
    Closed,
}

impl GripperState {
    /// As a simulator command.
    pub fn command(self) -> GripperCommand {
        match self {
            GripperState::Open => GripperCommand::Open,
            GripperState::Closed => GripperCommand::Close,
        }
    }

    /// From a simulator command.
    pub fn from_command(c: GripperCommand) -> GripperState {
        match c {
            GripperCommand::Open => GripperState::Open,
            GripperCommand::Close => GripperState::Closed,
        }
    }
}

/// A block displaced by the user's hand.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct HandMove {
    /// The block (or hook).
    pub body: String,
    /// Where its centre goes before it settles (m, world frame).
    pub position: [f64; 3],
}

/// One recorded sample.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(untagged)]
pub enum RawSample {
    /// The gripper handle of one arm.
    Gripper {
        /// Time (s).
        t: f64,
        /// Which arm.
        arm: ArmRef,
        /// Commanded TCP pose.
        pose: GripperPose,
        /// Commanded gripper state.
        gripper: GripperState,
    },
    /// A hand move of a block.
    Move {
        /// Time (s).
        t: f64,
        /// The move.
        #[serde(rename = "move")]
        hand: HandMove,
    },
}

impl RawSample {
    /// The sample's time (s).
    pub fn t(&self) -> f64 {
        match self {
            RawSample::Gripper { t, .. } | RawSample::Move { t, .. } => *t,
        }
    }
}

/// Where a recording starts.
#[derive(Clone, Debug, PartialEq)]
pub enum RecordingScene {
    /// A benchmark's template scene.
    Benchmark(Benchmark),
    /// A scene given inline (boxed: a snapshot is large).
    Scene(Box<WorldSnapshot>),
}

impl RecordingScene {
    /// The starting world as a snapshot (validated).
    pub fn snapshot(&self) -> Result<WorldSnapshot, RecorderError> {
        match self {
            RecordingScene::Benchmark(b) => Ok(b.scene_snapshot()),
            RecordingScene::Scene(s) => {
                World::from_snapshot(s).map_err(|e| RecorderError::Input {
                    path: format!("scene.{}", e.path),
                    message: e.message,
                })?;
                Ok((**s).clone())
            }
        }
    }
}

/// A raw recording (see the module documentation for the JSON format).
#[derive(Clone, Debug, PartialEq)]
pub struct RawRecording {
    /// The starting scene.
    pub scene: RecordingScene,
    /// Nominal sample period (s).
    pub dt: f64,
    /// The samples, in time order.
    pub samples: Vec<RawSample>,
    /// The taught goal, if given.
    pub goal: Option<Vec<String>>,
    /// Seed copied into the demonstration (0 if absent).
    pub seed: u64,
}

fn input(path: impl Into<String>, message: impl Into<String>) -> RecorderError {
    RecorderError::Input {
        path: path.into(),
        message: message.into(),
    }
}

fn number(v: &Value, path: &str) -> Result<f64, RecorderError> {
    match v.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        _ => Err(input(path, format!("expected a finite number, got {v}"))),
    }
}

fn vec3(v: &Value, path: &str) -> Result<[f64; 3], RecorderError> {
    let a = v
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or_else(|| input(path, format!("expected [x, y, z], got {v}")))?;
    Ok([
        number(&a[0], &format!("{path}[0]"))?,
        number(&a[1], &format!("{path}[1]"))?,
        number(&a[2], &format!("{path}[2]"))?,
    ])
}

fn field<'v>(o: &'v Value, key: &str, path: &str) -> Result<&'v Value, RecorderError> {
    o.get(key)
        .ok_or_else(|| input(format!("{path}.{key}"), "missing"))
}

fn parse_sample(v: &Value, p: &str) -> Result<RawSample, RecorderError> {
    if !v.is_object() {
        return Err(input(p, "expected an object"));
    }
    let t = number(field(v, "t", p)?, &format!("{p}.t"))?;
    if t < 0.0 {
        return Err(input(format!("{p}.t"), "must not be negative"));
    }
    if let Some(m) = v.get("move") {
        let mp = format!("{p}.move");
        let body = field(m, "body", &mp)?
            .as_str()
            .ok_or_else(|| input(format!("{mp}.body"), "expected a body name"))?
            .to_ascii_lowercase();
        let position = vec3(field(m, "position", &mp)?, &format!("{mp}.position"))?;
        return Ok(RawSample::Move {
            t,
            hand: HandMove { body, position },
        });
    }
    let arm_v = field(v, "arm", p)?;
    let arm = match arm_v {
        Value::Number(n) => ArmRef::Index(
            n.as_u64()
                .ok_or_else(|| input(format!("{p}.arm"), "expected an arm index or name"))?
                as usize,
        ),
        Value::String(s) => ArmRef::Name(s.to_ascii_lowercase()),
        _ => return Err(input(format!("{p}.arm"), "expected an arm index or name")),
    };
    let pose_v = field(v, "pose", p)?;
    let pp = format!("{p}.pose");
    let position = vec3(field(pose_v, "position", &pp)?, &format!("{pp}.position"))?;
    let yaw = number(field(pose_v, "yaw", &pp)?, &format!("{pp}.yaw"))?;
    let g = field(v, "gripper", p)?;
    let gripper = match g.as_str() {
        Some("open") => GripperState::Open,
        Some("closed") | Some("close") => GripperState::Closed,
        _ => {
            return Err(input(
                format!("{p}.gripper"),
                format!("expected \"open\" or \"closed\", got {g}"),
            ))
        }
    };
    Ok(RawSample::Gripper {
        t,
        arm,
        pose: GripperPose { position, yaw },
        gripper,
    })
}

/// The recording's scene: a named benchmark or an inline scene (checked), not both.
fn parse_scene(v: &Value) -> Result<RecordingScene, RecorderError> {
    Ok(match (v.get("benchmark"), v.get("scene")) {
        (Some(_), Some(_)) => {
            return Err(input(
                "scene",
                "give either \"benchmark\" or \"scene\", not both",
            ))
        }
        (Some(b), None) => {
            let name = b.as_str().unwrap_or("");
            RecordingScene::Benchmark(
                Benchmark::parse(name).ok_or_else(|| {
                    input("benchmark", format!("unknown benchmark {b} (b1, b2, b3)"))
                })?,
            )
        }
        (None, Some(s)) => {
            let snap: WorldSnapshot =
                serde_json::from_value(s.clone()).map_err(|e| input("scene", e.to_string()))?;
            let scene = RecordingScene::Scene(Box::new(snap));
            scene.snapshot()?;
            scene
        }
        (None, None) => {
            return Err(input(
                "benchmark",
                "missing (give \"benchmark\": \"b1\" or an inline \"scene\")",
            ))
        }
    })
}

/// The samples, in non-decreasing time order.
fn parse_samples(v: &Value) -> Result<Vec<RawSample>, RecorderError> {
    let arr = v
        .get("samples")
        .ok_or_else(|| input("samples", "missing"))?
        .as_array()
        .ok_or_else(|| input("samples", "expected an array"))?;
    let mut samples = Vec::with_capacity(arr.len());
    let mut last = f64::NEG_INFINITY;
    for (i, s) in arr.iter().enumerate() {
        let p = format!("samples[{i}]");
        let s = parse_sample(s, &p)?;
        if s.t() < last {
            return Err(input(
                format!("{p}.t"),
                format!("goes back in time ({} s after {} s)", s.t(), last),
            ));
        }
        last = s.t();
        samples.push(s);
    }
    Ok(samples)
}

/// The optional taught goal: an array of fact strings.
fn parse_goal(v: &Value) -> Result<Option<Vec<String>>, RecorderError> {
    Ok(match v.get("goal") {
        None | Some(Value::Null) => None,
        Some(Value::Array(a)) => Some(
            a.iter()
                .enumerate()
                .map(|(i, f)| {
                    f.as_str()
                        .map(str::to_string)
                        .ok_or_else(|| input(format!("goal[{i}]"), "expected a fact string"))
                })
                .collect::<Result<Vec<_>, _>>()?,
        ),
        Some(_) => return Err(input("goal", "expected an array of fact strings")),
    })
}

impl RawRecording {
    /// Parses and checks a recording; errors name the key path (`samples[3].pose.yaw: …`) or
    /// the line and column of malformed JSON.
    pub fn from_json(text: &str) -> Result<RawRecording, RecorderError> {
        let v: Value = serde_json::from_str(text).map_err(|e| {
            input(
                format!("line {} column {}", e.line(), e.column()),
                e.to_string(),
            )
        })?;
        if !v.is_object() {
            return Err(input("(root)", "expected a JSON object"));
        }
        let scene = parse_scene(&v)?;
        let dt = match v.get("dt") {
            None => 0.01,
            Some(d) => {
                let x = number(d, "dt")?;
                if x <= 0.0 {
                    return Err(input("dt", "must be positive"));
                }
                x
            }
        };
        let samples = parse_samples(&v)?;
        let goal = parse_goal(&v)?;
        let seed = match v.get("seed") {
            None => 0,
            Some(s) => s
                .as_u64()
                .ok_or_else(|| input("seed", "expected an unsigned integer"))?,
        };
        Ok(RawRecording {
            scene,
            dt,
            samples,
            goal,
            seed,
        })
    }

    /// The recording as JSON (the format [`RawRecording::from_json`] reads).
    pub fn to_json(&self) -> String {
        let mut o = serde_json::Map::new();
        match &self.scene {
            RecordingScene::Benchmark(b) => {
                o.insert("benchmark".into(), Value::String(b.as_str().into()));
            }
            RecordingScene::Scene(s) => {
                o.insert(
                    "scene".into(),
                    serde_json::to_value(s).unwrap_or(Value::Null),
                );
            }
        }
        o.insert("dt".into(), serde_json::json!(self.dt));
        o.insert(
            "samples".into(),
            serde_json::to_value(&self.samples).unwrap_or(Value::Null),
        );
        if let Some(g) = &self.goal {
            o.insert("goal".into(), serde_json::json!(g));
        }
        o.insert("seed".into(), serde_json::json!(self.seed));
        Value::Object(o).to_string()
    }
}
