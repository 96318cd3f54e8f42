//! The arm a world moves: its kinematics, joint limits and speeds, ready posture, gripper width
//! and link capsules, for the built-in Panda ([`ArmModel::panda`]) or a robot read from its URDF
//! ([`ArmModel::from_robot`]).
//!
//! # Joint vectors
//! - Always `[f64; DOF]` (7 entries): a 6-joint arm leaves the last entry at 0 with the range
//!   `[0, 0]`, so the world, the executor and the streams handle both alike.
//! - A URDF joint without limits (continuous) gets the range `[−2π, 2π]`.
//!
//! # Link capsules
//! The world checks the arm against tables, shelves and blocks with one capsule per link, base
//! first and the hand last. A URDF arm's capsules are fitted once to its `<collision>` shapes
//! (mesh hulls included): one capsule per moving joint's frame around every shape that moves with
//! it, along the longest side of their bounding box, as small as covers them.

mod ik;
mod parts;

use std::sync::{Arc, OnceLock};

use nalgebra::{Isometry3, Point3, SMatrix, Vector3};

use super::geometry;
use super::panda::{self, Frame};
use super::robot::{Model, Robot, RobotCollision, RobotError};

pub use ik::{IkParams, IkSolution, Unreachable};
use parts::ChainShape;
pub(crate) use parts::{ArmPart, ArmShape};

/// Width of a joint vector: the most moving joints an arm has.
pub const DOF: usize = 7;

/// A joint vector (see the module docs for arms with fewer joints).
pub type Joints = [f64; DOF];

/// The range given to a joint without limits (rad).
const UNLIMITED: f64 = 2.0 * std::f64::consts::PI;

/// One link capsule of a URDF arm: the frame it moves with (0 the base, `i` the frame moved by
/// joint `i`) and its segment and radius in that frame.
#[derive(Clone, Debug, PartialEq)]
struct LinkCapsule {
    frame: usize,
    a: Vector3<f64>,
    b: Vector3<f64>,
    radius: f64,
}

/// How the arm's frames are computed.
#[derive(Clone, Debug, PartialEq)]
enum Kinematics {
    /// The built-in Panda's DH chain and hand-sized capsules ([`panda`]).
    Panda,
    /// A URDF chain with its collision shapes, and capsules fitted to them for drawing.
    Chain {
        model: Box<Model>,
        shapes: Vec<ChainShape>,
        capsules: Vec<LinkCapsule>,
    },
}

/// An arm's kinematic model (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct ArmModel {
    name: String,
    dof: usize,
    kinematics: Kinematics,
    pub(crate) lower: Joints,
    pub(crate) upper: Joints,
    pub(crate) velocity: Joints,
    pub(crate) ready: Joints,
    max_opening: f64,
    /// How many leading [`ArmPart`]s stand still while the first joint turns (the base): the
    /// tables they stand on are not checked against them.
    base_parts: usize,
}

impl ArmModel {
    /// The built-in Panda (its published DH parameters and limits), shared.
    pub fn panda() -> Arc<ArmModel> {
        static CELL: OnceLock<Arc<ArmModel>> = OnceLock::new();
        CELL.get_or_init(|| {
            Arc::new(ArmModel {
                name: "panda".into(),
                dof: DOF,
                kinematics: Kinematics::Panda,
                lower: panda::JOINT_LOWER,
                upper: panda::JOINT_UPPER,
                velocity: panda::JOINT_VELOCITY,
                ready: panda::READY,
                max_opening: panda::GRIPPER_MAX_OPENING,
                base_parts: 1,
            })
        })
        .clone()
    }

    /// The model of a robot read from its URDF: its chain, limits, home posture as the ready
    /// posture, gripper width, and link capsules fitted to its collision shapes.
    ///
    /// # Errors
    /// A collision mesh that cannot be read, a chain of other than 6 or 7 moving joints, or a
    /// moving joint without a positive velocity limit, named by the robot file.
    pub fn from_robot(robot: &Robot) -> Result<ArmModel, RobotError> {
        let at = |field: &str| format!("{}: {field}", robot.file.display());
        let model = Model::new(&robot.chain, &robot.tcp).map_err(|dof| RobotError {
            at: at("tip_link"),
            message: format!("{dof} moving joints; an arm needs 6 or 7"),
        })?;
        let dof = model.n;
        let (mut lower, mut upper, mut velocity, mut ready) =
            ([0.0; DOF], [0.0; DOF], [0.0; DOF], [0.0; DOF]);
        for (i, j) in robot.chain.moving().enumerate() {
            lower[i] = if j.lower.is_finite() {
                j.lower
            } else {
                -UNLIMITED
            };
            upper[i] = if j.upper.is_finite() {
                j.upper
            } else {
                UNLIMITED
            };
            if !(j.velocity > 0.0 && j.velocity.is_finite()) {
                return Err(RobotError {
                    at: at("urdf"),
                    message: format!(
                        "joint `{}` has no positive velocity limit ({})",
                        j.name, j.velocity
                    ),
                });
            }
            velocity[i] = j.velocity;
            ready[i] = robot.home[i].clamp(lower[i], upper[i]);
        }
        let shapes = chain_shapes(robot)?;
        let capsules = fit_capsules(&shapes, dof);
        let base_parts = shapes.iter().filter(|c| c.frame <= 1).count();
        Ok(ArmModel {
            name: robot.name.clone(),
            dof,
            kinematics: Kinematics::Chain {
                model: Box::new(model),
                shapes,
                capsules,
            },
            lower,
            upper,
            velocity,
            ready,
            max_opening: robot.gripper.max_opening,
            base_parts,
        })
    }

    /// The arm's name (`panda`, or the robot file's `name`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Number of moving joints (6 or 7).
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// The ready posture: gripper pointing down in front of the base (a URDF robot's `home`).
    pub fn ready(&self) -> Joints {
        self.ready
    }

    /// Lower joint limits (rad or m).
    pub fn lower(&self) -> &Joints {
        &self.lower
    }

    /// Upper joint limits (rad or m).
    pub fn upper(&self) -> &Joints {
        &self.upper
    }

    /// Largest finger opening (m).
    pub fn max_opening(&self) -> f64 {
        self.max_opening
    }

    /// Whether this is the built-in Panda.
    pub fn is_builtin(&self) -> bool {
        matches!(self.kinematics, Kinematics::Panda)
    }

    /// The joint vector of `values` (one per moving joint), padded; `None` for the wrong length.
    pub fn joints_of(&self, values: &[f64]) -> Option<Joints> {
        (values.len() == self.dof).then(|| {
            let mut q = [0.0; DOF];
            q[..self.dof].copy_from_slice(values);
            q
        })
    }

    /// Forward kinematics: the TCP pose in the world for joints `q` of an arm based at `base`.
    pub fn forward_kinematics(&self, base: &Isometry3<f64>, q: &Joints) -> Isometry3<f64> {
        match &self.kinematics {
            Kinematics::Panda => panda::forward_kinematics(base, q),
            Kinematics::Chain { model, .. } => base * model.frames(q).tcp,
        }
    }

    /// The TCP frame in the world.
    pub(crate) fn tcp_frame(&self, base: &Isometry3<f64>, q: &Joints) -> Frame {
        match &self.kinematics {
            Kinematics::Panda => panda::forward_frames(base, q).tcp,
            Kinematics::Chain { model, .. } => Frame::from_iso(&(base * model.frames(q).tcp)),
        }
    }

    /// The TCP frame and the geometric Jacobian (linear rows first), both in the world frame.
    pub(crate) fn tcp_and_jacobian(
        &self,
        base: &Isometry3<f64>,
        q: &Joints,
    ) -> (Frame, SMatrix<f64, 6, DOF>) {
        match &self.kinematics {
            Kinematics::Panda => {
                let f = panda::forward_frames(base, q);
                (f.tcp, panda::jacobian(&f))
            }
            Kinematics::Chain { model, .. } => {
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
        }
    }

    /// The link capsules `(a, b, radius)` at joints `q` (world frame): the base first, the
    /// hand last.
    pub(crate) fn link_capsules(
        &self,
        base: &Isometry3<f64>,
        q: &Joints,
    ) -> Vec<(Vector3<f64>, Vector3<f64>, f64)> {
        match &self.kinematics {
            Kinematics::Panda => geometry::panda_links(&panda::forward_frames(base, q)),
            Kinematics::Chain {
                model, capsules, ..
            } => {
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
                caps.push(geometry::hand_capsule(&(base * f.tcp)));
                caps
            }
        }
    }

    /// The solids the arm is checked with at joints `q` (world frame): the base's first
    /// ([`base_parts`](Self::base_parts) of them), the hand's capsule last.
    pub(crate) fn arm_parts(&self, base: &Isometry3<f64>, q: &Joints) -> Vec<ArmPart> {
        match &self.kinematics {
            Kinematics::Panda => self
                .link_capsules(base, q)
                .into_iter()
                .map(|(a, b, r)| ArmPart::capsule(a, b, r))
                .collect(),
            Kinematics::Chain { model, shapes, .. } => {
                let f = model.frames(q);
                let mut parts: Vec<ArmPart> = shapes
                    .iter()
                    .map(|s| {
                        let frame = if s.frame == 0 {
                            *base
                        } else {
                            base * f.links[s.frame - 1]
                        };
                        ArmPart::convex(frame * s.pose, &s.shape)
                    })
                    .collect();
                let (a, b, r) = geometry::hand_capsule(&(base * f.tcp));
                parts.push(ArmPart::capsule(a, b, r));
                parts
            }
        }
    }

    /// How many leading [`arm_parts`](Self::arm_parts) are the base's.
    pub(crate) fn base_parts(&self) -> usize {
        self.base_parts
    }

    /// Clamps joints to the limits.
    pub fn clamp(&self, q: &mut Joints) {
        for i in 0..DOF {
            q[i] = q[i].clamp(self.lower[i], self.upper[i]);
        }
    }

    /// The middle of every joint's range.
    pub(crate) fn mid(&self) -> Joints {
        let mut m = [0.0; DOF];
        for i in 0..DOF {
            m[i] = 0.5 * (self.lower[i] + self.upper[i]);
        }
        m
    }

    /// How far joints `q` are from their nearest limit, as a fraction of that joint's range (0
    /// at a limit, 0.5 in the middle of every range).
    pub fn limit_margin(&self, q: &Joints) -> f64 {
        (0..self.dof)
            .map(|i| {
                let range = self.upper[i] - self.lower[i];
                ((q[i] - self.lower[i]).min(self.upper[i] - q[i]) / range).max(0.0)
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// Largest joint step between the samples of a straight joint-space move checked for collisions
/// (rad): the executor's recovery and the streams' certification of it sample alike.
pub(crate) const JOINT_PATH_STEP: f64 = 0.05;

/// The samples of the straight joint-space move from `from` to `to`, at most
/// [`JOINT_PATH_STEP`] apart in every joint, `from` excluded and `to` included.
pub(crate) fn joint_line(from: &Joints, to: &Joints) -> impl Iterator<Item = Joints> {
    let (from, to) = (*from, *to);
    let span = from
        .iter()
        .zip(&to)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let n = ((span / JOINT_PATH_STEP).ceil() as usize).max(1);
    (1..=n).map(move |k| {
        let s = k as f64 / n as f64;
        let mut q = from;
        for (j, v) in q.iter_mut().enumerate() {
            *v += s * (to[j] - from[j]);
        }
        q
    })
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
