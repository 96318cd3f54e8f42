//! From a taught demonstration to a closed-loop [`Session`]: the glue between the recorder and the
//! reactive loop (what the page's "Run" does after teaching, and `Session.fromTaught` in wasm).
//!
//! A taught `demo.json` ([`TaughtDemo`]) carries, beside the benchmark demo fields, its initial
//! world `scene`, `L_0` and the goal `G`. The task it defines is
//!
//! ```text
//!   domain    the task folder's domain (the folder it was taught in), else the domain of the
//!             benchmark whose world the scene is (B1, B2 or B3)
//!   problem   objects of the scene,  :init = L_0 ∪ static facts,  :goal = G
//!             (static facts: the folder problem's, or the benchmark's)
//!   demo      a_1..a_N of the recording  →  L_0..L_N  (derived, as for every demo)
//!   skills    learned from the recorded motions (object-centric LQT-CP, `lfd::skill`)
//! ```
//!
//! and a session runs it from any initial world of the same workcell: the taught scene, a scene
//! the user arranged, or a seeded random one ([`random_scene`]). Loading checks everything before
//! anything is used ([`load`]): the JSON shape (with the key path), the scene, every action's
//! applicability in turn (`L_k` derived again) and `G ⊆ L_N`.

use serde::{Deserialize, Serialize};

use super::{RecorderError, SkillFit, TaughtDemo};
use crate::lfd::DemoTrace;
use crate::lfd::DomainModel;
use crate::lfd::TaskBuilder as _;
use crate::lfd::{mix_seed, Session, SessionOptions, SessionParams, SkillKind};
use crate::lfd::{Level, Method, Mode};
use crate::lqt::{Skill, SkillParams};
use crate::sim::demo::Demonstration;
use crate::sim::Benchmark;
use crate::sim::BenchmarkSources;
use crate::sim::TaskFolder;
use crate::sim::{SceneGraph, World};
use nalgebra::{Isometry3, Point3};

/// A loaded and checked taught demonstration, as the page lists it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct TaughtInfo {
    /// `b1`, `b2` or `b3`: the benchmark whose world and domain the demonstration uses (none
    /// when it was taught in a task folder).
    pub benchmark: Option<Benchmark>,
    /// The task folder whose world and domain the demonstration uses, by its name (`./mine`).
    pub folder: Option<String>,
    /// a_1..a_N.
    pub actions: Vec<String>,
    /// The arm of each action.
    pub arms: Vec<String>,
    /// L_0..L_N (fluents, sorted).
    pub states: Vec<Vec<String>>,
    /// The taught goal G.
    pub goal: Vec<String>,
}

/// How a taught task is run (JSON: every key optional).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(default, deny_unknown_fields)]
pub struct TaughtRunOptions {
    /// `logic-lfd` (default), `linear`, `rlds` or `tamp`.
    pub method: Method,
    /// `paper` (default) or `prioritised`.
    pub mode: Mode,
    /// Seed of the episode (and of the random initial world).
    pub seed: u64,
    /// `lqt` (default) or `dmp`.
    pub skill: SkillKind,
    /// The initial world as scene JSON (a world the user arranged); default: the taught scene.
    pub scene: Option<String>,
    /// Start from a seeded random arrangement of the taught scene instead ([`random_scene`]).
    pub random: bool,
}

fn refused(m: impl Into<String>) -> RecorderError {
    RecorderError::Refused(m.into())
}

/// Parses a taught `demo.json` (errors name the key path of a wrong value with its line and
/// column, or the line and column of malformed JSON).
pub fn parse(demo_json: &str) -> Result<TaughtDemo, RecorderError> {
    let v: serde_json::Value = crate::sim::parse_json(demo_json).map_err(json_input)?;
    for key in ["actions", "scene", "goal", "initial_facts"] {
        if v.get(key).is_none() {
            return Err(RecorderError::Input {
                path: key.into(),
                message: if key == "actions" {
                    "missing".into()
                } else {
                    "missing: this is not a taught demonstration (teach one in the page, or \
                     `logic-lfd demo segment` a recording)"
                        .into()
                },
            });
        }
    }
    crate::sim::parse_json(demo_json).map_err(json_input)
}

/// A JSON error as an input error: the path of the value at fault (or the line and column).
fn json_input(e: crate::sim::JsonError) -> RecorderError {
    let (path, message) = e.into_parts();
    RecorderError::Input { path, message }
}

/// Where a taught task's domain, `motions.json` and static facts come from: the task folder it
/// was taught in, or the benchmark whose workcell its scene is.
struct Base {
    /// The folder's or the benchmark's files (only the domain and motions are used).
    files: BenchmarkSources,
    /// Facts of the problem's `:init` the scene graph does not report (B3's `reaches`).
    statics: Vec<String>,
    benchmark: Option<Benchmark>,
    folder: Option<String>,
}

fn model_err(e: impl std::fmt::Display) -> RecorderError {
    RecorderError::Model(e.to_string())
}

/// The base of taught demo `t`: `folder` when given (its world must be the demo's), else the
/// benchmark named by the demo's scene.
fn base(t: &TaughtDemo, folder: Option<&TaskFolder>) -> Result<Base, RecorderError> {
    let Some(folder) = folder else {
        let b = Benchmark::parse(&t.scene.name).ok_or_else(|| {
            refused(format!(
                "the demonstration's world `{}` is none of the benchmarks b1, b2, b3: give the task \
                 folder it was taught in",
                t.scene.name
            ))
        })?;
        let files = b.sources().map_err(model_err)?;
        let domain = crate::pddl::parse_domain(&files.domain, &files.file("domain.pddl"))
            .map_err(model_err)?;
        // A folder may reuse a benchmark's world under its own domain (B1 in other names).
        if domain.name.text != t.domain {
            return Err(refused(format!(
                "the demonstration's domain `{}` is not {}'s `{}`: give the task folder it was \
                 taught in",
                t.domain,
                b.as_str().to_uppercase(),
                domain.name.text
            )));
        }
        return Ok(Base {
            files,
            statics: b.static_facts().iter().map(|f| f.to_string()).collect(),
            benchmark: Some(b),
            folder: None,
        });
    };
    let files = folder.sources().map_err(model_err)?;
    let world = crate::sim::world_from_json(&files.scene)
        .map_err(|e| RecorderError::Model(format!("{}: {e}", folder.path("scene.json"))))?;
    if world.name() != t.scene.name {
        return Err(refused(format!(
            "the demonstration's world `{}` is not the world `{}` of the task folder {}",
            t.scene.name,
            world.name(),
            folder.dir
        )));
    }
    let motions = files.parse_motions().map_err(|e| match e {
        Ok(m) => model_err(m),
        Err(text) => RecorderError::Model(text),
    })?;
    let domain =
        crate::pddl::parse_domain(&files.domain, &files.file("domain.pddl")).map_err(model_err)?;
    if domain.name.text != t.domain {
        return Err(refused(format!(
            "the demonstration's domain `{}` is not the domain `{}` of the task folder {}",
            t.domain, domain.name.text, folder.dir
        )));
    }
    let problem = crate::pddl::parse_problem(&files.problem, &files.file("problem.pddl"), &domain)
        .map_err(model_err)?;
    let scene_predicates = motions.scene_predicates();
    let statics = problem
        .init
        .iter()
        .filter(|a| !scene_predicates.contains(&domain.predicates[a.predicate].name.text))
        .map(|a| domain.atom_text(a, &[]))
        .collect();
    Ok(Base {
        files,
        statics,
        benchmark: None,
        folder: Some(folder.dir.clone()),
    })
}

/// The files of the taught task: the base's domain and motions, a problem with the taught scene's
/// objects, `L_0` (plus static facts) and the goal `G`, the taught scene and the demo itself.
fn sources(
    t: &TaughtDemo,
    demo_json: &str,
    base: &Base,
) -> Result<BenchmarkSources, RecorderError> {
    if t.goal.is_empty() {
        return Err(RecorderError::Input {
            path: "goal".into(),
            message: "empty: a taught task needs at least one goal fact".into(),
        });
    }
    sources_with_goal(t, demo_json, &t.goal, base)
}

/// [`sources`] with another goal (empty: `(and)`, for checking the demo before its goal).
fn sources_with_goal(
    t: &TaughtDemo,
    demo_json: &str,
    goal: &[String],
    base: &Base,
) -> Result<BenchmarkSources, RecorderError> {
    let files = &base.files;
    let domain = crate::pddl::parse_domain(&files.domain, "domain.pddl").map_err(model_err)?;
    let motions = std::sync::Arc::new(files.parse_motions().map_err(|e| match e {
        Ok(m) => model_err(m),
        Err(text) => RecorderError::Model(text),
    })?);
    let world = World::from_snapshot(&t.scene)
        .map_err(|e| RecorderError::Input {
            path: format!("scene.{}", e.path),
            message: e.message,
        })?
        .with_motions(motions);
    let mut objects = String::new();
    for o in SceneGraph::objects(&world) {
        if domain.type_index(&o.ty).is_some() {
            objects.push_str(&format!(" {} - {}", o.name, o.ty));
        }
    }
    let problem = format!(
        "(define (problem taught) (:domain {})\n  (:objects{})\n  (:init {} {})\n  (:goal (and {})))\n",
        domain.name.text,
        objects,
        t.initial_facts.join(" "),
        base.statics.join(" "),
        goal.join(" ")
    );
    let scene = serde_json::to_string(&t.scene).map_err(model_err)?;
    Ok(BenchmarkSources {
        folder: None,
        dir: files.dir.clone(),
        domain: files.domain.clone(),
        problem,
        scene,
        demo: demo_json.to_string(),
        motions: files.motions.clone(),
    })
}

/// The domain model and demonstration trace of a taught task (its `L_0..L_N`).
fn model_and_trace(
    files: &BenchmarkSources,
    actions: &[String],
) -> Result<(DomainModel, World, DemoTrace), RecorderError> {
    let motions = std::sync::Arc::new(files.parse_motions().map_err(|e| match e {
        Ok(m) => RecorderError::Model(m.to_string()),
        Err(text) => RecorderError::Model(text),
    })?);
    let world = World::from_json(&files.scene)
        .map_err(|e| RecorderError::Input {
            path: format!("scene.{}", e.path),
            message: e.message,
        })?
        .with_motions(std::sync::Arc::clone(&motions));
    let model = DomainModel::new(
        &files.domain,
        &files.file("domain.pddl"),
        &files.problem,
        "taught-problem.pddl",
        &motions.scene_predicates(),
    )
    .map_err(|e| RecorderError::Model(e.to_string()))?;
    let objects = SceneGraph::objects(&world);
    let facts = SceneGraph::from_world(&world).to_strings();
    let task = model
        .build(&objects, &facts)
        .map_err(|e| RecorderError::Model(e.to_string()))?;
    let trace = DemoTrace::derive(&task, actions).map_err(|e| RecorderError::Input {
        path: "actions".into(),
        message: e.to_string(),
    })?;
    Ok((model, world, trace))
}

/// Checks a taught `demo.json` completely and lists it: every action applies in turn from the
/// scene's facts (`L_0` must be the scene's facts), and the goal holds in `L_N`. A demo taught in
/// a task folder needs that `folder`; one taught in a benchmark's workcell, none.
pub fn load(
    demo_json: &str,
    folder: Option<&TaskFolder>,
) -> Result<(TaughtDemo, TaughtInfo), RecorderError> {
    Ok(load_on(demo_json, folder)?.0)
}

/// [`load`], and the task's base.
fn load_on(
    demo_json: &str,
    folder: Option<&TaskFolder>,
) -> Result<((TaughtDemo, TaughtInfo), Base), RecorderError> {
    let t = parse(demo_json)?;
    let base = base(&t, folder)?;
    // The actions are checked first (on the task without a goal), then the goal.
    let files = sources_with_goal(&t, demo_json, &[], &base)?;
    let actions: Vec<String> = t.demo.actions.iter().map(|a| a.action.clone()).collect();
    if actions.is_empty() {
        return Err(RecorderError::Input {
            path: "actions".into(),
            message: "empty: nothing was demonstrated".into(),
        });
    }
    let (_, _, trace) = model_and_trace(&files, &actions)?;
    // L_0 lists the scene's fluents: facts of static predicates (the type facts a folder's scene
    // may report) belong to the task, not to the demonstration's states.
    let scene_facts: Vec<String> = trace
        .states
        .first()
        .map(|s| s.iter().cloned().collect())
        .unwrap_or_default();
    let mut l0 = t.initial_facts.clone();
    l0.sort();
    if scene_facts != l0 {
        return Err(RecorderError::Input {
            path: "initial_facts".into(),
            message: format!(
                "not the facts of the scene ({})",
                super::change_text(
                    &l0.iter()
                        .filter(|f| !scene_facts.contains(f))
                        .cloned()
                        .collect::<Vec<_>>(),
                    &scene_facts
                        .iter()
                        .filter(|f| !l0.contains(f))
                        .cloned()
                        .collect::<Vec<_>>()
                )
            ),
        });
    }
    let states: Vec<Vec<String>> = trace
        .states
        .iter()
        .map(|s| s.iter().cloned().collect())
        .collect();
    let last = states.last().cloned().unwrap_or_default();
    for (i, g) in t.goal.iter().enumerate() {
        if !last.contains(g) && !base.statics.contains(g) {
            return Err(RecorderError::Input {
                path: format!("goal[{i}]"),
                message: format!("{g} does not hold at the end of the demonstration"),
            });
        }
    }
    if t.goal.is_empty() {
        return Err(RecorderError::Input {
            path: "goal".into(),
            message: "empty: a taught task needs at least one goal fact".into(),
        });
    }
    let info = TaughtInfo {
        benchmark: base.benchmark,
        folder: base.folder.clone(),
        actions: trace.actions.clone(),
        arms: t.demo.actions.iter().map(|a| a.arm.clone()).collect(),
        states,
        goal: t.goal.clone(),
    };
    Ok(((t, info), base))
}

/// A seeded random initial world for a taught task: the taught scene after an unseen-state
/// change (L3, else L2) and a motion-level spread (L1), each drawn from `seed`. Same seed, same
/// world. `folder` as for [`load`].
pub fn random_scene(
    demo_json: &str,
    seed: u64,
    folder: Option<&TaskFolder>,
) -> Result<String, RecorderError> {
    let ((t, info), base) = load_on(demo_json, folder)?;
    let files = sources(&t, demo_json, &base)?;
    let (_, template, trace) = model_and_trace(&files, &info.actions)?;
    let mut last = String::new();
    for attempt in 0..8u64 {
        let s = mix_seed(seed, attempt);
        let mut w = template.clone();
        let changed = [Level::L3, Level::L2].into_iter().any(|level| {
            match crate::lfd::inject(&mut w, level, &trace, &[], s) {
                Ok(_) => true,
                Err(e) => {
                    last = e;
                    false
                }
            }
        });
        if changed {
            let _ = crate::lfd::inject(&mut w, Level::L1, &trace, &[], mix_seed(s, 1));
            return serde_json::to_string(&w.snapshot())
                .map_err(|e| RecorderError::Model(e.to_string()));
        }
    }
    Err(refused(format!(
        "no random initial world could be drawn from the taught scene: {last}"
    )))
}

/// A closed-loop session running the taught task (see the module docs); `folder` as for [`load`].
pub fn session(
    demo_json: &str,
    options: &TaughtRunOptions,
    folder: Option<&TaskFolder>,
) -> Result<Session, RecorderError> {
    let ((t, _), base) = load_on(demo_json, folder)?;
    let files = sources(&t, demo_json, &base)?;
    let scene = match (&options.scene, options.random) {
        (Some(_), true) => {
            return Err(RecorderError::Input {
                path: "options".into(),
                message: "give either `scene` or `random`, not both".into(),
            })
        }
        (Some(s), false) => Some(s.clone()),
        (None, true) => Some(random_scene(demo_json, options.seed, folder)?),
        (None, false) => None,
    };
    if let Some(s) = &scene {
        let w = crate::sim::world_from_json(s).map_err(|e| RecorderError::Input {
            path: format!("scene.{}", e.path),
            message: e.message,
        })?;
        if w.name() != t.scene.name {
            return Err(RecorderError::Input {
                path: "scene.name".into(),
                message: format!(
                    "the world `{}` is not the taught task's world `{}`",
                    w.name(),
                    t.scene.name
                ),
            });
        }
    }
    let opts = SessionOptions {
        // A folder's task only labels its log with a benchmark, as `Session.fromFolder` does.
        benchmark: base.benchmark.unwrap_or(Benchmark::B1),
        method: options.method,
        mode: options.mode,
        seed: options.seed,
        skill: options.skill,
        blocks: None,
    };
    Session::with_sources(
        opts,
        &files,
        scene.as_deref(),
        Some(demo_json),
        SessionParams::default(),
    )
    .map_err(|e| RecorderError::Model(e.to_string()))
}

/// Re-runs the episode log of a taught session (its `demo_json` is the taught demo) exactly;
/// `folder` as for [`load`].
pub fn replay(episode_json: &str, folder: Option<&TaskFolder>) -> Result<Session, RecorderError> {
    let v: serde_json::Value =
        serde_json::from_str(episode_json).map_err(|e| RecorderError::Input {
            path: format!("line {} column {}", e.line(), e.column()),
            message: e.to_string(),
        })?;
    let demo = v
        .get("demo_json")
        .and_then(|d| d.as_str())
        .ok_or_else(|| RecorderError::Input {
            path: "demo_json".into(),
            message: "missing: not the episode of a taught task".into(),
        })?;
    let ((t, _), base) = load_on(demo, folder)?;
    let files = sources(&t, demo, &base)?;
    Session::replay_with_sources(&files, episode_json)
        .map_err(|e| RecorderError::Model(e.to_string()))
}

/// How well the skills the loop learns from a taught demo reproduce the recorded motions: every
/// action is split at its gripper event into the approach (start → grasp/release) and the retreat
/// (→ end), as [`crate::lfd::SkillLibrary`] does, an LQT-CP skill is learned from each part
/// (object-centric samples) and planned from the part's first sample. One fit per part, named
/// `(action) approach` / `(action) retreat`.
pub fn skill_fits(demo: &Demonstration) -> Result<Vec<SkillFit>, RecorderError> {
    let mut out = vec![];
    for a in &demo.actions {
        let pts: Vec<Point3<f64>> = a
            .samples
            .iter()
            .map(|s| Point3::new(s[0], s[1], s[2]))
            .collect();
        let Some(split) = a
            .gripper
            .iter()
            .find(|g| g.step > 0 && g.step < pts.len())
            .map(|g| g.step)
        else {
            continue;
        };
        for (part, seg) in [("approach", &pts[..=split]), ("retreat", &pts[split..])] {
            if seg.len() < 8 {
                continue;
            }
            let err = |e: crate::lqt::LqtError| {
                refused(format!(
                    "{} {part}: learning its LQT-CP skill failed: {e}",
                    a.action
                ))
            };
            let skill = Skill::learn(seg, demo.dt, SkillParams::default()).map_err(err)?;
            let tr = skill
                .plan(&seg[0], &Isometry3::identity(), &[])
                .map_err(err)?;
            let n = seg.len().min(tr.positions.len());
            let sq: f64 = (0..n)
                .map(|k| (tr.positions[k] - seg[k]).norm_squared())
                .sum();
            let goal_error = match (tr.positions.last(), seg.last()) {
                (Some(p), Some(q)) => (p - q).norm(),
                _ => 0.0,
            };
            out.push(SkillFit {
                action: format!("{} {part}", a.action),
                steps: seg.len(),
                rms_error: (sq / n.max(1) as f64).sqrt(),
                goal_error,
            });
        }
    }
    Ok(out)
}
