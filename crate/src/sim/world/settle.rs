//! Settling (contact rule 2): where a released or moved body comes to rest (a shape cast
//! straight down onto the first body under it, supported if its centroid lies over a top face
//! there), the stack resting on a body, releases, and bodies lost to the floor.

use super::{World, WorldEvent};
use crate::sim::collide;
use crate::sim::geometry::yaw_of;
use crate::sim::BodyKind;
use crate::sim::Relation;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::query::ShapeCastOptions;

/// Where a released or moved body would come to rest.
pub(super) enum Settle {
    /// On `support` (body index) with its centre lowered by `drop`.
    On { support: usize, drop: f64 },
    /// Nothing under it, or its centre is not above the surface it would touch.
    Falls(String),
    /// It overlaps a body already at its start height.
    Blocked(usize),
}

/// A settling body's downward shape cast starts this far above its pose (m), so that resting
/// on its support is no hit at the start.
const SETTLE_LIFT: f64 = 0.005;

/// A body that overlaps another even when lifted may still settle if that other's top is at
/// most this far above its lifted bottom (m): it lies below, not in the way.
const LIFTED_OVERLAP_SLACK: f64 = 0.003;

impl World {
    /// Blocks resting (transitively) on body `bi`, bottom to top.
    pub(crate) fn stack_above(&self, bi: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut frontier = vec![bi];
        while let Some(cur) = frontier.pop() {
            let (lo, hi) = self.bodies[cur].aabb();
            for (j, b) in self.bodies.iter().enumerate() {
                if j == bi || out.contains(&j) || !b.is_movable() || b.lost || self.is_held(j) {
                    continue;
                }
                let c = b.centroid_at(&b.pose);
                let (blo, _) = b.aabb();
                if (blo.z - hi.z).abs() <= self.params.support_tolerance
                    && c.x >= lo.x
                    && c.x <= hi.x
                    && c.y >= lo.y
                    && c.y <= hi.y
                    && self.bodies[cur].top_under(c.x, c.y, 0.0).is_some()
                {
                    out.push(j);
                    frontier.push(j);
                }
            }
        }
        out.sort_by(|&a, &b| {
            self.bodies[a]
                .pose
                .translation
                .z
                .total_cmp(&self.bodies[b].pose.translation.z)
        });
        out
    }

    /// Where body `bi` would come to rest if let go at `pose` (tilt removed, yaw kept); `ignore`
    /// lists bodies that are not obstacles.
    pub(super) fn settle_probe(
        &self,
        bi: usize,
        pose: &Isometry3<f64>,
        ignore: &[usize],
    ) -> Settle {
        self.settle_probe_among(bi, pose, ignore, false)
    }

    /// [`World::settle_probe`]; with `held_obstacles`, bodies held by a gripper are obstacles
    /// too (a dragged block must not fall through a carried one).
    pub(super) fn settle_probe_among(
        &self,
        bi: usize,
        pose: &Isometry3<f64>,
        ignore: &[usize],
        held_obstacles: bool,
    ) -> Settle {
        match self.settle_probe_once(bi, pose, ignore, held_obstacles) {
            Settle::Blocked(j) => {
                // Wedged under an overhang (a block pushed over its edge): what lies above its
                // centre cannot hold it up; it rests on what is below, if that holds it.
                let centre = pose.translation.z;
                let mut above: Vec<usize> = ignore.to_vec();
                above.extend(
                    (0..self.bodies.len())
                        .filter(|&k| k != bi && self.bodies[k].aabb().0.z > centre),
                );
                let limit = self.params.wedged_rest_depth();
                match self.settle_probe_once(bi, pose, &above, held_obstacles) {
                    Settle::On { support, drop } => {
                        // Only if, at rest, it presses into none of them beyond the tolerance.
                        let mut rest = self.bodies[bi].clone();
                        rest.pose = *pose;
                        rest.pose.translation.z -= drop;
                        let clear = above[ignore.len()..].iter().all(|&k| {
                            self.bodies[k].lost || rest.penetration(&self.bodies[k]) <= limit
                        });
                        if clear {
                            Settle::On { support, drop }
                        } else {
                            Settle::Blocked(j)
                        }
                    }
                    _ => Settle::Blocked(j),
                }
            }
            settle => settle,
        }
    }

    /// One probe of [`World::settle_probe_among`], `ignore` excepted.
    fn settle_probe_once(
        &self,
        bi: usize,
        pose: &Isometry3<f64>,
        ignore: &[usize],
        held_obstacles: bool,
    ) -> Settle {
        let b = &self.bodies[bi];
        let lift = SETTLE_LIFT;
        let start = Isometry3::from_parts(
            Translation3::from(pose.translation.vector + Vector3::new(0.0, 0.0, lift)),
            pose.rotation,
        );
        let (lo, _) = b.aabb_at(&start);
        let max_fall = (lo.z - self.floor_z).max(0.0);
        let down = Vector3::new(0.0, 0.0, -1.0);
        let mut best: Option<(f64, usize)> = None;
        for (j, o) in self.bodies.iter().enumerate() {
            if j == bi || o.lost || ignore.contains(&j) || (!held_obstacles && self.is_held(j)) {
                continue;
            }
            for (bp, bc) in &b.parts {
                let biso = start * bp;
                for (op, oc) in o.world_parts() {
                    let opts = ShapeCastOptions {
                        max_time_of_impact: max_fall,
                        target_distance: 0.0,
                        stop_at_penetration: true,
                        compute_impact_geometry_on_penetration: false,
                    };
                    if let Some(hit) =
                        collide::cast(&biso, &down, bc, &op, &Vector3::zeros(), oc, opts)
                    {
                        if best.is_none_or(|(t, _)| hit.time_of_impact < t) {
                            best = Some((hit.time_of_impact, j));
                        }
                    }
                }
            }
        }
        let Some((toi, j)) = best else {
            return Settle::Falls("nothing is under it".into());
        };
        if toi <= 0.0 {
            // Overlapping something even when lifted: only acceptable if that body is below.
            let (_, ohi) = self.bodies[j].aabb();
            if ohi.z > lo.z + LIFTED_OVERLAP_SLACK {
                return Settle::Blocked(j);
            }
        }
        let rest = Isometry3::from_parts(
            Translation3::from(start.translation.vector + down * toi),
            start.rotation,
        );
        let c = b.centroid_at(&rest);
        let (rlo, _) = b.aabb_at(&rest);
        // Supported if some body whose top is at the contact height lies under the centroid.
        let supported = self.bodies.iter().enumerate().any(|(k, o)| {
            k != bi
                && !o.lost
                && !ignore.contains(&k)
                && !self.is_held(k)
                && o.top_under(c.x, c.y, 0.0)
                    .is_some_and(|t| (t - rlo.z).abs() <= self.params.support_tolerance)
        });
        if !supported {
            return Settle::Falls(format!(
                "its centre is not above {} (it would tip over)",
                self.bodies[j].name
            ));
        }
        Settle::On {
            support: j,
            drop: pose.translation.z - rest.translation.z,
        }
    }

    /// Why a dragged or released body may not come to rest on body `support`, if it may not: a body held by
    /// a gripper, the hook, or a block in a domain that declares no `on_block` fact (the scene graph
    /// could not say where it is, and lifting the block below would leave it in the air).
    pub(super) fn support_refusal(&self, support: usize) -> Option<String> {
        let s = &self.bodies[support];
        if self.is_held(support) {
            return Some(format!(
                "it would land on {}, which a gripper holds",
                s.name
            ));
        }
        match s.kind {
            BodyKind::Hook => Some(format!("it would rest on the hook {}", s.name)),
            BodyKind::Block
                if !self.motions.facts.is_empty() && !self.motions.reports(Relation::OnBlock) =>
            {
                Some(format!(
                    "it would rest on the block {} and this domain cannot stack blocks (no predicate for a block on a block)",
                    s.name
                ))
            }
            _ => None,
        }
    }

    /// Pose with the tilt removed (yaw about `z` kept).
    pub(crate) fn upright(pose: &Isometry3<f64>) -> Isometry3<f64> {
        let yaw = yaw_of(&pose.rotation);
        Isometry3::from_parts(
            pose.translation,
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
        )
    }

    /// What opening arm `arm`'s gripper now would do to its load: `Err(why)` if the load would
    /// fall, end inside another body, or come to rest where a drag may not leave a body (on a
    /// held body, on the hook, on a block in a scene without `on`: the scene graph could not say
    /// where it is). Nothing held, or an unknown arm: `Ok`.
    pub fn release_check(&self, arm: usize) -> Result<(), String> {
        let Some((bi, _)) = self.arms.get(arm).and_then(|a| a.holding) else {
            return Ok(());
        };
        let pose = Self::upright(&self.bodies[bi].pose);
        match self.settle_probe(bi, &pose, &[]) {
            Settle::On { support, .. } => self.support_refusal(support).map_or(Ok(()), Err),
            Settle::Falls(reason) => Err(reason),
            Settle::Blocked(j) => Err(format!("it would be inside {}", self.bodies[j].name)),
        }
    }

    pub(super) fn release(&mut self, ai: usize, bi: usize, events: &mut Vec<WorldEvent>) {
        let pose = Self::upright(&self.bodies[bi].pose);
        self.bodies[bi].pose = pose;
        match self.settle_probe(bi, &pose, &[]) {
            Settle::On { support, drop } => {
                self.bodies[bi].pose.translation.z -= drop;
                events.push(WorldEvent::Released {
                    arm: self.arms[ai].name.clone(),
                    body: self.bodies[bi].name.clone(),
                    support: self.bodies[support].name.clone(),
                    drop,
                });
            }
            Settle::Falls(reason) => self.make_lost(bi, reason, events),
            Settle::Blocked(j) => {
                let reason = format!("released inside {}", self.bodies[j].name);
                self.make_lost(bi, reason, events)
            }
        }
    }

    pub(super) fn make_lost(&mut self, bi: usize, reason: String, events: &mut Vec<WorldEvent>) {
        let b = &mut self.bodies[bi];
        let (lo, _) = b.aabb();
        b.pose.translation.z += self.floor_z - lo.z;
        b.lost = true;
        events.push(WorldEvent::Lost {
            body: b.name.clone(),
            reason,
        });
    }
}
