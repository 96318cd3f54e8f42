//! One closed-loop episode stepped by the caller: the same loop as `logic-lfd run`, shaped for the
//! browser (see `briefs/frame-contract.md`): [`Session::step`] advances whole 10 ms simulation
//! ticks and replans inside; [`Session::frame`] is what the page draws.
//!
//! Per tick (paper Algorithm 1, with the executor of [`super::exec`]):
//!
//! ```text
//!   no action running → S_C ← SceneGraph(world); decision ← Controller(S_C)   (may replan)
//!   action running    → one skill tick; every tick S_C is compared with what the action
//!                       leaves untouched — a task-level change interrupts it (not for linear)
//!   action finished   → if S_C is the predicted state, advance the plan; else the next
//!                       decision replans
//! ```
//!
//! Replay identity: the episode JSON records the options, the initial scene and every external
//! event (user drag, injected disturbance, cancel) with its tick; [`Session::replay`] re-runs the
//! loop tick by tick and reproduces the episode exactly. Planning times (`time_ms`) are wall-clock
//! measurements of the caller's clock and are excluded from the identity ([`EpisodeLog::canonical`]
//! zeroes them).

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::plan::{Clock, NoClock};
use crate::sim::snapshot::WorldSnapshot;
use crate::sim::{MoveOutcome, Refused, SceneGraph, World};
use crate::tamp::streams::{StreamBinder, StreamParams};
use crate::tamp::{classify, ActionKind, Binder, Binding, Placement, PlanarPose};

use super::control::{ControlParams, Controller, Decision, FailReason, Replan};
use super::demo::DemoTrace;
use super::exec::{ActionExec, ExecParams, ExecStatus};
use super::logic::Mode;
use super::model::DomainModel;
use super::skill::SkillLibrary;
use super::{LfdError, Method};

/// The three benchmarks of the paper.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BenchmarkId {
    /// Tower of four blocks.
    #[default]
    B1,
    /// Workspace reach with a hook and a shelf.
    B2,
    /// Dual-arm transportation.
    B3,
}

impl BenchmarkId {
    /// All benchmarks.
    pub const ALL: [BenchmarkId; 3] = [BenchmarkId::B1, BenchmarkId::B2, BenchmarkId::B3];

    /// `b1`, `b2`, `b3`.
    pub fn as_str(self) -> &'static str {
        match self {
            BenchmarkId::B1 => "b1",
            BenchmarkId::B2 => "b2",
            BenchmarkId::B3 => "b3",
        }
    }

    /// Parses `b1`..`b3` (or the directory names).
    pub fn parse(s: &str) -> Option<Self> {
        crate::sim::benchmark::Benchmark::parse(s).map(|b| match b {
            crate::sim::benchmark::Benchmark::B1 => BenchmarkId::B1,
            crate::sim::benchmark::Benchmark::B2 => BenchmarkId::B2,
            crate::sim::benchmark::Benchmark::B3 => BenchmarkId::B3,
        })
    }

    /// The simulator's benchmark.
    pub fn sim(self) -> crate::sim::benchmark::Benchmark {
        match self {
            BenchmarkId::B1 => crate::sim::benchmark::Benchmark::B1,
            BenchmarkId::B2 => crate::sim::benchmark::Benchmark::B2,
            BenchmarkId::B3 => crate::sim::benchmark::Benchmark::B3,
        }
    }

    /// The benchmark's files (embedded in the library).
    pub fn sources(self) -> Result<BenchmarkSources, SessionError> {
        let b = self.sim();
        let demo = match self {
            BenchmarkId::B1 => include_str!("../../../domains/b1-tower/demo.json"),
            BenchmarkId::B2 => include_str!("../../../domains/b2-workspace-reach/demo.json"),
            BenchmarkId::B3 => include_str!("../../../domains/b3-dual-arm/demo.json"),
        };
        let scene = serde_json::to_string(&b.scene_snapshot())
            .map_err(|e| SessionError::Json(format!("scene: {e}")))?;
        Ok(BenchmarkSources {
            dir: b.dir_name().to_string(),
            domain: b.domain_pddl().to_string(),
            problem: b.problem_pddl().to_string(),
            scene,
            demo: demo.to_string(),
        })
    }
}

/// The text of a benchmark's files.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BenchmarkSources {
    /// Directory name under `domains/` (for error messages).
    pub dir: String,
    /// `domain.pddl`.
    pub domain: String,
    /// `problem.pddl` (the template task).
    pub problem: String,
    /// `scene.json` (the template task's initial world).
    pub scene: String,
    /// `demo.json` (the demonstration).
    pub demo: String,
}

/// Which motion skill family executes the actions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SkillKind {
    /// LQT-CP (the paper's).
    #[default]
    Lqt,
    /// Classic DMP (the comparison).
    Dmp,
}

/// How a session is set up (JSON: snake_case keys, defaults for all but `benchmark`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SessionOptions {
    /// `b1`, `b2` or `b3`.
    pub benchmark: BenchmarkId,
    /// `logic-lfd`, `linear`, `rlds` or `tamp`.
    #[serde(default)]
    pub method: Method,
    /// `paper` or `prioritised`.
    #[serde(default)]
    pub mode: Mode,
    /// Seed of every random choice of the episode.
    #[serde(default)]
    pub seed: u64,
    /// `lqt` or `dmp`.
    #[serde(default)]
    pub skill: SkillKind,
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
    /// A JSON document (demo, episode) is malformed.
    #[error("{0}")]
    Json(String),
}

/// The status line of the page.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Status {
    /// `idle`, `planning`, `executing`, `replanning`, `done` or `failed`.
    pub kind: String,
    /// In words: "executing step 3 of 7: (stack c d)", "replanning because …", "failed because …".
    pub message: String,
    /// The step being executed (1-based), if any.
    pub step: Option<usize>,
    /// Number of steps in the plan, if any.
    pub of: Option<usize>,
}

/// End effector position and its commanded target (for the trajectory chart).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EePoint {
    /// Arm index.
    pub arm: usize,
    /// TCP position (m).
    pub pos: [f64; 3],
    /// Commanded position (m); the TCP position when idle.
    pub target: [f64; 3],
}

/// Everything the page draws after a step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Frame {
    /// Simulated seconds.
    pub t: f64,
    /// 10 ms steps so far.
    pub tick: u64,
    /// Every body pose, arm joints and link capsules, grippers.
    pub world: WorldSnapshot,
    /// The status line.
    pub status: Status,
    /// The current plan, actions as `(stack a b)`.
    pub plan: Vec<String>,
    /// Index into `plan` of the action being executed.
    pub executing: Option<usize>,
    /// The demonstration's actions a_1..a_N.
    pub demo: Vec<String>,
    /// L_0..L_N (fluents).
    pub demo_states: Vec<Vec<String>>,
    /// Demonstration state index the current plan joins.
    pub matched_k: Option<usize>,
    /// S_C, sorted.
    pub facts: Vec<String>,
    /// Facts that appeared since the previous frame.
    pub facts_added: Vec<String>,
    /// Facts that disappeared since the previous frame.
    pub facts_removed: Vec<String>,
    /// The last replan.
    pub last_replan: Option<Replan>,
    /// Number of replans so far.
    pub replans: usize,
    /// End effector positions and targets.
    pub ee: Vec<EePoint>,
}

/// The outcome of an accepted drag.
pub type PerturbOutcome = MoveOutcome;

/// What an injected disturbance did.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Injection {
    /// `l1`..`l4`.
    pub level: String,
    /// What it did, in words.
    pub description: String,
    /// Bodies moved or added: (name, new centre).
    pub moved: Vec<(String, [f64; 3])>,
}

/// An external event of the episode, with the tick before which it happened.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum EpisodeEvent {
    /// A user drag.
    Perturb {
        /// Tick.
        tick: u64,
        /// Body.
        body: String,
        /// Requested centre (m).
        position: [f64; 3],
    },
    /// An injected disturbance.
    Inject {
        /// Tick.
        tick: u64,
        /// `l1`..`l4`.
        level: String,
        /// What it did.
        description: String,
    },
    /// The plan was dropped.
    Cancel {
        /// Tick.
        tick: u64,
    },
}

/// One executed (or interrupted) action.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ActionRecord {
    /// The action.
    pub action: String,
    /// Tick it started.
    pub start_tick: u64,
    /// Tick it ended.
    pub end_tick: Option<u64>,
    /// `done`, `interrupted: …`, `failed: …`, `no effect`.
    pub outcome: String,
}

/// The end of an episode.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeResult {
    /// The goal holds.
    pub success: bool,
    /// Why it failed.
    pub reason: Option<FailReason>,
    /// Simulated execution time (s).
    pub time_s: f64,
    /// Ticks.
    pub ticks: u64,
    /// Actions completed.
    pub actions_executed: usize,
    /// Replans (including the initial plan).
    pub replans: usize,
}

/// The full log of an episode; replays exactly.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeLog {
    /// Format version (1).
    pub version: u32,
    /// The session options (benchmark, method, mode, seed, skill).
    pub options: SessionOptions,
    /// The initial world.
    pub scene: WorldSnapshot,
    /// The demonstration JSON if not the benchmark's own.
    pub demo_json: Option<String>,
    /// External events.
    pub events: Vec<EpisodeEvent>,
    /// Every replan.
    pub replans: Vec<Replan>,
    /// Every action started.
    pub actions: Vec<ActionRecord>,
    /// Ticks simulated so far.
    pub ticks: u64,
    /// The result, when the episode ended.
    pub result: Option<EpisodeResult>,
    /// The final facts.
    pub final_facts: Vec<String>,
    /// The final world.
    pub final_world: WorldSnapshot,
}

impl EpisodeLog {
    /// The log with wall-clock planning times zeroed: equal for two runs of the same episode.
    pub fn canonical(&self) -> EpisodeLog {
        let mut c = self.clone();
        for r in &mut c.replans {
            r.time_ms = 0.0;
        }
        c
    }
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
/// `action` / `name` field).
pub fn demo_actions(demo_json: &str) -> Result<Vec<String>, SessionError> {
    let v: serde_json::Value =
        serde_json::from_str(demo_json).map_err(|e| SessionError::Json(format!("demo: {e}")))?;
    let arr = v
        .get("actions")
        .and_then(|a| a.as_array())
        .ok_or_else(|| SessionError::Json("demo: actions: missing array".into()))?;
    arr.iter()
        .enumerate()
        .map(|(i, a)| {
            let s = a
                .as_str()
                .or_else(|| a.get("action").and_then(|x| x.as_str()))
                .or_else(|| a.get("name").and_then(|x| x.as_str()));
            s.map(super::demo::normalize_action).ok_or_else(|| {
                SessionError::Json(format!("demo: actions[{i}]: expected an action string"))
            })
        })
        .collect()
}

/// The placements the demonstration used for its surface releases (`place`,
/// `place-on-shelf`): action → the resting pose (`sim::demo` anchor poses).
fn demo_hints(demo_json: &str) -> std::collections::BTreeMap<String, PlanarPose> {
    let mut out = std::collections::BTreeMap::new();
    if let Ok(d) = crate::sim::demo::from_json(demo_json) {
        for a in d.actions {
            if a.name.starts_with("place") {
                let p = a.anchor_pose.position;
                out.entry(a.action.clone()).or_insert(PlanarPose {
                    x: p[0],
                    y: p[1],
                    yaw: a.anchor_pose.yaw,
                });
            }
        }
    }
    out
}

/// A closed-loop episode stepped by the caller.
pub struct Session {
    options: SessionOptions,
    sources: BenchmarkSources,
    params: SessionParams,
    model: DomainModel,
    trace: DemoTrace,
    skills: SkillLibrary,
    hints: std::collections::BTreeMap<String, PlanarPose>,
    initial: WorldSnapshot,
    demo_json: Option<String>,
    world: World,
    controller: Controller,
    exec: Option<ActionExec>,
    bindings: Vec<Binding>,
    tick: u64,
    carry: f64,
    outcome: Option<Result<(), FailReason>>,
    prev_facts: Vec<String>,
    frame_added: Vec<String>,
    frame_removed: Vec<String>,
    events: Vec<EpisodeEvent>,
    actions: Vec<ActionRecord>,
    failures_in_a_row: usize,
    injections: u64,
    actions_done: usize,
}

fn facts_of(world: &World) -> Vec<String> {
    let mut f = SceneGraph::from_world(world).to_strings();
    f.sort();
    f
}

fn objects_of(world: &World) -> Vec<(String, String)> {
    SceneGraph::objects(world)
        .into_iter()
        .map(|o| (o.name, o.kind))
        .collect()
}

/// A seed for the `n`-th random draw of an episode (SplitMix64 of `seed ⊕ n·φ`).
pub fn mix(seed: u64, n: u64) -> u64 {
    let mut z = seed ^ n.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Session {
    /// A session on the benchmark's template scene and demonstration.
    pub fn new(options: SessionOptions) -> Result<Session, SessionError> {
        let files = options.benchmark.sources()?;
        Session::with_sources(options, &files, None, None, SessionParams::default())
    }

    /// A session on a given scene (a world snapshot JSON) and optionally another demonstration
    /// (a `demo.json`: `actions` as strings or objects with an `action` field).
    pub fn from_scene(
        options: SessionOptions,
        scene_json: &str,
        demo_json: Option<&str>,
    ) -> Result<Session, SessionError> {
        let files = options.benchmark.sources()?;
        Session::with_sources(
            options,
            &files,
            Some(scene_json),
            demo_json,
            SessionParams::default(),
        )
    }

    /// Re-runs a logged episode tick by tick (see [`Session::replay_with_sources`]).
    pub fn replay(episode_json: &str) -> Result<Session, SessionError> {
        let log: EpisodeLog = serde_json::from_str(episode_json)
            .map_err(|e| SessionError::Json(format!("episode: {e}")))?;
        let files = log.options.benchmark.sources()?;
        Session::replay_with_sources(&files, episode_json)
    }

    /// A session on `files` (the benchmark), starting from `scene_json` (the template scene if
    /// `None`) with the demonstration `demo_json` (the benchmark's if `None`).
    pub fn with_sources(
        options: SessionOptions,
        files: &BenchmarkSources,
        scene_json: Option<&str>,
        demo_json: Option<&str>,
        params: SessionParams,
    ) -> Result<Session, SessionError> {
        // Through the snapshot once, so the logged initial scene reloads to this very world.
        let world = World::from_json(scene_json.unwrap_or(&files.scene))?;
        let world = World::from_snapshot(&world.snapshot())?;
        let template = World::from_json(&files.scene)?;
        let predicates = template.snapshot().predicates;
        let model = DomainModel::new(
            &files.domain,
            &format!("domains/{}/domain.pddl", files.dir),
            &files.problem,
            &format!("domains/{}/problem.pddl", files.dir),
            &predicates,
        )?;
        // The demonstration is derived on the template task (its initial state is the template
        // scene's facts).
        let template_task = {
            use super::control::TaskBuilder;
            model.build(&objects_of(&template), &facts_of(&template))?
        };
        let actions = demo_actions(demo_json.unwrap_or(&files.demo))?;
        let trace = DemoTrace::derive(&template_task, &actions)?;
        let objects = objects_of(&world);
        let task = {
            use super::control::TaskBuilder;
            model.build(&objects, &facts_of(&world))?
        };
        let controller = Controller::new(
            options.method,
            options.mode,
            params.control,
            trace.clone(),
            task,
            objects,
        );
        let prev_facts = facts_of(&world);
        let hooks: Vec<String> = world
            .snapshot()
            .bodies
            .iter()
            .filter(|b| b.kind == crate::sim::snapshot::BodyKind::Hook)
            .map(|b| b.name.clone())
            .collect();
        let skills = SkillLibrary::learn(demo_json.unwrap_or(&files.demo), options.skill, &hooks);
        let hints = demo_hints(demo_json.unwrap_or(&files.demo));
        Ok(Session {
            sources: files.clone(),
            initial: world.snapshot(),
            demo_json: demo_json.map(str::to_string),
            options,
            params,
            model,
            trace,
            skills,
            hints,
            world,
            controller,
            exec: None,
            bindings: vec![],
            tick: 0,
            carry: 0.0,
            outcome: None,
            prev_facts,
            frame_added: vec![],
            frame_removed: vec![],
            events: vec![],
            actions: vec![],
            failures_in_a_row: 0,
            injections: 0,
            actions_done: 0,
        })
    }

    /// The options.
    pub fn options(&self) -> &SessionOptions {
        &self.options
    }

    /// The world.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Mutable access to the world (disturbance injectors).
    pub fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    /// Ticks simulated.
    pub fn tick(&self) -> u64 {
        self.tick
    }

    /// Actions completed with their effect.
    pub fn actions_done(&self) -> usize {
        self.actions_done
    }

    /// Whether an action is being executed.
    pub fn is_executing(&self) -> bool {
        self.exec.is_some()
    }

    /// The episode's outcome, once it ended.
    pub fn outcome(&self) -> Option<&Result<(), FailReason>> {
        self.outcome.as_ref()
    }

    /// The benchmark's PDDL model.
    pub fn model(&self) -> &DomainModel {
        &self.model
    }

    /// The controller (plan, replans, task).
    pub fn controller(&self) -> &Controller {
        &self.controller
    }

    /// Advances whole 10 ms ticks covering `dt_secs` (fractions carry over); replans inside.
    pub fn step(&mut self, dt_secs: f64, clock: &dyn Clock) -> Frame {
        let dt = self.world.dt();
        let want = self.carry + dt_secs.max(0.0);
        let n = (want / dt + 1e-9).floor() as u64;
        self.carry = want - n as f64 * dt;
        for _ in 0..n {
            if self.outcome.is_some() {
                break;
            }
            self.tick_once(clock);
        }
        let facts = facts_of(&self.world);
        self.frame_added = facts
            .iter()
            .filter(|f| !self.prev_facts.contains(f))
            .cloned()
            .collect();
        self.frame_removed = self
            .prev_facts
            .iter()
            .filter(|f| !facts.contains(f))
            .cloned()
            .collect();
        self.prev_facts = facts;
        self.frame()
    }

    /// Runs until the episode ends or `max_ticks` more ticks have passed.
    pub fn run_to_end(&mut self, max_ticks: u64, clock: &dyn Clock) {
        for _ in 0..max_ticks {
            if self.outcome.is_some() {
                break;
            }
            self.tick_once(clock);
        }
    }

    /// One 10 ms tick of the loop.
    pub fn tick_once(&mut self, clock: &dyn Clock) {
        if self.outcome.is_some() {
            return;
        }
        if self.world.time() > self.params.max_time {
            self.outcome = Some(Err(FailReason::Budget {
                what: "simulated time".into(),
            }));
            return;
        }
        if self.exec.is_none() && !self.start_next_action(clock) {
            return;
        }
        let Some(exec) = self.exec.as_mut() else {
            return;
        };
        let status = exec.tick(&mut self.world, &self.skills, &self.params.exec);
        self.tick += 1;
        let linear = self.options.method == Method::Linear;
        match status {
            ExecStatus::Running => {
                if !linear {
                    let facts = facts_of(&self.world);
                    if !self.controller.consistent_during_action(&facts) {
                        self.end_action("interrupted: the scene changed".into());
                    }
                }
            }
            ExecStatus::Done => {
                let facts = facts_of(&self.world);
                if linear || self.controller.action_had_its_effect(&facts) {
                    self.controller.advance();
                    self.actions_done += 1;
                    self.failures_in_a_row = 0;
                    self.end_action("done".into());
                } else {
                    self.failures_in_a_row += 1;
                    self.end_action("no effect".into());
                    self.check_failures();
                }
            }
            ExecStatus::Failed(why) => {
                let action = self
                    .exec
                    .as_ref()
                    .map(|e| e.action.clone())
                    .unwrap_or_default();
                self.end_action(format!("failed: {why}"));
                if linear {
                    self.outcome = Some(Err(FailReason::ActionFailed { action, why }));
                } else {
                    self.controller
                        .replan_after_failure(format!("{action} failed: {why}"));
                    self.failures_in_a_row += 1;
                    self.check_failures();
                }
            }
        }
    }

    fn check_failures(&mut self) {
        if self.failures_in_a_row >= self.params.max_action_failures {
            let action = self
                .actions
                .last()
                .map(|a| a.action.clone())
                .unwrap_or_default();
            let why = self
                .actions
                .last()
                .map(|a| a.outcome.clone())
                .unwrap_or_default();
            self.outcome = Some(Err(FailReason::ActionFailed { action, why }));
        }
    }

    fn end_action(&mut self, outcome: String) {
        self.exec = None;
        if let Some(a) = self.actions.last_mut() {
            if a.end_tick.is_none() {
                a.end_tick = Some(self.tick);
                a.outcome = outcome;
            }
        }
    }

    /// Asks the controller what to do; starts the action. `false` if nothing to execute.
    fn start_next_action(&mut self, clock: &dyn Clock) -> bool {
        let facts = facts_of(&self.world);
        let objects = objects_of(&self.world);
        let before = self.controller.replans().len();
        // The streams certify the executor's motions: the same heights.
        let streams = StreamParams {
            motion: self.params.exec.motion,
            ..self.params.streams
        };
        let mut binder = StreamBinder::new(
            &self.world,
            mix(self.options.seed, before as u64 + 1),
            streams,
        )
        .with_hints(&self.hints);
        let decision =
            self.controller
                .decide(&facts, &objects, &self.model, &mut binder, clock, self.tick);
        let replanned = self.controller.replans().len() > before;
        if replanned {
            match self.options.method {
                Method::Linear => {
                    // The demonstration's placements, as demonstrated (no task-level feedback,
                    // nothing re-sampled); blocks are re-targeted by the skills.
                    let task = self.controller.task();
                    self.bindings = self
                        .controller
                        .plan_ops()
                        .iter()
                        .map(|&o| {
                            let op = &task.operators[o];
                            match classify(task, op, &self.world) {
                                Some(ActionKind::Release {
                                    placement: Some(p), ..
                                }) => Some(p),
                                Some(ActionKind::Release { .. }) => {
                                    self.hints.get(&op.name).map(|h| Placement::At {
                                        x: h.x,
                                        y: h.y,
                                        yaw: h.yaw,
                                    })
                                }
                                _ => None,
                            }
                            .into()
                        })
                        .collect();
                }
                Method::Rlds => {
                    // No new actions: only surface placements are re-targeted.
                    let ops = self.controller.plan_ops().to_vec();
                    let task = self.controller.task().clone();
                    self.bindings = binder
                        .bind(&task, &ops, 0)
                        .unwrap_or_else(|_| vec![Binding::default(); ops.len()]);
                }
                Method::LogicLfd | Method::Tamp => {
                    self.bindings = self.controller.bindings().to_vec();
                }
            }
        }
        drop(binder);
        match decision {
            Decision::Done => {
                self.outcome = Some(Ok(()));
                false
            }
            Decision::Failed(r) => {
                self.outcome = Some(Err(r));
                false
            }
            Decision::Execute { index, action } => {
                let task = self.controller.task();
                let op = &task.operators[self.controller.plan_ops()[index]];
                let Some(mut kind) = classify(task, op, &self.world) else {
                    self.outcome = Some(Err(FailReason::ActionFailed {
                        action,
                        why: "the executor does not know this kind of action".into(),
                    }));
                    return false;
                };
                let binding = self.bindings.get(index).cloned().unwrap_or_default();
                if let ActionKind::Pull { turn, .. } = &mut kind {
                    if let Some(Placement::Stroke(t)) = binding.placement {
                        *turn = t;
                    }
                }
                if let ActionKind::Release { placement, .. } = &mut kind {
                    if placement.is_none() {
                        placement.clone_from(&binding.placement);
                    }
                    if placement.is_none() {
                        self.outcome = Some(Err(FailReason::ActionFailed {
                            action,
                            why: "no placement could be bound".into(),
                        }));
                        return false;
                    }
                }
                let exec =
                    ActionExec::new(&action, kind, &self.world, &self.skills, &self.params.exec)
                        .with_hand_yaw(binding.hand_yaw);
                self.exec = Some(match binding.transit {
                    Some(z) => exec.with_transit(z),
                    None => exec,
                });
                self.actions.push(ActionRecord {
                    action,
                    start_tick: self.tick,
                    end_tick: None,
                    outcome: "running".into(),
                });
                true
            }
        }
    }

    /// Moves a block as a user drag does (refused with a reason if impossible).
    pub fn perturb(&mut self, body: &str, position: [f64; 3]) -> Result<PerturbOutcome, Refused> {
        let out = self
            .world
            .move_block(body, Vector3::new(position[0], position[1], position[2]))?;
        self.events.push(EpisodeEvent::Perturb {
            tick: self.tick,
            body: body.to_string(),
            position,
        });
        Ok(out)
    }

    /// Drops the current plan; the loop replans on the next step.
    pub fn cancel(&mut self) {
        self.controller.cancel();
        if self.exec.is_some() {
            self.end_action("interrupted: cancelled".into());
        }
        self.events.push(EpisodeEvent::Cancel { tick: self.tick });
    }

    /// Restarts the episode from the initial scene with a new seed.
    pub fn reset(&mut self, seed: u64) {
        let mut options = self.options.clone();
        options.seed = seed;
        let scene = serde_json::to_string(&self.initial).unwrap_or_default();
        if let Ok(s) = Session::with_sources(
            options,
            &self.sources,
            Some(&scene),
            self.demo_json.as_deref(),
            self.params,
        ) {
            *self = s;
        }
    }

    /// The full log of the episode so far.
    pub fn log(&self) -> EpisodeLog {
        let result = self.outcome.as_ref().map(|o| EpisodeResult {
            success: o.is_ok(),
            reason: o.as_ref().err().cloned(),
            time_s: self.world.time(),
            ticks: self.tick,
            actions_executed: self.actions_done,
            replans: self.controller.replans().len(),
        });
        EpisodeLog {
            version: 1,
            options: self.options.clone(),
            scene: self.initial.clone(),
            demo_json: self.demo_json.clone(),
            events: self.events.clone(),
            replans: self.controller.replans().to_vec(),
            actions: self.actions.clone(),
            ticks: self.tick,
            result,
            final_facts: facts_of(&self.world),
            final_world: self.world.snapshot(),
        }
    }

    /// The full log as JSON; [`Session::replay`] reproduces the episode from it.
    pub fn episode_json(&self) -> String {
        serde_json::to_string(&self.log()).unwrap_or_default()
    }

    /// Re-runs a logged episode tick by tick, applying its events at their ticks.
    pub fn replay_with_sources(
        files: &BenchmarkSources,
        episode_json: &str,
    ) -> Result<Session, SessionError> {
        let log: EpisodeLog = serde_json::from_str(episode_json)
            .map_err(|e| SessionError::Json(format!("episode: {e}")))?;
        let scene = serde_json::to_string(&log.scene)
            .map_err(|e| SessionError::Json(format!("episode: scene: {e}")))?;
        let mut s = Session::with_sources(
            log.options.clone(),
            files,
            Some(&scene),
            log.demo_json.as_deref(),
            SessionParams::default(),
        )?;
        let mut events = log.events.iter().peekable();
        let clock = NoClock;
        loop {
            while let Some(e) = events.peek() {
                let t = match e {
                    EpisodeEvent::Perturb { tick, .. }
                    | EpisodeEvent::Inject { tick, .. }
                    | EpisodeEvent::Cancel { tick } => *tick,
                };
                if t > s.tick {
                    break;
                }
                match e {
                    EpisodeEvent::Perturb { body, position, .. } => {
                        let _ = s.perturb(body, *position);
                    }
                    EpisodeEvent::Inject { level, .. } => {
                        let _ = s.inject(level);
                    }
                    EpisodeEvent::Cancel { .. } => s.cancel(),
                }
                events.next();
            }
            if s.outcome.is_some() {
                break;
            }
            if s.tick >= log.ticks {
                // The final decision (done / failed) takes no tick.
                if log.result.is_some() {
                    s.tick_once(&clock);
                }
                break;
            }
            let before = s.tick;
            s.tick_once(&clock);
            if s.tick == before && s.outcome.is_none() && s.exec.is_none() {
                break;
            }
        }
        Ok(s)
    }

    /// The current frame without stepping.
    pub fn frame(&self) -> Frame {
        let facts = facts_of(&self.world);
        let plan = self.controller.plan_names().to_vec();
        let executing = self.exec.as_ref().map(|_| self.controller.cursor());
        let replans = self.controller.replans();
        let status = self.status(&plan, executing);
        let ee = (0..self.world.arm_names().len())
            .filter_map(|a| {
                let tcp = self.world.tcp_pose(a)?.translation.vector;
                let target = self
                    .exec
                    .as_ref()
                    .filter(|e| e.arm() == a)
                    .and_then(|e| e.target())
                    .unwrap_or(tcp);
                Some(EePoint {
                    arm: a,
                    pos: [tcp.x, tcp.y, tcp.z],
                    target: [target.x, target.y, target.z],
                })
            })
            .collect();
        Frame {
            t: self.world.time(),
            tick: self.tick,
            world: self.world.snapshot(),
            status,
            plan,
            executing,
            demo: self.trace.actions.clone(),
            demo_states: self
                .trace
                .states
                .iter()
                .map(|s| s.iter().cloned().collect())
                .collect(),
            matched_k: self.controller.matched_k(),
            facts,
            facts_added: self.frame_added.clone(),
            facts_removed: self.frame_removed.clone(),
            last_replan: replans.last().cloned(),
            replans: replans.len(),
            ee,
        }
    }

    fn status(&self, plan: &[String], executing: Option<usize>) -> Status {
        let st = |kind: &str, message: String, step: Option<usize>, of: Option<usize>| Status {
            kind: kind.into(),
            message,
            step,
            of,
        };
        match &self.outcome {
            Some(Ok(())) => return st("done", "done: the goal holds".into(), None, None),
            Some(Err(r)) => return st("failed", format!("failed because {r}"), None, None),
            None => {}
        }
        match executing {
            Some(i) => {
                let replan = self.controller.replans().last();
                let fresh = replan.is_some_and(|r| r.tick + 50 > self.tick && r.reason != "start");
                let kind = if fresh { "replanning" } else { "executing" };
                let msg = match (fresh, replan) {
                    (true, Some(r)) => format!(
                        "replanned because {}; executing step {} of {}: {}",
                        r.reason,
                        i + 1,
                        plan.len(),
                        plan.get(i).cloned().unwrap_or_default()
                    ),
                    _ => format!(
                        "executing step {} of {}: {}",
                        i + 1,
                        plan.len(),
                        plan.get(i).cloned().unwrap_or_default()
                    ),
                };
                st(kind, msg, Some(i + 1), Some(plan.len()))
            }
            None if self.tick == 0 => st("idle", "ready".into(), None, None),
            None => st("planning", "planning".into(), None, None),
        }
    }

    /// Injects a disturbance of level `l1`..`l4` now (seeded by the session's seed and the
    /// number of injections so far); what it did, in words and data.
    pub fn inject(&mut self, level: &str) -> Result<Injection, SessionError> {
        let n = self.injections;
        let spots: Vec<(f64, f64)> = self.hints.values().map(|h| (h.x, h.y)).collect();
        let inj = super::disturb::inject(
            &mut self.world,
            level,
            &self.trace,
            &spots,
            mix(self.options.seed, 1_000_003 + n),
        )
        .map_err(SessionError::Json)?;
        self.injections += 1;
        self.events.push(EpisodeEvent::Inject {
            tick: self.tick,
            level: level.to_string(),
            description: inj.description.clone(),
        });
        Ok(inj)
    }
}
