//! How a session is set up: its options (JSON), tunables and errors, the demonstration's
//! actions and placements as a `demo.json` gives them, and the seed of each random draw.

use crate::tamp::PlanarPose;
use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::lfd::ControlParams;
use crate::lfd::ExecParams;
use crate::lfd::LfdError;
use crate::lfd::SkillKind;
use crate::lfd::{DemoTrace, DomainModel, TaskBuilder};
use crate::lfd::{Method, Mode};
use crate::sim::Benchmark;
use crate::sim::BodyKind;
use crate::sim::SceneGraph;
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
    /// A robot put in an arm's place cannot reach a body the task needs
    /// ([`Session::set_robots`](super::Session::set_robots)).
    #[error("{0}")]
    Reach(String),
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
    demo_actions_in(demo_json, "demo")
}

/// [`demo_actions`], its errors naming the demonstration `label` (`demo`, or a folder's
/// `./mine/demo.json`, where a JSON syntax error reads `./mine/demo.json:3:5: trailing comma`).
pub(super) fn demo_actions_in(demo_json: &str, label: &str) -> Result<Vec<String>, SessionError> {
    let refused = |e: crate::sim::JsonError| {
        SessionError::Json(if e.path.is_empty() && label != "demo" {
            format!("{label}:{}:{}: {}", e.line, e.column, e.message)
        } else {
            format!("{label}: {e}")
        })
    };
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
    let v = match serde_json::from_str::<serde_json::Value>(demo_json) {
        Ok(v) => v,
        // Malformed JSON: its syntax error, not what the first reader expected where it stopped.
        Err(e) => {
            return Err(refused(crate::sim::JsonError {
                path: String::new(),
                message: syntax_message(&e),
                line: e.line(),
                column: e.column(),
            }))
        }
    };
    let arr = v
        .get("actions")
        .and_then(|a| a.as_array())
        .ok_or_else(|| SessionError::Json(format!("{label}: actions: missing array")))?;
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
                SessionError::Json(format!("{label}: actions[{i}]: expected an action string"))
            })
        })
        .collect()
}

/// serde_json's message without its ` at line L column C`.
fn syntax_message(e: &serde_json::Error) -> String {
    let full = e.to_string();
    let suffix = format!(" at line {} column {}", e.line(), e.column());
    full.strip_suffix(&suffix).unwrap_or(&full).to_string()
}

/// How messages name a session's demonstration: the folder's `demo.json` when it comes from
/// a directory, else `demo`.
pub(super) fn demo_label(files: &crate::sim::BenchmarkSources, given: bool) -> String {
    if !given && files.dir.contains('/') {
        files.file("demo.json")
    } else {
        "demo".into()
    }
}

/// Refuses a task whose scene contradicts its problem ([`crate::sim::check_names`]): a scene
/// object the problem does not declare, a physical problem object the scene lacks, a scene
/// that does not show what `:init` states. Files that do not parse are left to their readers.
pub(super) fn check_scene(files: &crate::sim::BenchmarkSources) -> Result<(), SessionError> {
    let found = crate::sim::check_scene_against_problem(files);
    let Some(first) = found.first() else {
        return Ok(());
    };
    let located = first.path.starts_with(|c: char| c.is_ascii_digit());
    let path = if located {
        format!("{}:{}", first.file, first.path)
    } else {
        first.file.clone()
    };
    let mut message = if located || first.path.is_empty() {
        first.message.clone()
    } else {
        format!("{}: {}", first.path, first.message)
    };
    for f in &found[1..] {
        message += &format!("; {f}");
    }
    Err(SessionError::Folder(crate::sim::FolderError {
        path,
        message,
    }))
}

/// The error for demonstration step `index` (`action`) that is no action of the task: which
/// part of it is unknown (the action, an object, the number of arguments), naming the file and
/// the step.
pub(super) fn unknown_step(
    domain: &crate::pddl::Domain,
    objects: &[crate::pddl::ObjectDecl],
    label: &str,
    index: usize,
    action: &str,
) -> SessionError {
    let (name, args) = crate::plan::fact_args(action);
    let names: Vec<&str> = objects.iter().map(|o| o.name.as_str()).collect();
    let why = match domain.actions.iter().find(|a| a.name.text == name) {
        None => {
            let actions: Vec<&str> = domain
                .actions
                .iter()
                .map(|a| a.name.text.as_str())
                .collect();
            format!(
                "the domain has no action `{name}` (its actions: {})",
                actions.join(" ")
            )
        }
        Some(a) if a.params.len() != args.len() => format!(
            "`{name}` takes {} argument{}, the step gives {}",
            a.params.len(),
            if a.params.len() == 1 { "" } else { "s" },
            args.len()
        ),
        Some(_) => {
            let unknown: Vec<String> = args
                .iter()
                .filter(|x| !names.contains(x))
                .map(|x| format!("`{x}`"))
                .collect();
            if unknown.is_empty() {
                "its arguments do not fit the action's parameter types (or a precondition on \
                 equality rules it out)"
                    .to_string()
            } else {
                format!(
                    "unknown object{} {} (the task's objects: {})",
                    if unknown.len() == 1 { "" } else { "s" },
                    unknown.join(", "),
                    names.join(" ")
                )
            }
        }
    };
    SessionError::Folder(crate::sim::FolderError {
        path: label.to_string(),
        message: format!("actions[{index}] (step {}) `{action}`: {why}", index + 1),
    })
}

/// What a task's files give before a scene is chosen: their `motions.json` (checked against the
/// domain), the template world that reads its facts through it, and the domain model.
pub(super) fn template_of(
    files: &crate::sim::BenchmarkSources,
) -> Result<(std::sync::Arc<crate::sim::Motions>, World, DomainModel), SessionError> {
    let motions = std::sync::Arc::new(files.parse_motions().map_err(|e| match e {
        Ok(m) => SessionError::Motions(m),
        Err(pddl) => SessionError::Lfd(LfdError::Model(pddl)),
    })?);
    let template = crate::sim::world_from_json(&files.scene)?.with_motions(motions.clone());
    let model = DomainModel::new(
        &files.domain,
        &files.file("domain.pddl"),
        &files.problem,
        &files.file("problem.pddl"),
        &motions.scene_predicates(),
    )?;
    Ok((motions, template, model))
}

/// The demonstration trace (`L_0 … L_N`) of a task's files, derived on its template scene as
/// a session derives it: errors name the file and step, as a session's do.
pub fn demo_trace_of(files: &crate::sim::BenchmarkSources) -> Result<DemoTrace, SessionError> {
    let (_, template, model) = template_of(files)?;
    check_scene(files)?;
    let objects = SceneGraph::objects(&template);
    let facts = SceneGraph::from_world(&template).to_strings();
    let task = model.build(&objects, &facts)?;
    let label = demo_label(files, false);
    let actions = demo_actions_in(&files.demo, &label)?;
    DemoTrace::derive(&task, &actions).map_err(|e| trace_error(e, model.domain(), &objects, &label))
}

/// A session's error for a demonstration that does not derive: an unknown step names what is
/// unknown ([`unknown_step`]), an inapplicable one its file and JSON path.
pub(super) fn trace_error(
    e: LfdError,
    domain: &crate::pddl::Domain,
    objects: &[crate::pddl::ObjectDecl],
    label: &str,
) -> SessionError {
    match e {
        LfdError::UnknownAction { index, action } => {
            unknown_step(domain, objects, label, index, &action)
        }
        LfdError::DemoNotApplicable {
            index,
            action,
            false_literals,
            location: None,
        } => SessionError::Lfd(LfdError::DemoNotApplicable {
            location: Some(format!("{label}: actions[{index}]")),
            index,
            action,
            false_literals,
        }),
        e => SessionError::Lfd(e),
    }
}

/// Every check of a task folder before it runs (`logic-lfd scene check --domain DIR`): the
/// files read ([`TaskFolder::sources`]), the scene against the problem and its layout
/// ([`crate::sim::check_sources`]), then the demonstration on the template scene
/// ([`demo_trace_of`]). Empty when the folder is ready to run.
///
/// [`TaskFolder::sources`]: crate::sim::TaskFolder::sources
pub fn check_folder(folder: &crate::sim::TaskFolder) -> Vec<crate::sim::Finding> {
    let sources = match folder.sources() {
        Ok(s) => s,
        Err(e) => return vec![crate::sim::Finding::new(&e.path, "", e.message)],
    };
    let mut found = crate::sim::check_sources(&sources);
    if crate::sim::check_names(&sources).is_empty() {
        if let Err(e) = demo_trace_of(&sources) {
            let text = e.to_string();
            // The error names its file first (`./mine/demo.json: …`); keep it as the file.
            let demo = sources.file("demo.json");
            let message = text
                .strip_prefix(&format!("{demo}: "))
                .unwrap_or(&text)
                .to_string();
            found.push(crate::sim::Finding::new(&demo, "", message));
        }
    }
    found
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
