//! The incremental recorder: replay edits in the simulator, explain every fact change by one
//! operator of the grounded task, segment the motion (see the module docs of [`super`]).

use super::recording::{ArmRef, GripperPose, GripperState, HandMove, RawSample};
use super::{RecorderError, RecorderEvent, RecorderParams, Segment, Taught, TaughtDemo};
use crate::pddl;
use crate::plan::{self, State, Task};
use crate::sim::benchmark::Benchmark;
use crate::sim::demo::{AnchorPose, DemoAction, Demonstration, GripperEvent, KeyPoint};
use crate::sim::geometry::wrap;
use crate::sim::panda;
use crate::sim::snapshot::{BodyKind, WorldSnapshot};
use crate::sim::{GripperCommand, SceneGraph, World, WorldEvent};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

/// How a [`Recorder`] is set up.
#[derive(Clone, Debug, PartialEq)]
pub struct RecorderOptions {
    /// Name of the domain file, for error messages.
    pub domain_file: String,
    /// A PDDL problem `(text, file name)` whose `:init` supplies static facts the scene graph does
    /// not report (B3's `reaches`). Without it they come from the benchmark whose name the scene
    /// carries, if any.
    pub problem_pddl: Option<(String, String)>,
    /// Tunables.
    pub params: RecorderParams,
}

impl Default for RecorderOptions {
    fn default() -> Self {
        RecorderOptions {
            domain_file: "domain.pddl".into(),
            problem_pddl: None,
            params: RecorderParams::default(),
        }
    }
}

/// One arm's gripper as the page's handle shows it.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
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
/// use logic_lfd::recorder::synth::Edit;
/// use logic_lfd::sim::benchmark::Benchmark;
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

fn model_err(e: impl std::fmt::Display) -> RecorderError {
    RecorderError::Model(e.to_string())
}

/// Yaw (rotation about world `z`) of an orientation: the heading of its `x` axis.
pub(crate) fn yaw_of(rot: &UnitQuaternion<f64>) -> f64 {
    let x = rot * Vector3::x();
    libm::atan2(x.y, x.x)
}

/// The gripper yaw of a TCP orientation (inverse of [`panda::down_orientation`]).
pub(crate) fn gripper_yaw(rot: &UnitQuaternion<f64>) -> f64 {
    yaw_of(&(rot * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)))
}

fn round_to(v: f64, q: f64) -> f64 {
    (v / q).round() * q
}

fn sorted_facts(world: &World) -> Vec<String> {
    let mut f = SceneGraph::from_world(world).to_strings();
    f.sort();
    f
}

impl Recorder {
    /// A recorder on the world `scene` for the PDDL domain `domain_pddl`. The task is grounded
    /// from the scene's objects and facts (plus static facts, see [`RecorderOptions`]).
    pub fn new(
        scene: &WorldSnapshot,
        domain_pddl: &str,
        options: RecorderOptions,
    ) -> Result<Recorder, RecorderError> {
        let world = World::from_snapshot(scene).map_err(|e| RecorderError::Input {
            path: format!("scene.{}", e.path),
            message: e.message,
        })?;
        let domain = pddl::parse_domain(domain_pddl, &options.domain_file).map_err(model_err)?;
        let preds: Vec<String> = scene.predicates.clone();
        // Static facts: from the problem's init (predicates the scene graph does not report), or
        // from the benchmark the scene is.
        let statics: Vec<String> = match &options.problem_pddl {
            Some((text, file)) => {
                let p = pddl::parse_problem(text, file, &domain).map_err(model_err)?;
                p.init
                    .iter()
                    .filter(|a| !preds.contains(&domain.predicates[a.predicate].name.text))
                    .map(|a| atom_text(&domain, a))
                    .collect()
            }
            None => Benchmark::parse(&scene.name)
                .map(|b| b.static_facts().iter().map(|f| f.to_string()).collect())
                .unwrap_or_default(),
        };
        let facts = sorted_facts(&world);
        let mut objects = String::new();
        for o in SceneGraph::objects(&world) {
            if domain.type_index(&o.kind).is_some() {
                objects.push_str(&format!(" {} - {}", o.name, o.kind));
            }
        }
        let mut init: Vec<&str> = facts.iter().map(String::as_str).collect();
        init.extend(statics.iter().map(String::as_str));
        let problem_text = format!(
            "(define (problem taught) (:domain {})\n (:objects{})\n (:init {})\n (:goal (and)))\n",
            domain.name.text,
            objects,
            init.join(" ")
        );
        let problem = pddl::parse_problem(&problem_text, "<scene>", &domain).map_err(|e| {
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

    fn apply_sample(&mut self, sample: &RawSample) -> Result<(), RecorderError> {
        let t = sample.t();
        if !t.is_finite() {
            return Err(RecorderError::Input {
                path: "t".into(),
                message: "expected a finite number".into(),
            });
        }
        let dt = self.world.dt();
        let cur = *self.cur_t.get_or_insert(t);
        if t + 0.5 * dt < cur - 1e-9 && self.log_t.last().is_some_and(|&l| t + 0.5 * dt < l) {
            return Err(RecorderError::Input {
                path: "t".into(),
                message: format!(
                    "goes back in time ({t} s after {} s)",
                    self.log_t.last().copied().unwrap_or(cur)
                ),
            });
        }
        let same_time = t + 0.5 * dt < cur;
        if !same_time {
            // Catch up: the world keeps following the previous commands until t.
            while self.time() + 0.5 * dt < t {
                self.step_once()?;
            }
        }
        match sample {
            RawSample::Gripper {
                arm, pose, gripper, ..
            } => {
                let ai = arm
                    .resolve(&self.world)
                    .ok_or_else(|| RecorderError::Input {
                        path: "arm".into(),
                        message: format!(
                            "no such arm {} (arms: {})",
                            match arm {
                                ArmRef::Index(i) => i.to_string(),
                                ArmRef::Name(n) => format!("{n:?}"),
                            },
                            self.world.arm_names().join(", ")
                        ),
                    })?;
                if !(pose.position.iter().all(|v| v.is_finite()) && pose.yaw.is_finite()) {
                    return Err(RecorderError::Input {
                        path: "pose".into(),
                        message: "expected finite numbers".into(),
                    });
                }
                let target = Isometry3::from_parts(
                    Translation3::from(Vector3::from(pose.position)),
                    panda::down_orientation(pose.yaw),
                );
                self.world
                    .command_arm(ai, target, gripper.command())
                    .map_err(model_err)?;
            }
            RawSample::Move { hand, .. } => {
                let HandMove { body, position } = hand;
                self.world
                    .move_block(body, Vector3::from(*position))
                    .map_err(|e| RecorderError::Physics {
                        t: self.time(),
                        message: e.to_string(),
                    })?;
            }
        }
        if !same_time || matches!(sample, RawSample::Move { .. }) {
            self.step_once()?;
        }
        Ok(())
    }

    /// One simulator step with every check; logs it.
    fn step_once(&mut self) -> Result<(), RecorderError> {
        if self.log_t.len() >= self.params.max_steps {
            return Err(RecorderError::Refused(format!(
                "the recording is longer than {} simulator steps",
                self.params.max_steps
            )));
        }
        let t = self.time();
        let events = self.world.step();
        let step = self.log_t.len();
        let mut cause = Cause::Other;
        for e in &events {
            match e {
                WorldEvent::Lost { body, reason } => {
                    return Err(RecorderError::Physics {
                        t,
                        message: format!("{body} fell: {reason}"),
                    })
                }
                WorldEvent::Released {
                    arm,
                    body,
                    support,
                    drop,
                } => {
                    if *drop > self.params.max_release_drop {
                        return Err(RecorderError::Physics {
                            t,
                            message: format!(
                                "{arm} released {body} in mid-air, {:.0} mm above {support} \
                                 (at most {:.0} mm counts as putting it down)",
                                drop * 1000.0,
                                self.params.max_release_drop * 1000.0
                            ),
                        });
                    }
                    cause = Cause::Release(body.clone());
                }
                WorldEvent::Grasped { body, .. } => cause = Cause::Grasp(body.clone()),
                _ => {}
            }
        }
        let facts = sorted_facts(&self.world);
        if facts != self.facts {
            self.explain_change(t, step, &facts, cause)?;
            self.facts = facts;
        }
        if let Err(v) = self.world.check_invariants() {
            let text: Vec<String> = v.iter().map(|x| x.to_string()).collect();
            return Err(RecorderError::Physics {
                t,
                message: text.join("; "),
            });
        }
        let n = self.world.arm_names().len();
        self.log_t.push(t);
        self.log_tcp.push(
            (0..n)
                .map(|a| self.world.tcp_pose(a).unwrap_or_else(Isometry3::identity))
                .collect(),
        );
        self.log_grip.push(
            (0..n)
                .map(|a| {
                    self.world
                        .arm_command(a)
                        .map(|c| c.1)
                        .unwrap_or(GripperCommand::Open)
                })
                .collect(),
        );
        self.log_bodies.push(
            self.body_names
                .iter()
                .map(|b| self.world.body_pose(b).unwrap_or_else(Isometry3::identity))
                .collect(),
        );
        self.log_events
            .extend(events.into_iter().map(|e| (step, e)));
        self.cur_t = Some(t + self.world.dt());
        Ok(())
    }

    /// Finds the operator that explains `S → facts`, records it, or errors.
    fn explain_change(
        &mut self,
        t: f64,
        step: usize,
        facts: &[String],
        cause: Cause,
    ) -> Result<(), RecorderError> {
        let old: std::collections::BTreeSet<&String> = self.facts.iter().collect();
        let new: std::collections::BTreeSet<&String> = facts.iter().collect();
        let added: Vec<String> = new.difference(&old).map(|s| s.to_string()).collect();
        let removed: Vec<String> = old.difference(&new).map(|s| s.to_string()).collect();
        let next = match self.task.state_from_names(facts) {
            Ok(s) => s,
            Err(e) => {
                return Err(RecorderError::Unexplained {
                    t,
                    added,
                    removed,
                    hint: format!("; {e}"),
                })
            }
        };
        let found = self
            .task
            .operators
            .iter()
            .position(|o| o.applicable(&self.state) && o.apply(&self.state) == next);
        let Some(op) = found else {
            let hint = self.closest_hint(&next);
            return Err(RecorderError::Unexplained {
                t,
                added,
                removed,
                hint,
            });
        };
        let name = &self.task.operators[op].name;
        let arm = name
            .trim_matches(|c| c == '(' || c == ')')
            .split_whitespace()
            .skip(1)
            .find_map(|w| self.world.arm_index(w))
            .ok_or_else(|| {
                RecorderError::Model(format!(
                    "at t = {t:.2} s: the action {name} explains the change but names no arm of the scene"
                ))
            })?;
        self.actions.push(ActionRec {
            op,
            arm,
            step,
            cause,
            added,
            removed,
        });
        self.state = next;
        Ok(())
    }

    /// "; the closest action … needs … / would …" for an unexplained change.
    fn closest_hint(&self, next: &State) -> String {
        let s = &self.state;
        let mut best: Option<(usize, usize)> = None;
        for (i, o) in self.task.operators.iter().enumerate() {
            let unmet = o.pre.iter().filter(|&&f| !s.contains(f)).count()
                + o.pre_neg.iter().filter(|&&f| s.contains(f)).count();
            let after = o.apply(s);
            let diff = (0..self.task.facts.len() as u32)
                .filter(|&f| after.contains(f) != next.contains(f))
                .count();
            let score = unmet + diff;
            if best.is_none_or(|(b, _)| score < b) {
                best = Some((score, i));
            }
        }
        let Some((_, i)) = best else {
            return String::new();
        };
        let o = &self.task.operators[i];
        let name = |f: &u32| self.task.facts[*f as usize].clone();
        let mut parts = vec![];
        let missing: Vec<String> = o
            .pre
            .iter()
            .filter(|&&f| !s.contains(f))
            .map(name)
            .collect();
        if !missing.is_empty() {
            parts.push(format!("needs {}", missing.join(" ")));
        }
        let forbidden: Vec<String> = o
            .pre_neg
            .iter()
            .filter(|&&f| s.contains(f))
            .map(name)
            .collect();
        if !forbidden.is_empty() {
            parts.push(format!("needs not {}", forbidden.join(" ")));
        }
        let after = o.apply(s);
        let too_much: Vec<u32> = (0..self.task.facts.len() as u32)
            .filter(|&f| after.contains(f) != next.contains(f))
            .collect();
        if !too_much.is_empty() {
            let want_add: Vec<String> = too_much
                .iter()
                .filter(|&&f| next.contains(f) && !after.contains(f))
                .map(name)
                .collect();
            let want_del: Vec<String> = too_much
                .iter()
                .filter(|&&f| !next.contains(f) && after.contains(f))
                .map(name)
                .collect();
            let mut d = vec![];
            if !want_add.is_empty() {
                d.push(format!("does not make {} true", want_add.join(" ")));
            }
            if !want_del.is_empty() {
                d.push(format!("does not make {} false", want_del.join(" ")));
            }
            parts.push(d.join(" and "));
        }
        format!("; the closest action {} {}", o.name, parts.join("; "))
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

    /// The recognised actions so far, with their sample ranges (the last one's end is provisional).
    pub fn segments(&self) -> Vec<Segment> {
        (0..self.actions.len()).map(|i| self.segment(i)).collect()
    }

    fn segment(&self, i: usize) -> Segment {
        let (start, end) = self.range(i);
        let a = &self.actions[i];
        let t_at = |k: usize| self.log_t.get(k).copied().unwrap_or(0.0);
        Segment {
            index: i,
            action: self.task.operators[a.op].name.clone(),
            arm: self.world.arm_names()[a.arm].to_string(),
            t_start: t_at(start),
            t_event: t_at(a.step),
            t_end: t_at(end),
            added: a.added.clone(),
            removed: a.removed.clone(),
        }
    }

    /// The demonstration states L_0..L_N so far (fluents, sorted).
    pub fn demo_states(&self) -> Vec<Vec<String>> {
        let mut s = self.init_state.clone();
        let mut out = vec![self.names(&s)];
        for a in &self.actions {
            s = self.task.operators[a.op].apply(&s);
            out.push(self.names(&s));
        }
        out
    }

    fn names(&self, s: &State) -> Vec<String> {
        let mut v = self.task.state_names(s);
        v.sort();
        v
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
            let n = crate::sim::scene_graph::normalise(g);
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
            world: World::from_snapshot(&self.initial).map_err(model_err)?,
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

    // ------------------------------------------------------------------ segmentation

    /// Log index range `[start, end]` of action `i`.
    fn range(&self, i: usize) -> (usize, usize) {
        let start = if i == 0 { 0 } else { self.boundary(i - 1) + 1 };
        let end = if i + 1 == self.actions.len() {
            self.log_t.len().saturating_sub(1)
        } else {
            self.boundary(i)
        };
        (start.min(end), end)
    }

    /// The last log index of action `i` (i < N − 1): see the module docs.
    fn boundary(&self, i: usize) -> usize {
        let a = &self.actions[i];
        let b = &self.actions[i + 1];
        let (e, e2) = (a.step, b.step);
        if e2 <= e + 1 {
            return e;
        }
        let pos = |k: usize, arm: usize| self.log_tcp[k][arm].translation.vector;
        let moved = |k: usize, arm: usize| {
            k > 0 && (pos(k, arm) - pos(k - 1, arm)).norm() > self.params.still_per_step
        };
        if a.arm != b.arm {
            let last_move = (e + 1..e2).rev().find(|&k| moved(k, a.arm)).unwrap_or(e);
            let first_other = (e + 1..e2).find(|&k| moved(k, b.arm));
            let mut bnd = last_move;
            if let Some(f) = first_other {
                bnd = bnd.min(f.saturating_sub(1));
            }
            return bnd.max(e);
        }
        let z0 = pos(e, a.arm).z;
        let speed = |k: usize| {
            if k == 0 {
                0.0
            } else {
                (pos(k, a.arm) - pos(k - 1, a.arm)).norm()
            }
        };
        if let Some(k) = (e + 1..e2).find(|&k| pos(k, a.arm).z >= z0 + self.params.lift_height) {
            // The end of the lift: the first local minimum of the speed once the speed has come
            // down from its peak (the lift height is often reached while still accelerating; a
            // cut there leaves both neighbours starting or ending at full speed).
            let mut peak = (e + 1..=k).map(speed).fold(0.0, f64::max);
            for k2 in k..e2 - 1 {
                let v = speed(k2);
                if v < peak && v <= speed(k2 + 1) {
                    return k2;
                }
                peak = peak.max(v);
            }
            return e2 - 1;
        }
        (e + 1..e2)
            .max_by(|&x, &y| pos(x, a.arm).z.total_cmp(&pos(y, a.arm).z))
            .unwrap_or(e)
    }

    fn body_pose_at(&self, name: &str, k: usize) -> Option<Isometry3<f64>> {
        let j = self.body_names.iter().position(|b| b == name)?;
        self.log_bodies.get(k).map(|v| v[j])
    }

    fn demo_action(&self, i: usize) -> Result<DemoAction, RecorderError> {
        let a = &self.actions[i];
        let op_name = self.task.operators[a.op].name.clone();
        let words: Vec<String> = op_name
            .trim_matches(|c| c == '(' || c == ')')
            .split_whitespace()
            .map(String::from)
            .collect();
        let (start, end) = self.range(i);
        let (anchor, anchor_pose) = match &a.cause {
            Cause::Grasp(b) => (b.clone(), self.body_pose_at(b, start)),
            Cause::Release(b) => (b.clone(), self.body_pose_at(b, end)),
            Cause::Other => {
                // The first argument naming a body that is not held (the block a hook pulls).
                let held: Vec<&str> = (0..self.world.arm_names().len())
                    .filter_map(|r| self.world.held_by(r))
                    .collect();
                let name = words
                    .iter()
                    .skip(1)
                    .find(|w| self.body_names.contains(w) && !held.contains(&w.as_str()))
                    .or_else(|| words.iter().skip(1).find(|w| self.body_names.contains(w)))
                    .cloned()
                    .ok_or_else(|| {
                        RecorderError::Model(format!("{op_name} names no block or hook"))
                    })?;
                let p = self.body_pose_at(&name, start);
                (name, p)
            }
        };
        let anchor_pose = AnchorPose::from_pose(
            &anchor_pose
                .ok_or_else(|| RecorderError::Model(format!("{op_name}: no pose of {anchor}")))?,
        );
        let frame = anchor_pose.isometry();
        let inv = frame.inverse();
        let samples = (start..=end)
            .map(|k| {
                let tcp = self.log_tcp[k][a.arm];
                let lp = inv * Point3::from(tcp.translation.vector);
                let yaw = wrap(gripper_yaw(&tcp.rotation) - anchor_pose.yaw);
                [
                    round_to(lp.x, 1e-4),
                    round_to(lp.y, 1e-4),
                    round_to(lp.z, 1e-4),
                    round_to(yaw, 1e-3),
                ]
            })
            .collect();
        let mut gripper = vec![GripperEvent {
            step: 0,
            command: self.log_grip[start][a.arm],
        }];
        for k in start + 1..=end {
            let g = self.log_grip[k][a.arm];
            if g != self.log_grip[k - 1][a.arm] {
                gripper.push(GripperEvent {
                    step: k - start,
                    command: g,
                });
            }
        }
        let mut key_points = vec![];
        match &a.cause {
            Cause::Grasp(_) => key_points.push(KeyPoint {
                step: a.step - start,
                label: "grasp".into(),
            }),
            Cause::Release(_) => key_points.push(KeyPoint {
                step: a.step - start,
                label: "release".into(),
            }),
            Cause::Other => {
                if let Some((k, _)) = self.log_events.iter().find(|(k, e)| {
                    *k >= start
                        && *k <= end
                        && matches!(e, WorldEvent::Pushed { body, .. } if *body == anchor)
                }) {
                    key_points.push(KeyPoint {
                        step: k - start,
                        label: "contact".into(),
                    });
                }
                key_points.push(KeyPoint {
                    step: a.step - start,
                    label: "pulled".into(),
                });
            }
        }
        Ok(DemoAction {
            action: op_name,
            name: words.first().cloned().unwrap_or_default(),
            args: words.iter().skip(1).cloned().collect(),
            arm: self.world.arm_names()[a.arm].to_string(),
            anchor,
            anchor_pose,
            samples,
            gripper,
            key_points,
        })
    }

    /// Ends the recording: the demonstration (`demo.json`), its states and the skill fits. Refused
    /// when nothing was demonstrated, when an arm still holds something, or when the goal does not
    /// hold in L_N.
    pub fn finish(&self) -> Result<Taught, RecorderError> {
        if self.actions.is_empty() {
            return Err(RecorderError::Refused(
                "nothing was demonstrated: no fact of the scene changed".into(),
            ));
        }
        for (r, name) in self.world.arm_names().iter().enumerate() {
            if let Some(b) = self.world.held_by(r) {
                return Err(RecorderError::Refused(format!(
                    "the recording ends while {name} holds {b}: put it down first"
                )));
            }
        }
        let states = self.demo_states();
        let last = states.last().cloned().unwrap_or_default();
        let goal = match &self.goal {
            Some(g) => {
                for f in g {
                    if !last.contains(f) && !self.task.static_facts.contains(f) {
                        return Err(RecorderError::Refused(format!(
                            "the goal fact {f} does not hold at the end of the demonstration"
                        )));
                    }
                }
                g.clone()
            }
            None => last.clone(),
        };
        let actions = (0..self.actions.len())
            .map(|i| self.demo_action(i))
            .collect::<Result<Vec<_>, _>>()?;
        let dt = self.world.dt();
        let demo = Demonstration {
            benchmark: self.initial.name.clone(),
            seed: self.seed,
            dt,
            frame_convention: FRAME_CONVENTION.to_string(),
            actions,
        };
        let skills = if self.params.learn_skills {
            super::taught::skill_fits(&demo)?
        } else {
            vec![]
        };
        Ok(Taught {
            demo: TaughtDemo {
                demo,
                domain: self.domain_name.clone(),
                initial_facts: states[0].clone(),
                goal,
                scene: self.initial.clone(),
            },
            states,
            skills,
        })
    }
}

const FRAME_CONVENTION: &str =
    "samples are [x, y, z, yaw] of the gripper tool centre point in the \
anchor frame (anchor centre + its yaw about world z; pick/unstack/pull: the object at the action's \
start; place/place-on-shelf/stack: the carried object's resting pose at the action's end), every \
10 ms; gripper pointing straight down; yaw relative to the anchor's yaw";

fn atom_text(domain: &pddl::Domain, a: &pddl::Atom) -> String {
    let mut s = format!("({}", domain.predicates[a.predicate].name.text);
    for t in &a.args {
        s.push(' ');
        s.push_str(t.text());
    }
    s.push(')');
    s
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
