//! The predicted scene as boxes: the tables' and shelves' and the movable bodies' boxes where
//! the rolled-forward state has them, shrunk or grown for the tests of a certification.

use nalgebra::{Isometry3, Vector3};
use parry3d_f64::shape::Cuboid;

use super::boxes::{box_aabb, Obstacle};
use super::{Geo, StreamBinder};
use crate::sim::BodyKind;

impl StreamBinder<'_> {
    /// Half the size of block `body` (its world AABB's), or [`NON_BLOCK_HALF_EXTENT`] each way
    /// for any other body.
    pub(super) fn half_extents(&self, body: &str) -> Vector3<f64> {
        match self.world.body_aabb(body) {
            Some((lo, hi)) if self.world.body_kind(body) == Some(BodyKind::Block) => {
                0.5 * (hi - lo)
            }
            _ => Vector3::repeat(NON_BLOCK_HALF_EXTENT),
        }
    }

    /// The boxes of movable `body` at `pose`.
    pub(super) fn parts_at(
        &self,
        body: &str,
        pose: &Isometry3<f64>,
    ) -> Vec<(Isometry3<f64>, Cuboid)> {
        self.local
            .get(body)
            .map(|v| v.iter().map(|(off, c)| (pose * off, *c)).collect())
            .unwrap_or_default()
    }

    /// Box `c` shrunk by the contact slack ([`shrunk_by`]).
    pub(super) fn shrink(&self, c: &Cuboid) -> Cuboid {
        shrunk_by(c, self.params.contact_slack)
    }

    /// A carried or pushed body's box `c` as tested against a shelf (which is shrunk by the
    /// contact slack): it may press in only [`HELD_OVERLAP`], where the simulator stops it; grown
    /// by `margin` if that is more.
    pub(super) fn pressed(&self, c: &Cuboid, margin: f64) -> Cuboid {
        let grow = margin.max(self.params.contact_slack - HELD_OVERLAP);
        Cuboid::new(c.half_extents + Vector3::repeat(grow))
    }

    /// The tables' and shelves' boxes (world frame).
    pub(super) fn fixed_boxes(&self) -> Vec<(Isometry3<f64>, Cuboid)> {
        self.fixed
            .iter()
            .flat_map(|b| b.parts.iter().copied())
            .collect()
    }

    /// Everything arm `arm` may not touch in `geo`: fixed bodies and movable bodies other than
    /// `exclude` and the arm's own load (bodies carried by other arms included). The arms
    /// themselves do not collide with each other in the simulator (nor in the demonstration's
    /// hand-over), so they are not obstacles.
    pub(super) fn obstacles(&self, geo: &Geo, arm: usize, exclude: &[&str]) -> Vec<Obstacle> {
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

    /// The boxes of every body in `geo` but `body` and the held ones, unshrunk (what the
    /// executor's grasp choice sees in the world).
    pub(super) fn boxes_except(&self, geo: &Geo, body: &str) -> Vec<(Isometry3<f64>, Cuboid)> {
        let mut out = self.fixed_boxes();
        for (name, pose) in &geo.poses {
            if name != body && !geo.is_held(name) {
                out.extend(self.parts_at(name, pose));
            }
        }
        out
    }
}

/// `c` with every half extent `slack` smaller, but at least half of what it was (where
/// `sim::geometry::shrunk` keeps at least 0.1 mm: the two differ on thin boxes).
pub(super) fn shrunk_by(c: &Cuboid, slack: f64) -> Cuboid {
    let h = c.half_extents;
    Cuboid::new((h - Vector3::repeat(slack)).sup(&(h * 0.5)))
}

/// How far a carried body may press into a shelf in a certified motion (m): within the
/// simulator's stop for a carried body (0.9 of its 2 mm penetration tolerance), where the
/// contact slack alone would let it press up to twice the slack.
pub(super) const HELD_OVERLAP: f64 = 0.001;

/// The half extents assumed for a body that is not a block (the hook) where only its size
/// matters (m).
pub(super) const NON_BLOCK_HALF_EXTENT: f64 = 0.03;
