//! The collision model of a URDF robot: each link's `<collision>` shapes as parry shapes, the
//! link poses for a joint vector and gripper opening, self-collision and the distance to an
//! obstacle.
//!
//! **Links.** The chain's links, and every link hanging below one of them through `fixed` joints
//! or the gripper's finger joints (the hand, the fingers, a flange, a camera mount); branches
//! through other moving joints are left out. Finger joints take
//! `lower + (upper − lower) · opening / max_opening`: for the Panda each finger moves half the
//! opening.
//!
//! **Shapes.** Boxes, cylinders and spheres as they are (a URDF cylinder runs along its frame's
//! z, a parry cylinder along y: the shape is turned); a mesh as the convex hull of its scaled
//! vertices (STL, OBJ or COLLADA), one hull per file, computed once per process.
//!
//! **Self-collision pairs**, as MoveIt's setup assistant finds its "Adjacent" and "Default"
//! pairs: every two links with shapes are checked, except (1) links that move together (joined by
//! fixed joints) or are joined by one moving joint (counting links joined by fixed joints as one
//! body: the fingers are adjacent to the hand and to the link the hand is bolted to), and
//! (2) links whose shapes touch at the home posture with the gripper closed or open — their
//! hulls overlap by construction, so a check would always fire. MoveIt's "Never" pairs (never
//! seen touching over random postures) are still checked: a sampled "never" is not a proof.

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use parry3d_f64::query::{self, ClosestPoints};
use parry3d_f64::shape::Shape;

use super::chain::Chain;
use super::file::{Robot, RobotError};
use super::hull::LinkShape;
use super::urdf::{JointKind, UrdfJoint};

/// One link of the collision model and its shapes.
#[derive(Clone, Debug)]
pub struct CollisionLink {
    /// The link's name.
    pub name: String,
    /// Its collision shapes, in the link's frame.
    pub shapes: Vec<LinkShape>,
}

/// Why a pair of links is not checked for self-collision.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairExclusion {
    /// The links move together or are joined by one moving joint.
    Adjacent,
    /// The links' shapes touch at the home posture.
    TouchAtHome,
}

/// A link below the chain: its parent's index in the model, the joint's origin and motion.
#[derive(Clone, Debug)]
struct Hanging {
    link: usize,
    parent: usize,
    joint: UrdfJoint,
    finger: bool,
}

/// The collision model of a robot (see the module docs for which links, shapes and pairs).
#[derive(Clone, Debug)]
pub struct RobotCollision {
    links: Vec<CollisionLink>,
    chain: Chain,
    /// Links below the chain, each after its parent.
    hanging: Vec<Hanging>,
    max_opening: f64,
    /// Pairs of link indices checked for self-collision.
    pairs: Vec<(usize, usize)>,
    /// Pairs left out, and why.
    excluded: Vec<(usize, usize, PairExclusion)>,
}

/// A joint's motion at position `v`.
fn motion(j: &UrdfJoint, v: f64) -> Isometry3<f64> {
    match j.kind {
        JointKind::Revolute | JointKind::Continuous => Isometry3::from_parts(
            Translation3::identity(),
            UnitQuaternion::from_axis_angle(&j.axis, v),
        ),
        JointKind::Prismatic => Isometry3::from_parts(
            Translation3::from(j.axis.into_inner() * v),
            UnitQuaternion::identity(),
        ),
        JointKind::Fixed => Isometry3::identity(),
    }
}

/// The signed distance between two posed shapes: the gap, or minus the penetration depth.
///
/// From `query::closest_points`, not `query::distance`: parry 0.25's cuboid–cuboid distance
/// overestimates the gap (dimforge/parry#431).
fn signed_distance(
    p1: &Isometry3<f64>,
    s1: &dyn Shape,
    p2: &Isometry3<f64>,
    s2: &dyn Shape,
) -> f64 {
    match query::closest_points(p1, s1, p2, s2, f64::MAX) {
        Ok(ClosestPoints::WithinMargin(a, b)) => (a - b).norm(),
        // Overlapping: the contact's (negative) distance is the depth.
        Ok(ClosestPoints::Intersecting) => query::contact(p1, s1, p2, s2, 0.0)
            .ok()
            .flatten()
            .map_or(0.0, |c| c.dist.min(0.0)),
        // Unbounded margin: never disjoint. Every shape built here is convex, which parry
        // supports.
        Ok(ClosestPoints::Disjoint) | Err(_) => f64::INFINITY,
    }
}

impl RobotCollision {
    /// The collision model of `robot`: reads its meshes (hulls are cached per file) and chooses
    /// the self-collision pairs; an error names the mesh file (and line) that cannot be read.
    pub fn new(robot: &Robot) -> Result<RobotCollision, RobotError> {
        let chain = robot.chain.clone();
        let mut names: Vec<String> = std::iter::once(chain.base.clone())
            .chain(chain.joints.iter().map(|j| j.child.clone()))
            .collect();
        // Follow fixed and finger joints down from the chain's links, breadth first.
        let mut hanging = Vec::new();
        let mut at = 0;
        while at < names.len() {
            let here = names[at].clone();
            for j in robot.urdf.joints.iter().filter(|j| j.parent == here) {
                let finger = robot.gripper.joints.contains(&j.name);
                if (j.kind == JointKind::Fixed || finger) && !names.contains(&j.child) {
                    names.push(j.child.clone());
                    hanging.push(Hanging {
                        link: names.len() - 1,
                        parent: at,
                        joint: j.clone(),
                        finger,
                    });
                }
            }
            at += 1;
        }
        let mut links = Vec::with_capacity(names.len());
        for name in names {
            let mut shapes = Vec::new();
            if let Some(l) = robot.urdf.links.iter().find(|l| l.name == name) {
                for c in &l.collisions {
                    let at = format!("{}:{}:1", robot.urdf_file.display(), c.line);
                    let file = match &c.geometry {
                        super::urdf::Geometry::Mesh { filename, .. } => {
                            Some(robot.mesh_path(filename).map_err(|m| RobotError {
                                at: at.clone(),
                                message: m,
                            })?)
                        }
                        _ => None,
                    };
                    let shape =
                        LinkShape::new(&c.origin, &c.geometry, file.as_deref(), &robot.files)
                            .map_err(|e| RobotError {
                                at: at.clone(),
                                message: format!("collision of link `{name}`: {e}"),
                            })?;
                    shapes.push(shape);
                }
            }
            links.push(CollisionLink { name, shapes });
        }
        let mut model = RobotCollision {
            links,
            chain,
            hanging,
            max_opening: robot.gripper.max_opening,
            pairs: Vec::new(),
            excluded: Vec::new(),
        };
        model.choose_pairs(robot)?;
        Ok(model)
    }

    /// Sorts every pair of links with shapes into checked and excluded (module docs).
    fn choose_pairs(&mut self, robot: &Robot) -> Result<(), RobotError> {
        let n = self.links.len();
        // Bodies: links joined by fixed joints share one (a union–find over the model's joints).
        let mut body: Vec<usize> = (0..n).collect();
        fn root(body: &mut [usize], mut i: usize) -> usize {
            while body[i] != i {
                body[i] = body[body[i]];
                i = body[i];
            }
            i
        }
        // (parent, child, fixed) of every joint of the model, chain joints first.
        let mut joints: Vec<(usize, usize, bool)> = Vec::new();
        let mut parent = 0;
        for (k, j) in self.chain.joints.iter().enumerate() {
            joints.push((parent, k + 1, !j.moves()));
            parent = k + 1;
        }
        joints.extend(
            self.hanging
                .iter()
                .map(|h| (h.parent, h.link, h.joint.kind == JointKind::Fixed)),
        );
        for &(p, c, fixed) in &joints {
            if fixed {
                let (a, b) = (root(&mut body, p), root(&mut body, c));
                body[a] = b;
            }
        }
        let bodies: Vec<usize> = (0..n).map(|i| root(&mut body, i)).collect();
        let adjacent = |a: usize, b: usize| {
            let (ba, bb) = (bodies[a], bodies[b]);
            ba == bb
                || joints.iter().any(|&(p, c, _)| {
                    let (bp, bc) = (bodies[p], bodies[c]);
                    (bp, bc) == (ba, bb) || (bp, bc) == (bb, ba)
                })
        };
        let home = robot.home.clone();
        let poses: Vec<Vec<Isometry3<f64>>> = [0.0, self.max_opening]
            .iter()
            .map(|&o| self.poses(&home, o))
            .collect::<Result<_, _>>()
            .map_err(|m| RobotError {
                at: format!("{}: home", robot.file.display()),
                message: m,
            })?;
        for a in 0..n {
            for b in a + 1..n {
                if self.links[a].shapes.is_empty() || self.links[b].shapes.is_empty() {
                    continue;
                }
                if adjacent(a, b) {
                    self.excluded.push((a, b, PairExclusion::Adjacent));
                } else if poses.iter().any(|p| self.pair_depth(a, b, p).is_some()) {
                    self.excluded.push((a, b, PairExclusion::TouchAtHome));
                } else {
                    self.pairs.push((a, b));
                }
            }
        }
        Ok(())
    }

    /// The model's links: the chain's (base first), then those hanging below them.
    pub fn links(&self) -> &[CollisionLink] {
        &self.links
    }

    /// The pairs of links checked for self-collision, by name.
    pub fn checked_pairs(&self) -> Vec<(&str, &str)> {
        self.pairs
            .iter()
            .map(|&(a, b)| (self.links[a].name.as_str(), self.links[b].name.as_str()))
            .collect()
    }

    /// The pairs of links left out of self-collision checks, by name, and why.
    pub fn excluded_pairs(&self) -> Vec<(&str, &str, PairExclusion)> {
        self.excluded
            .iter()
            .map(|&(a, b, w)| (self.links[a].name.as_str(), self.links[b].name.as_str(), w))
            .collect()
    }

    /// Each link's pose in the base link's frame, in [`RobotCollision::links`] order.
    fn poses(&self, q: &[f64], opening: f64) -> Result<Vec<Isometry3<f64>>, String> {
        self.chain.check_joints(q)?;
        if !(0.0..=self.max_opening).contains(&opening) {
            return Err(format!(
                "gripper opening {opening} m is outside [0, {}]",
                self.max_opening
            ));
        }
        let mut out: Vec<Isometry3<f64>> = self
            .chain
            .link_frames(q)
            .into_iter()
            .map(|(_, t)| t)
            .collect();
        for h in &self.hanging {
            let v = if h.finger {
                let (lo, hi) = h.joint.limits.map_or((0.0, 0.0), |l| (l.lower, l.upper));
                lo + (hi - lo) * opening / self.max_opening
            } else {
                0.0
            };
            let t = out[h.parent] * h.joint.origin * motion(&h.joint, v);
            out.push(t);
        }
        Ok(out)
    }

    /// Each link's name and pose in the base link's frame for joint vector `q` and gripper
    /// opening `opening` (m); refused when `q` has the wrong length or either lies outside its
    /// limits.
    pub fn link_poses(
        &self,
        q: &[f64],
        opening: f64,
    ) -> Result<Vec<(String, Isometry3<f64>)>, String> {
        let poses = self.poses(q, opening)?;
        Ok(self
            .links
            .iter()
            .zip(poses)
            .map(|(l, t)| (l.name.clone(), t))
            .collect())
    }

    /// The deepest overlap (≥ 0; 0 when only touching) of links `a` and `b` at link poses `p`,
    /// `None` when they are apart.
    fn pair_depth(&self, a: usize, b: usize, p: &[Isometry3<f64>]) -> Option<f64> {
        let mut deepest: Option<f64> = None;
        for sa in &self.links[a].shapes {
            let pa = p[a] * sa.pose;
            let ca = p[a] * sa.sphere.0;
            for sb in &self.links[b].shapes {
                let cb = p[b] * sb.sphere.0;
                if (ca - cb).norm() > sa.sphere.1 + sb.sphere.1 {
                    continue;
                }
                // The bounding boxes' separating-axis test is exact and far cheaper than GJK.
                let (ba, bb) = (p[a] * sa.bound.0, p[b] * sb.bound.0);
                if !query::details::intersection_test_cuboid_cuboid(
                    &ba.inv_mul(&bb),
                    &sa.bound.1,
                    &sb.bound.1,
                ) {
                    continue;
                }
                let pb = p[b] * sb.pose;
                if let Ok(Some(c)) = query::contact(&pa, &*sa.shape, &pb, &*sb.shape, 0.0) {
                    let depth = (-c.dist).max(0.0);
                    deepest = Some(deepest.map_or(depth, |d| d.max(depth)));
                }
            }
        }
        deepest
    }

    /// The checked pairs of links that touch or overlap at joint vector `q` and gripper opening
    /// `opening`: `(link, link, depth)`, the depth of the deepest overlap in metres (0 when they
    /// only touch), in [`RobotCollision::links`] order.
    pub fn self_collisions(
        &self,
        q: &[f64],
        opening: f64,
    ) -> Result<Vec<(String, String, f64)>, String> {
        let p = self.poses(q, opening)?;
        Ok(self
            .pairs
            .iter()
            .filter_map(|&(a, b)| {
                self.pair_depth(a, b, &p)
                    .map(|d| (self.links[a].name.clone(), self.links[b].name.clone(), d))
            })
            .collect())
    }

    /// The checked pair of links closest to each other at `q` and `opening`, with their signed
    /// distance (m; negative: the overlap's depth). `None` when no pair is checked.
    pub fn closest_pair(
        &self,
        q: &[f64],
        opening: f64,
    ) -> Result<Option<(String, String, f64)>, String> {
        let p = self.poses(q, opening)?;
        let mut best: Option<(usize, usize, f64)> = None;
        for &(a, b) in &self.pairs {
            for sa in &self.links[a].shapes {
                for sb in &self.links[b].shapes {
                    let d = signed_distance(
                        &(p[a] * sa.pose),
                        &*sa.shape,
                        &(p[b] * sb.pose),
                        &*sb.shape,
                    );
                    if best.is_none_or(|(_, _, bd)| d < bd) {
                        best = Some((a, b, d));
                    }
                }
            }
        }
        Ok(best.map(|(a, b, d)| (self.links[a].name.clone(), self.links[b].name.clone(), d)))
    }

    /// The link nearest to `shape` at `pose` (base link frame), and its signed distance (m;
    /// negative: the overlap's depth), at `q` and `opening`. `None` when no link has a shape.
    pub fn distance_to(
        &self,
        shape: &dyn Shape,
        pose: &Isometry3<f64>,
        q: &[f64],
        opening: f64,
    ) -> Result<Option<(String, f64)>, String> {
        let p = self.poses(q, opening)?;
        let s = shape.compute_local_bounding_sphere();
        let centre = pose * s.center;
        // Nearest bounding sphere first: once a distance is known, every shape whose sphere gap
        // (a lower bound) is not below it is skipped without GJK.
        let mut order: Vec<(f64, usize, &LinkShape)> = self
            .links
            .iter()
            .enumerate()
            .flat_map(|(i, l)| {
                let at = p[i];
                l.shapes.iter().map(move |ls| {
                    let gap = (at * ls.sphere.0 - centre).norm() - ls.sphere.1 - s.radius;
                    (gap, i, ls)
                })
            })
            .collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best: Option<(usize, f64)> = None;
        for (gap, i, ls) in order {
            if best.is_some_and(|(_, bd)| gap >= bd) {
                break;
            }
            let d = signed_distance(&(p[i] * ls.pose), &*ls.shape, pose, shape);
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
        Ok(best.map(|(i, d)| (self.links[i].name.clone(), d)))
    }
}
