//! The hook's pushes (contact rule 3): blocks the carried hook's blade sweeps into move
//! horizontally with what stands on them, and fall when pushed off their support.

use super::settle::Settle;
use super::{World, WorldEvent};
use crate::sim::collide;
use crate::sim::BodyKind;
use nalgebra::{Isometry3, Vector3};
use parry3d_f64::query::ShapeCastOptions;

/// A hook moving less than this horizontally in a step pushes nothing (m).
const MIN_HOOK_STROKE: f64 = 1e-9;

/// A push shorter than this moves nothing and reports nothing (m).
const MIN_PUSH: f64 = 1e-12;

/// A contact pushes sideways only if the horizontal part of its unit normal is at least this
/// long; a steeper normal is the hook resting on the block.
const MIN_SIDEWAYS_NORMAL: f64 = 0.7;

/// How far past the deepest contact a blade still inside a block drives it (m), so they end
/// apart.
const PUSH_CLEARANCE: f64 = 1e-4;

impl World {
    /// The hook (body `hi`) moved from `before` to its current pose: blocks hit by the swept blade
    /// are pushed horizontally by the remaining part of the motion (with what stands on them).
    pub(super) fn hook_push(
        &mut self,
        hi: usize,
        before: &Isometry3<f64>,
        events: &mut Vec<WorldEvent>,
    ) {
        let after = self.bodies[hi].pose;
        let d = after.translation.vector - before.translation.vector;
        let horiz = Vector3::new(d.x, d.y, 0.0);
        if horiz.norm() < MIN_HOOK_STROKE {
            return;
        }
        for bi in 0..self.bodies.len() {
            let b = &self.bodies[bi];
            if b.kind != BodyKind::Block || b.lost || self.is_held(bi) {
                continue;
            }
            // Swept test: the hook's boxes translate along d from `before` (parry shape cast).
            let mut toi = f64::INFINITY;
            for (hp, hc) in &self.bodies[hi].parts {
                let hiso = before * hp;
                for (bp, bc) in b.world_parts() {
                    let opts = ShapeCastOptions {
                        max_time_of_impact: 1.0,
                        target_distance: 0.0,
                        stop_at_penetration: false,
                        compute_impact_geometry_on_penetration: false,
                    };
                    if let Some(hit) =
                        collide::cast(&hiso, &d, hc, &bp, &Vector3::zeros(), bc, opts)
                    {
                        // Separating contacts at time 0 are discarded by parry
                        // (`stop_at_penetration: false`), so a hit is a blade driving into it.
                        toi = toi.min(hit.time_of_impact);
                    }
                }
            }
            let mut push = if toi > 1.0 {
                Vector3::zeros()
            } else {
                horiz * (1.0 - toi)
            };
            // The hook also turns a little as the arm tracks its stroke, which a translation
            // alone does not cover: a blade still inside the block after the push drives it
            // further along the contact's (horizontal) normal.
            push += self.hook_overlap_push(hi, bi, &push);
            if push.norm() < MIN_PUSH {
                continue;
            }
            let stack = self.stack_above(bi);
            for &si in std::iter::once(&bi).chain(stack.iter()) {
                self.bodies[si].pose.translation.vector += push;
            }
            events.push(WorldEvent::Pushed {
                body: self.bodies[bi].name.clone(),
                by: self.bodies[hi].name.clone(),
                displacement: [push.x, push.y],
            });
            // Pushed off its support? Then it (and its stack) falls.
            for si in std::iter::once(bi).chain(stack) {
                if let Settle::Falls(reason) =
                    self.settle_probe(si, &self.bodies[si].pose.clone(), &[hi])
                {
                    self.make_lost(si, reason, events);
                }
            }
        }
    }

    /// How far block `bi`, already moved by `push`, must move further so that the hook `hi` (at
    /// its pose) no longer overlaps it sideways: the horizontal part of the deepest contact's
    /// normal times its depth (zero when they do not overlap, or the contact is vertical: a hook
    /// resting on a block does not push it).
    fn hook_overlap_push(&self, hi: usize, bi: usize, push: &Vector3<f64>) -> Vector3<f64> {
        let mut best = Vector3::zeros();
        // Runs every step the hook is carried: apart (AABBs disjoint) means no overlap.
        let (hlo, hhi) = self.bodies[hi].aabb();
        let (blo, bhi) = self.bodies[bi].aabb();
        if (0..3).any(|i| hlo[i] > bhi[i] + push[i] || blo[i] + push[i] > hhi[i]) {
            return best;
        }
        let shift = Isometry3::translation(push.x, push.y, push.z);
        for (hiso, hc) in self.bodies[hi].world_parts() {
            for (biso, bc) in self.bodies[bi].world_parts() {
                let Some(k) = collide::contact(&hiso, hc, &(shift * biso), bc, 0.0) else {
                    continue;
                };
                let n = k.normal1.into_inner();
                let side = Vector3::new(n.x, n.y, 0.0);
                if k.dist >= 0.0 || side.norm() < MIN_SIDEWAYS_NORMAL {
                    continue;
                }
                let step = side.normalize() * (-k.dist + PUSH_CLEARANCE);
                if step.norm() > best.norm() {
                    best = step;
                }
            }
        }
        best
    }
}
