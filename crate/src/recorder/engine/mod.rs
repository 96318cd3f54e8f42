//! The incremental recorder: replay edits in the simulator, explain every fact change by one
//! operator of the grounded task, segment the motion (see the module docs of [`super`]).
//!
//! This file holds the [`Recorder`], its construction, its atomic edits (checkpoint and
//! rollback) and the queries of the page; `replay.rs` steps the simulator and explains each fact
//! change, `segment.rs` cuts the motion into the demonstration's actions.

mod replay;
mod segment;

use super::recording::{ArmRef, GripperPose, GripperState, RawSample};
use super::{RecorderError, RecorderEvent, RecorderParams, Segment};
use crate::pddl;
use crate::pddl::Source;
use crate::plan::{self, State, Task};
pub(crate) use crate::sim::geometry::gripper_yaw;
use crate::sim::Benchmark;
use crate::sim::Motions;
use crate::sim::TaskFolder;
use crate::sim::{BodyKind, WorldSnapshot};
use crate::sim::{GripperCommand, SceneGraph, World, WorldEvent};
use nalgebra::Isometry3;
use std::sync::Arc;

/// How a [`Recorder`] is set up.
#[derive(Clone, Debug, PartialEq)]
pub struct RecorderOptions {
    /// Name of the domain file, for error messages.
    pub domain_file: String,
    /// A PDDL problem whose `:init` supplies static facts the scene graph does not report (B3's
    /// `reaches`). Without it they come from the benchmark whose name the scene carries, if any.
    pub problem_pddl: Option<Source>,
    /// The domain's `motions.json`. Without it, the motions of the benchmark whose name the scene
    /// carries.
    pub motions_json: Option<Source>,
    /// Tunables.
    pub params: RecorderParams,
}

impl Default for RecorderOptions {
    fn default() -> Self {
        RecorderOptions {
            domain_file: "domain.pddl".into(),
            problem_pddl: None,
            motions_json: None,
            params: RecorderParams::default(),
        }
    }
}

/// One arm's gripper as the page's handle shows it.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct GripperHandle {
    /// Arm name.
    pub arm: String,
    /// TCP position, world frame (m).
    pub position: [f64; 3],
    /// Gripper yaw about world `z` (rad).
    pub yaw: f64,
    /// Commanded gripper state.
    pub gripper: GripperState,
    /// The body held, if any.
    pub holding: Option<String>,
}

/// What kind of gripper event caused an action.
#[derive(Clone, Debug, PartialEq)]
enum Cause {
    Grasp(String),
    Release(String),
    Other,
}

/// One recognised action.
#[derive(Clone, Debug)]
struct ActionRec {
    op: usize,
    arm: usize,
    /// Log index of the step whose fact change it is.
    step: usize,
    cause: Cause,
    added: Vec<String>,
    removed: Vec<String>,
}

/// Lengths to roll back to when an edit fails.
pub(super) struct Checkpoint {
    world: World,
    log_len: usize,
    pub(super) edits_len: usize,
    events_len: usize,
    actions_len: usize,
    state: State,
    facts: Vec<String>,
    cur_t: Option<f64>,
}

/// A demonstration being recorded (see the module docs of [`crate::recorder`]).
///
/// ```
/// use logic_lfd::recorder::{Recorder, RecorderOptions};
/// use logic_lfd::recorder::Edit;
/// use logic_lfd::sim::Benchmark;
/// let b = Benchmark::B1;
/// let mut rec = Recorder::new(&b.scene_snapshot(), b.domain_pddl(), RecorderOptions::default()).unwrap();
/// // Quick mode: drag block c onto block d; the arm motion is synthesised and segmented.
/// let ev = rec.push(&Edit::Drag { body: "c".into(), onto: Some("d".into()), position: None, yaw: None, arm: None }).unwrap();
/// assert_eq!(ev.new_segments.len(), 2);
/// assert_eq!(rec.segments()[1].action, "(stack panda c d)");
/// assert!(rec.demo_states()[2].contains(&"(on c d)".to_string()));
/// ```
pub struct Recorder {
    params: RecorderParams,
    initial: WorldSnapshot,
    world: World,
    domain_name: String,
    task: Task,
    init_state: State,
    state: State,
    facts: Vec<String>,
    /// Time label of the next step (s); `None` before the first sample.
    cur_t: Option<f64>,
    body_names: Vec<String>,
    // Logs, one entry per simulator step.
    log_t: Vec<f64>,
    log_tcp: Vec<Vec<Isometry3<f64>>>,
    log_grip: Vec<Vec<GripperCommand>>,
    log_bodies: Vec<Vec<Isometry3<f64>>>,
    log_events: Vec<(usize, WorldEvent)>,
    actions: Vec<ActionRec>,
    /// Accepted samples with the log length after each.
    edits: Vec<(RawSample, usize)>,
    goal: Option<Vec<String>>,
    seed: u64,
}

/// A model error carrying `e`'s message.
fn model_err(e: impl std::fmt::Display) -> RecorderError {
    RecorderError::Model(e.to_string())
}

/// The world's facts (fluents), sorted.
fn sorted_facts(world: &World) -> Vec<String> {
    let mut f = SceneGraph::from_world(world).to_strings();
    f.sort();
    f
}

/// The static facts of the task: from the problem's init (predicates the scene graph does not
/// report), or from the benchmark the scene is.
fn static_facts(
    scene: &WorldSnapshot,
    world: &World,
    domain: &pddl::Domain,
    problem_pddl: &Option<Source>,
) -> Result<Vec<String>, RecorderError> {
    let preds: Vec<String> = world.motions().scene_predicates();
    Ok(match problem_pddl {
        Some(src) => {
            let p = pddl::parse_problem(&src.text, &src.file, domain).map_err(model_err)?;
            p.init
                .iter()
                .filter(|a| !preds.contains(&domain.predicates[a.predicate].name.text))
                .map(|a| domain.atom_text(a, &[]))
                .collect()
        }
        None => Benchmark::parse(&scene.name)
            .map(|b| b.static_facts().iter().map(|f| f.to_string()).collect())
            .unwrap_or_default(),
    })
}

/// What the domain's actions and predicates mean: the given `motions.json`, or the benchmark's
/// the scene is.
fn scene_motions(
    scene: &WorldSnapshot,
    domain: &pddl::Domain,
    motions_json: &Option<Source>,
) -> Result<Arc<Motions>, RecorderError> {
    match motions_json {
        Some(src) => Motions::parse(&src.text, &src.file, domain)
            .map(Arc::new)
            .map_err(|e| RecorderError::Model(e.to_string())),
        None => Benchmark::parse(&scene.name)
            .map(Benchmark::motions)
            .ok_or_else(|| {
                RecorderError::Model(format!(
                    "the scene `{}` is no benchmark's: give the domain's motions.json",
                    scene.name
                ))
            }),
    }
}

/// The PDDL problem of the scene: its objects the domain has a type for, its facts and the
/// static facts as `:init`, an empty goal.
fn scene_problem(
    domain: &pddl::Domain,
    world: &World,
    facts: &[String],
    statics: &[String],
) -> Result<pddl::Problem, pddl::PddlError> {
    let objects = SceneGraph::objects(world)
        .into_iter()
        .filter(|o| domain.type_index(&o.ty).is_some());
    pddl::ProblemBuilder::new(domain, "taught")
        .objects(objects)
        .init(facts.iter().chain(statics).cloned())
        .build()
}

impl Recorder {
    /// A recorder on the world `scene` for the PDDL domain `domain_pddl`. The task is grounded
    /// from the scene's objects and facts (plus static facts, see [`RecorderOptions`]).
    pub fn new(
        scene: &WorldSnapshot,
        domain_pddl: &str,
        options: RecorderOptions,
    ) -> Result<Recorder, RecorderError> {
        let domain = pddl::parse_domain(domain_pddl, &options.domain_file).map_err(model_err)?;
        let motions = scene_motions(scene, &domain, &options.motions_json)?;
        let world = World::from_snapshot(scene)
            .map_err(|e| RecorderError::Input {
                path: format!("scene.{}", e.path),
                message: e.message,
            })?
            .with_motions(motions);
        let statics = static_facts(scene, &world, &domain, &options.problem_pddl)?;
        let facts = sorted_facts(&world);
        let problem = scene_problem(&domain, &world, &facts, &statics).map_err(|e| {
            RecorderError::Model(format!(
                "the scene does not fit the domain {}: {e}",
                domain.name.text
            ))
        })?;
        let task = plan::ground(&domain, &problem).map_err(model_err)?;
        let state = task.state_from_names(&facts).map_err(model_err)?;
        let body_names: Vec<String> = scene
            .bodies
            .iter()
            .filter(|b| matches!(b.kind, BodyKind::Block | BodyKind::Hook))
            .map(|b| b.name.clone())
            .collect();
        Ok(Recorder {
            params: options.params,
            initial: scene.clone(),
            world,
            domain_name: domain.name.text.clone(),
            init_state: state.clone(),
            state,
            task,
            facts,
            cur_t: None,
            body_names,
            log_t: vec![],
            log_tcp: vec![],
            log_grip: vec![],
            log_bodies: vec![],
            log_events: vec![],
            actions: vec![],
            edits: vec![],
            goal: None,
            seed: 0,
        })
    }

    /// A recorder on a benchmark's template scene and domain.
    pub fn for_benchmark(b: Benchmark) -> Result<Recorder, RecorderError> {
        Recorder::new(
            &b.scene_snapshot(),
            b.domain_pddl(),
            RecorderOptions {
                domain_file: format!("domains/{}/domain.pddl", b.dir_name()),
                ..RecorderOptions::default()
            },
        )
    }

    /// A recorder on a task folder's scene (or `scene`, another world of the same task), domain,
    /// `motions.json` and the static facts of its `problem.pddl`; errors name the folder's file.
    pub fn for_folder(
        folder: &TaskFolder,
        scene: Option<&WorldSnapshot>,
    ) -> Result<Recorder, RecorderError> {
        let files = folder
            .sources()
            .map_err(|e| RecorderError::Model(e.to_string()))?;
        let own;
        let scene = match scene {
            Some(s) => s,
            None => {
                own = crate::sim::world_from_json(&files.scene)
                    .map_err(|e| {
                        RecorderError::Model(format!("{}: {e}", folder.path("scene.json")))
                    })?
                    .snapshot();
                &own
            }
        };
        let source = |name: &str, text: &str| Source::new(folder.path(name), text);
        Recorder::new(
            scene,
            &files.domain,
            RecorderOptions {
                domain_file: folder.path("domain.pddl"),
                problem_pddl: Some(source("problem.pddl", &files.problem)),
                motions_json: Some(source("motions.json", &files.motions)),
                ..RecorderOptions::default()
            },
        )
    }

    /// Sets the seed written into the demonstration.
    pub fn set_seed(&mut self, seed: u64) {
        self.seed = seed;
    }

    /// The world as it is now.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The grounded task the recording is checked against.
    pub fn task(&self) -> &Task {
        &self.task
    }

    /// The tunables.
    pub fn params(&self) -> &RecorderParams {
        &self.params
    }

    /// Recording time of the next step (s).
    pub fn time(&self) -> f64 {
        self.cur_t.unwrap_or(0.0)
    }

    /// The current facts (fluents, sorted).
    pub fn facts(&self) -> &[String] {
        &self.facts
    }

    pub(super) fn checkpoint(&self) -> Checkpoint {
        Checkpoint {
            world: self.world.clone(),
            log_len: self.log_t.len(),
            edits_len: self.edits.len(),
            events_len: self.log_events.len(),
            actions_len: self.actions.len(),
            state: self.state.clone(),
            facts: self.facts.clone(),
            cur_t: self.cur_t,
        }
    }

    pub(super) fn rollback(&mut self, c: Checkpoint, edits_len: usize) {
        self.edits.truncate(edits_len);
        self.world = c.world;
        self.log_t.truncate(c.log_len);
        self.log_tcp.truncate(c.log_len);
        self.log_grip.truncate(c.log_len);
        self.log_bodies.truncate(c.log_len);
        self.log_events.truncate(c.events_len);
        self.actions.truncate(c.actions_len);
        self.state = c.state;
        self.facts = c.facts;
        self.cur_t = c.cur_t;
    }

    pub(super) fn event_since(&self, c: &Checkpoint) -> RecorderEvent {
        RecorderEvent {
            t: self.time(),
            new_segments: (c.actions_len..self.actions.len())
                .map(|i| self.segment(i))
                .collect(),
            world_events: self.log_events[c.events_len..]
                .iter()
                .map(|(_, e)| e.clone())
                .collect(),
            facts: self.facts.clone(),
        }
    }

    /// Applies one raw sample (atomically: on error the recorder is unchanged).
    pub fn push_sample(&mut self, sample: &RawSample) -> Result<RecorderEvent, RecorderError> {
        let c = self.checkpoint();
        let edits_len = self.edits.len();
        match self.apply_sample(sample) {
            Ok(()) => {
                let ev = self.event_since(&c);
                self.edits.push((sample.clone(), self.log_t.len()));
                Ok(ev)
            }
            Err(e) => {
                self.rollback(c, edits_len);
                Err(e)
            }
        }
    }

    /// Applies several samples as one edit (all or nothing).
    pub(crate) fn push_samples(
        &mut self,
        samples: &[RawSample],
    ) -> Result<RecorderEvent, RecorderError> {
        let c = self.checkpoint();
        let edits_len = self.edits.len();
        for s in samples {
            if let Err(e) = self.apply_sample(s) {
                self.rollback(c, edits_len);
                return Err(e);
            }
            self.edits.push((s.clone(), self.log_t.len()));
        }
        Ok(self.event_since(&c))
    }

    // ------------------------------------------------------------------ queries for the page

    /// The taught goal, if one was set ([`Recorder::set_goal`]).
    pub fn goal(&self) -> Option<&[String]> {
        self.goal.as_deref()
    }

    /// Number of accepted samples.
    pub fn sample_count(&self) -> usize {
        self.edits.len()
    }

    /// Where every arm's gripper is now (what the page's gripper handles show), in arm order.
    pub fn handles(&self) -> Vec<GripperHandle> {
        let names = self.world.arm_names();
        (0..names.len())
            .map(|a| {
                let tcp = self.world.tcp_pose(a).unwrap_or_else(Isometry3::identity);
                let p = tcp.translation.vector;
                GripperHandle {
                    arm: names[a].to_string(),
                    position: [p.x, p.y, p.z],
                    yaw: gripper_yaw(&tcp.rotation),
                    gripper: GripperState::from_command(
                        self.world
                            .arm_command(a)
                            .map(|c| c.1)
                            .unwrap_or(GripperCommand::Open),
                    ),
                    holding: self.world.held_by(a).map(str::to_string),
                }
            })
            .collect()
    }

    /// The accepted samples as a raw recording (what `logic-lfd demo segment` reads); segmenting
    /// it gives the same actions as this recorder.
    pub fn recording(&self) -> super::RawRecording {
        let scene = match Benchmark::parse(&self.initial.name) {
            Some(b) if b.scene_snapshot() == self.initial => super::RecordingScene::Benchmark(b),
            _ => super::RecordingScene::Scene(Box::new(self.initial.clone())),
        };
        super::RawRecording {
            scene,
            dt: self.world.dt(),
            samples: self.edits.iter().map(|(s, _)| s.clone()).collect(),
            goal: self.goal.clone(),
            seed: self.seed,
        }
    }

    /// Sets the taught goal G: facts that must hold in L_N (any spelling of `(p a b)`).
    pub fn set_goal(&mut self, goal: Vec<String>) -> Result<(), RecorderError> {
        let mut norm = Vec::with_capacity(goal.len());
        for (i, g) in goal.iter().enumerate() {
            let n = crate::sim::normalise(g);
            if self.task.fact_id(&n).is_none() && !self.task.static_facts.contains(&n) {
                return Err(RecorderError::Input {
                    path: format!("[{i}]"),
                    message: format!("{g} is not a fact of the domain's task"),
                });
            }
            norm.push(n);
        }
        self.goal = Some(norm);
        Ok(())
    }

    /// Removes the last recognised action and everything recorded after the end of the one before
    /// it (the world goes back to that moment). Returns the removed segment, if any.
    pub fn undo_last_segment(&mut self) -> Result<Option<Segment>, RecorderError> {
        let Some(last) = self.actions.len().checked_sub(1) else {
            return Ok(None);
        };
        let removed = self.segment(last);
        let keep_steps = if last == 0 {
            0
        } else {
            self.boundary(last - 1) + 1
        };
        let keep: Vec<RawSample> = self
            .edits
            .iter()
            .take_while(|(_, n)| *n <= keep_steps)
            .map(|(s, _)| s.clone())
            .collect();
        let mut fresh = Recorder {
            params: self.params.clone(),
            initial: self.initial.clone(),
            world: World::from_snapshot(&self.initial)
                .map_err(model_err)?
                .with_motions(self.world.motions_arc()),
            domain_name: self.domain_name.clone(),
            task: self.task.clone(),
            init_state: self.init_state.clone(),
            state: self.init_state.clone(),
            facts: vec![],
            cur_t: None,
            body_names: self.body_names.clone(),
            log_t: vec![],
            log_tcp: vec![],
            log_grip: vec![],
            log_bodies: vec![],
            log_events: vec![],
            actions: vec![],
            edits: vec![],
            goal: self.goal.clone(),
            seed: self.seed,
        };
        fresh.facts = sorted_facts(&fresh.world);
        for s in &keep {
            fresh.push_sample(s)?;
        }
        *self = fresh;
        Ok(Some(removed))
    }
}

/// A gripper sample at time `t` (used by the synthesiser and the tests).
pub(crate) fn gripper_sample(
    t: f64,
    arm: usize,
    pose: &Isometry3<f64>,
    grip: GripperCommand,
) -> RawSample {
    let p = pose.translation.vector;
    RawSample::Gripper {
        t,
        arm: ArmRef::Index(arm),
        pose: GripperPose {
            position: [p.x, p.y, p.z],
            yaw: gripper_yaw(&pose.rotation),
        },
        gripper: GripperState::from_command(grip),
    }
}
