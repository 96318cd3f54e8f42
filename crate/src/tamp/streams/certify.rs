//! Certifying a motion: the TCP path through via-points sampled and tracked by IK as the
//! simulator's joint tracker follows it, with the executor's transit and joint-space recovery,
//! every sample's links and load tested against the obstacles.

use std::collections::BTreeMap;

use crate::sim::collide::{self, Solid};
use nalgebra::{Isometry3, Translation3, Vector3};
use parry3d_f64::shape::Cuboid;

use super::boxes::{box_aabb, overlaps, Obstacle};
use super::{fmt_point, Geo, Predicted, StreamBinder};
use crate::sim::panda::DOF;
use crate::sim::LINK_TOLERANCE;
use crate::sim::{joint_line, ArmModel, ArmShape};
use crate::tamp::{joint_recovery, transit_height, JointMoves, RecoveryRoute};
use std::sync::Arc;

/// Why a candidate was not certified (counted in [`StreamStats`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Reject {
    /// The IK tracker cannot follow the path (or the pose is out of reach).
    Ik,
    /// A link or the carried body hits something along the path.
    Collision,
}

/// A part of a carried body as a certification tests it.
#[derive(Clone, Copy, Debug)]
pub(super) struct LoadPart {
    /// Its pose in the TCP frame.
    pub(super) offset: Isometry3<f64>,
    /// Its box grown by the transfer margin (shrunk by the contact slack without one).
    pub(super) wide: Cuboid,
    /// Its box shrunk by the contact slack.
    pub(super) plain: Cuboid,
    /// Its box as far as it may press into a shelf ([`HELD_OVERLAP`]).
    pub(super) pressed: Cuboid,
}

/// What a motion hits: in words, and the name of the body hit.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Hit {
    pub(super) words: String,
    pub(super) body: String,
}

/// Arm `arm` of a certification at joints `q`, carrying `load` among `obstacles` (`start`: its
/// contacts at the start of the path), as a joint-space recovery sees it.
struct TrackedArm<'a, 'w> {
    binder: &'a mut StreamBinder<'w>,
    arm: usize,
    base: &'a Isometry3<f64>,
    model: Arc<ArmModel>,
    q: [f64; DOF],
    load: &'a [LoadPart],
    obstacles: &'a [Obstacle],
    start: &'a StartContacts,
}

impl JointMoves for TrackedArm<'_, '_> {
    type Hit = Hit;

    fn joints(&self) -> Option<[f64; DOF]> {
        Some(self.q)
    }

    fn tcp_position(&self) -> Option<Vector3<f64>> {
        Some(
            self.model
                .forward_kinematics(self.base, &self.q)
                .translation
                .vector,
        )
    }

    fn ready(&self) -> Option<[f64; DOF]> {
        Some(self.model.ready())
    }

    fn solve_with_room(&self, pose: &Isometry3<f64>) -> Option<[f64; DOF]> {
        let ik = &self.binder.world.params().planning_ik;
        self.model
            .inverse_kinematics_with_room(self.base, pose, &self.q, ik)
            .ok()
            .map(|s| s.joints)
    }

    fn solve_near(&self, pose: &Isometry3<f64>) -> Option<[f64; DOF]> {
        let ik = &self.binder.world.params().planning_ik;
        self.model
            .inverse_kinematics_near(self.base, pose, &self.q, ik)
            .ok()
            .map(|s| s.joints)
    }

    fn joint_move_hits(&mut self, from: &[f64; DOF], to: &[f64; DOF]) -> Option<Hit> {
        self.binder.joint_leg_hits(
            self.arm,
            self.base,
            from,
            to,
            self.load,
            self.obstacles,
            self.start,
        )
    }
}

/// A part of an arm in a certification: one of its links (by index) or a part of its load.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Part {
    Link(usize),
    /// The last link capsule, the hand's.
    Hand,
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

/// The shape of a [`Part`]: a solid of the arm or a load part's box.
enum PartShape {
    Arm(ArmShape),
    Cuboid(Cuboid),
}

impl PartShape {
    fn as_shape(&self) -> &dyn Solid {
        match self {
            PartShape::Arm(s) => s,
            PartShape::Cuboid(c) => c,
        }
    }
}

/// Contacts at the start of a certified path, which the path may leave but not deepen:
/// penetration depth per part and obstacle.
type StartContacts = BTreeMap<Contact, f64>;

impl StreamBinder<'_> {
    /// Arm `arm`'s kinematic model (the built-in Panda for an unknown arm).
    fn arm_model(&self, arm: usize) -> Arc<ArmModel> {
        self.world
            .arm_model(arm)
            .cloned()
            .unwrap_or_else(ArmModel::panda)
    }

    /// Certifies the TCP path through `via` for arm `arm` carrying what `geo` says it carries:
    /// returns the joints at the end, or why not. `exclude`: bodies the motion may touch.
    pub(super) fn certify_path(
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
        let model = self.arm_model(arm);
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
                q = match model.inverse_kinematics(&base, &tcp, &q, ik) {
                    Ok(sol) => sol.joints,
                    Err(e) if !end => e.best_joints,
                    // A straight line is not the skill's path: the tracker may also come in
                    // from where the segment started. Either way without restarts.
                    Err(_) => match model.inverse_kinematics(&base, &tcp, &q_from, ik) {
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
    pub(super) fn collision(&mut self, why: String, body: &str) -> Reject {
        self.last_rejection = Some(why);
        self.blocked_by(body);
        self.stats.rejected_collision += 1;
        Reject::Collision
    }

    /// Notes that `body` is in the way of the candidate being certified, if it is movable (a
    /// table or shelf is not: no action can clear it).
    pub(super) fn blocked_by(&mut self, body: &str) {
        if self.local.contains_key(body) && !self.last_blockers.iter().any(|b| b == body) {
            self.last_blockers.push(body.to_string());
        }
    }

    /// Starts certifying a candidate of the action being bound: nothing is in its way yet.
    pub(super) fn begin_candidate(&mut self) {
        self.last_blockers.clear();
    }

    /// The candidate being certified failed: what was in its way blocked the action.
    pub(super) fn candidate_failed(&mut self) {
        let blockers = std::mem::take(&mut self.last_blockers);
        self.blockers
            .entry(self.action)
            .or_default()
            .extend(blockers);
    }

    /// Certifies the path through `via`, whose first point is the goal of the action's
    /// approach: straight, or, when that hits something, as a transit (straight up to
    /// [`transit_height`], across above `via[0]`, straight down to it: the executor's
    /// `ActionExec::with_transit`). The joints at the end and the transit's TCP height, if one
    /// was needed. A rejection tells why both were refused.
    pub(super) fn certify_approach(
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
        let Some(z) = transit_height(&Predicted { binder: self, geo }, arm, goal) else {
            return Err(Reject::Collision);
        };
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

    /// The executor's joint-space recovery from joints `q` to the TCP pose `goal`
    /// ([`joint_recovery`], the route the executor takes): `None` if the planning IK finds no
    /// solution, else the joints where the recovery ends, after the tracker's line from a
    /// solution on the way, or what the straight move to the solution hits.
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
        let model = self.arm_model(arm);
        let mut tracked = TrackedArm {
            binder: self,
            arm,
            base,
            model,
            q: *q,
            load,
            obstacles,
            start,
        };
        let recovery = joint_recovery(&mut tracked, goal)?;
        Some(match recovery.route {
            RecoveryRoute::Straight | RecoveryRoute::ByReady { .. } => Ok(recovery.goal),
            RecoveryRoute::Near { joints, pose, hit } => self
                .track_line(arm, base, &joints, &pose, goal, load, obstacles, start)
                .ok_or(hit),
            RecoveryRoute::Blocked(hit) => Err(hit),
        })
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
        let model = self.arm_model(arm);
        for (tcp, end) in line_samples(from, to, self.params.path_step) {
            self.stats.path_samples += 1;
            let ik = if end { &self.settle_ik } else { &self.track_ik };
            q = match model.inverse_kinematics(base, &tcp, &q, ik) {
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
        let model = self.arm_model(arm);
        for qk in joint_line(from, to) {
            self.stats.path_samples += 1;
            let tcp = model.forward_kinematics(base, &qk);
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
        let (parts, base) = self.world.arm_parts(arm, q);
        let hand = parts.len().saturating_sub(1);
        for (i, part) in parts.into_iter().enumerate().skip(base) {
            for (oi, o) in obstacles.iter().enumerate() {
                if overlaps(&part.lo, &part.hi, o) {
                    out.push(Overlap {
                        contact: Contact {
                            part: if i == hand { Part::Hand } else { Part::Link(i) },
                            obstacle: oi,
                        },
                        iso: part.iso,
                        shape: PartShape::Arm(part.shape.clone()),
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
                        Part::Link(_) | Part::Hand if o.fixed => {
                            LINK_TOLERANCE - self.params.contact_slack
                        }
                        _ => 0.0,
                    };
                    (d0 + START_CONTACT_DRIFT).max(tolerated)
                });
                hits(&pair.iso, pair.shape.as_shape(), o, allowed)
            })?
            .contact;
        let o = &obstacles[oi].name;
        let words = match part {
            Part::Hand => format!("the hand hits {o}"),
            Part::Link(i) => format!("link {i} hits {o}"),
            Part::Load(_) => format!("the carried body hits {o}"),
        };
        Some(Hit {
            words,
            body: o.clone(),
        })
    }
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

/// Whether shape `c` at `iso` hits obstacle `o`: overlaps it, or, when it started the path
/// inside it, is now deeper than `allowed_depth`.
fn hits(iso: &Isometry3<f64>, c: &dyn Solid, o: &Obstacle, allowed_depth: Option<f64>) -> bool {
    match allowed_depth {
        Some(allowed) => depth_in(iso, c, o).is_some_and(|d| d > allowed),
        None => collide::intersects(iso, c, &o.iso, &o.shape),
    }
}

/// How deep shape `c` at `iso` is inside obstacle `o` (m), if they overlap.
fn depth_in(iso: &Isometry3<f64>, c: &dyn Solid, o: &Obstacle) -> Option<f64> {
    match collide::contact(iso, c, &o.iso, &o.shape, 0.0) {
        Some(k) if k.dist < 0.0 => Some(-k.dist),
        _ => None,
    }
}

/// How much deeper than at its start a contact may get along a certified path (m): numerical
/// noise of the depth, not a motion into the obstacle.
const START_CONTACT_DRIFT: f64 = 1e-4;
