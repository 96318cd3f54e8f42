//! The release streams: a body put down on a block or on a surface (table, shelf, region), its
//! resting spots sampled and ordered, each spot and the release motion certified.

use crate::sim::collide;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::shape::Cuboid;
use rand::Rng;

use super::boxes::box_aabb;
use super::{Geo, Held, StreamBinder, Transit};
use crate::sim::geometry::{grasp_pose_at, hand_within, raised};
use crate::sim::yaw_of;
use crate::sim::BodyKind;
use crate::tamp::release_turns;
use crate::tamp::PlanarPose;
use crate::tamp::ReleaseTarget;

/// A support surface a body may be put down on: its top face's x and y ranges and its height
/// (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Surface {
    pub(super) x: [f64; 2],
    pub(super) y: [f64; 2],
    pub(super) z: f64,
}

impl Surface {
    /// Whether `(x, y)` lies on the surface (edges included).
    fn contains(&self, x: f64, y: f64) -> bool {
        self.x[0] <= x && x <= self.x[1] && self.y[0] <= y && y <= self.y[1]
    }
}

/// Sorts `spots` by their distance to `(x, y)`, nearest first (stable): each distance computed
/// once, not at every comparison (`libm::hypot` is a software square root in wasm).
fn sort_nearest_first(spots: &mut Vec<Spot>, x: f64, y: f64) {
    let mut keyed: Vec<(f64, Spot)> = spots
        .drain(..)
        .map(|s| (libm::hypot(s.at.x - x, s.at.y - y), s))
        .collect();
    keyed.sort_by(|a, b| a.0.total_cmp(&b.0));
    spots.extend(keyed.into_iter().map(|(_, s)| s));
}

/// A candidate resting spot for a body put down on a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Spot {
    /// Which sample it is: 0 for the demonstration's hint.
    pub(super) sample: usize,
    /// Centre and yaw of the resting body.
    pub(super) at: PlanarPose,
    /// Height of the surface's top (m).
    pub(super) top: f64,
}

impl StreamBinder<'_> {
    /// Where `body` rests centred on top of block `y`, as `geo` has `y`.
    pub(super) fn on_block_pose(&self, geo: &Geo, body: &str, y: &str) -> Option<Isometry3<f64>> {
        let py = geo.poses.get(y).copied()?;
        let hy = self.half_extents(y);
        let hb = self.half_extents(body);
        Some(Isometry3::from_parts(
            Translation3::from(py.translation.vector + Vector3::z() * (hy.z + hb.z)),
            py.rotation,
        ))
    }

    /// Certifies `arm` putting its load down with the body at `pose` (approach from above,
    /// open, retreat up) and rolls `geo` on: `None` if it cannot, else the height of the
    /// transit its approach needs, if any, and the hand's yaw it certified (`None` uncertified).
    /// A square block may be put down turned by a quarter turn (it looks the same): the hand
    /// nearest the arm's heading first (what the executor does uncertified), then the next
    /// nearest (the hand turned a quarter, e.g. lengthwise beside a tower); the executor puts
    /// the hand where it was certified.
    pub(super) fn release(
        &mut self,
        geo: &mut Geo,
        arm: usize,
        pose: &Isometry3<f64>,
        certify: bool,
    ) -> Option<(Transit, Option<f64>)> {
        let Held { body, grasp: g } = geo.held.get(&arm).cloned()?;
        let turns = release_turns(self.world, arm, &body, pose, &g, None);
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
        let retreat = raised(&tcp, self.params.motion.approach_height);
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
            let drop = raised(&tcp, self.params.motion.release_clearance);
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
                    if collide::intersects(&iso, test_shape, &oiso, &other) {
                        return false;
                    }
                }
            }
            for b in &self.fixed {
                for (fiso, fc) in &b.parts {
                    if collide::intersects(&iso, &me, fiso, fc) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// The support surfaces a release onto `target` may use: the tables or shelves, or a
    /// region (which narrows the table it lies on).
    pub(super) fn surfaces(&self, target: &ReleaseTarget, body: &str) -> Vec<Surface> {
        let mut out = vec![];
        match target {
            ReleaseTarget::Region(name) => {
                if let Some(s) = self.region_surface(name, body) {
                    out.push(s);
                }
            }
            ReleaseTarget::Surface(kind) => {
                for b in self.fixed.iter().filter(|b| b.kind == *kind) {
                    if let Some((lo, hi)) = self.world.body_aabb(&b.name) {
                        out.push(Surface {
                            x: [lo.x, hi.x],
                            y: [lo.y, hi.y],
                            z: hi.z,
                        });
                    }
                }
            }
            ReleaseTarget::Block(_) => {}
        }
        out
    }

    /// Region `name`, as a surface for `body`.
    fn region_surface(&self, name: &str, body: &str) -> Option<Surface> {
        let r = self.regions.iter().find(|r| r.name == name)?;
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
        // A region holds a body by its centre (`SceneGraph`): the candidates' edge margin (half
        // the body and SURFACE_EDGE_MARGIN, for the edge of a real surface) becomes
        // REGION_INSET from the region's edge.
        let h = self.half_extents(body);
        let grow = (h.x.max(h.y) + SURFACE_EDGE_MARGIN - REGION_INSET).max(0.0);
        top.is_finite().then(|| Surface {
            x: [r.min[0] - grow, r.max[0] + grow],
            y: [r.min[1] - grow, r.max[1] + grow],
            z: top,
        })
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
    pub(super) fn in_annulus(&self, a: usize, x: f64, y: f64) -> bool {
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
    pub(super) fn surface_candidates(
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
        sort_nearest_first(&mut drawn, at.x, at.y);
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
        sort_nearest_first(&mut lattice, at.x, at.y);
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
    pub(super) fn try_surface(
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
                            .reachable(a, &raised(&g, self.params.motion.approach_height))
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
}

/// Gap between neighbouring spots of a surface's packing lattice beyond the clearance (m).
const LATTICE_GAP: f64 = 0.002;

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
/// turned along the shelf with its handle 1 cm from it stops the arm at the shelf).
const HOOK_SHELF_CLEARANCE: f64 = 0.08;

/// How many quarter turns of a square block (nearest the arm's heading first) a certified
/// release tries.
const CERTIFIED_TURNS: usize = 2;
