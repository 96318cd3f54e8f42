//! One closed-loop episode (`logic-lfd run`): a [`Session`] stepped to the end, with one
//! disturbance injected at a seeded moment.
//!
//! The moment is drawn from the seed: action `j ~ U{1, …, N − 2}` (N = demonstration length),
//! then either *during* action j + 1, `d ~ U{0.2 s, …, 1 s}` into it while the arm moves (L1
//! always: the approached body moved or the hand pushed, paper §IV-B's motion-level
//! disturbance; L2–L4 by a seeded coin), or at the first idle moment after action j. A
//! mid-motion injection whose action ends first waits for the next action; one that cannot be
//! produced falls back to the next idle moment, and an idle one that cannot to the next action
//! boundary; an episode that ends first says so ([`EpisodeReport::not_injected`]).
//!
//! What a disturbance cost is measured against the same episode run undisturbed: the time lost,
//! and for a mid-motion one the largest distance of the TCP from the undisturbed run's path of
//! that action after the hit ([`MotionEffect`]).

use serde::{Deserialize, Serialize};

use crate::lfd::Level;
use crate::lfd::{FailReason, Replan};
use nalgebra::Vector3;

use crate::lfd::{
    mix_seed, sources_for, EpisodeLog, Injection, Session, SessionError, SessionOptions,
    SessionParams, SkillKind,
};
use crate::lfd::{Method, Mode};
use crate::plan::Clock;
use crate::sim::ArmModel;
use crate::sim::{Benchmark, BenchmarkSources};
use std::sync::Arc;

/// The draw of the episode's seed that picks the action after which the disturbance comes.
const INJECT_AFTER_DRAW: u64 = 77;
/// The draw that picks how far into the action a mid-motion disturbance comes.
const INJECT_DELAY_DRAW: u64 = 78;
/// The draw that decides whether an L2–L4 disturbance comes mid-motion or at an idle moment.
const MID_MOTION_DRAW: u64 = 79;
/// Ticks into an action at which a mid-motion disturbance comes (10 ms ticks: 0.2–1 s).
const INJECT_DELAY_TICKS: std::ops::Range<u64> = 20..100;

/// What to run.
#[derive(Clone, Debug, PartialEq)]
pub struct EpisodeSpec {
    /// Benchmark.
    pub benchmark: Benchmark,
    /// Disturbance injected during execution (`None`: undisturbed).
    pub level: Option<Level>,
    /// Method.
    pub method: Method,
    /// Multi-goal mode (Logic-LfD).
    pub mode: Mode,
    /// Seed of the episode.
    pub seed: u64,
    /// Initial scene JSON (`None`: the benchmark's template scene).
    pub scene: Option<String>,
    /// Robots in place of the scene's arms: none (the scene's own), one for every arm, or one
    /// per arm ([`Session::set_robots`]).
    pub robots: Vec<Arc<ArmModel>>,
}

/// What an episode did.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeReport {
    /// The goal holds at the end.
    pub success: bool,
    /// Why not.
    pub reason: Option<FailReason>,
    /// Actions executed with their effect.
    pub actions_executed: usize,
    /// Replans (the initial plan included).
    pub replans: usize,
    /// Planning time of every replan (ms, caller's clock).
    pub planning_ms: Vec<f64>,
    /// Simulated execution time (s).
    pub execution_s: f64,
    /// The injected disturbance.
    pub injection: Option<Injection>,
    /// Why a disturbance was asked for and never injected (the last refusal, or the episode
    /// ended first).
    #[serde(default)]
    pub not_injected: Option<String>,
    /// Simulated time lost to the disturbance (s): `execution_s` minus that of the same
    /// episode run undisturbed (when both reached the goal).
    #[serde(default)]
    pub time_lost_s: Option<f64>,
    /// What a disturbance that hit a moving arm did to its motion.
    #[serde(default)]
    pub motion: Option<MotionEffect>,
    /// The full log (replays exactly).
    pub log: EpisodeLog,
}

/// What a mid-motion disturbance did to the motion it hit, against the undisturbed run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MotionEffect {
    /// The action it hit.
    pub action: String,
    /// The arm executing it.
    pub arm: String,
    /// The tick it came at.
    pub tick: u64,
    /// Largest distance of the TCP from the undisturbed run's TCP path of this action, from the
    /// hit to the action's end (mm): the deviation the skill's feedback absorbed.
    pub deviation_mm: f64,
    /// Extra simulated time the action took (s, against the undisturbed run).
    pub action_time_lost_s: f64,
}

impl EpisodeReport {
    /// Planning time of the first plan (ms).
    pub fn first_plan_ms(&self) -> Option<f64> {
        self.planning_ms.first().copied()
    }

    /// The replans after the first.
    pub fn replans_after_start(&self) -> &[Replan] {
        self.log.replans.get(1..).unwrap_or(&[])
    }
}

/// Runs one episode to its end (at most `params.max_time` simulated seconds).
pub fn run_episode(
    spec: &EpisodeSpec,
    params: SessionParams,
    clock: &dyn Clock,
) -> Result<EpisodeReport, SessionError> {
    run_episode_with_blocks(spec, None, params, clock)
}

/// [`run_episode`] on the benchmark's generated tower task with `blocks` blocks (`None`: the
/// template task).
pub fn run_episode_with_blocks(
    spec: &EpisodeSpec,
    blocks: Option<usize>,
    params: SessionParams,
    clock: &dyn Clock,
) -> Result<EpisodeReport, SessionError> {
    let sources = sources_for(spec.benchmark, blocks)?;
    episode(spec, &sources, blocks, params, clock)
}

/// [`run_episode`] on other files: a domain of its own (its PDDL, demonstration and
/// `motions.json`) in the benchmark's workcell, with the benchmark's disturbances.
pub fn run_episode_with(
    spec: &EpisodeSpec,
    sources: &BenchmarkSources,
    params: SessionParams,
    clock: &dyn Clock,
) -> Result<EpisodeReport, SessionError> {
    episode(spec, sources, None, params, clock)
}

fn episode(
    spec: &EpisodeSpec,
    sources: &BenchmarkSources,
    blocks: Option<usize>,
    params: SessionParams,
    clock: &dyn Clock,
) -> Result<EpisodeReport, SessionError> {
    let run = drive(spec, sources, blocks, params, clock)?;
    let s = &run.session;
    let log = s.log();
    let (success, reason) = match s.outcome() {
        Some(Ok(())) => (true, None),
        Some(Err(r)) => (false, Some(r.clone())),
        None => (
            false,
            Some(FailReason::Budget {
                what: "simulated time".into(),
            }),
        ),
    };
    let mut report = EpisodeReport {
        success,
        reason,
        actions_executed: s.actions_done(),
        replans: log.replans.len(),
        planning_ms: log.replans.iter().map(|r| r.time_ms).collect(),
        execution_s: s.world().time(),
        injection: run.injection.clone(),
        not_injected: run.not_injected.clone(),
        time_lost_s: None,
        motion: None,
        log,
    };
    if report.injection.is_some() {
        let undisturbed = EpisodeSpec {
            level: None,
            ..spec.clone()
        };
        let calm = drive(&undisturbed, sources, blocks, params, clock)?;
        if success && calm.session.outcome().is_some_and(|o| o.is_ok()) {
            report.time_lost_s = Some(report.execution_s - calm.session.world().time());
        }
        report.motion = motion_effect(&run, &calm);
    }
    Ok(report)
}

/// A driven episode: the session at its end, what was injected, and every arm's TCP after each
/// tick (`tcp[t]`: after tick t; `tcp[0]`: at the start).
struct Driven {
    session: Session,
    injection: Option<Injection>,
    not_injected: Option<String>,
    /// A mid-motion injection: its tick, the arm it hit and the TCPs right after it.
    hit: Option<(u64, usize, Vec<[f64; 3]>)>,
    tcp: Vec<Vec<[f64; 3]>>,
}

fn tcps(s: &Session) -> Vec<[f64; 3]> {
    let w = s.world();
    (0..w.arm_names().len())
        .map(|a| {
            w.tcp_pose(a)
                .map_or([0.0; 3], |p| p.translation.vector.into())
        })
        .collect()
}

/// When the episode's disturbance comes (see the module header).
struct Schedule {
    /// Action boundary after which it comes at the first idle moment.
    next_try: usize,
    /// Mid-motion first: ticks into an action once `next_try` actions are done.
    delay: Option<u64>,
}

impl Schedule {
    fn new(spec: &EpisodeSpec, n: usize) -> Schedule {
        let n = n.max(3) as u64;
        let after = 1 + (mix_seed(spec.seed, INJECT_AFTER_DRAW) % (n - 2)) as usize;
        let span = INJECT_DELAY_TICKS.end - INJECT_DELAY_TICKS.start;
        let mid = spec.level == Some(Level::L1) || mix_seed(spec.seed, MID_MOTION_DRAW) % 2 == 0;
        Schedule {
            next_try: after,
            delay: mid
                .then(|| INJECT_DELAY_TICKS.start + mix_seed(spec.seed, INJECT_DELAY_DRAW) % span),
        }
    }

    /// Whether to try now (never once the plan's last action is done: the goal holds then).
    fn due(&self, s: &Session) -> bool {
        let c = s.controller();
        if s.actions_done() < self.next_try || c.cursor() >= c.plan_ops().len() {
            return false;
        }
        match self.delay {
            Some(d) => s.moving().is_some() && s.action_ticks().is_some_and(|t| t >= d),
            None => !s.is_executing(),
        }
    }

    /// The try failed: a mid-motion one falls back to the next idle moment, an idle one to the
    /// next action boundary.
    fn refused(&mut self, s: &Session) {
        if self.delay.take().is_none() {
            self.next_try = s.actions_done() + 1;
        }
    }
}

fn drive(
    spec: &EpisodeSpec,
    sources: &BenchmarkSources,
    blocks: Option<usize>,
    params: SessionParams,
    clock: &dyn Clock,
) -> Result<Driven, SessionError> {
    let options = SessionOptions {
        benchmark: spec.benchmark,
        method: spec.method,
        mode: spec.mode,
        seed: spec.seed,
        skill: SkillKind::Lqt,
        blocks,
    };
    let mut s = Session::with_sources(options, sources, spec.scene.as_deref(), None, params)?;
    s.set_robots(&spec.robots)?;
    let mut schedule = Schedule::new(spec, s.controller().trace().len());
    let mut tcp = vec![tcps(&s)];
    let mut injection: Option<Injection> = None;
    let mut not_injected = spec.level.map(|_| "the episode ended first".to_string());
    let mut hit = None;
    let max_ticks = (params.max_time / s.world().dt()).ceil() as u64 + 10;
    for _ in 0..max_ticks {
        if s.outcome().is_some() {
            break;
        }
        if let Some(level) = spec.level {
            if injection.is_none() && schedule.due(&s) {
                let moving = s.moving();
                match s.inject(level.as_str()) {
                    Ok(i) => {
                        hit = moving
                            .filter(|_| i.during.is_some())
                            .map(|m| (s.tick(), m.arm, tcps(&s)));
                        injection = Some(i);
                        not_injected = None;
                    }
                    Err(e) => {
                        not_injected = Some(e.to_string());
                        schedule.refused(&s);
                    }
                }
            }
        }
        let before = s.tick();
        s.tick_once(clock);
        if s.tick() > before {
            tcp.push(tcps(&s));
        }
    }
    Ok(Driven {
        session: s,
        injection,
        not_injected,
        hit,
        tcp,
    })
}

/// The TCP's largest distance, from the hit to the end of the action hit, from the undisturbed
/// run's TCP path of the same action (a polyline), and the extra time the action took.
fn motion_effect(run: &Driven, calm: &Driven) -> Option<MotionEffect> {
    let (tick, arm, at_hit) = run.hit.as_ref()?;
    let arm = *arm;
    let inj = run.injection.as_ref().filter(|i| i.level == Level::L1)?;
    let action = inj.during.clone()?;
    let log = run.session.log();
    let calm_log = calm.session.log();
    let i = log
        .actions
        .iter()
        .position(|a| a.start_tick <= *tick && a.end_tick.is_none_or(|e| *tick < e))?;
    let rec = &log.actions[i];
    let other = calm_log.actions.get(i).filter(|a| a.action == rec.action)?;
    let arm_name = run.session.world().arm_names().get(arm)?.to_string();
    let path = |d: &Driven, from: u64, to: Option<u64>| -> Vec<Vector3<f64>> {
        let end = to.map_or(d.tcp.len(), |e| (e as usize + 1).min(d.tcp.len()));
        d.tcp[(from as usize).min(end)..end]
            .iter()
            .filter_map(|t| t.get(arm).map(|p| Vector3::from(*p)))
            .collect()
    };
    let nominal = path(calm, other.start_tick, other.end_tick);
    if nominal.is_empty() {
        return None;
    }
    let mut after = vec![Vector3::from(*at_hit.get(arm)?)];
    after.extend(path(run, *tick + 1, rec.end_tick));
    let deviation = after
        .iter()
        .map(|p| distance_to_path(p, &nominal))
        .fold(0.0, f64::max);
    let ticks = |a: &crate::lfd::ActionRecord| {
        a.end_tick
            .unwrap_or(a.start_tick)
            .saturating_sub(a.start_tick) as f64
    };
    Some(MotionEffect {
        action,
        arm: arm_name,
        tick: *tick,
        deviation_mm: deviation * 1e3,
        action_time_lost_s: (ticks(rec) - ticks(other)) * run.session.world().dt(),
    })
}

/// Distance from `p` to the polyline `path` (not empty).
fn distance_to_path(p: &Vector3<f64>, path: &[Vector3<f64>]) -> f64 {
    if path.len() == 1 {
        return (p - path[0]).norm();
    }
    path.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let ab = b - a;
            let l2 = ab.norm_squared();
            let t = if l2 > 0.0 {
                ((p - a).dot(&ab) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p - (a + ab * t)).norm()
        })
        .fold(f64::INFINITY, f64::min)
}
