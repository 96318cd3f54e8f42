//! Streams: samplers of an action's continuous parameters, each sample certified before use.
//!
//! For a skeleton a_1..a_n the binder rolls the geometric state forward (body poses, each arm's
//! TCP pose and joint angles, what each arm holds and with which grasp) and, per action,
//!
//! ```text
//!   grasp x by r:        g = top grasp of x (yaw ∈ yaw_x + k·π/2, closest to the arm's heading)
//!                        certify the motion  tcp → g + h·ẑ → g → g + l·ẑ
//!   release x on y:      p = x centred on y's top, tcp(p) = p · G⁻¹ (G: the held grasp)
//!                        certify  x@p ∩ others = ∅  and the motion  tcp → tcp(p) + h·ẑ → tcp(p) → up
//!   release x on a surface (table / shelf / region R):
//!                        sample (u, v) ~ U(top face ∩ R ∩ reach annulus of r), yaw ~ U{0, π/2}
//!                        certify as above; hand-over spots also graspable by every other arm
//!   pull x with hook:    (contact, pulled) = sim::demo::pull_hook_poses(base, x, PULL_TARGET_RADIUS)
//!                        (the executor's own stroke); certify the stroke's motion; predict x's
//!                        new pose by a parry shape cast of the hook along the stroke
//!                        (x moves by d·(1 − toi)), then cast x along its push: it may hit nothing
//!                        and must end on the table inside r's reach annulus
//! ```
//!
//! **Certifying a motion.** The TCP path through the via-points (the executor's phases,
//! `lfd::exec`: approach from above, the gripper event, the retreat up) is sampled every
//! `path_step` (1.5 cm). At each sample the arm's joints come from damped-least-squares IK
//! warm-started at the previous sample *without restarts* — what the simulator's joint tracker
//! can follow: between via-points it may lag behind the path (the links are checked where the
//! tracker leaves them), at a via-point it must converge (the executor fails an action whose
//! arm cannot reach its via-point). The arm's link capsules and the carried body (at `tcp · G`) are tested with parry
//! against every other body (tables, shelf, free blocks, the hook, bodies carried by other arms),
//! shrunk by `contact_slack` so resting contacts do not count. Arms do not collide with each
//! other in the simulator (the demonstrated hand-over has one gripper above the other), so
//! arm–arm contact is not tested.
//!
//! **Transits.** When an action's approach (from where the arm is to its pre-grasp, pre-release
//! or pre-stroke pose) hits something, it is certified again as a transit: straight up to the
//! TCP height `z` of `tamp::transit_height` (what the arm carries 3 cm above every top
//! between the two), across, straight down. The binding records `z` and the executor flies
//! exactly that (`ActionExec::with_transit`).
//!
//! A skeleton fails at the first action for which no sample (within the budget) is certified.
//! Actions from the demonstration's suffix (Logic-LfD) skip certification: their motion comes from
//! the demonstrated skills re-targeted to the objects, only their surface placements are sampled.
//! Pulls are the exception: their stroke is computed, not demonstrated, so it is certified.
//!
//! One file per stage: `certify` (a motion), `grasp`, `place` (releases on blocks and
//! surfaces), `pull`; `obstacles` holds the predicted scene's boxes; this file the binder, its
//! rolled-forward state and the walk along a skeleton.

use std::collections::{BTreeMap, BTreeSet};

use nalgebra::{Isometry3, Vector3};
use parry3d_f64::shape::Cuboid;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;

use super::action::{classify, release_target, ActionKind, Binding, Placement, PlanarPose};
use super::motion::{rise_before_action, MotionParams, Scene};
use super::{BindFailure, Binder};
use crate::plan::{Operator, Task};
use crate::sim::demo::PULL_LIFT;
use crate::sim::panda::DOF;
use crate::sim::BodyKind;
use crate::sim::World;
use crate::sim::{ArmModel, IkParams};

mod boxes;
mod certify;
mod grasp;
mod obstacles;
mod place;
mod pull;

use boxes::{box_aabb, FixedBody};

/// Tunables of the streams.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StreamParams {
    /// Samples drawn per surface placement before the action is declared unbindable.
    pub placement_samples: usize,
    /// The heights of the motions certified (the executor's: the session passes the same).
    pub motion: MotionParams,
    /// Height of the hook above its contact and pulled poses at the ends of a stroke (m).
    pub pull_lift: f64,
    /// Spacing of the samples along a certified TCP path (m).
    pub path_step: f64,
    /// IK iterations per path sample (warm start, no restarts: the joint tracker's view).
    pub path_ik_iterations: usize,
    /// IK iterations at a via-point (the tracker's settle time; warm start, no restarts).
    pub settle_ik_iterations: usize,
    /// Shapes are shrunk by this before collision tests, so touching faces do not count (m).
    pub contact_slack: f64,
    /// Free space kept around a placed body (m).
    pub clearance: f64,
    /// Free space kept around a carried body on its way to a placement's approach pose (m):
    /// the learned skill's path deviates from the straight line the streams check.
    pub transfer_margin: f64,
    /// Other certified spots tried per surface placement when a later action of the skeleton
    /// cannot be bound (backtracking).
    pub max_alternatives: usize,
    /// How far beyond the placing arm's minimum reach (the inner edge of its reach annulus) a
    /// block is put down (m): there the elbow folds to its limit, the joint tracker stalls at
    /// it, and a tower built on the block rises in the same column.
    pub placement_inner_margin: f64,
    /// Certifications one binding of a skeleton may spend on backtracking.
    pub certification_budget: usize,
}

impl Default for StreamParams {
    fn default() -> Self {
        StreamParams {
            placement_samples: 48,
            motion: MotionParams::default(),
            pull_lift: PULL_LIFT,
            path_step: 0.015,
            path_ik_iterations: 30,
            settle_ik_iterations: 300,
            contact_slack: 0.002,
            clearance: 0.008,
            transfer_margin: 0.015,
            max_alternatives: 3,
            placement_inner_margin: 0.05,
            certification_budget: 400,
        }
    }
}

/// Counters of a binder's work (for reports and tests).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StreamStats {
    /// Path samples checked (IK + collision tests).
    pub path_samples: usize,
    /// Candidates rejected because the arm cannot track the path.
    pub rejected_ik: usize,
    /// Candidates rejected for a collision along the path or at the placement.
    pub rejected_collision: usize,
    /// Pulls rejected by the shape-cast prediction.
    pub rejected_pull: usize,
    /// Transits tried after a straight approach was blocked.
    pub transits: usize,
}

/// The rolled-forward geometric state of a skeleton.
#[derive(Clone, Debug)]
struct Geo {
    /// Every movable body (held ones where they are carried).
    poses: BTreeMap<String, Isometry3<f64>>,
    /// What each arm that holds something holds.
    held: BTreeMap<usize, Held>,
    /// TCP pose per arm.
    tcp: Vec<Isometry3<f64>>,
    /// Joint angles per arm.
    q: Vec<[f64; DOF]>,
}

impl Geo {
    /// Whether an arm holds `body`.
    fn is_held(&self, body: &str) -> bool {
        self.held.values().any(|h| h.body == body)
    }
}

/// What an arm carries: the body and its pose in the TCP frame.
#[derive(Clone, Debug)]
struct Held {
    body: String,
    grasp: Isometry3<f64>,
}

/// Binds skeletons against a world with certified samples.
pub struct StreamBinder<'w> {
    world: &'w World,
    fixed: Vec<FixedBody>,
    /// Boxes of every movable body in its own frame.
    local: BTreeMap<String, Vec<(Isometry3<f64>, Cuboid)>>,
    regions: Vec<crate::sim::RegionSnapshot>,
    reach: Vec<crate::sim::ReachSnapshot>,
    rng: Pcg64Mcg,
    params: StreamParams,
    track_ik: IkParams,
    settle_ik: IkParams,
    /// Certifications (IK + collision tests of a candidate) done so far.
    pub certifications: usize,
    /// Why the last rejected candidate was rejected, in words (for failure reports).
    last_rejection: Option<String>,
    /// The movable bodies in the way of the candidate being certified (the last rejections').
    last_blockers: Vec<String>,
    /// The action (index into the skeleton) being bound.
    action: usize,
    /// Per action of the last skeleton: the movable bodies that blocked its candidates.
    blockers: BTreeMap<usize, BTreeSet<String>>,
    /// Backtracking stops once `certifications` passes this (set per skeleton).
    budget_end: usize,
    /// How far [`Binder::widen`] may raise `placement_samples`: [`WIDEN_LIMIT`] times the
    /// initial count (one replan may try up to twice `max_skeletons` skeletons; unbounded
    /// doubling drew millions of spots per placement).
    widest_placement_samples: usize,
    /// What the certifications did.
    pub stats: StreamStats,
    /// Poses of the movable bodies after the last successfully bound skeleton (predicted).
    predicted: BTreeMap<String, Isometry3<f64>>,
    /// Placements the demonstration used, by action `(…)`: where the resting body's centre
    /// was; by body name: where the demonstration's scene had it.
    hints: BTreeMap<String, PlanarPose>,
}

impl<'w> StreamBinder<'w> {
    /// A binder over `world` drawing samples from `seed`.
    pub fn new(world: &'w World, seed: u64, params: StreamParams) -> Self {
        let snap = world.snapshot();
        let fixed = snap
            .bodies
            .iter()
            .filter(|b| matches!(b.kind, BodyKind::Table | BodyKind::Shelf))
            .map(|b| FixedBody {
                name: b.name.clone(),
                kind: b.kind,
                parts: world.body_shapes(&b.name),
            })
            .collect();
        let local = snap
            .bodies
            .iter()
            .filter(|b| matches!(b.kind, BodyKind::Block | BodyKind::Hook) && !b.lost)
            .filter_map(|b| {
                let cur = world.body_pose(&b.name)?;
                let parts = world
                    .body_shapes(&b.name)
                    .into_iter()
                    .map(|(iso, c)| (cur.inverse() * iso, c))
                    .collect();
                Some((b.name.clone(), parts))
            })
            .collect();
        let track_ik = IkParams {
            max_iterations: params.path_ik_iterations,
            restarts: 0,
            ..world.params().planning_ik.clone()
        };
        let settle_ik = IkParams {
            max_iterations: params.settle_ik_iterations,
            ..track_ik.clone()
        };
        StreamBinder {
            settle_ik,
            world,
            fixed,
            local,
            regions: snap.regions.clone(),
            reach: snap.arms.iter().map(|a| a.reach.clone()).collect(),
            rng: Pcg64Mcg::seed_from_u64(seed),
            params,
            track_ik,
            certifications: 0,
            last_rejection: None,
            last_blockers: vec![],
            action: 0,
            blockers: BTreeMap::new(),
            budget_end: 0,
            widest_placement_samples: params.placement_samples.saturating_mul(WIDEN_LIMIT),
            stats: StreamStats::default(),
            predicted: BTreeMap::new(),
            hints: BTreeMap::new(),
        }
    }

    /// Placements to try first: by action `(…)` (the demonstration's placement for it), else by
    /// the name of the body put down (where the demonstration had it).
    pub fn with_hints(mut self, hints: &BTreeMap<String, PlanarPose>) -> Self {
        self.hints = hints.clone();
        self
    }

    /// The parameters in use.
    pub fn params(&self) -> &StreamParams {
        &self.params
    }

    /// Where the last successfully bound skeleton leaves `body` (a block or the hook).
    pub fn predicted_pose(&self, body: &str) -> Option<Isometry3<f64>> {
        self.predicted.get(body).copied()
    }

    /// The geometric state of the world now, as a skeleton's binding starts from it.
    fn geo(&self) -> Geo {
        let mut poses = BTreeMap::new();
        for name in self.local.keys() {
            if let Some(p) = self.world.body_pose(name) {
                poses.insert(name.clone(), p);
            }
        }
        let n = self.world.arm_names().len();
        let mut held = BTreeMap::new();
        for a in 0..n {
            if let (Some(h), Some(g)) = (self.world.held_by(a), self.world.grasp_transform(a)) {
                held.insert(
                    a,
                    Held {
                        body: h.to_string(),
                        grasp: g,
                    },
                );
            }
        }
        Geo {
            poses,
            held,
            tcp: (0..n)
                .map(|a| self.world.tcp_pose(a).unwrap_or_else(Isometry3::identity))
                .collect(),
            q: (0..n)
                .map(|a| self.world.joints(a).unwrap_or(ArmModel::panda().ready()))
                .collect(),
        }
    }

    fn arm_name(&self, arm: usize) -> String {
        self.world
            .arm_names()
            .get(arm)
            .map(|s| s.to_string())
            .unwrap_or_else(|| format!("#{arm}"))
    }

    /// Binds the skeleton's actions from `i` on from the geometric state `geo`, pushing one
    /// binding per action onto `out`. Surface placements are choice points
    /// ([`StreamBinder::bind_on_surface`]). Err: the index of the deepest action that could not
    /// be bound.
    fn bind_from(
        &mut self,
        sk: &Skeleton,
        i: usize,
        mut geo: Geo,
        out: &mut Vec<Binding>,
    ) -> Result<Geo, usize> {
        let Some(&o) = sk.ops.get(i) else {
            return Ok(geo);
        };
        let op = &sk.task.operators[o];
        self.action = i;
        let Some(kind) = classify(op, self.world) else {
            out.push(Binding::default());
            return self.bind_from(sk, i + 1, geo, out);
        };
        // A pull is certified even in the demonstration's suffix: its stroke is computed from
        // the block's pose, not demonstrated, and the 40 cm hook sweeps past other blocks.
        let certify = i < sk.demo_from || matches!(kind, ActionKind::Pull { .. });
        let binding = match kind {
            ActionKind::Grasp { arm, body } => {
                self.begin_candidate();
                let Some(transit) = self.grasp(&mut geo, arm, &body, certify) else {
                    self.candidate_failed();
                    return Err(i);
                };
                Binding {
                    placement: None,
                    transit,
                    hand_yaw: None,
                }
            }
            ActionKind::Release {
                arm,
                body,
                placement: Some(Placement::OnBlock(y)),
            } => {
                let Some(pose) = self.on_block_pose(&geo, &body, &y) else {
                    return Err(i);
                };
                self.begin_candidate();
                let Some((transit, hand_yaw)) = self.release(&mut geo, arm, &pose, certify) else {
                    self.candidate_failed();
                    return Err(i);
                };
                Binding {
                    transit,
                    placement: Some(Placement::OnBlock(y)),
                    hand_yaw,
                }
            }
            ActionKind::Release { arm, body, .. } => {
                return self.bind_on_surface(sk, i, arm, &body, certify, geo, out);
            }
            ActionKind::Pull { arm, body, .. } => {
                let (turn, transit) = self.pull(&mut geo, arm, &body, certify).ok_or(i)?;
                Binding {
                    placement: Some(Placement::Stroke(turn)),
                    transit,
                    hand_yaw: None,
                }
            }
        };
        out.push(binding);
        self.bind_from(sk, i + 1, geo, out)
    }

    /// Binds action `i` of the skeleton, `arm` putting `body` down on a surface, and the
    /// actions after it: a choice point. When a later action cannot be bound, up to
    /// `max_alternatives` other certified spots are tried (depth first) while the certification
    /// budget lasts. Err: the index of the deepest action that could not be bound.
    #[allow(clippy::too_many_arguments)]
    fn bind_on_surface(
        &mut self,
        sk: &Skeleton,
        i: usize,
        arm: usize,
        body: &str,
        certify: bool,
        geo: Geo,
        out: &mut Vec<Binding>,
    ) -> Result<Geo, usize> {
        let op = &sk.task.operators[sk.ops[i]];
        let surfaces = release_target(op, self.world)
            .map(|t| self.surfaces(&t, body))
            .unwrap_or_default();
        // The demonstration's placement for this action, else where it had the body.
        let hint = self
            .hints
            .get(&op.name)
            .or_else(|| self.hints.get(body))
            .copied();
        let candidates = self.surface_candidates(&geo, arm, &surfaces, hint);
        let mut deepest = i;
        let mut certified = 0;
        for c in candidates {
            if certified > self.params.max_alternatives || self.certifications > self.budget_end {
                break;
            }
            let Some((next, transit, hand_yaw)) = self.try_surface(&geo, arm, c, hint, certify)
            else {
                continue;
            };
            certified += 1;
            out.push(Binding {
                placement: Some(Placement::At {
                    x: c.at.x,
                    y: c.at.y,
                    yaw: c.at.yaw,
                }),
                transit,
                hand_yaw,
            });
            match self.bind_from(sk, i + 1, next, out) {
                Ok(end) => return Ok(end),
                Err(j) => {
                    deepest = deepest.max(j);
                    out.truncate(i);
                }
            }
        }
        Err(deepest)
    }
}

/// The rolled-forward state `geo` as the motion policy's scene: tops are those of the
/// obstacles (shrunk by the contact slack), a load's extent that of its boxes where it is
/// carried.
struct Predicted<'a, 'w> {
    binder: &'a StreamBinder<'w>,
    geo: &'a Geo,
}

impl Scene for Predicted<'_, '_> {
    fn tcp(&self, arm: usize) -> Option<Isometry3<f64>> {
        self.geo.tcp.get(arm).copied()
    }

    fn load_aabb(&self, arm: usize) -> Option<Option<(Vector3<f64>, Vector3<f64>)>> {
        let geo = self.geo;
        Some(geo.held.get(&arm).map(|h| {
            self.binder
                .parts_at(&h.body, &(geo.tcp[arm] * h.grasp))
                .iter()
                .fold(
                    (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN)),
                    |(lo, hi), (iso, c)| {
                        let (l, h) = box_aabb(iso, c);
                        (lo.inf(&l), hi.sup(&h))
                    },
                )
        }))
    }

    fn highest_top_in(&self, arm: usize, lo: [f64; 2], hi: [f64; 2]) -> f64 {
        self.binder
            .obstacles(self.geo, arm, &[])
            .iter()
            .filter(|o| o.lo.x <= hi[0] && o.hi.x >= lo[0] && o.lo.y <= hi[1] && o.hi.y >= lo[1])
            .fold(f64::MIN, |m, o| m.max(o.hi.z))
    }

    fn boxes_except(&self, body: &str) -> Vec<(Isometry3<f64>, Cuboid)> {
        self.binder.boxes_except(self.geo, body)
    }
}

/// A skeleton being bound: the operators of `task`, the demonstration's from `demo_from` on.
struct Skeleton<'a> {
    task: &'a Task,
    ops: &'a [usize],
    demo_from: usize,
}

/// A point in millimetres, for messages.
fn fmt_point(p: &Vector3<f64>) -> String {
    format!("({:.0}, {:.0}, {:.0}) mm", p.x * 1e3, p.y * 1e3, p.z * 1e3)
}

/// [`Binder::widen`] raises the samples per placement to at most this many times the initial.
pub const WIDEN_LIMIT: usize = 16;

/// The TCP height of the transit an action's approach needs (`None`: straight is clear).
type Transit = Option<f64>;

impl Binder for StreamBinder<'_> {
    fn bind(
        &mut self,
        task: &Task,
        ops: &[usize],
        demo_from: usize,
    ) -> Result<Vec<Binding>, BindFailure> {
        let mut geo = self.geo();
        // An empty hand down among bodies rises first (as the executor's next action does).
        for arm in 0..geo.tcp.len() {
            if let Some(up) = rise_before_action(self.world, arm, &self.params.motion) {
                if let Ok(q) = self.certify_path(&geo, arm, &[up], &[], 0.0) {
                    geo.q[arm] = q;
                }
                geo.tcp[arm] = up;
            }
        }
        let mut out = Vec::with_capacity(ops.len());
        self.last_rejection = None;
        self.blockers.clear();
        self.budget_end = self.certifications + self.params.certification_budget;
        let sk = Skeleton {
            task,
            ops,
            demo_from,
        };
        match self.bind_from(&sk, 0, geo, &mut out) {
            Ok(end) => {
                self.predicted = end.poses;
                Ok(out)
            }
            Err(action) => Err(BindFailure {
                action,
                reason: self.last_rejection.clone(),
                blockers: self
                    .blockers
                    .get(&action)
                    .map(|b| b.iter().cloned().collect())
                    .unwrap_or_default(),
            }),
        }
    }

    fn widen(&mut self) {
        self.params.placement_samples =
            (self.params.placement_samples * 2).min(self.widest_placement_samples);
    }

    fn moves_body(&self, op: &Operator, body: &str) -> bool {
        super::action::moves_body(self.world.motions(), op, body)
    }
}
