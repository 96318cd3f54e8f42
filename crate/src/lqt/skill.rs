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
use super::solver::{FeedbackGains, LqtConfig, LqtCp};
use super::task::{build_reference, Target, TargetRole, Tracking};
use super::trajectory::{
    plan_orientations, to_object, to_world, GripperEvent, MotionSkill, Policy, Trajectory, ViaPoint,
};
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
