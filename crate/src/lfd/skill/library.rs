//! The skill library: one learned skill per action schema and segment, and how a segment
//! without one moves.

use std::collections::BTreeMap;

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};

use crate::lqt::{Dmp, DmpParams, FeedbackController, Skill, SkillParams, Trajectory, ViaPoint};
use crate::sim::demo::DemoAction;
use crate::sim::{MotionKind, Motions};

use super::kind::SkillKind;
use super::stroke;

/// A demonstrated retreat is learned only when it ends within this distance of where it starts
/// (m): an object-centric lift, not a return to a home pose.
const LOCAL_RETREAT_SPAN: f64 = 0.2;

/// A measured TCP this far off a learned skill's commanded position is fed back to its
/// controller (m): a perturbation, not tracking lag.
const FEEDBACK_DEVIATION: f64 = 0.01;

/// Fewest samples a demonstrated segment needs to learn a skill from.
const MIN_SKILL_SAMPLES: usize = 8;

/// A learned motion skill of either family.
#[derive(Clone, Debug)]
pub enum LearnedSkill {
    /// LQT-CP (the paper's).
    Lqt(Box<Skill>),
    /// Classic DMP (the comparison).
    Dmp(Box<Dmp>),
}

impl LearnedSkill {
    /// Plans from `start` (world, at rest) for the object frame `object_pose`, through
    /// `via_points` (object frame; a DMP ignores them).
    pub fn plan(
        &self,
        start: &Point3<f64>,
        object_pose: &Isometry3<f64>,
        via_points: &[ViaPoint],
    ) -> Option<Trajectory> {
        match self {
            LearnedSkill::Lqt(s) => s.plan(start, object_pose, via_points).ok(),
            LearnedSkill::Dmp(d) => d.plan(start, object_pose, via_points).ok(),
        }
    }

    /// Learns a skill of family `kind` from `demo` (object frame) sampled every `dt`, an LQT-CP
    /// one with `params`.
    pub(super) fn learn(
        kind: SkillKind,
        demo: &[Point3<f64>],
        dt: f64,
        params: SkillParams,
    ) -> Option<LearnedSkill> {
        if demo.len() < MIN_SKILL_SAMPLES {
            return None;
        }
        match kind {
            SkillKind::Lqt => Skill::learn(demo, dt, params)
                .ok()
                .map(|s| LearnedSkill::Lqt(Box::new(s))),
            SkillKind::Dmp => Dmp::learn(demo, dt, DmpParams::default())
                .ok()
                .map(|d| LearnedSkill::Dmp(Box::new(d))),
        }
    }
}

/// The segments of an action a skill is learned for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SegmentKind {
    /// From the start to the gripper event (grasp or release point).
    Approach,
    /// From the gripper event on (a lift near the object).
    Retreat,
    /// A pull's descent behind the block and its drag (via-points: the block's far edges).
    Stroke,
}

impl SegmentKind {
    /// The segment's name in a skill key.
    pub fn as_str(self) -> &'static str {
        match self {
            SegmentKind::Approach => "approach",
            SegmentKind::Retreat => "retreat",
            SegmentKind::Stroke => "stroke",
        }
    }
}

/// The key of the skill of action schema `action`'s `segment`: `action/segment`, with `@hook`
/// when the action's object is a hook.
pub fn skill_key(action: &str, segment: SegmentKind, on_hook: bool) -> String {
    let hook = if on_hook { "@hook" } else { "" };
    format!("{action}/{}{hook}", segment.as_str())
}

/// One planned segment.
#[derive(Clone, Debug)]
pub enum SkillSegment {
    /// A precomputed position profile (one position per tick).
    Profile {
        /// Positions, the last is the goal.
        positions: Vec<Vector3<f64>>,
        /// Orientation at the start.
        start_rotation: UnitQuaternion<f64>,
    },
    /// A learned skill run in closed loop.
    Closed {
        /// The skill's feedback controller.
        ctrl: Box<FeedbackController>,
        /// The nominal motion's positions, one per tick (world); the last is its goal.
        nominal: Vec<Vector3<f64>>,
        /// Orientation at the start.
        start_rotation: UnitQuaternion<f64>,
    },
}

impl SkillSegment {
    /// A learned skill's planned trajectory run in closed loop from orientation
    /// `start_rotation`; `None` for an empty trajectory.
    pub fn closed(traj: &Trajectory, start_rotation: UnitQuaternion<f64>) -> Option<SkillSegment> {
        if traj.positions.is_empty() {
            return None;
        }
        Some(SkillSegment::Closed {
            nominal: traj.positions.iter().map(|p| p.coords).collect(),
            ctrl: Box::new(traj.controller()),
            start_rotation,
        })
    }

    /// The planned positions, one per tick: the profile, or a learned skill's nominal motion.
    fn path(&self) -> &[Vector3<f64>] {
        match self {
            SkillSegment::Profile { positions, .. } => positions,
            SkillSegment::Closed { nominal, .. } => nominal,
        }
    }

    /// Ticks of the nominal motion.
    pub fn len(&self) -> usize {
        self.path().len()
    }

    /// Whether the segment is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Orientation at the start.
    pub fn start_rotation(&self) -> UnitQuaternion<f64> {
        match self {
            SkillSegment::Profile { start_rotation, .. }
            | SkillSegment::Closed { start_rotation, .. } => *start_rotation,
        }
    }

    /// The commanded position for tick `t`; `measured` is the TCP now (fed back to a learned
    /// skill's controller when it is more than 1 cm off: a perturbation).
    pub fn command(&mut self, t: usize, measured: &Vector3<f64>) -> Vector3<f64> {
        match self {
            SkillSegment::Profile { positions, .. } => positions[t.min(positions.len() - 1)],
            SkillSegment::Closed { ctrl, .. } => {
                // The paper's u_t = −K̃_t x̃_t with the measured state, once it is a perturbation
                // rather than the joint tracker's lag. Feeding the lag back every tick restarts
                // each step from behind the plan: measured, it costs no success on blocks but
                // makes the learned hook stroke miss its block (B2 Table I 65 % instead of 100 %,
                // Fig. 4 0/3 pulls; docs/levels.md).
                let m = Point3::from(*measured);
                let off = (ctrl.position().coords - measured).norm() > FEEDBACK_DEVIATION;
                let fb = off.then_some(&m);
                ctrl.step(fb).coords
            }
        }
    }

    /// The planned position for tick `t` (of the nominal motion, for a learned skill): where
    /// the segment will take the hand when nothing disturbs it.
    pub fn planned(&self, t: usize) -> Vector3<f64> {
        let path = self.path();
        path[t.min(path.len() - 1)]
    }

    /// The current commanded position (for drawing).
    pub fn current(&self, t: usize) -> Vector3<f64> {
        match self {
            SkillSegment::Profile { positions, .. } => positions[t.min(positions.len() - 1)],
            SkillSegment::Closed { ctrl, .. } => ctrl.position().coords,
        }
    }

    /// Where the segment ends.
    pub fn goal(&self) -> Vector3<f64> {
        self.planned(usize::MAX)
    }

    /// The anchor moved: steer to its new frame. `false` if the segment cannot (re-plan it).
    pub fn retarget(&mut self, old: &Isometry3<f64>, new: &Isometry3<f64>) -> bool {
        match self {
            SkillSegment::Profile { .. } => false,
            SkillSegment::Closed { ctrl, nominal, .. } => {
                ctrl.retarget(new);
                let moved = new * old.inverse();
                for p in nominal.iter_mut() {
                    *p = (moved * Point3::from(*p)).coords;
                }
                true
            }
        }
    }
}

/// A learned skill with what it was learned for.
#[derive(Clone, Debug)]
pub(super) struct Entry {
    pub(super) skill: LearnedSkill,
    /// The declared motion of the action it was learned from.
    pub(super) motion: MotionKind,
    /// A stroke's demonstration and via-points (relative to the hook's contact pose).
    pub(super) stroke: Option<stroke::DemoStroke>,
}

/// The skills available to the executor, by [`skill_key`].
#[derive(Clone, Debug, Default)]
pub struct SkillLibrary {
    pub(super) skills: BTreeMap<String, Entry>,
}

/// The TCP positions of a demonstrated action's samples, in its anchor frame.
fn positions(a: &DemoAction) -> Vec<Point3<f64>> {
    a.samples
        .iter()
        .map(|s| Point3::new(s[0], s[1], s[2]))
        .collect()
}

/// The approach and retreat of a demonstrated grasp or release, split at its gripper event; the
/// retreat only when it stays near the object (in B3 the demo's retreat returns to the arm's
/// home pose: not object-centric, so it is a plain lift).
fn event_segments(a: &DemoAction) -> Vec<(SegmentKind, Vec<Point3<f64>>)> {
    let Some(ev) = a
        .gripper
        .iter()
        .find(|g| g.step > 0 && g.step < a.samples.len())
    else {
        return vec![];
    };
    let pts = positions(a);
    let mut out = vec![(SegmentKind::Approach, pts[..=ev.step].to_vec())];
    let retreat = &pts[ev.step..];
    let local = retreat
        .first()
        .zip(retreat.last())
        .is_some_and(|(a, b)| (a - b).norm() < LOCAL_RETREAT_SPAN);
    if local {
        out.push((SegmentKind::Retreat, retreat.to_vec()));
    }
    out
}

impl SkillLibrary {
    /// Learns the skills from a `demo.json` with trajectories (see `sim::demo`). A demo without
    /// trajectories (only `actions` names) gives an empty library (minimum-jerk motion).
    /// Actions whose anchor is one of `hooks` learn `…@hook` skills. What each action does comes
    /// from the domain's `motions`.
    pub fn learn(
        demo_json: &str,
        kind: SkillKind,
        hooks: &[String],
        motions: &Motions,
    ) -> SkillLibrary {
        let mut skills = BTreeMap::new();
        let Ok(demo) = crate::sim::demo::from_json(demo_json) else {
            return SkillLibrary { skills };
        };
        // The learned keys in demo order (the donors of undemonstrated schemas).
        let mut order = Vec::new();
        for a in &demo.actions {
            let Some(motion) = motions.actions.get(&a.name).map(|d| d.motion) else {
                continue;
            };
            let on_hook = hooks.contains(&a.anchor);
            let learn =
                |seg: &[Point3<f64>], params| LearnedSkill::learn(kind, seg, demo.dt, params);
            let learned: Vec<(SegmentKind, Entry)> = match motion {
                MotionKind::Grasp | MotionKind::Release => event_segments(a)
                    .into_iter()
                    .filter_map(|(segment, seg)| {
                        let skill = learn(&seg, SkillParams::default())?;
                        Some((
                            segment,
                            Entry {
                                skill,
                                motion,
                                stroke: None,
                            },
                        ))
                    })
                    .collect(),
                MotionKind::Pull => stroke::demo_stroke(a, demo.dt)
                    .and_then(|st| {
                        let skill = learn(&st.positions, stroke::params())?;
                        Some(vec![(
                            SegmentKind::Stroke,
                            Entry {
                                skill,
                                motion,
                                stroke: Some(st),
                            },
                        )])
                    })
                    .unwrap_or_default(),
                MotionKind::None => vec![],
            };
            for (segment, entry) in learned {
                let key = skill_key(&a.name, segment, on_hook);
                if let std::collections::btree_map::Entry::Vacant(slot) = skills.entry(key) {
                    order.push(slot.key().clone());
                    slot.insert(entry);
                }
            }
        }
        borrow_undemonstrated(&mut skills, &order, motions);
        SkillLibrary { skills }
    }

    /// The keys of the learned skills, in order.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.skills.keys().map(String::as_str)
    }

    /// The learned skill of `key`.
    pub fn get(&self, key: &str) -> Option<&LearnedSkill> {
        self.skills.get(key).map(|e| &e.skill)
    }

    /// Whether a learned skill exists for `key` ([`skill_key`]).
    pub fn has(&self, name: &str) -> bool {
        self.skills.contains_key(name)
    }

    /// Plans the segment of skill `name` from `start`: with a learned skill relative to `anchor` (the
    /// object frame: centre + yaw), else a minimum-jerk profile to `goal` over `steps` ticks.
    pub fn segment(
        &self,
        name: &str,
        start: &Isometry3<f64>,
        goal: &Isometry3<f64>,
        anchor: Option<&Isometry3<f64>>,
        steps: usize,
    ) -> SkillSegment {
        if let (Some(entry), Some(anchor)) = (self.skills.get(name), anchor) {
            let from = Point3::from(start.translation.vector);
            let closed = entry
                .skill
                .plan(&from, anchor, &[])
                .and_then(|traj| SkillSegment::closed(&traj, start.rotation));
            if let Some(seg) = closed {
                return seg;
            }
        }
        let x0 = start.translation.vector;
        let xt = goal.translation.vector;
        let n = steps.max(2);
        let positions = (1..=n)
            .map(|i| {
                let s = i as f64 / n as f64;
                let b = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
                x0 + (xt - x0) * b
            })
            .collect();
        SkillSegment::Profile {
            positions,
            start_rotation: start.rotation,
        }
    }
}

/// Gives every grasp or release schema of `motions` the demo does not show the skills (per
/// segment, plain and `@hook`) of the first demonstrated schema (`order`: the learned keys in
/// demo order) with the same declared motion.
fn borrow_undemonstrated(
    skills: &mut BTreeMap<String, Entry>,
    order: &[String],
    motions: &Motions,
) {
    for (name, decl) in &motions.actions {
        if !matches!(decl.motion, MotionKind::Grasp | MotionKind::Release) {
            continue;
        }
        for segment in [SegmentKind::Approach, SegmentKind::Retreat] {
            for on_hook in [false, true] {
                let key = skill_key(name, segment, on_hook);
                if skills.contains_key(&key) {
                    continue;
                }
                let suffix = skill_key("", segment, on_hook);
                let donor = order
                    .iter()
                    .filter(|k| k.ends_with(&suffix))
                    .filter_map(|k| skills.get(k))
                    .find(|e| e.motion == decl.motion)
                    .cloned();
                if let Some(e) = donor {
                    skills.insert(key, e);
                }
            }
        }
    }
}
