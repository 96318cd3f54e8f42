//! The solids an arm is checked with against the workcell, posed for one joint vector: the
//! built-in Panda's link capsules, or a URDF arm's own collision shapes (mesh hulls, boxes,
//! cylinders, spheres); the hand's capsule last in both.

use nalgebra::{Isometry3, Point3, Vector3};
#[cfg(not(first_load))]
use parry3d_f64::bounding_volume::Aabb;
#[cfg(not(first_load))]
use parry3d_f64::shape::{Ball, SharedShape};
use parry3d_f64::shape::{Capsule, Cuboid, SupportMap};

use crate::sim::collide::Solid;

/// The shape of an [`ArmPart`].
#[derive(Clone)]
pub(crate) enum ArmShape {
    /// A capsule in world coordinates (the part's pose is the identity).
    Capsule(Capsule),
    /// A convex collision shape of a URDF link.
    #[cfg(not(first_load))]
    Convex(SharedShape),
}

/// What a shape without a support map (none is built) is checked as: nothing.
#[cfg(not(first_load))]
static NOTHING: Ball = Ball { radius: 0.0 };

impl Solid for ArmShape {
    fn support_map(&self) -> &dyn SupportMap {
        match self {
            ArmShape::Capsule(c) => c,
            #[cfg(not(first_load))]
            ArmShape::Convex(s) => s.as_support_map().unwrap_or(&NOTHING),
        }
    }
    fn cuboid(&self) -> Option<&Cuboid> {
        match self {
            ArmShape::Capsule(_) => None,
            #[cfg(not(first_load))]
            ArmShape::Convex(s) => s.as_cuboid(),
        }
    }
}

/// One solid of an arm, posed in the world, with its world bounding box.
#[derive(Clone)]
pub(crate) struct ArmPart {
    /// Its pose.
    pub(crate) iso: Isometry3<f64>,
    /// Its shape.
    pub(crate) shape: ArmShape,
    /// Lower corner of its world bounding box.
    pub(crate) lo: Vector3<f64>,
    /// Upper corner of its world bounding box.
    pub(crate) hi: Vector3<f64>,
}

impl ArmPart {
    /// The capsule from `a` to `b` of radius `r` (world frame).
    pub(crate) fn capsule(a: Vector3<f64>, b: Vector3<f64>, r: f64) -> ArmPart {
        ArmPart {
            iso: Isometry3::identity(),
            shape: ArmShape::Capsule(Capsule::new(Point3::from(a), Point3::from(b), r)),
            lo: a.inf(&b) - Vector3::repeat(r),
            hi: a.sup(&b) + Vector3::repeat(r),
        }
    }

    /// A convex shape at `iso` (world frame).
    #[cfg(not(first_load))]
    /// `local` is the shape's own bounding box, moved with it (not recomputed from its
    /// vertices: a hull has a hundred of them).
    pub(super) fn convex(iso: Isometry3<f64>, shape: &SharedShape, local: &Aabb) -> ArmPart {
        let bb = local.transform_by(&iso);
        ArmPart {
            iso,
            shape: ArmShape::Convex(shape.clone()),
            lo: bb.mins.coords,
            hi: bb.maxs.coords,
        }
    }

    /// Whether its bounding box overlaps the box from `lo` to `hi`.
    pub(crate) fn near(&self, lo: &Vector3<f64>, hi: &Vector3<f64>) -> bool {
        (0..3).all(|i| self.lo[i] <= hi[i] && lo[i] <= self.hi[i])
    }
}
