//! The kinematic chain from a base link to a tip link of a URDF, and its forward kinematics.
//!
//! Each joint moves its child's frame relative to its parent's as
//!
//! ```text
//! T_child = T_parent · T_origin · M(q),   M(q) = Rot(axis, q) (revolute, continuous)
//!                                          M(q) = Trans(axis · q) (prismatic), identity (fixed)
//! ```
//!
//! with `q` one entry of the joint vector per moving joint, in chain order.

use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

use super::urdf::{JointKind, Urdf};

/// One joint of a chain, base side first.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainJoint {
    /// The joint's name.
    pub name: String,
    /// How it moves.
    pub kind: JointKind,
    /// The link it moves.
    pub child: String,
    /// Pose of the child's frame in the parent's at position 0.
    pub origin: Isometry3<f64>,
    /// The unit axis.
    pub axis: Unit<Vector3<f64>>,
    /// Position limits (`-∞, ∞` for a continuous joint).
    pub lower: f64,
    /// Upper position limit.
    pub upper: f64,
    /// Velocity limit.
    pub velocity: f64,
}

impl ChainJoint {
    /// Whether the joint moves (takes an entry of the joint vector).
    pub fn moves(&self) -> bool {
        self.kind != JointKind::Fixed
    }

    fn motion(&self, q: f64) -> Isometry3<f64> {
        match self.kind {
            JointKind::Revolute | JointKind::Continuous => Isometry3::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&self.axis, q),
            ),
            JointKind::Prismatic => Isometry3::from_parts(
                Translation3::from(self.axis.into_inner() * q),
                UnitQuaternion::identity(),
            ),
            JointKind::Fixed => Isometry3::identity(),
        }
    }
}

/// The joints from a base link to a tip link.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    /// The base link.
    pub base: String,
    /// The tip link.
    pub tip: String,
    /// The joints, base side first, fixed joints included.
    pub joints: Vec<ChainJoint>,
}

impl Chain {
    /// The chain of `urdf` from `base` to `tip`; the message says which link is missing or that
    /// `tip` does not descend from `base`.
    pub fn new(urdf: &Urdf, base: &str, tip: &str) -> Result<Chain, String> {
        for link in [base, tip] {
            if !urdf.links.iter().any(|l| l.name == link) {
                return Err(format!("the URDF has no link `{link}`"));
            }
        }
        let mut joints = Vec::new();
        let mut at = tip.to_string();
        while at != base {
            let Some(j) = urdf.joints.iter().find(|j| j.child == at) else {
                return Err(format!(
                    "link `{tip}` is not below link `{base}` (`{at}` has no parent joint)"
                ));
            };
            if joints.len() > urdf.joints.len() {
                return Err(format!("the joints above link `{tip}` form a loop"));
            }
            let (lower, upper, velocity) = match (j.kind, j.limits) {
                (JointKind::Continuous, l) => (
                    f64::NEG_INFINITY,
                    f64::INFINITY,
                    l.map_or(f64::INFINITY, |l| l.velocity),
                ),
                (_, Some(l)) => (l.lower, l.upper, l.velocity),
                (_, None) => (0.0, 0.0, 0.0),
            };
            joints.push(ChainJoint {
                name: j.name.clone(),
                kind: j.kind,
                child: j.child.clone(),
                origin: j.origin,
                axis: j.axis,
                lower,
                upper,
                velocity,
            });
            at = j.parent.clone();
        }
        joints.reverse();
        Ok(Chain {
            base: base.into(),
            tip: tip.into(),
            joints,
        })
    }

    /// Number of moving joints (the length of a joint vector).
    pub fn dof(&self) -> usize {
        self.joints.iter().filter(|j| j.moves()).count()
    }

    /// The moving joints, in joint-vector order.
    pub fn moving(&self) -> impl Iterator<Item = &ChainJoint> {
        self.joints.iter().filter(|j| j.moves())
    }

    /// The frame of every link of the chain in the base's frame (the base first, at identity),
    /// for joint vector `q` (`q.len()` must be [`Chain::dof`]).
    pub fn link_frames(&self, q: &[f64]) -> Vec<(String, Isometry3<f64>)> {
        assert_eq!(q.len(), self.dof(), "joint vector length");
        let mut out = Vec::with_capacity(self.joints.len() + 1);
        out.push((self.base.clone(), Isometry3::identity()));
        let mut t = Isometry3::identity();
        let mut qi = q.iter();
        for j in &self.joints {
            let v = if j.moves() {
                *qi.next().unwrap_or(&0.0)
            } else {
                0.0
            };
            t = t * j.origin * j.motion(v);
            out.push((j.child.clone(), t));
        }
        out
    }

    /// The tip link's frame in the base's frame for joint vector `q`.
    pub fn tip_frame(&self, q: &[f64]) -> Isometry3<f64> {
        self.link_frames(q)
            .pop()
            .map_or(Isometry3::identity(), |(_, t)| t)
    }

    /// Checks that `q` is a joint vector of this chain within its limits; the message says what
    /// is wrong.
    pub fn check_joints(&self, q: &[f64]) -> Result<(), String> {
        if q.len() != self.dof() {
            return Err(format!(
                "{} joint values for {} joints",
                q.len(),
                self.dof()
            ));
        }
        self.outside_limits(q).map_or(Ok(()), Err)
    }

    /// The first joint whose `q` entry lies outside its limits, with its name and limits.
    pub fn outside_limits(&self, q: &[f64]) -> Option<String> {
        self.moving().zip(q).find_map(|(j, v)| {
            (*v < j.lower || *v > j.upper)
                .then(|| format!("{} = {v} is outside [{}, {}]", j.name, j.lower, j.upper))
        })
    }
}
