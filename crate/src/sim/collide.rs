//! Collision queries between the workcell's solids: boxes ([`Cuboid`]) and arm links
//! ([`Capsule`]).
//!
//! Each query runs the parry algorithm that parry's `DefaultQueryDispatcher` picks for these two
//! shape types (separating axes for box–box overlap, GJK/EPA otherwise), so results are the same
//! bit for bit as through `parry3d_f64::query`. The dispatcher itself is not used: it reaches
//! every shape parry knows (meshes, height fields, voxels, compound shapes) and would bring all of
//! their code into the wasm modules.

use nalgebra::{Isometry3, Vector3};
use parry3d_f64::query::details;
use parry3d_f64::query::{Contact, ShapeCastHit, ShapeCastOptions};
use parry3d_f64::shape::{Capsule, Cuboid, SupportMap};

/// A convex solid of the workcell: a box or a capsule.
pub trait Solid {
    /// The solid as a support map (what GJK and EPA read).
    fn support_map(&self) -> &dyn SupportMap;
    /// The solid as a box, if it is one (box–box overlap has its own test).
    fn cuboid(&self) -> Option<&Cuboid> {
        None
    }
}

impl Solid for Cuboid {
    fn support_map(&self) -> &dyn SupportMap {
        self
    }
    fn cuboid(&self) -> Option<&Cuboid> {
        Some(self)
    }
}

impl Solid for Capsule {
    fn support_map(&self) -> &dyn SupportMap {
        self
    }
}

/// Whether `a` at `pos1` and `b` at `pos2` overlap (touching counts), as
/// `parry3d_f64::query::intersection_test`.
pub fn intersects(
    pos1: &Isometry3<f64>,
    a: &(impl Solid + ?Sized),
    pos2: &Isometry3<f64>,
    b: &(impl Solid + ?Sized),
) -> bool {
    let pos12 = pos1.inv_mul(pos2);
    match (a.cuboid(), b.cuboid()) {
        (Some(c1), Some(c2)) => details::intersection_test_cuboid_cuboid(&pos12, c1, c2),
        _ => details::intersection_test_support_map_support_map(
            &pos12,
            a.support_map(),
            b.support_map(),
        ),
    }
}

/// The contact between `a` at `pos1` and `b` at `pos2` if they are closer than `prediction`
/// (`dist < 0`: penetration depth), in world coordinates, as `parry3d_f64::query::contact`.
pub fn contact(
    pos1: &Isometry3<f64>,
    a: &(impl Solid + ?Sized),
    pos2: &Isometry3<f64>,
    b: &(impl Solid + ?Sized),
    prediction: f64,
) -> Option<Contact> {
    let pos12 = pos1.inv_mul(pos2);
    let mut c = details::contact_support_map_support_map(
        &pos12,
        a.support_map(),
        b.support_map(),
        prediction,
    )?;
    c.transform_by_mut(pos1, pos2);
    Some(c)
}

/// The first time of impact of `a` (at `pos1`, moving at `vel1`) with `b` (at `pos2`, moving at
/// `vel2`), as `parry3d_f64::query::cast_shapes`.
pub fn cast(
    pos1: &Isometry3<f64>,
    vel1: &Vector3<f64>,
    a: &(impl Solid + ?Sized),
    pos2: &Isometry3<f64>,
    vel2: &Vector3<f64>,
    b: &(impl Solid + ?Sized),
    options: ShapeCastOptions,
) -> Option<ShapeCastHit> {
    let pos12 = pos1.inv_mul(pos2);
    let vel12 = pos1.inverse_transform_vector(&(vel2 - vel1));
    details::cast_shapes_support_map_support_map(
        &pos12,
        &vel12,
        a.support_map(),
        b.support_map(),
        options,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Point3, Translation3, UnitQuaternion};
    use parry3d_f64::query;
    use parry3d_f64::shape::Shape;
    use rand::{Rng, SeedableRng};

    fn pose(rng: &mut rand_pcg::Pcg64) -> Isometry3<f64> {
        let t = Translation3::new(
            rng.random_range(-0.15..0.15),
            rng.random_range(-0.15..0.15),
            rng.random_range(-0.15..0.15),
        );
        let r = UnitQuaternion::from_euler_angles(
            rng.random_range(-3.0..3.0),
            rng.random_range(-3.0..3.0),
            rng.random_range(-3.0..3.0),
        );
        Isometry3::from_parts(t, r)
    }

    fn cuboid(rng: &mut rand_pcg::Pcg64) -> Cuboid {
        Cuboid::new(Vector3::new(
            rng.random_range(0.01..0.1),
            rng.random_range(0.01..0.1),
            rng.random_range(0.01..0.1),
        ))
    }

    fn capsule(rng: &mut rand_pcg::Pcg64) -> Capsule {
        let a = Point3::new(
            rng.random_range(-0.1..0.1),
            0.0,
            rng.random_range(-0.1..0.1),
        );
        let b = Point3::new(
            0.0,
            rng.random_range(-0.1..0.1),
            rng.random_range(-0.1..0.1),
        );
        Capsule::new(a, b, rng.random_range(0.005..0.05))
    }

    /// Every query agrees bit for bit with parry's dispatcher on the pair; whether they overlap.
    fn agree(
        a: &(impl Solid + Shape),
        b: &(impl Solid + Shape),
        rng: &mut rand_pcg::Pcg64,
    ) -> bool {
        let (p1, p2) = (pose(rng), pose(rng));
        let overlap = intersects(&p1, a, &p2, b);
        assert_eq!(overlap, query::intersection_test(&p1, a, &p2, b).unwrap());
        assert_eq!(
            contact(&p1, a, &p2, b, 0.02),
            query::contact(&p1, a, &p2, b, 0.02).unwrap()
        );
        let v1 = Vector3::new(0.0, 0.0, -0.3);
        let v2 = Vector3::new(rng.random_range(-0.3..0.3), 0.1, 0.0);
        let opts = ShapeCastOptions {
            max_time_of_impact: 2.0,
            stop_at_penetration: rng.random_bool(0.5),
            ..Default::default()
        };
        // `ShapeCastHit` has no `PartialEq`; its `Debug` prints every float exactly.
        assert_eq!(
            format!("{:?}", cast(&p1, &v1, a, &p2, &v2, b, opts)),
            format!(
                "{:?}",
                query::cast_shapes(&p1, &v1, a, &p2, &v2, b, opts).unwrap()
            )
        );
        overlap
    }

    #[test]
    fn queries_match_parrys_dispatcher_on_boxes_and_capsules() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        let mut overlaps = [0usize; 2];
        for _ in 0..2000 {
            let (c1, c2, k1, k2) = (
                cuboid(&mut rng),
                cuboid(&mut rng),
                capsule(&mut rng),
                capsule(&mut rng),
            );
            for overlap in [
                agree(&c1, &c2, &mut rng),
                agree(&c1, &k1, &mut rng),
                agree(&k1, &c2, &mut rng),
                agree(&k1, &k2, &mut rng),
            ] {
                overlaps[usize::from(overlap)] += 1;
            }
        }
        // The sample reaches both the separated and the overlapping cases.
        assert!(overlaps.iter().all(|&n| n > 500), "{overlaps:?}");
    }
}
