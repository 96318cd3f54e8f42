//! Motion skills for the reactive loop: an LQT-CP skill learned from one demonstrated segment,
//! stored in the frame of the object it acts on (paper §III-B, "object-centric").
//!
//! * `Skill::learn(demo, dt, params)`: the demo's end-effector positions in the object frame
//!   become the reference of an LQT-CP problem in DMP mode — track the demo's acceleration profile
//!   (`q = [0, …, w_track]` on the tracked derivative), reach the demo's final position (and zero
//!   velocity) at the last step with goal precision. Via-points (also in the object frame) get the
//!   same precision as the goal (paper: "assigning the same importance to via-point and goal").
//! * Planning happens in the object frame: the start state is mapped into it
//!   (`p_o = T⁻¹ p_w`, derivatives rotated by `Rᵀ`), so the reference μ and the weights Q do not
//!   depend on the object pose at all. The [`LqtCp`] factorisation is cached per skill (per set
//!   of via-points, the only thing that changes Q); a new object pose or a new start only costs the
//!   rollout. Positions are mapped back with `p_w = T p_o`.
//! * Orientation, simply: with demo rotations `R^o_t` (object frame) the planned orientation is
//!   `R_t = slerp(I, Δ, 1 - s_t) · R_obj R^o_t`, `s_t = t/(T-1)`, where `Δ` is the rotation from the
//!   demo's first relative orientation (in the world) to the actual start orientation: the motion
//!   starts where the gripper is and blends linearly (geodesically) into the demo's relative
//!   orientation, which it follows exactly at the end.
//! * Gripper open/close is an event at the skill's end ([`GripperEvent`]).
//! * Execution: [`Trajectory::controller`] gives a [`FeedbackController`] stepped once per `dt`
//!   with the measured end-effector position: `u_t = -K̃_t x̃_t` in the object frame, so a pushed
//!   end effector is pulled back onto a path to the goal; [`FeedbackController::retarget`] moves
//!   the object frame mid-motion (the object was pushed) and the same gains steer to the new goal.

use super::basis::Basis;
use super::dmp::DmpRunner;
use super::solver::{FeedbackGains, LqtConfig, LqtCp};
use super::task::{build_reference, Target, TargetRole, Tracking};
use super::LqtError;
use nalgebra::{DMatrix, Isometry3, Point3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// Tunables of an LQT-CP skill.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SkillParams {
    /// Integrator order (3: jerk commands, state = position, velocity, acceleration).
    pub order: usize,
    /// Basis functions of the controls (K ≤ T-1).
    pub basis: Basis,
    /// Control weight r (1/(m/s^order)²).
    pub r: f64,
    /// Which derivative of the demo is tracked along the way (2: acceleration, DMP mode; 0:
    /// position); must be < order.
    pub tracked_derivative: usize,
    /// Precision of that tracking (1/(m/s^i)²).
    pub w_track: f64,
    /// Precision of the goal position at the last step (1/m²); also the via-point default.
    pub w_goal: f64,
    /// Precision of the zero goal velocity at the last step (1/(m/s)²); 0 leaves it free.
    pub w_goal_vel: f64,
}

impl Default for SkillParams {
    fn default() -> Self {
        SkillParams {
            order: 3,
            basis: Basis::rbf_uniform(10, 100.0),
            r: 1e-9,
            tracked_derivative: 2,
            w_track: 1e-2,
            w_goal: 1e6,
            w_goal_vel: 1e3,
        }
    }
}

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
    start_state: Vec<f64>,
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

/// An LQT-CP motion skill learned from one demonstrated segment. Deserialisation re-learns (and
/// so validates) the skill from its stored demo and parameters.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(try_from = "SkillData")]
pub struct Skill {
    params: SkillParams,
    dt: f64,
    demo: Vec<Point3<f64>>,
    demo_rotations: Vec<UnitQuaternion<f64>>,
    gripper_event: Option<GripperEvent>,
    /// Factorisation, reference and gains of the skill without via-points (μ and Q are
    /// object-frame constants, so a new object pose or start only costs the rollout).
    #[serde(skip)]
    cache: OnceLock<(LqtCp, DMatrix<f64>, FeedbackGains)>,
}

/// The serialised form of [`Skill`].
#[derive(Deserialize)]
struct SkillData {
    params: SkillParams,
    dt: f64,
    demo: Vec<Point3<f64>>,
    demo_rotations: Vec<UnitQuaternion<f64>>,
    gripper_event: Option<GripperEvent>,
}

impl TryFrom<SkillData> for Skill {
    type Error = LqtError;

    fn try_from(d: SkillData) -> Result<Self, LqtError> {
        if d.demo_rotations.len() != d.demo.len() {
            return Err(LqtError::input(
                "demo_rotations",
                format!(
                    "expected {} rotations (one per demo position), got {}",
                    d.demo.len(),
                    d.demo_rotations.len()
                ),
            ));
        }
        let mut skill = Skill::learn_poses_inner(&d.demo, d.demo_rotations, d.dt, d.params)?;
        skill.gripper_event = d.gripper_event;
        Ok(skill)
    }
}

fn check_demo(demo: &[Point3<f64>], dt: f64) -> Result<(), LqtError> {
    if demo.len() < 3 {
        return Err(LqtError::input(
            "demo",
            format!("expected at least 3 positions, got {}", demo.len()),
        ));
    }
    if let Some(i) = demo
        .iter()
        .position(|p| !p.coords.iter().all(|v| v.is_finite()))
    {
        return Err(LqtError::input(
            format!("demo[{i}]"),
            "expected finite coordinates",
        ));
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(LqtError::input(
            "dt",
            format!("expected a finite positive time step, got {dt}"),
        ));
    }
    Ok(())
}

/// Map a world state (derivative-major, 3 coords) into the object frame.
fn to_object(pose: &Isometry3<f64>, world: &[f64]) -> Vec<f64> {
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
fn to_world(pose: &Isometry3<f64>, obj: &[f64]) -> Vec<f64> {
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

impl Skill {
    /// Learn a skill from demonstrated end-effector positions in the object frame.
    pub fn learn(demo: &[Point3<f64>], dt: f64, params: SkillParams) -> Result<Skill, LqtError> {
        let rotations = vec![UnitQuaternion::identity(); demo.len()];
        Self::learn_poses_inner(demo, rotations, dt, params)
    }

    /// Learn from demonstrated end-effector poses in the object frame (positions and orientations).
    pub fn learn_poses(
        demo: &[Isometry3<f64>],
        dt: f64,
        params: SkillParams,
    ) -> Result<Skill, LqtError> {
        let pos: Vec<Point3<f64>> = demo
            .iter()
            .map(|p| Point3::from(p.translation.vector))
            .collect();
        let rot = demo.iter().map(|p| p.rotation).collect();
        Self::learn_poses_inner(&pos, rot, dt, params)
    }

    fn learn_poses_inner(
        demo: &[Point3<f64>],
        demo_rotations: Vec<UnitQuaternion<f64>>,
        dt: f64,
        params: SkillParams,
    ) -> Result<Skill, LqtError> {
        check_demo(demo, dt)?;
        if params.tracked_derivative >= params.order {
            return Err(LqtError::input(
                "params.tracked_derivative",
                format!(
                    "expected a derivative below the order {}, got {}",
                    params.order, params.tracked_derivative
                ),
            ));
        }
        let skill = Skill {
            params,
            dt,
            demo: demo.to_vec(),
            demo_rotations,
            gripper_event: None,
            cache: OnceLock::new(),
        };
        // Validate everything (and warm the cache) now rather than at the first plan.
        let (lqt, mu) = skill.build(&[])?;
        let gains = lqt.feedback(&mu)?;
        let _ = skill.cache.set((lqt, mu, gains));
        Ok(skill)
    }

    /// Tunables.
    pub fn params(&self) -> &SkillParams {
        &self.params
    }

    /// Time step of the demo and of the plans (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Demonstrated positions in the object frame (m).
    pub fn demo(&self) -> &[Point3<f64>] {
        &self.demo
    }

    /// Demonstrated orientations in the object frame (identity if not given).
    pub fn demo_rotations(&self) -> &[UnitQuaternion<f64>] {
        &self.demo_rotations
    }

    /// Gripper event at the end of the skill.
    pub fn gripper_event(&self) -> Option<GripperEvent> {
        self.gripper_event
    }

    /// The same skill with a gripper event at its end.
    pub fn with_gripper_event(mut self, event: GripperEvent) -> Skill {
        self.gripper_event = Some(event);
        self
    }

    /// The LQT configuration of this skill.
    pub fn config(&self) -> LqtConfig {
        LqtConfig {
            dim: 3,
            order: self.params.order,
            dt: self.dt,
            n_steps: self.demo.len(),
            r: self.params.r,
            basis: self.params.basis.clone(),
        }
    }

    /// Object-frame targets: the goal, then the via-points.
    fn targets(&self, via_points: &[ViaPoint]) -> Result<Vec<Target>, LqtError> {
        let t_n = self.demo.len();
        let goal = self.demo[t_n - 1];
        let mut targets = Vec::with_capacity(via_points.len() + 1);
        let with_vel = self.params.order >= 2 && self.params.w_goal_vel > 0.0;
        for (j, v) in via_points.iter().enumerate() {
            if !(v.phase.is_finite() && (0.0..=1.0).contains(&v.phase)) {
                return Err(LqtError::input(
                    format!("via_points[{j}].phase"),
                    format!("expected a number in [0, 1], got {}", v.phase),
                ));
            }
            let vel = v.velocity.filter(|_| with_vel);
            targets.push(Target {
                t: ((v.phase * (t_n - 1) as f64).round() as usize).max(1),
                role: TargetRole::Via,
                pos: v.position.as_slice().to_vec(),
                w_pos: v.weight.unwrap_or(self.params.w_goal),
                vel: vel.map(|u| u.as_slice().to_vec()),
                w_vel: vel.map(|_| self.params.w_goal_vel),
            });
        }
        targets.push(Target {
            t: t_n - 1,
            role: TargetRole::Goal,
            pos: goal.coords.as_slice().to_vec(),
            w_pos: self.params.w_goal,
            vel: (self.params.order >= 2 && self.params.w_goal_vel > 0.0).then(|| vec![0.0; 3]),
            w_vel: (self.params.order >= 2 && self.params.w_goal_vel > 0.0)
                .then_some(self.params.w_goal_vel),
        });
        Ok(targets)
    }

    /// Build the object-frame problem (μ, Q) and factor it.
    fn build(&self, via_points: &[ViaPoint]) -> Result<(LqtCp, DMatrix<f64>), LqtError> {
        let config = self.config();
        let t_n = self.demo.len();
        let mut weights = vec![0.0; self.params.order];
        weights[self.params.tracked_derivative] = self.params.w_track;
        let tracking = Tracking {
            demo_pos: DMatrix::from_fn(t_n, 3, |t, d| self.demo[t][d]),
            weights_per_order: weights,
        };
        let targets = self.targets(via_points)?;
        let (mu, q) = build_reference(&config, &targets, Some(&tracking))?;
        Ok((LqtCp::new(config, &q)?, mu))
    }

    /// Plan from a full world start state (derivative-major: position, velocity, …; 3·order).
    pub fn plan_from_state(
        &self,
        start_state: &[f64],
        object_pose: &Isometry3<f64>,
        via_points: &[ViaPoint],
        start_orientation: Option<&UnitQuaternion<f64>>,
    ) -> Result<Trajectory, LqtError> {
        let nx = 3 * self.params.order;
        super::solver::check_vector("start_state", start_state, nx)?;
        let x0 = to_object(object_pose, start_state);
        let gains = if via_points.is_empty() {
            match self.cache.get() {
                Some(c) => c.2.clone(),
                None => {
                    let (lqt, mu) = self.build(&[])?;
                    let gains = lqt.feedback(&mu)?;
                    self.cache.get_or_init(|| (lqt, mu, gains)).2.clone()
                }
            }
        } else {
            let (lqt, mu) = self.build(via_points)?;
            lqt.feedback(&mu)?
        };
        let roll = gains.rollout(&x0, None)?;
        let t_n = self.demo.len();
        let mut positions = Vec::with_capacity(t_n);
        let mut velocities = Vec::with_capacity(t_n);
        for t in 0..t_n {
            let row: Vec<f64> = (0..nx).map(|c| roll.x[(t, c)]).collect();
            let w = to_world(object_pose, &row);
            positions.push(Point3::new(w[0], w[1], w[2]));
            velocities.push(if self.params.order >= 2 {
                Vector3::new(w[3], w[4], w[5])
            } else if t + 1 < t_n {
                Vector3::new(roll.u[(t, 0)], roll.u[(t, 1)], roll.u[(t, 2)])
            } else {
                Vector3::zeros()
            });
        }
        Ok(Trajectory {
            dt: self.dt,
            positions,
            velocities,
            orientations: plan_orientations(&self.demo_rotations, object_pose, start_orientation),
            gripper_event: self.gripper_event,
            object_pose: *object_pose,
            start_state: x0,
            policy: Policy::LqtCp(gains),
        })
    }

    /// Plan from a start pose (at rest): the orientation blends from the start's into the demo's.
    pub fn plan_pose(
        &self,
        start: &Isometry3<f64>,
        object_pose: &Isometry3<f64>,
        via_points: &[ViaPoint],
    ) -> Result<Trajectory, LqtError> {
        let mut x = vec![0.0; 3 * self.params.order];
        x[..3].copy_from_slice(start.translation.vector.as_slice());
        self.plan_from_state(&x, object_pose, via_points, Some(&start.rotation))
    }
}

impl Skill {
    /// Plan from `start` (world, at rest) for an object at `object_pose`, through `via_points`
    /// (object frame). The same as [`MotionSkill::plan`], without importing the trait.
    pub fn plan(
        &self,
        start: &Point3<f64>,
        object_pose: &Isometry3<f64>,
        via_points: &[ViaPoint],
    ) -> Result<Trajectory, LqtError> {
        let mut x = vec![0.0; 3 * self.params.order];
        x[..3].copy_from_slice(start.coords.as_slice());
        self.plan_from_state(&x, object_pose, via_points, None)
    }
}

impl MotionSkill for Skill {
    fn plan(
        &self,
        start: &Point3<f64>,
        object_pose: &Isometry3<f64>,
        via_points: &[ViaPoint],
    ) -> Result<Trajectory, LqtError> {
        Skill::plan(self, start, object_pose, via_points)
    }
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
