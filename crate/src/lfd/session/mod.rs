//! One closed-loop episode stepped by the caller: the same loop as `logic-lfd run`, shaped for the
//! browser.
//!
//! Frame contract (what the page's worker relies on): [`Session::step`]`(dt)` runs the whole
//! 10 ms simulation ticks that `dt` simulated seconds cover (a remainder carries over to the
//! next call), replanning inside, and returns a [`Frame`]: plain serde data, complete on its own
//! (world snapshot, status line, plan and the step being executed, the demonstration and
//! L_0..L_N, S_C, and the facts added and removed since the previous step). [`Session::frame`]
//! returns it again without stepping. [`Session::perturb`], [`Session::inject`] and
//! [`Session::cancel`] act between steps and are logged with their tick; a drag or an injection
//! after the episode ended (done or failed) opens it again, so the loop stays reactive.
//!
//! Per tick (paper Algorithm 1, with the executor of [`super::exec`]; file `tick.rs`):
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
//!
//! This file holds the session itself (construction, accessors, the user's and the injector's
//! disturbances); `options.rs` its set-up, `tick.rs` the loop, `frame.rs` what the page draws and
//! `log.rs` the episode log and its replay.

mod frame;
mod log;
mod options;
mod replay;
mod tick;
mod view;

use super::disturb::motion::{inject_during_motion, Moving};
use super::disturb::Injection;
use crate::sim::BenchmarkSources;
pub use frame::{EePoint, Frame, PerturbOutcome, Status, StatusKind};
pub use log::{ActionRecord, EpisodeEvent, EpisodeLog, EpisodeResult};
pub use options::{
    check_folder, demo_actions, demo_trace_of, mix_seed, sources_for, SessionError, SessionOptions,
    SessionParams,
};

use nalgebra::Vector3;
use std::sync::Arc;

use crate::pddl::ObjectDecl;
use crate::sim::ArmModel;
use crate::sim::WorldSnapshot;
use crate::sim::{BodyKind, Refused, SceneGraph, World};

use super::catalogue::Level;
use super::control::{Controller, FailReason, TaskBuilder};
use super::demo::DemoTrace;
use super::exec::ActionExec;
use super::model::DomainModel;
use super::skill::SkillLibrary;
use crate::tamp::Binding;
use options::{demo_hints, PlacementHints};

/// The stream of seeds of injected disturbances: injection `n` is seeded `mix_seed(seed, base + n)`.
const INJECT_SEED_BASE: u64 = 1_000_003;

/// Where a session's world comes from.
enum Start<'a> {
    /// A scene file's JSON.
    Json(&'a str),
    /// A world's snapshot (its arms' robot models with it).
    Snapshot(&'a WorldSnapshot),
}

/// A closed-loop episode stepped by the caller.
pub struct Session {
    options: SessionOptions,
    sources: BenchmarkSources,
    params: SessionParams,
    model: DomainModel,
    trace: DemoTrace,
    skills: SkillLibrary,
    hints: PlacementHints,
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

fn objects_of(world: &World) -> Vec<ObjectDecl> {
    SceneGraph::objects(world)
}

impl Session {
    /// A session on the benchmark's template scene and demonstration.
    pub fn new(options: SessionOptions) -> Result<Session, SessionError> {
        let files = sources_for(options.benchmark, options.blocks)?;
        Session::with_sources(options, &files, None, None, SessionParams::default())
    }

    /// A session on a given scene (a world snapshot JSON) and optionally another demonstration
    /// (a `demo.json`: `actions` as strings or objects with an `action` field).
    pub fn from_scene(
        options: SessionOptions,
        scene_json: &str,
        demo_json: Option<&str>,
    ) -> Result<Session, SessionError> {
        let files = sources_for(options.benchmark, options.blocks)?;
        Session::with_sources(
            options,
            &files,
            Some(scene_json),
            demo_json,
            SessionParams::default(),
        )
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
        let scene = Start::Json(scene_json.unwrap_or(&files.scene));
        Session::starting(options, files, scene, demo_json, params)
    }

    /// [`Session::with_sources`] from a scene given as JSON or as a snapshot (which carries its
    /// arms' robot models).
    fn starting(
        options: SessionOptions,
        files: &BenchmarkSources,
        scene: Start<'_>,
        demo_json: Option<&str>,
        params: SessionParams,
    ) -> Result<Session, SessionError> {
        let (motions, template, model) = options::template_of(files)?;
        // Through the snapshot once, so the logged initial scene reloads to this very world. One
        // JSON reader for scenes in the session: a second would add its own copy of the scene's
        // deserialiser to the page's first-load module.
        let snapshot = match scene {
            Start::Json(json) => default_robots(crate::sim::world_from_json(json)?.snapshot()),
            Start::Snapshot(s) => s.clone(),
        };
        let world = World::from_snapshot(&snapshot)?.with_motions(Arc::clone(&motions));
        motions
            .check_arms(world.arm_names().len())
            .map_err(SessionError::Json)?;
        // The demonstration is derived on the template task (its initial state is the template
        // scene's facts).
        // A scene that contradicts its problem would show only as an inapplicable step.
        options::check_scene(files)?;
        let template_objects = objects_of(&template);
        let template_task = model.build(&template_objects, &facts_of(&template))?;
        let label = options::demo_label(files, demo_json.is_some());
        let actions = options::demo_actions_in(demo_json.unwrap_or(&files.demo), &label)?;
        let trace = DemoTrace::derive(&template_task, &actions)
            .map_err(|e| options::trace_error(e, model.domain(), &template_objects, &label))?;
        let objects = objects_of(&world);
        let task = model.build(&objects, &facts_of(&world))?;
        let controller = Controller::new(
            options.method,
            options.mode,
            params.control,
            trace.clone(),
            task,
            objects,
        );
        let prev_facts = facts_of(&world);
        let hooks = world.hook_names();
        let skills = SkillLibrary::learn(
            demo_json.unwrap_or(&files.demo),
            options.skill,
            &hooks,
            &motions,
        );
        let hints = demo_hints(demo_json.unwrap_or(&files.demo), &template);
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

    /// The arm in the middle of a move (not at a gripper event) and the body it approaches
    /// (a grasp's object); `None` when no action moves an arm now.
    pub fn moving(&self) -> Option<Moving> {
        let e = self.exec.as_ref()?;
        e.target()?;
        Some(Moving {
            arm: e.arm(),
            approached: match &e.kind {
                crate::tamp::ActionKind::Grasp { body, .. } => Some(body.clone()),
                _ => None,
            },
        })
    }

    /// Ticks since the running action started (`None` when idle).
    pub fn action_ticks(&self) -> Option<u64> {
        self.exec.as_ref()?;
        self.actions.last().map(|a| self.tick - a.start_tick)
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

    /// Moves a block as a user drag does (refused with a reason if impossible, or if no arm
    /// could work the block where it would lie: [`crate::sim::handleable`]).
    pub fn perturb(&mut self, body: &str, position: [f64; 3]) -> Result<PerturbOutcome, Refused> {
        let mut trial = self.world.clone();
        let out = trial.move_block(body, Vector3::new(position[0], position[1], position[2]))?;
        crate::sim::handleable(&trial, body).map_err(|_| Refused {
            body: body.to_string(),
            reason: if trial.hook_names().is_empty() {
                "no arm could grasp it there (beyond every arm's reach)".into()
            } else {
                "no arm could grasp it there, nor pull it in with the hook".into()
            },
        })?;
        self.world = trial;
        self.events.push(EpisodeEvent::Perturb {
            tick: self.tick,
            body: body.to_string(),
            position,
        });
        self.reopen();
        Ok(out)
    }

    /// A disturbance after the episode ended opens it again: the loop observes the new scene and
    /// plans on (a finished tower knocked over is rebuilt; a failure the user fixed is retried
    /// with a fresh failure count).
    fn reopen(&mut self) {
        if self.outcome.take().is_some() {
            self.failures_in_a_row = 0;
        }
    }

    /// Puts robots in place of the scene's arms before the first step: one robot for every arm,
    /// or one per arm, each at its ready posture on the arm's base ([`World::set_robot`]).
    ///
    /// # Errors
    /// After the first step, for another number of robots, or for an arm holding a body.
    pub fn set_robots(&mut self, robots: &[Arc<ArmModel>]) -> Result<(), SessionError> {
        if robots.is_empty() {
            return Ok(());
        }
        if self.tick > 0 {
            return Err(SessionError::Json(
                "robots are chosen before the episode's first step".into(),
            ));
        }
        let arms = self.world.arm_names().len();
        if robots.len() != 1 && robots.len() != arms {
            return Err(SessionError::Json(format!(
                "{} robots for {arms} arm{}: give one robot, or one per arm",
                robots.len(),
                if arms == 1 { "" } else { "s" }
            )));
        }
        let before = self.world.clone();
        for arm in 0..arms {
            let robot = &robots[arm.min(robots.len() - 1)];
            if let Err(e) = self.world.set_robot(arm, Arc::clone(robot)) {
                self.world = before;
                return Err(e.into());
            }
        }
        // Truth on reach: a block the scene's arms could work that the robots cannot is named.
        let snap = self.world.snapshot();
        for b in snap
            .bodies
            .iter()
            .filter(|b| b.kind == BodyKind::Block && !b.lost)
        {
            if crate::sim::handleable(&before, &b.name).is_err() {
                continue;
            }
            if let Err(why) = crate::sim::handleable(&self.world, &b.name) {
                let p = b.pose.position;
                let near = snap
                    .arms
                    .iter()
                    .map(|a| {
                        let q = a.base.position;
                        (libm::hypot(p[0] - q[0], p[1] - q[1]), a.name.as_str())
                    })
                    .fold((f64::INFINITY, ""), |m, d| if d.0 < m.0 { d } else { m });
                self.world = before;
                return Err(SessionError::Reach(format!(
                    "block {} lies {:.3} m from the base of arm {}, out of the robots' reach: {why}",
                    b.name, near.0, near.1
                )));
            }
        }
        self.initial = self.world.snapshot();
        Ok(())
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
        if let Ok(s) = Session::starting(
            options,
            &self.sources,
            Start::Snapshot(&self.initial),
            self.demo_json.as_deref(),
            self.params,
        ) {
            *self = s;
        }
    }

    /// Injects a disturbance of level `l1`..`l4` now (seeded by the session's seed and the
    /// number of injections so far); what it did, in words and data.
    pub fn inject(&mut self, level: &str) -> Result<Injection, SessionError> {
        let mut world = self.world.clone();
        let mut inj = self.injection_on(&mut world, level)?;
        self.world = world;
        inj.during = self.exec.as_ref().map(|e| e.action.clone());
        self.injections += 1;
        self.events.push(EpisodeEvent::Inject {
            tick: self.tick,
            level: level.to_string(),
            description: inj.description.clone(),
        });
        self.reopen();
        Ok(inj)
    }

    /// Whether [`Session::inject`] of `level` would apply now (`Err` says why not), without
    /// changing anything: the same injection tried on a copy of the world.
    pub fn can_inject(&self, level: &str) -> Result<(), SessionError> {
        self.injection_on(&mut self.world.clone(), level)
            .map(|_| ())
    }

    /// The injection of `level` that [`Session::inject`] makes now, applied to `world` (the
    /// session's world or a copy of it).
    fn injection_on(&self, world: &mut World, level: &str) -> Result<Injection, SessionError> {
        let Some(parsed) = Level::parse(level) else {
            return Err(SessionError::Json(format!(
                "unknown disturbance level {:?} (l1..l4)",
                level.to_ascii_lowercase()
            )));
        };
        let seed = mix_seed(self.options.seed, INJECT_SEED_BASE + self.injections);
        match (parsed, self.moving()) {
            // While the arm moves, L1 acts on that motion: the approached body or the hand.
            (Level::L1, Some(m)) => inject_during_motion(world, &self.trace, &m, seed),
            _ => {
                let busy: Vec<usize> = self.exec.iter().map(ActionExec::arm).collect();
                super::disturb::inject(world, parsed, &self.trace, &busy, seed)
            }
        }
        .map_err(SessionError::Json)
    }
}

/// A scene's arms that name no robot, on the default arm: the Franka Emika Panda from its own
/// URDF. The page's first-load module keeps the built-in Panda (its DH chain and link capsules):
/// the URDF's collision meshes do not fit its size budget.
#[cfg(not(first_load))]
fn default_robots(mut scene: crate::sim::WorldSnapshot) -> crate::sim::WorldSnapshot {
    if let Some(panda) = ArmModel::shipped("panda") {
        for arm in scene.arms.iter_mut().filter(|a| a.robot.is_none()) {
            arm.robot = Some(panda.name().to_string());
            arm.model = Some(Arc::clone(&panda));
        }
    }
    scene
}

/// The first-load module's arms stay the built-in Panda.
#[cfg(first_load)]
fn default_robots(scene: crate::sim::WorldSnapshot) -> crate::sim::WorldSnapshot {
    scene
}
