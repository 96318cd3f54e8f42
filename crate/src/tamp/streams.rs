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
//! TCP height `z` of `sim::geometry::transit_z` (what the arm carries 3 cm above every top
//! between the two), across, straight down. The binding records `z` and the executor flies
//! exactly that (`ActionExec::with_transit`).
//!
//! A skeleton fails at the first action for which no sample (within the budget) is certified.
//! Actions from the demonstration's suffix (Logic-LfD) skip certification: their motion comes from
//! the demonstrated skills re-targeted to the objects, only their surface placements are sampled.
//! Pulls are the exception: their stroke is computed, not demonstrated, so it is certified.

use std::collections::{BTreeMap, BTreeSet};

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::query;
use parry3d_f64::shape::{Capsule, Cuboid, Shape};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::action::{classify, ActionKind, Binding, Placement, PlanarPose};
use super::motion::NEAR_RECOVERY_FRACTIONS;
use super::{BindFailure, Binder};
use crate::plan::{fact_args, Task};
use crate::sim::demo::{pull_hook_poses_turned, PULL_LIFT, PULL_TARGET_RADIUS, PULL_TURNS};
use crate::sim::geometry::{
    clear_grasp_at, grasp_pose_at, hand_within, link_capsules, quarter_turns, raised, rise_first,
    transit_z,
};
use crate::sim::panda::{self, IkParams, DOF};
use crate::sim::snapshot::BodyKind;
use crate::sim::{yaw_of, World, LINK_TOLERANCE};

/// Tunables of the streams.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StreamParams {
    /// Samples drawn per surface placement before the action is declared unbindable.
    pub placement_samples: usize,
    /// Height of the approach pose above grasps and placements, and of the retreat after a
    /// release (m); the session keeps it equal to the executor's.
    pub approach_height: f64,
    /// Height the held body is lifted to after a grasp (m); kept equal to the executor's.
    pub lift_height: f64,
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
    /// Height above its rest pose at which a released body is let go (m); kept equal to the
    /// executor's.
    pub release_clearance: f64,
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
            approach_height: 0.10,
            lift_height: 0.12,
            pull_lift: PULL_LIFT,
            path_step: 0.015,
            path_ik_iterations: 30,
            settle_ik_iterations: 300,
            contact_slack: 0.002,
            clearance: 0.008,
            release_clearance: 0.003,
            transfer_margin: 0.015,
            max_alternatives: 3,
            placement_inner_margin: 0.05,
            certification_budget: 400,
        }
    }
}

/// A point in millimetres, for messages.
fn fmt_point(p: &Vector3<f64>) -> String {
    format!("({:.0}, {:.0}, {:.0}) mm", p.x * 1e3, p.y * 1e3, p.z * 1e3)
}

/// A part of a carried body as a certification tests it.
#[derive(Clone, Copy, Debug)]
struct LoadPart {
    /// Its pose in the TCP frame.
    offset: Isometry3<f64>,
    /// Its box grown by the transfer margin (shrunk by the contact slack without one).
    wide: Cuboid,
    /// Its box shrunk by the contact slack.
    plain: Cuboid,
    /// Its box as far as it may press into a shelf ([`HELD_OVERLAP`]).
    pressed: Cuboid,
}

/// A table or shelf: no action moves it.
#[derive(Clone, Debug)]
struct FixedBody {
    name: String,
    kind: BodyKind,
    /// Its boxes in the world.
    parts: Vec<(Isometry3<f64>, Cuboid)>,
}

/// What a motion hits: in words, and the name of the body hit.
#[derive(Clone, Debug, PartialEq)]
struct Hit {
    words: String,
    body: String,
}

/// What an arm carries: the body and its pose in the TCP frame.
#[derive(Clone, Debug)]
struct Held {
    body: String,
    grasp: Isometry3<f64>,
}

/// A support surface a body may be put down on: its top face's x and y ranges and its height
/// (m).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Surface {
    x: [f64; 2],
    y: [f64; 2],
    z: f64,
}

impl Surface {
    /// Whether `(x, y)` lies on the surface (edges included).
    fn contains(&self, x: f64, y: f64) -> bool {
        self.x[0] <= x && x <= self.x[1] && self.y[0] <= y && y <= self.y[1]
    }
}

/// A candidate resting spot for a body put down on a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Spot {
    /// Which sample it is: 0 for the demonstration's hint.
    sample: usize,
    /// Centre and yaw of the resting body.
    at: PlanarPose,
    /// Height of the surface's top (m).
    top: f64,
}

/// Why a candidate was not certified (counted in [`StreamStats`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Reject {
    /// The IK tracker cannot follow the path (or the pose is out of reach).
    Ik,
    /// A link or the carried body hits something along the path.
    Collision,
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

/// An obstacle of one certification: a box (shrunk by the contact slack) and its world AABB.
struct Obstacle {
    name: String,
    /// A table: the carried body's transfer margin does not apply to it (a load on its way
    /// from a low pose would otherwise start inside the margin).
    support: bool,
    /// A table or shelf: no action moves it.
    fixed: bool,
    iso: Isometry3<f64>,
    shape: Cuboid,
    lo: Vector3<f64>,
    hi: Vector3<f64>,
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
    fn is_held(&self, body: &str) -> bool {
        self.held.values().any(|h| h.body == body)
    }
}

/// Binds skeletons against a world with certified samples.
pub struct StreamBinder<'w> {
    world: &'w World,
    fixed: Vec<FixedBody>,
    /// Boxes of every movable body in its own frame.
    local: BTreeMap<String, Vec<(Isometry3<f64>, Cuboid)>>,
    regions: Vec<crate::sim::snapshot::RegionSnapshot>,
    reach: Vec<crate::sim::snapshot::ReachSnapshot>,
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
    /// Placements the demonstration used, by action: where the resting body's centre was.
    hints: BTreeMap<String, PlanarPose>,
}

/// World AABB of a box at a pose.
fn box_aabb(iso: &Isometry3<f64>, c: &Cuboid) -> (Vector3<f64>, Vector3<f64>) {
    let r = iso.rotation.to_rotation_matrix();
    let m = r.matrix().abs();
    let ext = m * c.half_extents;
    let t = iso.translation.vector;
    (t - ext, t + ext)
}

fn overlaps(lo: &Vector3<f64>, hi: &Vector3<f64>, o: &Obstacle) -> bool {
    lo.x <= o.hi.x
        && hi.x >= o.lo.x
        && lo.y <= o.hi.y
        && hi.y >= o.lo.y
        && lo.z <= o.hi.z
        && hi.z >= o.lo.z
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

    /// Placements to try first for these actions (the demonstration's).
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
                .map(|a| self.world.joints(a).unwrap_or(panda::READY))
                .collect(),
        }
    }

    fn half_extents(&self, body: &str) -> Vector3<f64> {
        match self.world.body_aabb(body) {
            Some((lo, hi)) if self.world.body_kind(body) == Some(BodyKind::Block) => {
                0.5 * (hi - lo)
            }
            _ => Vector3::repeat(NON_BLOCK_HALF_EXTENT),
        }
    }

    /// The boxes of movable `body` at `pose`.
    fn parts_at(&self, body: &str, pose: &Isometry3<f64>) -> Vec<(Isometry3<f64>, Cuboid)> {
        self.local
            .get(body)
            .map(|v| v.iter().map(|(off, c)| (pose * off, *c)).collect())
            .unwrap_or_default()
    }

    fn shrink(&self, c: &Cuboid) -> Cuboid {
        shrunk_by(c, self.params.contact_slack)
    }

    /// A carried or pushed body's box `c` as tested against a shelf (which is shrunk by the
    /// contact slack): it may press in only [`HELD_OVERLAP`], where the simulator stops it; grown
    /// by `margin` if that is more.
    fn pressed(&self, c: &Cuboid, margin: f64) -> Cuboid {
        let grow = margin.max(self.params.contact_slack - HELD_OVERLAP);
        Cuboid::new(c.half_extents + Vector3::repeat(grow))
    }

    /// The tables' and shelves' boxes (world frame).
    fn fixed_boxes(&self) -> Vec<(Isometry3<f64>, Cuboid)> {
        self.fixed
            .iter()
            .flat_map(|b| b.parts.iter().copied())
            .collect()
    }

    /// Everything arm `arm` may not touch in `geo`: fixed bodies and movable bodies other than
    /// `exclude` and the arm's own load (bodies carried by other arms included). The arms
    /// themselves do not collide with each other in the simulator (nor in the demonstration's
    /// hand-over), so they are not obstacles.
    fn obstacles(&self, geo: &Geo, arm: usize, exclude: &[&str]) -> Vec<Obstacle> {
        let mut out = vec![];
        for b in &self.fixed {
            for (iso, c) in &b.parts {
                let shape = self.shrink(c);
                let (lo, hi) = box_aabb(iso, &shape);
                out.push(Obstacle {
                    name: b.name.clone(),
                    support: b.kind == BodyKind::Table,
                    fixed: true,
                    iso: *iso,
                    shape,
                    lo,
                    hi,
                });
            }
        }
        let mine = geo.held.get(&arm).map(|h| h.body.as_str());
        for (name, pose) in &geo.poses {
            if Some(name.as_str()) == mine || exclude.contains(&name.as_str()) {
                continue;
            }
            for (iso, c) in self.parts_at(name, pose) {
                let shape = self.shrink(&c);
                let (lo, hi) = box_aabb(&iso, &shape);
                out.push(Obstacle {
                    name: name.clone(),
                    support: false,
                    fixed: false,
                    iso,
                    shape,
                    lo,
                    hi,
                });
            }
        }
        out
    }

    /// Certifies the TCP path through `via` for arm `arm` carrying what `geo` says it carries:
    /// returns the joints at the end, or why not. `exclude`: bodies the motion may touch.
    fn certify_path(
        &mut self,
        geo: &Geo,
        arm: usize,
        via: &[Isometry3<f64>],
        exclude: &[&str],
        load_margin: f64,
    ) -> Result<[f64; DOF], Reject> {
        self.certifications += 1;
        let Some(base) = self.world.arm_base(arm) else {
            return Err(Reject::Ik);
        };
        let obstacles = self.obstacles(geo, arm, exclude);
        // Each part of the load: its pose in the TCP frame, grown by the margin, as it is.
        let load: Vec<LoadPart> = geo
            .held
            .get(&arm)
            .map(|h| {
                self.local
                    .get(&h.body)
                    .map(|v| {
                        v.iter()
                            .map(|(off, c)| {
                                let plain = self.shrink(c);
                                let wide = if load_margin > 0.0 {
                                    Cuboid::new(c.half_extents + Vector3::repeat(load_margin))
                                } else {
                                    plain
                                };
                                LoadPart {
                                    offset: h.grasp * off,
                                    wide,
                                    plain,
                                    pressed: self.pressed(c, load_margin),
                                }
                            })
                            .collect()
                    })
                    .unwrap_or_default()
            })
            .unwrap_or_default();
        // An arm or load that starts in contact (a hook stopped against a block, a wrist
        // stopped at the table) may leave that contact: against what it touches at the start it
        // may only get shallower, as in the simulator's contact stops.
        let start = self.start_contacts(arm, &geo.q[arm], &geo.tcp[arm], &load, &obstacles);
        let mut q = geo.q[arm];
        let mut from = geo.tcp[arm];
        for to in via {
            let q_from = q;
            for (tcp, end) in line_samples(&from, to, self.params.path_step) {
                self.stats.path_samples += 1;
                // Between via-points the tracker may lag behind the command (the links are
                // checked where it leaves them); at a via-point it has the settle time to
                // converge (no restarts either way).
                let ik = if end { &self.settle_ik } else { &self.track_ik };
                q = match panda::inverse_kinematics(&base, &tcp, &q, ik) {
                    Ok(sol) => sol.joints,
                    Err(e) if !end => e.best_joints,
                    // A straight line is not the skill's path: the tracker may also come in
                    // from where the segment started. Either way without restarts.
                    Err(_) => match panda::inverse_kinematics(&base, &tcp, &q_from, ik) {
                        Ok(sol) => sol.joints,
                        // The executor's joint-space recovery: the planning IK (with restarts)
                        // from where the tracker stalled, then a straight joint-space move.
                        Err(_) => match self
                            .joint_recovery(arm, &base, &tcp, &q, &load, &obstacles, &start)
                        {
                            Some(Ok(qg)) => qg,
                            Some(Err(hit)) => {
                                let why = format!(
                                    "{} on the {} arm's joint-space move to {}",
                                    hit.words,
                                    self.arm_name(arm),
                                    fmt_point(&tcp.translation.vector)
                                );
                                return Err(self.collision(why, &hit.body));
                            }
                            None => {
                                self.stats.rejected_ik += 1;
                                self.last_rejection = Some(format!(
                                    "the {} arm cannot follow its path to {}",
                                    self.arm_name(arm),
                                    fmt_point(&tcp.translation.vector)
                                ));
                                return Err(Reject::Ik);
                            }
                        },
                    },
                };
                if let Some(hit) = self.sample_hits(arm, &q, &tcp, &load, &obstacles, &start) {
                    let why = format!(
                        "{} with the {} arm's TCP at {}",
                        hit.words,
                        self.arm_name(arm),
                        fmt_point(&tcp.translation.vector)
                    );
                    return Err(self.collision(why, &hit.body));
                }
            }
            from = *to;
        }
        Ok(q)
    }

    /// Records a collision rejection with `body`, and why.
    fn collision(&mut self, why: String, body: &str) -> Reject {
        self.last_rejection = Some(why);
        self.blocked_by(body);
        self.stats.rejected_collision += 1;
        Reject::Collision
    }

    /// Notes that `body` is in the way of the candidate being certified, if it is movable (a
    /// table or shelf is not: no action can clear it).
    fn blocked_by(&mut self, body: &str) {
        if self.local.contains_key(body) && !self.last_blockers.iter().any(|b| b == body) {
            self.last_blockers.push(body.to_string());
        }
    }

    /// Starts certifying a candidate of the action being bound: nothing is in its way yet.
    fn begin_candidate(&mut self) {
        self.last_blockers.clear();
    }

    /// The candidate being certified failed: what was in its way blocked the action.
    fn candidate_failed(&mut self) {
        let blockers = std::mem::take(&mut self.last_blockers);
        self.blockers
            .entry(self.action)
            .or_default()
            .extend(blockers);
    }

    /// Certifies the path through `via`, whose first point is the goal of the action's
    /// approach: straight, or, when that hits something, as a transit (straight up to
    /// [`transit_z`], across above `via[0]`, straight down to it: the executor's
    /// `ActionExec::with_transit`). The joints at the end and the transit's TCP height, if one
    /// was needed. A rejection tells why both were refused.
    fn certify_approach(
        &mut self,
        geo: &Geo,
        arm: usize,
        via: &[Isometry3<f64>],
        exclude: &[&str],
        load_margin: f64,
    ) -> Result<([f64; DOF], Option<f64>), Reject> {
        let blockers_before = self.last_blockers.len();
        match self.certify_path(geo, arm, via, exclude, load_margin) {
            Ok(q) => return Ok((q, None)),
            Err(Reject::Ik) => return Err(Reject::Ik),
            Err(Reject::Collision) => {}
        }
        let (Some(goal), Some(from)) = (via.first(), geo.tcp.get(arm)) else {
            return Err(Reject::Collision);
        };
        let why = self.last_rejection.clone();
        let z = self.transit_height(geo, arm, goal);
        let mut up = *from;
        up.translation.z = z;
        let mut over = *goal;
        over.translation.z = z;
        let path: Vec<Isometry3<f64>> = [up, over].into_iter().chain(via.iter().copied()).collect();
        self.stats.transits += 1;
        match self.certify_path(geo, arm, &path, exclude, load_margin) {
            Ok(q) => {
                // What blocked the straight approach is not in the transit's way.
                self.last_blockers.truncate(blockers_before);
                Ok((q, Some(z)))
            }
            Err(e) => {
                self.last_rejection = Some(format!(
                    "{}; across at {:.0} mm: {}",
                    why.unwrap_or_default(),
                    z * 1e3,
                    self.last_rejection.take().unwrap_or_default()
                ));
                Err(e)
            }
        }
    }

    /// The TCP height of a transit of `arm` from where `geo` has it to `goal` ([`transit_z`]
    /// over the predicted bodies; the executor computes the same from the world).
    fn transit_height(&self, geo: &Geo, arm: usize, goal: &Isometry3<f64>) -> f64 {
        // The load's world AABB where the arm carries it now.
        let load = geo.held.get(&arm).map(|h| {
            self.parts_at(&h.body, &(geo.tcp[arm] * h.grasp))
                .iter()
                .fold(
                    (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN)),
                    |(lo, hi), (iso, c)| {
                        let (l, h) = box_aabb(iso, c);
                        (lo.inf(&l), hi.sup(&h))
                    },
                )
        });
        let obstacles = self.obstacles(geo, arm, &[]);
        let a = geo.tcp[arm].translation.vector;
        transit_z(&a, &goal.translation.vector, load, |lo, hi| {
            obstacles
                .iter()
                .filter(|o| {
                    o.lo.x <= hi[0] && o.hi.x >= lo[0] && o.lo.y <= hi[1] && o.hi.y >= lo[1]
                })
                .fold(f64::MIN, |m, o| m.max(o.hi.z))
        })
    }

    /// The executor's joint-space recovery from joints `q` to the TCP pose `goal`
    /// (`lfd::exec`: the planning IK from `q` and from the ready posture, the solution with the
    /// most room to the joint limits, then a straight move in joint space, or, where that
    /// sweeps through something, two by way of the ready posture, or, failing both, one to the
    /// solution nearest `q`): `None` if the planning IK finds no solution, else the goal joints
    /// or what the straight move hits.
    #[allow(clippy::too_many_arguments)]
    fn joint_recovery(
        &mut self,
        arm: usize,
        base: &Isometry3<f64>,
        goal: &Isometry3<f64>,
        q: &[f64; DOF],
        load: &[LoadPart],
        obstacles: &[Obstacle],
        start: &StartContacts,
    ) -> Option<Result<[f64; DOF], Hit>> {
        let sol =
            panda::inverse_kinematics_with_room(base, goal, q, &self.world.params().planning_ik)
                .ok()?;
        let Some(hit) = self.joint_leg_hits(arm, base, q, &sol.joints, load, obstacles, start)
        else {
            return Some(Ok(sol.joints));
        };
        // The straight move sweeps through something: by way of the ready posture instead.
        let via = panda::READY;
        let around = self
            .joint_leg_hits(arm, base, q, &via, load, obstacles, start)
            .or_else(|| self.joint_leg_hits(arm, base, &via, &sol.joints, load, obstacles, start));
        if around.is_none() {
            return Some(Ok(sol.joints));
        }
        // Failing both, straight to the solution nearest `q` for the goal or a point on the way
        // to it, the first a clear move reaches; the tracker then follows the rest of the way.
        let from = panda::forward_kinematics(base, q).translation.vector;
        let ik = self.world.params().planning_ik.clone();
        for s in NEAR_RECOVERY_FRACTIONS {
            let mut part = *goal;
            part.translation.vector = from.lerp(&goal.translation.vector, s);
            let Ok(near) = panda::inverse_kinematics_near(base, &part, q, &ik) else {
                continue;
            };
            if self
                .joint_leg_hits(arm, base, q, &near.joints, load, obstacles, start)
                .is_some()
            {
                continue;
            }
            return Some(
                self.track_line(arm, base, &near.joints, &part, goal, load, obstacles, start)
                    .ok_or(hit),
            );
        }
        Some(Err(hit))
    }

    /// The joints at the end of the tracker's straight TCP line from `from` (joints `q`) to
    /// `to`, sampled and checked like [`StreamBinder::certify_path`]'s (without its
    /// recoveries); `None` if the tracker cannot follow it or the arm hits something.
    #[allow(clippy::too_many_arguments)]
    fn track_line(
        &mut self,
        arm: usize,
        base: &Isometry3<f64>,
        q: &[f64; DOF],
        from: &Isometry3<f64>,
        to: &Isometry3<f64>,
        load: &[LoadPart],
        obstacles: &[Obstacle],
        start: &StartContacts,
    ) -> Option<[f64; DOF]> {
        let mut q = *q;
        for (tcp, end) in line_samples(from, to, self.params.path_step) {
            self.stats.path_samples += 1;
            let ik = if end { &self.settle_ik } else { &self.track_ik };
            q = match panda::inverse_kinematics(base, &tcp, &q, ik) {
                Ok(sol) => sol.joints,
                Err(e) if !end => e.best_joints,
                Err(_) => return None,
            };
            if self
                .sample_hits(arm, &q, &tcp, load, obstacles, start)
                .is_some()
            {
                return None;
            }
        }
        Some(q)
    }

    /// What arm `arm` (carrying `load`) hits on the straight joint-space move from `from` to
    /// `to`; `None` if nothing.
    #[allow(clippy::too_many_arguments)]
    fn joint_leg_hits(
        &mut self,
        arm: usize,
        base: &Isometry3<f64>,
        from: &[f64; DOF],
        to: &[f64; DOF],
        load: &[LoadPart],
        obstacles: &[Obstacle],
        start: &StartContacts,
    ) -> Option<Hit> {
        for qk in panda::joint_line(from, to) {
            self.stats.path_samples += 1;
            let tcp = panda::forward_kinematics(base, &qk);
            if let Some(hit) = self.sample_hits(arm, &qk, &tcp, load, obstacles, start) {
                return Some(hit);
            }
        }
        None
    }

    /// Every (part, obstacle) pair of arm `arm` at joints `q` (TCP `tcp`, carrying `load`) whose
    /// world AABBs overlap, links first (the base link stands on the table and is never tested),
    /// then the parts of the load (grown by its margin, except against a support), each part
    /// with its obstacles in order.
    fn overlapping_pairs(
        &self,
        arm: usize,
        q: &[f64; DOF],
        tcp: &Isometry3<f64>,
        load: &[LoadPart],
        obstacles: &[Obstacle],
    ) -> Vec<Overlap> {
        let mut out = vec![];
        for (i, (a, b, r)) in link_capsules(self.world, arm, q)
            .into_iter()
            .enumerate()
            .skip(1)
        {
            let cap = Capsule::new(Point3::from(a), Point3::from(b), r);
            let lo = a.inf(&b) - Vector3::repeat(r);
            let hi = a.sup(&b) + Vector3::repeat(r);
            for (oi, o) in obstacles.iter().enumerate() {
                if overlaps(&lo, &hi, o) {
                    out.push(Overlap {
                        contact: Contact {
                            part: Part::Link(i),
                            obstacle: oi,
                        },
                        iso: Isometry3::identity(),
                        shape: PartShape::Capsule(cap),
                    });
                }
            }
        }
        for (pi, part) in load.iter().enumerate() {
            let iso = tcp * part.offset;
            let (lo, hi) = box_aabb(&iso, &part.wide);
            for (oi, o) in obstacles.iter().enumerate() {
                if overlaps(&lo, &hi, o) {
                    let c = match (o.support, o.fixed) {
                        (true, _) => part.plain,
                        (false, true) => part.pressed,
                        (false, false) => part.wide,
                    };
                    out.push(Overlap {
                        contact: Contact {
                            part: Part::Load(pi),
                            obstacle: oi,
                        },
                        iso,
                        shape: PartShape::Cuboid(c),
                    });
                }
            }
        }
        out
    }

    /// Penetration depth of each (part, obstacle) pair that overlaps with the arm at joints `q`
    /// (TCP `tcp`, carrying `load`).
    fn start_contacts(
        &self,
        arm: usize,
        q: &[f64; DOF],
        tcp: &Isometry3<f64>,
        load: &[LoadPart],
        obstacles: &[Obstacle],
    ) -> StartContacts {
        self.overlapping_pairs(arm, q, tcp, load, obstacles)
            .into_iter()
            .filter_map(|o| {
                depth_in(&o.iso, o.shape.as_shape(), &obstacles[o.contact.obstacle])
                    .map(|d| (o.contact, d))
            })
            .collect()
    }

    /// What the arm at joints `q` (TCP `tcp`, carrying `load` in the TCP frame) hits.
    /// `start`: contacts at the start of the path, allowed as long as they get no deeper.
    fn sample_hits(
        &self,
        arm: usize,
        q: &[f64; DOF],
        tcp: &Isometry3<f64>,
        load: &[LoadPart],
        obstacles: &[Obstacle],
        start: &StartContacts,
    ) -> Option<Hit> {
        let Contact { part, obstacle: oi } = self
            .overlapping_pairs(arm, q, tcp, load, obstacles)
            .into_iter()
            .find(|pair| {
                let o = &obstacles[pair.contact.obstacle];
                let allowed = start.get(&pair.contact).map(|&d0| {
                    // A link already pressed into a table or shelf moves as the simulator lets
                    // it: deeper only while within its tolerance (the tracker's redundant joints
                    // take another path than this IK's, so the depth drifts either way).
                    let tolerated = match pair.contact.part {
                        Part::Link(_) if o.fixed => LINK_TOLERANCE - self.params.contact_slack,
                        _ => 0.0,
                    };
                    (d0 + START_CONTACT_DRIFT).max(tolerated)
                });
                hits(&pair.iso, pair.shape.as_shape(), o, allowed)
            })?
            .contact;
        let o = &obstacles[oi].name;
        let words = match part {
            Part::Link(i) => format!("link {i} hits {o}"),
            Part::Load(_) => format!("the carried body hits {o}"),
        };
        Some(Hit {
            words,
            body: o.clone(),
        })
    }

    fn arm_name(&self, arm: usize) -> String {
        self.world
            .arm_names()
            .get(arm)
            .map(|s| s.to_string())
            .unwrap_or_else(|| format!("#{arm}"))
    }

    /// Whether `body` resting at `pose` keeps `clearance` from the other free blocks and does not
    /// overlap anything else (touching faces allowed).
    fn placement_free(&mut self, geo: &Geo, body: &str, pose: &Isometry3<f64>) -> bool {
        self.certifications += 1;
        let slack = Vector3::repeat(self.params.contact_slack);
        let grow = Vector3::new(self.params.clearance, self.params.clearance, 0.0);
        for (iso, c) in self.parts_at(body, pose) {
            let h = c.half_extents;
            let me = self.shrink(&c);
            let grown = Cuboid::new((h + grow - slack).sup(&(h * 0.5)));
            for (name, p) in &geo.poses {
                if name == body || geo.is_held(name) {
                    continue;
                }
                let test_shape = if self.world.body_kind(name) == Some(BodyKind::Block) {
                    &grown
                } else {
                    &me
                };
                for (oiso, oc) in self.parts_at(name, p) {
                    let other = self.shrink(&oc);
                    if query::intersection_test(&iso, test_shape, &oiso, &other).unwrap_or(true) {
                        return false;
                    }
                }
            }
            for b in &self.fixed {
                for (fiso, fc) in &b.parts {
                    if query::intersection_test(&iso, &me, fiso, fc).unwrap_or(true) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// A body of `geo` (not held) above the middle of `body` at `pose` that overlaps, by more
    /// than the simulator's contact stop lets a lifted body press into another, the box `body`
    /// sweeps rising straight up by the lift height: what would stop its lift.
    fn overhang(&self, geo: &Geo, body: &str, pose: &Isometry3<f64>) -> Option<String> {
        let slack = self.overhang_slack();
        let rise = self.params.lift_height;
        let swept: Vec<(Isometry3<f64>, Cuboid)> = self
            .parts_at(body, pose)
            .into_iter()
            .map(|(iso, c)| {
                let tall = Cuboid::new(c.half_extents + Vector3::new(0.0, 0.0, 0.5 * rise));
                (raised(&iso, 0.5 * rise), shrunk_by(&tall, slack))
            })
            .collect();
        let middle = pose.translation.z;
        geo.poses
            .iter()
            .filter(|(name, _)| name.as_str() != body && !geo.is_held(name))
            .find_map(|(name, p)| {
                let parts = self.parts_at(name, p);
                let hit = parts.iter().any(|(oiso, oc)| {
                    let (lo, _) = box_aabb(oiso, oc);
                    let other = shrunk_by(oc, slack);
                    lo.z > middle
                        && swept.iter().any(|(iso, c)| {
                            query::intersection_test(iso, c, oiso, &other).unwrap_or(true)
                        })
                });
                hit.then(|| name.clone())
            })
    }

    /// How much [`StreamBinder::overhang`] shrinks each box (m): a little less than half of the
    /// overlap the simulator's contact stop allows ([`OVERHANG_SLACK_OF_TOLERANCE`] of the
    /// world's penetration tolerance).
    fn overhang_slack(&self) -> f64 {
        OVERHANG_SLACK_OF_TOLERANCE * self.world.params().penetration_tolerance
    }

    /// The boxes of every body in `geo` but `body` and the held ones, unshrunk (what the
    /// executor's grasp choice sees in the world).
    fn boxes_except(&self, geo: &Geo, body: &str) -> Vec<(Isometry3<f64>, Cuboid)> {
        let mut out = self.fixed_boxes();
        for (name, pose) in &geo.poses {
            if name != body && !geo.is_held(name) {
                out.extend(self.parts_at(name, pose));
            }
        }
        out
    }

    /// Certifies `arm` grasping `body` (approach from above, close, lift) and rolls `geo` on:
    /// `None` if it cannot, else the height of the transit its approach needs, if any.
    fn grasp(&mut self, geo: &mut Geo, arm: usize, body: &str, certify: bool) -> Option<Transit> {
        let pose = geo.poses.get(body).copied()?;
        // Certified or not, the body must rise free: a block dragged or nudged over its edge
        // stops the lift (the simulator's contact stop), and no motion of the hand helps.
        if let Some(over) = self.overhang(geo, body, &pose) {
            let why = format!("{over} overhangs {body}");
            self.collision(why, &over);
            return None;
        }
        let boxes = self.boxes_except(geo, body);
        let tcp = clear_grasp_at(
            self.world,
            arm,
            body,
            &pose,
            &boxes,
            self.params.approach_height,
        )?;
        let lifted = raised(&tcp, self.params.lift_height);
        let mut transit = None;
        if certify {
            let via = [raised(&tcp, self.params.approach_height), tcp];
            let (q, z) = self.certify_approach(geo, arm, &via, &[body], 0.0).ok()?;
            transit = z;
            let mut after = geo.clone();
            after.tcp[arm] = tcp;
            after.q[arm] = q;
            after.held.insert(
                arm,
                Held {
                    body: body.to_string(),
                    grasp: tcp.inverse() * pose,
                },
            );
            let q = self.certify_path(&after, arm, &[lifted], &[], 0.0).ok()?;
            geo.q[arm] = q;
        } else if let Ok(sol) = self.world.reachable(arm, &lifted) {
            geo.q[arm] = sol.joints;
        }
        geo.tcp[arm] = lifted;
        geo.held.insert(
            arm,
            Held {
                body: body.to_string(),
                grasp: tcp.inverse() * pose,
            },
        );
        geo.poses
            .insert(body.to_string(), raised(&pose, self.params.lift_height));
        Some(transit)
    }

    /// Certifies `arm` putting its load down with the body at `pose` (approach from above,
    /// open, retreat up) and rolls `geo` on: `None` if it cannot, else the height of the
    /// transit its approach needs, if any, and the hand's yaw it certified (`None` uncertified).
    /// A square block may be put down turned by a quarter turn (it looks the same): the hand
    /// nearest the arm's heading first (what the executor does uncertified), then the next
    /// nearest (the hand turned a quarter, e.g. lengthwise beside a tower); the executor puts
    /// the hand where it was certified.
    fn release(
        &mut self,
        geo: &mut Geo,
        arm: usize,
        pose: &Isometry3<f64>,
        certify: bool,
    ) -> Option<(Transit, Option<f64>)> {
        let Held { body, grasp: g } = geo.held.get(&arm).cloned()?;
        let turns = quarter_turns(self.world, arm, &body, pose, &g, None);
        let tries = if certify { CERTIFIED_TURNS } else { 1 };
        turns
            .iter()
            .take(tries)
            .find_map(|p| self.release_turned(geo, arm, p, certify))
    }

    /// [`StreamBinder::release`] with the body at `pose` as it is.
    fn release_turned(
        &mut self,
        geo: &mut Geo,
        arm: usize,
        pose: &Isometry3<f64>,
        certify: bool,
    ) -> Option<(Transit, Option<f64>)> {
        let Held { body, grasp: g } = geo.held.get(&arm).cloned()?;
        let tcp = pose * g.inverse();
        let hand_yaw = certify.then(|| yaw_of(&tcp.rotation));
        let retreat = raised(&tcp, self.params.approach_height);
        let mut transit = None;
        if certify {
            // The transfer to the approach pose is where the learned skill cuts corners (its
            // path is not the straight line checked here): the carried body keeps
            // `transfer_margin` from everything on the way. The descent is checked as is.
            let above = retreat; // the approach pose is also the retreat pose
            let margin = self.params.transfer_margin;
            let (q_above, z) = self
                .certify_approach(geo, arm, &[above], &[], margin)
                .ok()?;
            transit = z;
            let mut at_above = geo.clone();
            at_above.tcp[arm] = above;
            at_above.q[arm] = q_above;
            // The executor opens the gripper `release_clearance` above the rest pose.
            let drop = raised(&tcp, self.params.release_clearance);
            self.certify_path(&at_above, arm, &[drop], &[], 0.0).ok()?;
            let mut after = geo.clone();
            after.held.remove(&arm);
            after.poses.insert(body.clone(), *pose);
            after.tcp[arm] = drop;
            let q = self
                .certify_path(&after, arm, &[retreat], &[&body], 0.0)
                .ok()?;
            geo.q[arm] = q;
        } else {
            // Uncertified (the demonstration's own placement), the hand must still fit where it
            // lets go, clear of the tables and shelves by the contact slack: that is where it
            // grasps the body again, and a certified grasp there keeps that much room.
            if hand_within(&tcp, &self.fixed_boxes(), self.params.contact_slack) {
                return None;
            }
            if let Ok(sol) = self.world.reachable(arm, &retreat) {
                geo.q[arm] = sol.joints;
            }
        }
        geo.held.remove(&arm);
        geo.poses.insert(body, *pose);
        geo.tcp[arm] = retreat;
        Some((transit, hand_yaw))
    }

    /// The pose a pull stroke of `arm` leaves `body` at (shape cast of the carried hook along
    /// the executor's stroke, then of the block along its push), after certifying the stroke.
    /// Tries the radial stroke, then strokes turned by ±PULL_TURNS (certified ones only):
    /// the turn of the first that passes and the height of the transit its approach needs, if
    /// any; the geometric state rolled on.
    fn pull(
        &mut self,
        geo: &mut Geo,
        arm: usize,
        body: &str,
        certify: bool,
    ) -> Option<(f64, Transit)> {
        let turns: &[f64] = if certify {
            &PULL_TURNS
        } else {
            &PULL_TURNS[..1]
        };
        turns.iter().find_map(|&turn| {
            self.begin_candidate();
            let found = self.pull_turned(geo, arm, body, certify, turn);
            if found.is_none() {
                self.candidate_failed();
            }
            found.map(|t| (turn, t))
        })
    }

    /// One pull stroke turned by `turn` (see [`pull_hook_poses_turned`]).
    fn pull_turned(
        &mut self,
        geo: &mut Geo,
        arm: usize,
        body: &str,
        certify: bool,
        turn: f64,
    ) -> Option<Transit> {
        let bp = geo.poses.get(body).copied()?;
        let Held {
            body: hook,
            grasp: g,
        } = geo.held.get(&arm).cloned()?;
        let base = self.world.arm_base(arm)?;
        let (contact, pulled) = pull_hook_poses_turned(&base, &bp, PULL_TARGET_RADIUS, turn)?;
        let tc = contact * g.inverse();
        let tp = pulled * g.inverse();
        let d = pulled.translation.vector - contact.translation.vector;
        // When does the blade meet the block along the stroke?
        let opts = query::ShapeCastOptions {
            max_time_of_impact: 1.0,
            target_distance: 0.0,
            stop_at_penetration: false,
            compute_impact_geometry_on_penetration: false,
        };
        let mut toi = f64::INFINITY;
        for (hiso, hc) in self.parts_at(&hook, &contact) {
            for (biso, bc) in self.parts_at(body, &bp) {
                if let Ok(Some(hit)) =
                    query::cast_shapes(&hiso, &d, &hc, &biso, &Vector3::zeros(), &bc, opts)
                {
                    toi = toi.min(hit.time_of_impact);
                }
            }
        }
        if toi > 1.0 {
            self.stats.rejected_pull += 1;
            self.last_rejection = Some(format!("the hook's stroke misses {body}"));
            return None;
        }
        let push = Vector3::new(d.x, d.y, 0.0) * (1.0 - toi);
        let moved = Isometry3::from_parts(
            Translation3::from(bp.translation.vector + push),
            bp.rotation,
        );
        let mut transit = None;
        if certify {
            // The block's own sweep may hit nothing but the hook.
            let others: Vec<Obstacle> = {
                let obs = self.obstacles(geo, arm, &[body, hook.as_str()]);
                obs.into_iter()
                    .filter(|o| {
                        // Its support (the table top it slides on) is not in the way.
                        o.hi.z > bp.translation.z - self.half_extents(body).z + SUPPORT_TOP_MARGIN
                    })
                    .collect()
            };
            for (biso, bc) in self.parts_at(body, &bp) {
                let plain = self.shrink(&bc);
                let pressed = self.pressed(&bc, 0.0);
                for o in &others {
                    let shape = if o.fixed { &pressed } else { &plain };
                    if let Ok(Some(hit)) = query::cast_shapes(
                        &biso,
                        &push,
                        shape,
                        &o.iso,
                        &Vector3::zeros(),
                        &o.shape,
                        opts,
                    ) {
                        if hit.time_of_impact <= 1.0 {
                            self.stats.rejected_pull += 1;
                            self.last_rejection =
                                Some(format!("the stroke would push {body} into {}", o.name));
                            let name = o.name.clone();
                            self.blocked_by(&name);
                            return None;
                        }
                    }
                }
            }
            let p = moved.translation.vector;
            let on_table = self.fixed.iter().any(|b| {
                b.kind == BodyKind::Table
                    && self.world.body_aabb(&b.name).is_some_and(|(lo, hi)| {
                        lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y
                    })
            });
            if !on_table || !self.in_annulus(arm, p.x, p.y) {
                self.stats.rejected_pull += 1;
                self.last_rejection = Some(format!(
                    "the stroke would leave {body} off the table or out of the {} arm's reach",
                    self.arm_name(arm)
                ));
                return None;
            }
            let via = [raised(&tc, self.params.pull_lift), tc];
            let (q, z) = self.certify_approach(geo, arm, &via, &[], 0.0).ok()?;
            transit = z;
            let mut stroke = geo.clone();
            stroke.tcp[arm] = tc;
            stroke.q[arm] = q;
            let q = self.certify_path(&stroke, arm, &[tp], &[body], 0.0).ok()?;
            let mut after = stroke;
            after.tcp[arm] = tp;
            after.q[arm] = q;
            after.poses.insert(body.to_string(), moved);
            let q = self
                .certify_path(&after, arm, &[raised(&tp, self.params.pull_lift)], &[], 0.0)
                .ok()?;
            geo.q[arm] = q;
        }
        geo.tcp[arm] = raised(&tp, self.params.pull_lift);
        geo.poses.insert(hook.clone(), geo.tcp[arm] * g);
        geo.poses.insert(body.to_string(), moved);
        Some(transit)
    }

    /// The support surfaces a release adding `adds` may use. A region
    /// (`(at x p)`) narrows the table it lies on: then only the region is used.
    fn surfaces(&self, adds: &[String], body: &str) -> Vec<Surface> {
        let regions = self.region_surfaces(adds, body);
        if !regions.is_empty() {
            return regions;
        }
        let mut out = vec![];
        for f in adds {
            let (p, a) = fact_args(f);
            if a.first() != Some(&body) {
                continue;
            }
            let kind = match p {
                "ontable" => Some(BodyKind::Table),
                "onshelf" => Some(BodyKind::Shelf),
                _ => None,
            };
            if let Some(kind) = kind {
                for b in self.fixed.iter().filter(|b| b.kind == kind) {
                    if let Some((lo, hi)) = self.world.body_aabb(&b.name) {
                        out.push(Surface {
                            x: [lo.x, hi.x],
                            y: [lo.y, hi.y],
                            z: hi.z,
                        });
                    }
                }
            }
        }
        out
    }

    /// The regions `(at body p)` of `adds`, as surfaces.
    fn region_surfaces(&self, adds: &[String], body: &str) -> Vec<Surface> {
        let mut out = vec![];
        for f in adds {
            let (p, a) = fact_args(f);
            if a.first() != Some(&body) {
                continue;
            }
            if p == "at" && a.len() == 2 {
                if let Some(r) = self.regions.iter().find(|r| r.name == a[1]) {
                    // The region lies on a table: its top is the highest table top under it.
                    let cx = 0.5 * (r.min[0] + r.max[0]);
                    let cy = 0.5 * (r.min[1] + r.max[1]);
                    let top = self
                        .fixed
                        .iter()
                        .filter(|b| b.kind == BodyKind::Table)
                        .filter_map(|b| self.world.body_aabb(&b.name))
                        .filter(|(lo, hi)| lo.x <= cx && cx <= hi.x && lo.y <= cy && cy <= hi.y)
                        .map(|(_, hi)| hi.z)
                        .fold(f64::NEG_INFINITY, f64::max);
                    // A region holds a body by its centre (`SceneGraph`): the candidates' edge
                    // margin (half the body and SURFACE_EDGE_MARGIN, for the edge of a real
                    // surface) becomes REGION_INSET from the region's edge.
                    let h = self.half_extents(body);
                    let grow = (h.x.max(h.y) + SURFACE_EDGE_MARGIN - REGION_INSET).max(0.0);
                    if top.is_finite() {
                        out.push(Surface {
                            x: [r.min[0] - grow, r.max[0] + grow],
                            y: [r.min[1] - grow, r.max[1] + grow],
                            z: top,
                        });
                    }
                }
            }
        }
        out
    }

    /// Whether some part of `body` at `pose` comes within `margin` of a shelf's footprint.
    fn near_shelf(&self, body: &str, pose: &Isometry3<f64>, margin: f64) -> bool {
        let parts: Vec<(Vector3<f64>, Vector3<f64>)> = self
            .parts_at(body, pose)
            .iter()
            .map(|(iso, c)| box_aabb(iso, c))
            .collect();
        self.fixed
            .iter()
            .filter(|b| b.kind == BodyKind::Shelf)
            .filter_map(|b| self.world.body_aabb(&b.name))
            .any(|(lo, hi)| {
                parts.iter().any(|(plo, phi)| {
                    phi.x > lo.x - margin
                        && plo.x < hi.x + margin
                        && phi.y > lo.y - margin
                        && plo.y < hi.y + margin
                })
            })
    }

    /// Whether arm `a`'s reach annulus contains `(x, y)`.
    fn in_annulus(&self, a: usize, x: f64, y: f64) -> bool {
        match (self.reach.get(a), self.world.arm_base(a)) {
            (Some(r), Some(b)) => {
                let d = libm::hypot(x - b.translation.x, y - b.translation.y);
                d >= r.min_radius && d <= r.max_radius
            }
            _ => false,
        }
    }

    /// Whether `(x, y)` is at least `margin` beyond arm `a`'s minimum reach.
    fn beyond_inner_reach(&self, a: usize, x: f64, y: f64, margin: f64) -> bool {
        match (self.reach.get(a), self.world.arm_base(a)) {
            (Some(r), Some(b)) => {
                libm::hypot(x - b.translation.x, y - b.translation.y) >= r.min_radius + margin
            }
            _ => false,
        }
    }

    /// Candidate resting spots for the body `arm` holds on one of
    /// `surfaces`: the demonstration's `hint` first (sample 0), then uniform samples ordered by
    /// horizontal distance from where the arm carries the body now (short transfers first: long
    /// sweeps across the workspace are where the joint tracker can get stuck).
    fn surface_candidates(
        &mut self,
        geo: &Geo,
        arm: usize,
        surfaces: &[Surface],
        hint: Option<PlanarPose>,
    ) -> Vec<Spot> {
        let Some(body) = geo.held.get(&arm).map(|h| h.body.clone()) else {
            return vec![];
        };
        if surfaces.is_empty() {
            return vec![];
        }
        let h = self.half_extents(&body);
        let margin = h.x.max(h.y) + SURFACE_EDGE_MARGIN;
        let mut candidates: Vec<Spot> = vec![];
        if let Some(at) = hint {
            if let Some(s) = surfaces.iter().find(|s| s.contains(at.x, at.y)) {
                candidates.push(Spot {
                    sample: 0,
                    at,
                    top: s.z,
                });
            }
        }
        let mut drawn = vec![];
        for n in 1..=self.params.placement_samples {
            let Surface {
                x: xr,
                y: yr,
                z: top,
            } = surfaces[self.rng.random_range(0..surfaces.len())];
            if xr[1] - xr[0] <= 2.0 * margin || yr[1] - yr[0] <= 2.0 * margin {
                continue;
            }
            let x = self.rng.random_range(xr[0] + margin..xr[1] - margin);
            let y = self.rng.random_range(yr[0] + margin..yr[1] - margin);
            let yaw = if self.rng.random_bool(0.5) {
                0.0
            } else {
                std::f64::consts::FRAC_PI_2
            };
            drawn.push(Spot {
                sample: n,
                at: PlanarPose { x, y, yaw },
                top,
            });
        }
        let at = geo
            .poses
            .get(&body)
            .map(|p| p.translation.vector)
            .unwrap_or_default();
        drawn.sort_by(|a, b| {
            libm::hypot(a.at.x - at.x, a.at.y - at.y)
                .total_cmp(&libm::hypot(b.at.x - at.x, b.at.y - at.y))
        });
        // On a small surface (a shelf) random spots waste room a later body needs: its spots
        // on a lattice at the packing pitch come first, nearest first.
        let pitch = 2.0 * h.x.max(h.y) + self.params.clearance + LATTICE_GAP;
        let mut lattice = vec![];
        for &Surface {
            x: xr,
            y: yr,
            z: top,
        } in surfaces
        {
            let nx = ((xr[1] - xr[0] - 2.0 * margin) / pitch).floor();
            let ny = ((yr[1] - yr[0] - 2.0 * margin) / pitch).floor();
            if nx < 0.0 || ny < 0.0 || (nx + 1.0) * (ny + 1.0) > SMALL_SURFACE_SPOTS as f64 {
                continue;
            }
            for i in 0..=nx as usize {
                for j in 0..=ny as usize {
                    let x = xr[0] + margin + i as f64 * pitch;
                    let y = yr[0] + margin + j as f64 * pitch;
                    lattice.push(Spot {
                        sample: 0,
                        at: PlanarPose { x, y, yaw: 0.0 },
                        top,
                    });
                }
            }
        }
        lattice.sort_by(|a, b| {
            libm::hypot(a.at.x - at.x, a.at.y - at.y)
                .total_cmp(&libm::hypot(b.at.x - at.x, b.at.y - at.y))
        });
        for (k, c) in lattice.iter_mut().enumerate() {
            c.sample = self.params.placement_samples + 1 + k;
        }
        if self.world.body_kind(&body) == Some(BodyKind::Block) {
            lattice.extend(drawn);
            drawn = lattice;
        }
        // The hook goes back near where the demonstration left it first (spots within
        // HOOK_HINT_RADIUS of its hint), anywhere else after.
        if self.world.body_kind(&body) != Some(BodyKind::Block) {
            if let Some(h) = hint {
                drawn.sort_by_key(|c| libm::hypot(c.at.x - h.x, c.at.y - h.y) >= HOOK_HINT_RADIUS);
            }
        }
        candidates.extend(drawn);
        candidates
    }

    /// Certifies one candidate resting spot for the body `arm` holds: inside the placing arm's
    /// reach annulus, collision-free, the release motion certified (when `certify`), and
    /// graspable by every other arm whose annulus contains it (hand-over spots). Returns the
    /// geometric state after the release and the height of the transit its approach needs, if
    /// any.
    fn try_surface(
        &mut self,
        geo: &Geo,
        arm: usize,
        spot: Spot,
        hint: Option<PlanarPose>,
        certify: bool,
    ) -> Option<(Geo, Transit, Option<f64>)> {
        let Spot {
            sample: n,
            at: PlanarPose { x, y, yaw },
            top,
        } = spot;
        let body = geo.held.get(&arm)?.body.clone();
        // Height of the body's frame above its lowest point (the hook's frame is not centred).
        let (lo, _) = self.world.body_aabb(&body)?;
        let lift = self.world.body_pose(&body)?.translation.z - lo.z;
        let is_block = self.world.body_kind(&body) == Some(BodyKind::Block);
        if is_block && !self.in_annulus(arm, x, y) {
            return None;
        }
        if is_block && !self.beyond_inner_reach(arm, x, y, self.params.placement_inner_margin) {
            self.stats.rejected_ik += 1;
            return None;
        }
        let pose = Isometry3::from_parts(
            Translation3::new(x, y, top + lift),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
        );
        if !self.placement_free(geo, &body, &pose) {
            self.stats.rejected_collision += 1;
            return None;
        }
        // The carried hook keeps every part of it clear of shelves and, unless its motion is
        // certified, stays near where the demonstration left it.
        if !is_block && n > 0 {
            let far = hint.is_some_and(|h| libm::hypot(x - h.x, y - h.y) >= HOOK_HINT_RADIUS);
            if self.near_shelf(&body, &pose, HOOK_SHELF_CLEARANCE) || (far && !certify) {
                return None;
            }
        }
        if is_block {
            // Hand-over spots must be graspable from the other side.
            let others: Vec<usize> = (0..self.reach.len())
                .filter(|&a| a != arm && self.in_annulus(a, x, y))
                .collect();
            let graspable = others.iter().all(|&a| {
                grasp_pose_at(self.world, a, &body, &pose).is_some_and(|g| {
                    self.world.reachable(a, &g).is_ok()
                        && self
                            .world
                            .reachable(a, &raised(&g, self.params.approach_height))
                            .is_ok()
                })
            });
            if !graspable {
                self.stats.rejected_ik += 1;
                return None;
            }
        }
        let mut next = geo.clone();
        let (transit, hand_yaw) = self.release(&mut next, arm, &pose, certify)?;
        Some((next, transit, hand_yaw))
    }

    /// Binds `ops[i..]` from the geometric state `geo`, pushing one binding per action onto
    /// `out`. Surface placements are choice points: when a later action cannot be bound, up to
    /// `max_alternatives` other certified spots are tried (depth first) while the certification
    /// budget lasts. Err: the index of the deepest action that could not be bound.
    fn bind_from(
        &mut self,
        task: &Task,
        ops: &[usize],
        demo_from: usize,
        i: usize,
        mut geo: Geo,
        out: &mut Vec<Binding>,
    ) -> Result<Geo, usize> {
        let Some(&o) = ops.get(i) else {
            return Ok(geo);
        };
        let op = &task.operators[o];
        self.action = i;
        let Some(kind) = classify(task, op, self.world) else {
            out.push(Binding::default());
            return self.bind_from(task, ops, demo_from, i + 1, geo, out);
        };
        // A pull is certified even in the demonstration's suffix: its stroke is computed from
        // the block's pose, not demonstrated, and the 40 cm hook sweeps past other blocks.
        let certify = i < demo_from || matches!(kind, ActionKind::Pull { .. });
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
                let Some(py) = geo.poses.get(&y).copied() else {
                    return Err(i);
                };
                let hy = self.half_extents(&y);
                let hb = self.half_extents(&body);
                let pose = Isometry3::from_parts(
                    Translation3::from(py.translation.vector + Vector3::z() * (hy.z + hb.z)),
                    py.rotation,
                );
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
                let adds: Vec<String> = op
                    .add
                    .iter()
                    .map(|&f| task.facts[f as usize].clone())
                    .collect();
                let surfaces = self.surfaces(&adds, &body);
                let hint = self.hints.get(&op.name).copied();
                let candidates = self.surface_candidates(&geo, arm, &surfaces, hint);
                let mut deepest = i;
                let mut certified = 0;
                for c in candidates {
                    if certified > self.params.max_alternatives
                        || self.certifications > self.budget_end
                    {
                        break;
                    }
                    let Some((next, transit, hand_yaw)) =
                        self.try_surface(&geo, arm, c, hint, certify)
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
                    match self.bind_from(task, ops, demo_from, i + 1, next, out) {
                        Ok(end) => return Ok(end),
                        Err(j) => {
                            deepest = deepest.max(j);
                            out.truncate(i);
                        }
                    }
                }
                return Err(deepest);
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
        self.bind_from(task, ops, demo_from, i + 1, geo, out)
    }
}

/// A part of an arm in a certification: one of its links (by index) or a part of its load.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Part {
    Link(usize),
    Load(usize),
}

/// A part of an arm and an obstacle (by index) it may touch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Contact {
    part: Part,
    obstacle: usize,
}

/// A part of an arm whose world AABB overlaps an obstacle's: the pair, the part's pose and its
/// shape.
struct Overlap {
    contact: Contact,
    iso: Isometry3<f64>,
    shape: PartShape,
}

/// The shape of a [`Part`]: a link's capsule or a load part's box.
enum PartShape {
    Capsule(Capsule),
    Cuboid(Cuboid),
}

impl PartShape {
    fn as_shape(&self) -> &dyn Shape {
        match self {
            PartShape::Capsule(c) => c,
            PartShape::Cuboid(c) => c,
        }
    }
}

/// `c` with every half extent `slack` smaller, but at least half of what it was (where
/// `sim::geometry::shrunk` keeps at least 0.1 mm: the two differ on thin boxes).
fn shrunk_by(c: &Cuboid, slack: f64) -> Cuboid {
    let h = c.half_extents;
    Cuboid::new((h - Vector3::repeat(slack)).sup(&(h * 0.5)))
}

/// The TCP poses along the straight line from `from` to `to`, at most `step` apart (`from`
/// excluded, `to` included), each with whether it is the last: what a path certification checks.
fn line_samples(
    from: &Isometry3<f64>,
    to: &Isometry3<f64>,
    step: f64,
) -> impl Iterator<Item = (Isometry3<f64>, bool)> {
    let (from, to) = (*from, *to);
    let len = (to.translation.vector - from.translation.vector).norm();
    let n = ((len / step).ceil() as usize).max(1);
    (1..=n).map(move |k| {
        let s = k as f64 / n as f64;
        let p = from.translation.vector.lerp(&to.translation.vector, s);
        let r = from.rotation.slerp(&to.rotation, s);
        (Isometry3::from_parts(Translation3::from(p), r), k == n)
    })
}

/// Contacts at the start of a certified path, which the path may leave but not deepen:
/// penetration depth per part and obstacle.
type StartContacts = BTreeMap<Contact, f64>;

/// Whether shape `c` at `iso` hits obstacle `o`: overlaps it, or, when it started the path
/// inside it, is now deeper than `allowed_depth`.
fn hits(iso: &Isometry3<f64>, c: &dyn Shape, o: &Obstacle, allowed_depth: Option<f64>) -> bool {
    match allowed_depth {
        Some(allowed) => depth_in(iso, c, o).is_some_and(|d| d > allowed),
        None => query::intersection_test(iso, c, &o.iso, &o.shape).unwrap_or(true),
    }
}

/// How deep shape `c` at `iso` is inside obstacle `o` (m), if they overlap.
fn depth_in(iso: &Isometry3<f64>, c: &dyn Shape, o: &Obstacle) -> Option<f64> {
    match query::contact(iso, c, &o.iso, &o.shape, 0.0) {
        Ok(Some(k)) if k.dist < 0.0 => Some(-k.dist),
        _ => None,
    }
}

/// How far a carried body may press into a shelf in a certified motion (m): within the
/// simulator's stop for a carried body (0.9 of its 2 mm penetration tolerance), where the
/// contact slack alone would let it press up to twice the slack.
const HELD_OVERLAP: f64 = 0.001;

/// How much deeper than at its start a contact may get along a certified path (m): numerical
/// noise of the depth, not a motion into the obstacle.
const START_CONTACT_DRIFT: f64 = 1e-4;

/// The half extents assumed for a body that is not a block (the hook) where only its size
/// matters (m).
const NON_BLOCK_HALF_EXTENT: f64 = 0.03;

/// The fraction of the world's penetration tolerance by which [`StreamBinder::overhang`]
/// shrinks each box: a little less than half of the overlap the contact stop allows.
const OVERHANG_SLACK_OF_TOLERANCE: f64 = 0.4;

/// A fixed body whose top is at most this far above a pushed body's bottom is its support, not
/// in the way of its push (m).
const SUPPORT_TOP_MARGIN: f64 = 0.005;

/// Gap between neighbouring spots of a surface's packing lattice beyond the clearance (m).
const LATTICE_GAP: f64 = 0.002;

/// [`Binder::widen`] raises the samples per placement to at most this many times the initial.
pub const WIDEN_LIMIT: usize = 16;

/// Surfaces with at most this many spots on the packing lattice are filled lattice first.
const SMALL_SURFACE_SPOTS: usize = 12;

/// Radius around the demonstrated hook placement whose spots are tried first (m).
const HOOK_HINT_RADIUS: f64 = 0.15;

/// How far a body put down on a surface keeps from the surface's edge, beyond its own half
/// width (m).
const SURFACE_EDGE_MARGIN: f64 = 0.01;

/// How far inside a region (`(at x p)`) a body's centre is put down (m): the executor lets go
/// within a few millimetres of where it was told.
const REGION_INSET: f64 = 0.01;

/// Room a put-down hook keeps between every part of it and a shelf's footprint (m): the hand
/// comes down on its handle to pick it up again, and the arm's links beside the shelf (a hook
/// turned along the shelf left its handle 1 cm from it; the arm was stopped at the shelf).
const HOOK_SHELF_CLEARANCE: f64 = 0.08;

/// How many quarter turns of a square block (nearest the arm's heading first) a certified
/// release tries.
const CERTIFIED_TURNS: usize = 2;

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
            if let Some(up) = rise_first(self.world, arm, self.params.approach_height) {
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
        match self.bind_from(task, ops, demo_from, 0, geo, &mut out) {
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
}
