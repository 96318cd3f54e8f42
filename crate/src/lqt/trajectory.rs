//! A planned end-effector trajectory and its closed-loop execution, shared by every motion
//! skill (the LQT-CP [`Skill`](super::Skill) and the classic [`Dmp`](super::Dmp)).
//!
//! Plans live in the frame of the object a skill acts on: states are mapped into it with
//! `p_o = T⁻¹ p_w` (derivatives rotated by `Rᵀ`) and back with `p_w = T p_o`.

use super::dmp::DmpRunner;
use super::solver::FeedbackGains;
use super::LqtError;
use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// A point the motion must pass through, in the object frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ViaPoint {
    /// Normalised time in [0, 1] (step `round(phase (T-1))`).
    pub phase: f64,
    /// Position in the object frame (m).
    pub position: Vector3<f64>,
    /// Precision (1/m²); `None` uses the goal's.
    pub weight: Option<f64>,
    /// Velocity to pass with, in the object frame (m/s), held with the goal velocity's
    /// precision; `None` leaves it free.
    #[serde(default)]
    pub velocity: Option<Vector3<f64>>,
}

/// What the gripper does when the skill ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GripperEvent {
    /// Open the gripper (place, release).
    Open,
    /// Close the gripper (pick, grasp the hook).
    Close,
}

/// The closed-loop policy behind a trajectory.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum Policy {
    /// LQT-CP: time-varying gains in the object frame.
    LqtCp(FeedbackGains),
    /// Classic DMP: the transformation system integrated from the measured state.
    Dmp(DmpRunner),
}

/// A planned end-effector trajectory with the means to execute it in closed loop.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Trajectory {
    /// Time step (s).
    pub dt: f64,
    /// World positions `p_0..p_{T-1}` (m).
    pub positions: Vec<Point3<f64>>,
    /// World velocities (m/s).
    pub velocities: Vec<Vector3<f64>>,
    /// World orientations of the end effector.
    pub orientations: Vec<UnitQuaternion<f64>>,
    /// Gripper event at the end, if any.
    pub gripper_event: Option<GripperEvent>,
    /// Object pose the trajectory was planned for.
    pub object_pose: Isometry3<f64>,
    /// Start state in the object frame (derivative-major, 3·order).
    pub(super) start_state: Vec<f64>,
    /// The feedback policy.
    pub policy: Policy,
}

/// Step-by-step closed-loop execution of a [`Trajectory`].
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct FeedbackController {
    policy: Policy,
    object_pose: Isometry3<f64>,
    /// Object-frame state (LQT: derivative-major 3·order; DMP: see [`DmpRunner`]).
    state: Vec<f64>,
    t: usize,
}

/// A skill that plans end-effector motions relative to an object.
pub trait MotionSkill {
    /// Plan from `start` (world, at rest) for an object at `object_pose`, through `via_points`.
    fn plan(
        &self,
        start: &Point3<f64>,
        object_pose: &Isometry3<f64>,
        via_points: &[ViaPoint],
    ) -> Result<Trajectory, LqtError>;
}

/// Map a world state (derivative-major, 3 coords) into the object frame.
pub(super) fn to_object(pose: &Isometry3<f64>, world: &[f64]) -> Vec<f64> {
    let mut out = world.to_vec();
    for i in 0..world.len() / 3 {
        let v = Vector3::new(world[3 * i], world[3 * i + 1], world[3 * i + 2]);
        let o = if i == 0 {
            pose.inverse_transform_point(&Point3::from(v)).coords
        } else {
            pose.inverse_transform_vector(&v)
        };
        out[3 * i..3 * i + 3].copy_from_slice(o.as_slice());
    }
    out
}

/// Map an object-frame state into the world.
pub(super) fn to_world(pose: &Isometry3<f64>, obj: &[f64]) -> Vec<f64> {
    let mut out = obj.to_vec();
    for i in 0..obj.len() / 3 {
        let v = Vector3::new(obj[3 * i], obj[3 * i + 1], obj[3 * i + 2]);
        let w = if i == 0 {
            pose.transform_point(&Point3::from(v)).coords
        } else {
            pose.transform_vector(&v)
        };
        out[3 * i..3 * i + 3].copy_from_slice(w.as_slice());
    }
    out
}

/// Orientations along a plan: blend from the start orientation into the demo's relative one.
pub(crate) fn plan_orientations(
    demo_rotations: &[UnitQuaternion<f64>],
    object_pose: &Isometry3<f64>,
    start: Option<&UnitQuaternion<f64>>,
) -> Vec<UnitQuaternion<f64>> {
    let t_n = demo_rotations.len();
    let rel: Vec<_> = demo_rotations
        .iter()
        .map(|r| object_pose.rotation * r)
        .collect();
    let delta = start.map(|s| s * rel[0].inverse());
    rel.iter()
        .enumerate()
        .map(|(t, r)| match &delta {
            Some(d) => {
                let s = t as f64 / (t_n - 1) as f64;
                UnitQuaternion::identity().slerp(d, 1.0 - s) * r
            }
            None => *r,
        })
        .collect()
}

impl Trajectory {
    /// Assemble a trajectory (no gripper event).
    pub(crate) fn from_parts(
        dt: f64,
        positions: Vec<Point3<f64>>,
        velocities: Vec<Vector3<f64>>,
        orientations: Vec<UnitQuaternion<f64>>,
        object_pose: Isometry3<f64>,
        start_state: Vec<f64>,
        policy: Policy,
    ) -> Trajectory {
        Trajectory {
            dt,
            positions,
            velocities,
            orientations,
            gripper_event: None,
            object_pose,
            start_state,
            policy,
        }
    }

    /// Number of steps T.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Whether the trajectory has no step (never true for a planned one).
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Total duration (s).
    pub fn duration(&self) -> f64 {
        self.dt * (self.len().saturating_sub(1)) as f64
    }

    /// The LQT-CP feedback command at step t for a measured world state (derivative-major,
    /// 3·order): `u_t = -K̃_t x̃_t` in the object frame, returned in the world frame.
    /// DMP trajectories have no gains: an error.
    pub fn control(&self, t: usize, measured_state: &[f64]) -> Result<Vector3<f64>, LqtError> {
        match &self.policy {
            Policy::LqtCp(g) => {
                super::solver::check_vector("measured_state", measured_state, 3 * g.order())?;
                let x = to_object(&self.object_pose, measured_state);
                let u = g.control(t, &x)?;
                Ok(self
                    .object_pose
                    .transform_vector(&Vector3::new(u[0], u[1], u[2])))
            }
            Policy::Dmp(_) => Err(LqtError::input(
                "policy",
                "a DMP trajectory has no feedback gains; use Trajectory::controller",
            )),
        }
    }

    /// A fresh closed-loop executor at step 0 (at the plan's start state).
    pub fn controller(&self) -> FeedbackController {
        FeedbackController {
            policy: self.policy.clone(),
            object_pose: self.object_pose,
            state: match &self.policy {
                Policy::LqtCp(_) => self.start_state.clone(),
                Policy::Dmp(r) => r.initial_state(),
            },
            t: 0,
        }
    }
}

impl FeedbackController {
    /// Current step index.
    pub fn step_index(&self) -> usize {
        self.t
    }

    /// Whether the motion is over (the controller then holds the final position).
    pub fn is_done(&self) -> bool {
        match &self.policy {
            Policy::LqtCp(g) => self.t >= g.n_controls(),
            Policy::Dmp(r) => self.t >= r.n_steps().saturating_sub(1),
        }
    }

    /// Length of the state this controller's policy expects (3·order, or 7 for a DMP).
    fn state_len(&self) -> usize {
        match &self.policy {
            Policy::LqtCp(g) if g.dim() == 3 => 3 * g.order(),
            Policy::LqtCp(_) => usize::MAX,
            Policy::Dmp(_) => 7,
        }
    }

    /// Whether state and policy agree (always, unless deserialised from inconsistent JSON; an
    /// inconsistent controller holds its position instead of panicking).
    fn consistent(&self) -> bool {
        self.state.len() == self.state_len()
    }

    /// Current commanded world position.
    pub fn position(&self) -> Point3<f64> {
        if !self.consistent() {
            return Point3::from(self.object_pose.translation.vector);
        }
        self.object_pose
            .transform_point(&Point3::new(self.state[0], self.state[1], self.state[2]))
    }

    /// Advance one step. `measured` is the measured world end-effector position (it replaces the
    /// controller's own position, so a pushed end effector is corrected); returns the next commanded
    /// world position (feed it to IK).
    pub fn step(&mut self, measured: Option<&Point3<f64>>) -> Point3<f64> {
        if !self.consistent() {
            self.t += 1;
            return self.position();
        }
        if let Some(m) = measured {
            if m.coords.iter().all(|v| v.is_finite()) {
                let o = self.object_pose.inverse_transform_point(m);
                self.state[..3].copy_from_slice(o.coords.as_slice());
            }
        }
        match &self.policy {
            Policy::LqtCp(g) => {
                if self.t < g.n_controls() {
                    if let Ok(u) = g.control(self.t, &self.state) {
                        g.step_state(&mut self.state, u.as_slice());
                    }
                } else {
                    // Hold: stop at the current position.
                    for v in self.state[3..].iter_mut() {
                        *v = 0.0;
                    }
                }
            }
            Policy::Dmp(r) => r.step(&mut self.state),
        }
        self.t += 1;
        self.position()
    }

    /// The object moved: express the controller's state in the new object frame; the same gains
    /// (object-frame reference) now steer to the new goal.
    pub fn retarget(&mut self, new_object_pose: &Isometry3<f64>) {
        if !self.consistent() {
            self.object_pose = *new_object_pose;
            return;
        }
        let n = match &self.policy {
            Policy::LqtCp(g) => 3 * g.order(),
            Policy::Dmp(_) => 6,
        };
        let world = to_world(&self.object_pose, &self.state[..n]);
        let obj = to_object(new_object_pose, &world);
        self.state[..n].copy_from_slice(&obj);
        self.object_pose = *new_object_pose;
    }
}
