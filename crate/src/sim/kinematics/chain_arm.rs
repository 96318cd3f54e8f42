//! An arm read from its URDF: its folded chain, its collision shapes and the capsules drawn for
//! it (the page's first-load module, which runs the built-in Panda alone, leaves this out).

use nalgebra::{Isometry3, Point3, SMatrix, Vector3};
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::shape::SharedShape;

use super::parts::ArmPart;
use crate::sim::panda::{hand_capsule, Frame, DOF};
use crate::sim::robot::{Model, Robot, RobotCollision, RobotError};

/// One link capsule of a URDF arm: the frame it moves with (0 the base, `i` the frame moved by
/// joint `i`) and its segment and radius in that frame.
#[derive(Clone, Debug, PartialEq)]
struct LinkCapsule {
    frame: usize,
    a: Vector3<f64>,
    b: Vector3<f64>,
    radius: f64,
}

/// A URDF collision shape that moves with one frame of the chain.
#[derive(Clone)]
struct ChainShape {
    /// 0 the base, `i` the frame moved by joint `i`.
    frame: usize,
    /// The shape's pose in that frame.
    pose: Isometry3<f64>,
    /// A convex shape (every shape of a robot's collision model is).
    shape: SharedShape,
    /// Its bounding box in its own frame.
    aabb: Aabb,
}

impl std::fmt::Debug for ChainShape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ChainShape")
            .field("frame", &self.frame)
            .field("pose", &self.pose)
            .finish()
    }
}

impl PartialEq for ChainShape {
    fn eq(&self, other: &Self) -> bool {
        self.frame == other.frame
            && self.pose == other.pose
            && std::sync::Arc::ptr_eq(&self.shape.0, &other.shape.0)
    }
}

/// A URDF chain with its collision shapes, and capsules fitted to them for drawing.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct ChainArm {
    model: Model,
    shapes: Vec<ChainShape>,
    capsules: Vec<LinkCapsule>,
}

impl ChainArm {
    /// The chain of `robot` with its TCP, its collision shapes and their drawing capsules.
    pub(super) fn new(robot: &Robot) -> Result<ChainArm, RobotError> {
        let model = Model::new(&robot.chain, &robot.tcp).map_err(|dof| RobotError {
            at: format!("{}: tip_link", robot.file.display()),
            message: format!("{dof} moving joints; an arm needs 6 or 7"),
        })?;
        let shapes = chain_shapes(robot)?;
        let capsules = fit_capsules(&shapes, model.n);
        Ok(ChainArm {
            model,
            shapes,
            capsules,
        })
    }

    /// Number of moving joints.
    pub(super) fn dof(&self) -> usize {
        self.model.n
    }

    /// How many leading shapes of [`ChainArm::arm_parts`] stand still while the first joint
    /// turns.
    pub(super) fn base_parts(&self) -> usize {
        self.shapes.iter().filter(|c| c.frame <= 1).count()
    }

    /// The TCP in the world.
    pub(super) fn tcp(&self, base: &Isometry3<f64>, q: &[f64; DOF]) -> Isometry3<f64> {
        base * self.model.frames(q).tcp
    }

    /// The TCP frame and the geometric Jacobian, both in the world frame.
    pub(super) fn tcp_and_jacobian(
        &self,
        base: &Isometry3<f64>,
        q: &[f64; DOF],
    ) -> (Frame, SMatrix<f64, 6, DOF>) {
        let model = &self.model;
        let f = model.frames(q);
        let local = model.jacobian(&f);
        let r = base.rotation.to_rotation_matrix();
        let mut j = SMatrix::<f64, 6, DOF>::zeros();
        for c in 0..DOF {
            let lin = r * local.fixed_view::<3, 1>(0, c).into_owned();
            let ang = r * local.fixed_view::<3, 1>(3, c).into_owned();
            j.fixed_view_mut::<3, 1>(0, c).copy_from(&lin);
            j.fixed_view_mut::<3, 1>(3, c).copy_from(&ang);
        }
        (Frame::from_iso(&(base * f.tcp)), j)
    }

    /// The drawing capsules at joints `q` (world frame), the hand's last.
    pub(super) fn link_capsules(
        &self,
        base: &Isometry3<f64>,
        q: &[f64; DOF],
    ) -> Vec<(Vector3<f64>, Vector3<f64>, f64)> {
        let (model, capsules) = (&self.model, &self.capsules);
        let f = model.frames(q);
        let frame = |k: usize| if k == 0 { *base } else { base * f.links[k - 1] };
        let mut caps: Vec<_> = capsules
            .iter()
            .map(|c| {
                let t = frame(c.frame);
                (
                    (t * Point3::from(c.a)).coords,
                    (t * Point3::from(c.b)).coords,
                    c.radius,
                )
            })
            .collect();
        caps.push(hand_capsule(&(base * f.tcp)));
        caps
    }

    /// The collision shapes at joints `q` (world frame), the hand's capsule last.
    pub(super) fn arm_parts(&self, base: &Isometry3<f64>, q: &[f64; DOF]) -> Vec<ArmPart> {
        let (model, shapes) = (&self.model, &self.shapes);
        let f = model.frames(q);
        let mut parts: Vec<ArmPart> = shapes
            .iter()
            .map(|s| {
                let frame = if s.frame == 0 {
                    *base
                } else {
                    base * f.links[s.frame - 1]
                };
                ArmPart::convex(frame * s.pose, &s.shape, &s.aabb)
            })
            .collect();
        let (a, b, r) = hand_capsule(&(base * f.tcp));
        parts.push(ArmPart::capsule(a, b, r));
        parts
    }
}

/// The collision shapes of a URDF arm's chain links (the hand and fingers below the tip
/// excepted: the kinematic hand's capsule stands for them), each in the frame that moves it,
/// ordered by frame.
fn chain_shapes(robot: &Robot) -> Result<Vec<ChainShape>, RobotError> {
    let collision = RobotCollision::new(robot)?;
    let chain = &robot.chain;
    let mut out = Vec::new();
    let mut add = |link: &str, frame: usize, rel: &Isometry3<f64>| {
        let Some(l) = collision.links().iter().find(|l| l.name == link) else {
            return;
        };
        for s in l
            .shapes
            .iter()
            .filter(|s| s.shape.as_support_map().is_some())
        {
            out.push(ChainShape {
                frame,
                pose: rel * s.pose,
                aabb: s.shape.compute_local_aabb(),
                shape: s.shape.clone(),
            });
        }
    };
    let mut frame = 0;
    let mut rel = Isometry3::identity();
    add(&chain.base, 0, &rel);
    for j in &chain.joints {
        if j.moves() {
            frame += 1;
            rel = Isometry3::identity();
        } else {
            rel *= j.origin;
        }
        add(&j.child, frame, &rel);
    }
    Ok(out)
}

/// The drawing capsules of a URDF arm (see the module docs): one per frame of `dof + 1` around
/// the points of its shapes (hull vertices, or the corners of a primitive's bounding box).
fn fit_capsules(shapes: &[ChainShape], dof: usize) -> Vec<LinkCapsule> {
    let mut points: Vec<Vec<Vector3<f64>>> = vec![Vec::new(); dof + 1];
    for s in shapes {
        let local: Vec<Point3<f64>> = match s.shape.as_convex_polyhedron() {
            Some(poly) => poly.points().to_vec(),
            None => {
                let bb = s.shape.compute_local_aabb();
                (0..8)
                    .map(|k| {
                        let pick = |bit: usize, i: usize| {
                            if k & bit == 0 {
                                bb.mins[i]
                            } else {
                                bb.maxs[i]
                            }
                        };
                        Point3::new(pick(1, 0), pick(2, 1), pick(4, 2))
                    })
                    .collect()
            }
        };
        points[s.frame].extend(local.iter().map(|p| (s.pose * p).coords));
    }
    let mut caps: Vec<LinkCapsule> = points
        .iter()
        .enumerate()
        .filter(|(_, p)| !p.is_empty())
        .map(|(frame, p)| fit_capsule(frame, p))
        .collect();
    if caps.first().is_none_or(|c| c.frame != 0) {
        // The base always comes first (the world skips it against the table it stands on).
        caps.insert(
            0,
            LinkCapsule {
                frame: 0,
                a: Vector3::zeros(),
                b: Vector3::zeros(),
                radius: 0.0,
            },
        );
    }
    caps
}

/// Fractions of the radius by which a capsule's segment may stop short of its points' extent.
const INSETS: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// The smallest capsule (by volume) along the longest side of `points`' bounding box that
/// covers every point, among segments stopping short of the extent by [`INSETS`] of the radius.
fn fit_capsule(frame: usize, points: &[Vector3<f64>]) -> LinkCapsule {
    let lo = points
        .iter()
        .fold(Vector3::repeat(f64::INFINITY), |m, p| m.inf(p));
    let hi = points
        .iter()
        .fold(Vector3::repeat(f64::NEG_INFINITY), |m, p| m.sup(p));
    let size = hi - lo;
    let axis = (0..3).fold(0, |b, i| if size[i] > size[b] { i } else { b });
    let centre = 0.5 * (lo + hi);
    let perp = |p: &Vector3<f64>| {
        let mut d = p - centre;
        d[axis] = 0.0;
        libm::sqrt(d.dot(&d))
    };
    let r0 = points.iter().map(perp).fold(0.0, f64::max);
    let mut best: Option<(f64, LinkCapsule)> = None;
    for inset in INSETS {
        let half = (0.5 * size[axis] - inset * r0).max(0.0);
        let (mut a, mut b) = (centre, centre);
        a[axis] -= half;
        b[axis] += half;
        let radius = points
            .iter()
            .map(|p| {
                let t = (p[axis] - centre[axis]).clamp(-half, half);
                let mut s = centre;
                s[axis] += t;
                let d = p - s;
                libm::sqrt(d.dot(&d))
            })
            .fold(0.0, f64::max);
        let volume = radius * radius * (2.0 * half + 4.0 / 3.0 * radius);
        if best.as_ref().is_none_or(|(v, _)| volume < *v) {
            best = Some((
                volume,
                LinkCapsule {
                    frame,
                    a,
                    b,
                    radius,
                },
            ));
        }
    }
    best.map(|(_, c)| c).unwrap_or(LinkCapsule {
        frame,
        a: centre,
        b: centre,
        radius: r0,
    })
}
