//! The pull stream: the hook's stroke (radial, then turned), where it leaves the pulled body
//! (shape casts of the hook and of the pushed body), the stroke's motion certified.

use crate::sim::collide;
use nalgebra::{Isometry3, Translation3, Vector3};
use parry3d_f64::query::ShapeCastOptions;

use super::boxes::Obstacle;
use super::{Geo, Held, StreamBinder, Transit};
use crate::sim::demo::{pull_hook_poses_turned, PULL_TARGET_RADIUS, PULL_TURNS};
use crate::sim::geometry::raised;
use crate::sim::BodyKind;

impl StreamBinder<'_> {
    /// The pose a pull stroke of `arm` leaves `body` at (shape cast of the carried hook along
    /// the executor's stroke, then of the block along its push), after certifying the stroke.
    /// Tries the radial stroke, then strokes turned by ±PULL_TURNS (certified ones only):
    /// the turn of the first that passes and the height of the transit its approach needs, if
    /// any; the geometric state rolled on.
    pub(super) fn pull(
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
        let opts = ShapeCastOptions {
            max_time_of_impact: 1.0,
            target_distance: 0.0,
            stop_at_penetration: false,
            compute_impact_geometry_on_penetration: false,
        };
        let mut toi = f64::INFINITY;
        for (hiso, hc) in self.parts_at(&hook, &contact) {
            for (biso, bc) in self.parts_at(body, &bp) {
                if let Some(hit) =
                    collide::cast(&hiso, &d, &hc, &biso, &Vector3::zeros(), &bc, opts)
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
                    if let Some(hit) = collide::cast(
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
}

/// A fixed body whose top is at most this far above a pushed body's bottom is its support, not
/// in the way of its push (m).
const SUPPORT_TOP_MARGIN: f64 = 0.005;
