//! How a session is set up: its options (JSON), tunables and errors, the demonstration's
//! actions and placements as a `demo.json` gives them, and the seed of each random draw.

use crate::tamp::PlanarPose;
use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::lfd::ControlParams;
use crate::lfd::ExecParams;
use crate::lfd::LfdError;
use crate::lfd::SkillKind;
use crate::lfd::{Method, Mode};
use crate::sim::Benchmark;
use crate::sim::BodyKind;
use crate::sim::World;
use crate::sim::{MotionKind, Onto};
use crate::tamp::StreamParams;

/// How a session is set up (JSON: snake_case keys, defaults for all but `benchmark`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct SessionOptions {
    /// The benchmark.
    pub benchmark: Benchmark,
    /// The method that closes the loop (default `logic-lfd`).
    #[serde(default)]
    pub method: Method,
    /// Logic-LfD's multi-goal mode (default `paper`).
    #[serde(default)]
    pub mode: Mode,
    /// Seed of every random choice of the episode.
    #[serde(default)]
    pub seed: u64,
    /// The motion skill family (default `lqt`).
    #[serde(default)]
    pub skill: SkillKind,
    /// Blocks of the benchmark's generated N-block tower task, within the benchmark's block
    /// range (`blockRange` in the npm package; B2 has none); absent: the template task.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[cfg_attr(feature = "wasm-core", tsify(type = "number | null"))]
    pub blocks: Option<usize>,
}

/// The files of benchmark `b`'s template task, or of its generated tower task with `blocks`
/// blocks ([`crate::sim::tower_task`]).
pub fn sources_for(
    b: Benchmark,
    blocks: Option<usize>,
) -> Result<crate::sim::BenchmarkSources, SessionError> {
    Ok(match blocks {
        None => b.sources()?,
        #[cfg(not(first_load))]
        Some(n) => crate::sim::tower_task(b, n)?,
        // Recording a generated task's demonstration needs the scripted expert, which the page's
        // first-load module leaves out.
        #[cfg(first_load)]
        Some(_) => {
            return Err(SessionError::Json(
                "generated tasks run on the page's full module, not its first-load module".into(),
            ))
        }
    })
}

/// What went wrong creating or replaying a session.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// The benchmark's PDDL or demonstration is unusable.
    #[error(transparent)]
    Lfd(#[from] LfdError),
    /// The scene JSON is invalid.
    #[error("scene: {0}")]
    Scene(#[from] crate::sim::SceneError),
    /// The domain's `motions.json` is unusable.
    #[error(transparent)]
    Motions(#[from] crate::sim::MotionsError),
    /// A task folder is incomplete, unreadable or not the one an episode ran on.
    #[error(transparent)]
    Folder(#[from] crate::sim::FolderError),
    /// A JSON document (demo, episode) is malformed.
    #[error("{0}")]
    Json(String),
}

/// Tunables of a session.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SessionParams {
    /// Task level.
    pub control: ControlParams,
    /// Action execution.
    pub exec: ExecParams,
    /// Streams.
    pub streams: StreamParams,
    /// Simulated time after which the episode fails (s).
    pub max_time: f64,
    /// Failed executions of the same action in a row before the episode fails.
    pub max_action_failures: usize,
}

impl Default for SessionParams {
    fn default() -> Self {
        SessionParams {
            control: ControlParams::default(),
            exec: ExecParams::default(),
            streams: StreamParams::default(),
            max_time: 240.0,
            max_action_failures: 3,
        }
    }
}

/// The demonstrated action sequence of a `demo.json` (`actions`: strings, or objects with an
/// `action` / `name` field). A demo whose actions carry trajectories (`samples`) is read whole as
/// a [`crate::sim::demo::Demonstration`]: a bad value anywhere in it, or malformed JSON, is refused
/// with its path (`demo: actions[2].samples[5][1]: …`) rather than leaving its skills unlearned.
pub fn demo_actions(demo_json: &str) -> Result<Vec<String>, SessionError> {
    let refused = |e: crate::sim::JsonError| SessionError::Json(format!("demo: {e}"));
    let whole = match crate::sim::demo::parse(demo_json) {
        Ok(d) => {
            let normalize =
                |a: &crate::sim::demo::DemoAction| crate::lfd::normalize_action(&a.action);
            return Ok(d.actions.iter().map(normalize).collect());
        }
        Err(e) => e,
    };
    // A demo without trajectories: its actions only. The page's first-load module reads JSON
    // values with serde_json alone (no path tracking), so this reader adds no copy of it.
    let Ok(v) = serde_json::from_str::<serde_json::Value>(demo_json) else {
        return Err(refused(whole));
    };
    let arr = v
        .get("actions")
        .and_then(|a| a.as_array())
        .ok_or_else(|| SessionError::Json("demo: actions: missing array".into()))?;
    if arr.iter().any(|a| a.get("samples").is_some()) {
        return Err(refused(whole));
    }
    arr.iter()
        .enumerate()
        .map(|(i, a)| {
            let s = a
                .as_str()
                .or_else(|| a.get("action").and_then(|x| x.as_str()))
                .or_else(|| a.get("name").and_then(|x| x.as_str()));
            s.map(crate::lfd::normalize_action).ok_or_else(|| {
                SessionError::Json(format!("demo: actions[{i}]: expected an action string"))
            })
        })
        .collect()
}

/// Where the demonstration put things down: action `(…)` → the resting pose; and block name →
/// where it stood in the demonstration's scene (for a release the demonstration does not have).
pub(super) type PlacementHints = BTreeMap<String, PlanarPose>;

/// The placements the demonstration used for its releases onto a surface or a region (not onto
/// a block): action → the resting pose (`sim::demo` anchor poses); and every block of the
/// demonstration's scene `world` → its pose there.
///
/// A block a new prefix puts down goes back first to where the demonstration had it: the rest
/// of the demonstration was shown with it there (a tower's bottom block put back on its spot
/// keeps the tower's top within reach).
pub(super) fn demo_hints(demo_json: &str, world: &World) -> PlacementHints {
    let mut out = BTreeMap::new();
    if let Ok(d) = crate::sim::demo::from_json(demo_json) {
        for a in d.actions {
            let onto_surface = world.motions().action(&a.action).is_some_and(|(m, args)| {
                m.motion == MotionKind::Release
                    && match m.onto {
                        Some(Onto::Param(i)) => args
                            .get(i)
                            .is_some_and(|y| world.body_kind(y) != Some(BodyKind::Block)),
                        Some(_) => true,
                        None => false,
                    }
            });
            if onto_surface {
                let p = a.anchor_pose.position;
                out.entry(a.action.clone()).or_insert(PlanarPose {
                    x: p[0],
                    y: p[1],
                    yaw: a.anchor_pose.yaw,
                });
            }
        }
    }
    for name in world.block_names() {
        if let Some(p) = world.body_pose(name) {
            out.entry(name.to_string()).or_insert(PlanarPose {
                x: p.translation.x,
                y: p.translation.y,
                yaw: crate::sim::yaw_of(&p.rotation),
            });
        }
    }
    out
}

/// A seed for the `n`-th random draw of an episode (SplitMix64 of `seed ⊕ n·φ`).
pub fn mix_seed(seed: u64, n: u64) -> u64 {
    let mut z = seed ^ n.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
