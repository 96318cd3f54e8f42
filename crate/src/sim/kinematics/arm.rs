//! [`ArmModel`]: an arm's kinematics, limits, ready posture, gripper and solids.

use std::sync::{Arc, OnceLock};

use nalgebra::{Isometry3, SMatrix, Vector3};

#[cfg(not(first_load))]
use super::chain_arm::ChainArm;
use super::parts::ArmPart;
use crate::sim::panda::{self, Frame, DOF};
#[cfg(not(first_load))]
use crate::sim::robot::{Robot, RobotError};

/// The range given to a joint without limits (rad).
#[cfg(not(first_load))]
const UNLIMITED: f64 = 2.0 * std::f64::consts::PI;

/// A joint vector (see the module docs for arms with fewer joints).
pub type Joints = [f64; DOF];

/// How the arm's frames are computed.
#[derive(Clone, Debug, PartialEq)]
enum Kinematics {
    /// The built-in Panda's DH chain and hand-sized capsules ([`panda`]).
    Panda,
    /// A URDF chain with its collision shapes, and capsules fitted to them for drawing.
    #[cfg(not(first_load))]
    Chain(Box<ChainArm>),
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
    /// posture, gripper width, and its collision shapes (capsules fitted to them for drawing).
    ///
    /// # Errors
    /// A collision mesh that cannot be read, a chain of other than 6 or 7 moving joints, or a
    /// moving joint without a positive velocity limit, named by the robot file.
    #[cfg(not(first_load))]
    pub fn from_robot(robot: &Robot) -> Result<ArmModel, RobotError> {
        let chain = ChainArm::new(robot)?;
        let dof = chain.dof();
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
                    at: format!("{}: urdf", robot.file.display()),
                    message: format!(
                        "joint `{}` has no positive velocity limit ({})",
                        j.name, j.velocity
                    ),
                });
            }
            velocity[i] = j.velocity;
            ready[i] = robot.home[i].clamp(lower[i], upper[i]);
        }
        let base_parts = chain.base_parts();
        Ok(ArmModel {
            name: robot.name.clone(),
            dof,
            kinematics: Kinematics::Chain(Box::new(chain)),
            lower,
            upper,
            velocity,
            ready,
            max_opening: robot.gripper.max_opening,
            base_parts,
        })
    }

    /// A robot shipped with the library ([`crate::sim::SHIPPED_ROBOTS`]: `panda`, the Franka
    /// Emika Panda from its own URDF, and `ur5`), built once and shared; `None` for another name.
    #[cfg(not(first_load))]
    pub fn shipped(name: &str) -> Option<Arc<ArmModel>> {
        static PANDA: OnceLock<Option<Arc<ArmModel>>> = OnceLock::new();
        static UR5: OnceLock<Option<Arc<ArmModel>>> = OnceLock::new();
        let cell = match name {
            "panda" => &PANDA,
            "ur5" => &UR5,
            _ => return None,
        };
        // The compiled-in files load (a test proves it); a failure would leave the name unknown.
        cell.get_or_init(|| {
            let robot = crate::sim::robot::shipped_robot(name)?.ok()?;
            ArmModel::from_robot(&robot).ok().map(Arc::new)
        })
        .clone()
    }

    /// The arm `spec` names: a shipped robot (`panda`, `ur5`) or a robot file (`robot.json`
    /// beside its URDF); a path that exists is read as a file even when it reads like a name.
    /// What `--robot` takes on the command line and `robot=` in Python.
    ///
    /// # Errors
    /// The robot file's error, located (`at`: the file, JSON path, URDF line or mesh).
    #[cfg(not(first_load))]
    pub fn load(spec: &std::path::Path) -> Result<Arc<ArmModel>, RobotError> {
        let shipped = spec
            .to_str()
            .and_then(|n| crate::sim::SHIPPED_ROBOTS.into_iter().find(|s| *s == n))
            .filter(|_| !spec.exists());
        if let Some(name) = shipped {
            return ArmModel::shipped(name).ok_or_else(|| RobotError {
                at: name.to_string(),
                message: "the shipped robot's files do not load".into(),
            });
        }
        Robot::load(spec)
            .and_then(|r| ArmModel::from_robot(&r))
            .map(Arc::new)
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

    /// Forward kinematics: the TCP pose in the world for joints `q` of an arm based at `base`.
    pub fn forward_kinematics(&self, base: &Isometry3<f64>, q: &Joints) -> Isometry3<f64> {
        match &self.kinematics {
            Kinematics::Panda => panda::forward_kinematics(base, q),
            #[cfg(not(first_load))]
            Kinematics::Chain(c) => c.tcp(base, q),
        }
    }

    /// The TCP frame in the world.
    pub(crate) fn tcp_frame(&self, base: &Isometry3<f64>, q: &Joints) -> Frame {
        match &self.kinematics {
            Kinematics::Panda => panda::forward_frames(base, q).tcp,
            #[cfg(not(first_load))]
            Kinematics::Chain(c) => Frame::from_iso(&c.tcp(base, q)),
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
            #[cfg(not(first_load))]
            Kinematics::Chain(c) => c.tcp_and_jacobian(base, q),
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
            Kinematics::Panda => panda::panda_links(&panda::forward_frames(base, q)),
            #[cfg(not(first_load))]
            Kinematics::Chain(c) => c.link_capsules(base, q),
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
            #[cfg(not(first_load))]
            Kinematics::Chain(c) => c.arm_parts(base, q),
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
