//! Boxes of the predicted scene: fixed bodies, obstacles with their bounds, overlap tests.

use nalgebra::{Isometry3, Vector3};
use parry3d_f64::shape::Cuboid;

use crate::sim::BodyKind;

/// A table or shelf: no action moves it.
#[derive(Clone, Debug)]
pub(super) struct FixedBody {
    pub(super) name: String,
    pub(super) kind: BodyKind,
    /// Its boxes in the world.
    pub(super) parts: Vec<(Isometry3<f64>, Cuboid)>,
}

/// An obstacle of one certification: a box (shrunk by the contact slack) and its world AABB.
pub(super) struct Obstacle {
    pub(super) name: String,
    /// A table: the carried body's transfer margin does not apply to it (a load on its way
    /// from a low pose would otherwise start inside the margin).
    pub(super) support: bool,
    /// A table or shelf: no action moves it.
    pub(super) fixed: bool,
    pub(super) iso: Isometry3<f64>,
    pub(super) shape: Cuboid,
    pub(super) lo: Vector3<f64>,
    pub(super) hi: Vector3<f64>,
}

/// World AABB of a box at a pose.
pub(super) fn box_aabb(iso: &Isometry3<f64>, c: &Cuboid) -> (Vector3<f64>, Vector3<f64>) {
    let r = iso.rotation.to_rotation_matrix();
    let m = r.matrix().abs();
    let ext = m * c.half_extents;
    let t = iso.translation.vector;
    (t - ext, t + ext)
}

/// Whether the AABB `lo`..`hi` meets obstacle `o`'s.
pub(super) fn overlaps(lo: &Vector3<f64>, hi: &Vector3<f64>, o: &Obstacle) -> bool {
    lo.x <= o.hi.x
        && hi.x >= o.lo.x
        && lo.y <= o.hi.y
        && hi.y >= o.lo.y
        && lo.z <= o.hi.z
        && hi.z >= o.lo.z
}
