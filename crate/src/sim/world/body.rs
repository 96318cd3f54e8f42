//! One body of the world (a union of boxes at a pose) and the geometric questions the stages
//! ask of it: bounds, centroid, containment of a point, the top face under a point, and the
//! penetration depth with another body.

use crate::sim::collide;
use crate::sim::BodyKind;
use nalgebra::{Isometry3, Point3, Vector3};
use parry3d_f64::shape::Cuboid;

/// One body: a union of boxes at a pose.
#[derive(Clone, Debug)]
pub(crate) struct Body {
    pub name: String,
    pub kind: BodyKind,
    /// Boxes in the body frame.
    pub parts: Vec<(Isometry3<f64>, Cuboid)>,
    pub pose: Isometry3<f64>,
    pub color: String,
    pub lost: bool,
}

impl Body {
    pub(crate) fn is_movable(&self) -> bool {
        matches!(self.kind, BodyKind::Block | BodyKind::Hook)
    }

    /// World poses of the parts.
    pub(crate) fn world_parts(&self) -> impl Iterator<Item = (Isometry3<f64>, &Cuboid)> + '_ {
        self.parts.iter().map(move |(p, c)| (self.pose * p, c))
    }

    /// World-frame axis-aligned bounds `(min, max)`.
    pub(crate) fn aabb(&self) -> (Vector3<f64>, Vector3<f64>) {
        self.aabb_at(&self.pose)
    }

    pub(crate) fn aabb_at(&self, pose: &Isometry3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = Vector3::repeat(f64::NEG_INFINITY);
        for (p, c) in &self.parts {
            let iso = pose * p;
            let r = iso.rotation.to_rotation_matrix();
            let m = r.matrix().abs();
            let ext = m * c.half_extents;
            let t = iso.translation.vector;
            lo = lo.inf(&(t - ext));
            hi = hi.sup(&(t + ext));
        }
        (lo, hi)
    }

    /// Volume-weighted centroid of the parts, world frame.
    pub(crate) fn centroid_at(&self, pose: &Isometry3<f64>) -> Vector3<f64> {
        let mut acc = Vector3::zeros();
        let mut vol = 0.0;
        for (p, c) in &self.parts {
            let v = c.half_extents.x * c.half_extents.y * c.half_extents.z;
            acc += (pose * p).translation.vector * v;
            vol += v;
        }
        acc / vol
    }

    /// Whether the world point lies inside some part grown by `margin`.
    pub(crate) fn contains_point(&self, pt: &Point3<f64>, margin: f64) -> bool {
        self.world_parts().any(|(iso, c)| {
            let l = iso.inverse_transform_point(pt);
            l.x.abs() <= c.half_extents.x + margin
                && l.y.abs() <= c.half_extents.y + margin
                && l.z.abs() <= c.half_extents.z + margin
        })
    }

    /// The highest top-face height of a part whose horizontal footprint contains `(x, y)`.
    pub(crate) fn top_under(&self, x: f64, y: f64, margin: f64) -> Option<f64> {
        let mut best: Option<f64> = None;
        for (iso, c) in self.world_parts() {
            let l = iso.inverse_transform_point(&Point3::new(x, y, iso.translation.vector.z));
            if l.x.abs() <= c.half_extents.x + margin && l.y.abs() <= c.half_extents.y + margin {
                let m = iso.rotation.to_rotation_matrix();
                let top = iso.translation.vector.z + (m.matrix().abs() * c.half_extents).z;
                best = Some(best.map_or(top, |b: f64| b.max(top)));
            }
        }
        best
    }

    /// Penetration depth with another body (≥ 0; 0 when apart or touching).
    pub(crate) fn penetration(&self, other: &Body) -> f64 {
        let (alo, ahi) = self.aabb();
        let (blo, bhi) = other.aabb();
        if (0..3).any(|i| alo[i] > bhi[i] || blo[i] > ahi[i]) {
            return 0.0;
        }
        let mut depth: f64 = 0.0;
        for (ia, ca) in self.world_parts() {
            for (ib, cb) in other.world_parts() {
                if let Some(c) = collide::contact(&ia, ca, &ib, cb, 0.0) {
                    depth = depth.max(-c.dist);
                }
            }
        }
        depth
    }
}
