//! One soak episode: draw its benchmark (none for a task folder's soak), mode, session seed and
//! disturbance schedule from the episode's seed, run the session tick by tick applying the disturbances when due, and check
//! every guarantee on the way (invariants, nothing partially applied, adopted plans valid, the
//! outcome stated and legitimate, the replay identical).

use crate::sim::ArmModel;
use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::reasons::{
    drag_proof, shelf_full_for, Check, Models, DRAGGED_AWAY, SHELF_FULL, UNSOLVABLE,
};
use super::report::{ExplainedFailure, SoakFinding, SoakParams, SoakReport};
use crate::lfd::FailReason;
use crate::lfd::{mix_seed, Session, SessionOptions, SessionParams, SkillKind};
use crate::lfd::{Method, Mode};
use crate::plan::NoClock;
use crate::sim::block_range;
use crate::sim::handleable;
use crate::sim::BodyKind;
use crate::sim::World;
use crate::sim::{Benchmark, BenchmarkSources};

/// One scheduled disturbance.
#[derive(Clone, Debug)]
enum Disturbance {
    Inject(&'static str),
    Drag(DragKind),
}

/// What a user-like drag aims at.
#[derive(Clone, Copy, Debug)]
enum DragKind {
    OntoBlock,
    TableSpot,
    Nudge,
    Hostile,
}

/// One disturbance, drawn with the schedule's weights.
fn draw_disturbance(rng: &mut Pcg64Mcg) -> Disturbance {
    match rng.random_range(0..10) {
        0..=1 => Disturbance::Inject("l1"),
        2 => Disturbance::Inject("l2"),
        3 => Disturbance::Inject("l3"),
        4 => Disturbance::Inject("l4"),
        5..=6 => Disturbance::Drag(DragKind::OntoBlock),
        7 => Disturbance::Drag(DragKind::TableSpot),
        8 => Disturbance::Drag(DragKind::Nudge),
        _ => Disturbance::Drag(DragKind::Hostile),
    }
}

/// The bodies the arms hold.
fn held(world: &World) -> Vec<String> {
    (0..world.arm_names().len())
        .filter_map(|a| world.held_by(a).map(str::to_string))
        .collect()
}

/// The centre of body `b`.
fn centre(world: &World, b: &str) -> Option<Vector3<f64>> {
    world.body_pose(b).map(|p| p.translation.vector)
}

/// A user-like drag request: (body, target centre).
fn draw_drag(world: &World, kind: DragKind, rng: &mut Pcg64Mcg) -> (String, [f64; 3]) {
    let held = held(world);
    let free: Vec<String> = world
        .block_names()
        .into_iter()
        .filter(|b| !world.is_lost(b) && !held.iter().any(|h| h == b))
        .map(str::to_string)
        .collect();
    let pick = |v: &[String], rng: &mut Pcg64Mcg| -> Option<String> {
        (!v.is_empty()).then(|| v[rng.random_range(0..v.len())].clone())
    };
    let Some(body) = pick(&free, rng) else {
        return ("a".into(), [0.4, 0.0, 0.2]);
    };
    let c = centre(world, &body).unwrap_or_default();
    let target = match kind {
        DragKind::OntoBlock => {
            let others: Vec<String> = free.iter().filter(|o| **o != body).cloned().collect();
            match pick(&others, rng).and_then(|o| centre(world, &o)) {
                Some(o) => o + Vector3::new(0.0, 0.0, 0.1),
                None => c,
            }
        }
        DragKind::TableSpot => {
            let tables = world.aabbs_of(BodyKind::Table);
            match tables.get(rng.random_range(0..tables.len().max(1))) {
                Some((lo, hi)) => Vector3::new(
                    rng.random_range(lo.x..=hi.x),
                    rng.random_range(lo.y..=hi.y),
                    hi.z + 0.05,
                ),
                None => c,
            }
        }
        DragKind::Nudge => {
            let a = rng.random_range(0.0..std::f64::consts::TAU);
            let r = rng.random_range(0.005..0.06);
            c + Vector3::new(r * libm::cos(a), r * libm::sin(a), 0.002)
        }
        DragKind::Hostile => {
            return match rng.random_range(0..6) {
                0 => (body, [f64::NAN, 0.0, 0.1]),
                1 => (body, [1e9, -1e9, 1e9]),
                2 => (body, [c.x, c.y, -5.0]),
                3 => (
                    held.first().cloned().unwrap_or_else(|| "table".into()),
                    [c.x, c.y, c.z + 0.2],
                ),
                4 => ("table".into(), [0.0, 0.0, 0.5]),
                _ => ("<no such body>".into(), [0.4, 0.0, 0.2]),
            }
        }
    };
    (body, [target.x, target.y, target.z])
}

/// What an episode draws from its seed before it starts, in this order.
struct EpisodeDraw {
    /// The benchmark (`None`: the task folder's task, nothing drawn).
    bench: Option<Benchmark>,
    mode: Mode,
    session_seed: u64,
    /// Disturbances by tick, sorted.
    schedule: Vec<(u64, Disturbance)>,
}

fn draw_episode(params: &SoakParams, rng: &mut Pcg64Mcg) -> EpisodeDraw {
    let bench = match params.blocks {
        _ if params.folder.is_some() => None,
        None => Some(Benchmark::ALL[rng.random_range(0..3)]),
        Some(n) => {
            let fits: Vec<Benchmark> = Benchmark::ALL
                .into_iter()
                .filter(|&b| block_range(b).is_ok_and(|r| r.contains(&n)))
                .collect();
            Some(
                fits.get(rng.random_range(0..fits.len().max(1)))
                    .copied()
                    .unwrap_or(Benchmark::B1),
            )
        }
    };
    let mode = if rng.random_bool(0.5) {
        Mode::Paper
    } else {
        Mode::Prioritised
    };
    let session_seed: u64 = rng.random();
    let mut schedule: Vec<(u64, Disturbance)> = (0..rng.random_range(0..=params.max_disturbances))
        .map(|_| {
            (
                rng.random_range(0..params.horizon_ticks),
                draw_disturbance(rng),
            )
        })
        .collect();
    schedule.sort_by_key(|(t, _)| *t);
    EpisodeDraw {
        bench,
        mode,
        session_seed,
        schedule,
    }
}

/// A running episode and what its checks need to remember.
struct EpisodeRun<'a> {
    params: &'a SoakParams,
    models: &'a Models,
    /// Episode index within the soak.
    e: usize,
    /// The benchmark (`None`: the task folder's task).
    bench: Option<Benchmark>,
    /// The benchmark's name or the task folder's, as findings name the task.
    task: String,
    session_seed: u64,
    s: Session,
    /// The episode's generator (drags draw their targets from it when they happen).
    rng: Pcg64Mcg,
    /// Blocks moved by accepted user drags (with what stood on them).
    dragged: BTreeSet<String>,
    /// Those of `dragged` that their last drag left where no arm can work them, with IK's reason.
    dragged_away: BTreeMap<String, String>,
    /// The session stopped advancing (no tick, no outcome, not executing).
    stalled: bool,
}

/// Runs episode `e` of a soak into `rep` (an empty report) and its episode JSON into
/// `json_out`; `folder`: the task folder's files, when the soak runs its task.
pub(super) fn soak_episode(
    params: &SoakParams,
    e: usize,
    models: &Models,
    folder: Option<&BenchmarkSources>,
    robots: &[Arc<ArmModel>],
    rep: &mut SoakReport,
    json_out: &mut String,
) -> Result<(), String> {
    let mut rng = Pcg64Mcg::seed_from_u64(mix_seed(params.seed, e as u64));
    let draw = draw_episode(params, &mut rng);
    let options = SessionOptions {
        // A task folder's session takes its files from the folder; the benchmark is unused.
        benchmark: draw.bench.unwrap_or(Benchmark::B1),
        method: Method::LogicLfd,
        mode: draw.mode,
        seed: draw.session_seed,
        skill: SkillKind::Lqt,
        blocks: params.blocks,
    };
    let (s, task) = match (draw.bench, folder) {
        (None, Some(f)) => (
            Session::with_sources(options, f, None, None, SessionParams::default()),
            f.dir.clone(),
        ),
        (Some(b), _) => (Session::new(options), b.as_str().to_string()),
        (None, None) => return Err("a task folder's soak needs the folder's files".into()),
    };
    let mut s = s.map_err(|e| e.to_string())?;
    s.set_robots(robots).map_err(|e| e.to_string())?;
    rep.episodes = 1;
    *rep.per_benchmark.entry(task.clone()).or_default() += 1;
    let mut run = EpisodeRun {
        params,
        models,
        e,
        bench: draw.bench,
        task,
        session_seed: draw.session_seed,
        s,
        rng,
        dragged: BTreeSet::new(),
        dragged_away: BTreeMap::new(),
        stalled: false,
    };
    run.run_ticks(&draw.schedule, rep);
    rep.ticks = run.s.tick();
    run.classify_outcome(rep);
    let json = run.s.episode_json();
    *json_out = json.clone();
    if params.check_replay {
        run.check_replay(&json, folder, robots, rep);
    }
    Ok(())
}

impl EpisodeRun<'_> {
    fn finding(&self, tick: u64, kind: &str, detail: String) -> SoakFinding {
        SoakFinding {
            episode: self.e,
            benchmark: self.task.clone(),
            session_seed: self.session_seed,
            tick,
            kind: kind.into(),
            detail,
        }
    }

    /// Checks the world's invariants; true (and a finding) when one is broken.
    fn invariant_check(&self, rep: &mut SoakReport, when: &str) -> bool {
        rep.invariant_checks += 1;
        if let Err(v) = self.s.world().check_invariants() {
            rep.invariant_violations += 1;
            let list: Vec<String> = v.iter().map(|v| v.to_string()).collect();
            rep.find(self.finding(
                self.s.tick(),
                "invariant",
                format!("{when}: {}", list.join("; ")),
            ));
            true
        } else {
            false
        }
    }

    /// Ticks the session until it ends or `max_ticks`, applying the disturbances due before each
    /// tick (as a replay applies them) and checking every plan adopted during a tick. After the
    /// first broken invariant, ticks are no longer checked (one finding per episode is enough).
    fn run_ticks(&mut self, schedule: &[(u64, Disturbance)], rep: &mut SoakReport) {
        let mut next = 0;
        let mut replans_seen = 0;
        let clock = NoClock;
        let mut broken = false;
        while self.s.outcome().is_none() && self.s.tick() < self.params.max_ticks {
            while next < schedule.len() && schedule[next].0 <= self.s.tick() {
                broken |= self.disturb(&schedule[next].1, rep);
                next += 1;
            }
            let pre = self.s.world().clone();
            let t0 = self.s.tick();
            self.s.tick_once(&clock);
            self.check_new_plans(&pre, &mut replans_seen, rep);
            if !broken {
                broken |= self.invariant_check(rep, "after a tick");
            }
            if self.s.tick() == t0 && self.s.outcome().is_none() && !self.s.is_executing() {
                self.stalled = true;
                break;
            }
        }
    }

    /// Applies one disturbance: an applied one is followed by an invariant check (returns
    /// whether it broke), a refused one must leave the world and the log unchanged.
    fn disturb(&mut self, d: &Disturbance, rep: &mut SoakReport) -> bool {
        let before_world = serde_json::to_string(&self.s.world().snapshot()).unwrap_or_default();
        let before_events = self.s.log().events.len();
        let (what, applied) = match d {
            Disturbance::Inject(level) => match self.s.inject(level) {
                Ok(_) => {
                    *rep.injections.entry((*level).into()).or_default() += 1;
                    (format!("inject {level}"), true)
                }
                Err(_) => {
                    rep.injections_refused += 1;
                    (format!("inject {level}"), false)
                }
            },
            Disturbance::Drag(kind) => self.drag(*kind, rep),
        };
        if applied {
            rep.disturbances += 1;
            return self.invariant_check(rep, &format!("after {what}"));
        }
        let after_world = serde_json::to_string(&self.s.world().snapshot()).unwrap_or_default();
        if after_world != before_world || self.s.log().events.len() != before_events {
            rep.partial_applies += 1;
            rep.find(self.finding(
                self.s.tick(),
                "partial_apply",
                format!("refused {what} changed the world or the log"),
            ));
        }
        false
    }

    /// A user-like drag; remembers which blocks it moved and which it left out of reach.
    fn drag(&mut self, kind: DragKind, rep: &mut SoakReport) -> (String, bool) {
        let (body, pos) = draw_drag(self.s.world(), kind, &mut self.rng);
        match self.s.perturb(&body, pos) {
            Ok(out) => {
                rep.drags_accepted += 1;
                let moved = std::iter::once(out.body.clone())
                    .chain(out.also_moved.iter().map(|(b, _)| b.clone()));
                for b in moved {
                    let block = self.s.world().body_kind(&b) == Some(BodyKind::Block);
                    match handleable(self.s.world(), &b) {
                        Err(why) if block => {
                            self.dragged_away.insert(b.clone(), why);
                        }
                        _ => {
                            self.dragged_away.remove(&b);
                        }
                    }
                    self.dragged.insert(b);
                }
                (format!("drag {body} to {pos:?}"), true)
            }
            Err(_) => {
                rep.drags_refused += 1;
                (format!("drag {body} to {pos:?}"), false)
            }
        }
    }

    /// Replays every plan adopted during the last tick with the validator, from `pre`, the world
    /// as it was before the tick (the plans were made from it).
    fn check_new_plans(&self, pre: &World, replans_seen: &mut usize, rep: &mut SoakReport) {
        let replans = self.s.controller().replans();
        if replans.len() > *replans_seen {
            for r in &replans[*replans_seen..] {
                rep.plans_checked += 1;
                rep.tamp_fallbacks += usize::from(r.fallback);
                if let Err(why) = self.models.validate(self.bench, pre, &r.plan) {
                    rep.invalid_plans += 1;
                    rep.find(self.finding(
                        r.tick,
                        "invalid_plan",
                        format!("plan {:?} (because {}): {why}", r.plan, r.reason),
                    ));
                }
            }
            *replans_seen = replans.len();
        }
    }

    /// The proof that a user drag explains the failure: its action acts on a dragged block
    /// that IK shows no arm can work.
    fn drag_explains(&self, reason: &FailReason) -> Option<String> {
        drag_proof(self.s.world(), reason, &self.dragged, &self.dragged_away)
    }

    /// The block a (single-alternative) goal puts on a shelf that finds no room on any.
    fn shelf_full(&self) -> Option<String> {
        let task = self.s.controller().task();
        let [goal] = task.goal.alternatives.as_slice() else {
            return None;
        };
        let goal_facts: Vec<String> = goal
            .pos
            .iter()
            .filter_map(|&f| task.facts.get(f as usize).cloned())
            .collect();
        let facts = crate::sim::SceneGraph::from_world(self.s.world()).to_strings();
        shelf_full_for(self.s.world(), &goal_facts, &facts)
    }

    /// Counts a legitimate failure with its class and proof.
    fn explained(&self, rep: &mut SoakReport, reason: &FailReason, class: &str, proof: String) {
        *rep.legitimate_failures.entry(class.into()).or_default() += 1;
        rep.explain(ExplainedFailure {
            episode: self.e,
            benchmark: self.task.clone(),
            session_seed: self.session_seed,
            reason: reason.to_string(),
            class: class.into(),
            proof,
        });
    }

    /// The proof of a failure other than an unsolvable task: a drag left the block its action
    /// acts on unworkable, or the shelf has no room for a block the goal puts on it.
    fn other_proof(&self, reason: &FailReason) -> Option<(&'static str, String)> {
        if let Some(p) = self.drag_explains(reason) {
            return Some((DRAGGED_AWAY, format!("IK: {p}")));
        }
        self.shelf_full().map(|b| {
            (
                SHELF_FULL,
                format!("no free footprint for {b} on any shelf's top"),
            )
        })
    }

    /// Counts the episode's outcome: a success, or a failure that is legitimate only with a
    /// proof (an exhaustive search that finds no plan, IK on a dragged block the failing action
    /// acts on, a full shelf); everything else is a finding: an exhausted budget, a stall, no
    /// outcome, an observed task that cannot be built, a failure without a proof.
    fn classify_outcome(&self, rep: &mut SoakReport) {
        let s = &self.s;
        let tick = s.tick();
        let reason = match s.outcome() {
            Some(Ok(())) => {
                rep.successes += 1;
                return;
            }
            Some(Err(r)) => r,
            None if self.stalled => {
                rep.stalls += 1;
                rep.find(self.finding(
                    tick,
                    "stall",
                    "the session stopped advancing without an outcome".into(),
                ));
                return;
            }
            None => {
                rep.no_outcome += 1;
                rep.find(self.finding(
                    tick,
                    "no_outcome",
                    format!("no outcome after {} ticks", self.params.max_ticks),
                ));
                return;
            }
        };
        let exhausted = match reason {
            FailReason::Budget { .. } => true,
            FailReason::NoPlan { message } => message.contains("exhausted"),
            _ => false,
        };
        if exhausted {
            rep.budget_exhausted += 1;
            rep.find(self.finding(tick, "budget", reason.to_string()));
            return;
        }
        let check = match reason {
            FailReason::NoPlan { .. } => {
                match self
                    .models
                    .check_solvable(self.bench, s.world(), self.params.check_nodes)
                {
                    Ok(c) => Some(c),
                    Err(e) => {
                        rep.input_errors += 1;
                        rep.find(self.finding(
                            tick,
                            "input_error",
                            format!("{reason}; the observed task cannot be checked: {e}"),
                        ));
                        return;
                    }
                }
            }
            _ => None,
        };
        if let Some(Check::Unsolvable { states }) = check {
            let proof = format!(
                "breadth-first search exhausted all {states} reachable states of the observed task without reaching the goal"
            );
            self.explained(rep, reason, UNSOLVABLE, proof);
            return;
        }
        if let Some((class, proof)) = self.other_proof(reason) {
            self.explained(rep, reason, class, proof);
            return;
        }
        rep.unexplained_failures += 1;
        let detail = match check {
            Some(Check::Solvable { length }) => format!(
                "{reason}, but the observed task has a plan of {length} actions"
            ),
            Some(Check::Undecided { expanded }) => format!(
                "{reason}, and the exhaustive check stopped after {expanded} expansions without a proof that no plan exists"
            ),
            _ => reason.to_string(),
        };
        rep.find(self.finding(tick, "unexplained_failure", detail));
    }

    /// Replays the episode JSON (on the task folder's files, if any) and compares the replay's
    /// JSON byte for byte.
    fn check_replay(
        &self,
        json: &str,
        folder: Option<&BenchmarkSources>,
        robots: &[Arc<ArmModel>],
        rep: &mut SoakReport,
    ) {
        rep.replays_checked += 1;
        let replayed = match folder {
            Some(f) => Session::replay_on(f, json, robots),
            None => Session::replay_with_robots(json, robots),
        };
        match replayed {
            Ok(r) if r.episode_json() == json => {}
            Ok(_) => {
                rep.replay_mismatches += 1;
                rep.find(self.finding(
                    self.s.tick(),
                    "replay",
                    "the replayed episode JSON differs".into(),
                ));
            }
            Err(err) => {
                rep.replay_mismatches += 1;
                rep.find(self.finding(self.s.tick(), "replay", format!("replay failed: {err}")));
            }
        }
    }
}
