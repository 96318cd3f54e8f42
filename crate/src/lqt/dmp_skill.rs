//! The classic DMP as a motion skill: a plan integrates the DMP from the start to the goal
//! in the object frame, and the same integrator runs the plan in closed loop.

use super::dmp::{Dmp, DmpRunner};
use super::trajectory::{plan_orientations, MotionSkill, Policy, Trajectory, ViaPoint};
use super::LqtError;
use nalgebra::{Isometry3, Point3, Vector3};

impl MotionSkill for Dmp {
    /// Via-points are ignored: a classic DMP cannot encode them.
    fn plan(
        &self,
        start: &Point3<f64>,
        object_pose: &Isometry3<f64>,
        via_points: &[ViaPoint],
    ) -> Result<Trajectory, LqtError> {
        Dmp::plan(self, start, object_pose, via_points)
    }
}

impl Dmp {
    /// Plan from `start` (world, at rest) to the demo's goal in the frame of `object_pose`.
    /// Via-points are ignored: a classic DMP cannot encode them (the paper's comparison).
    pub fn plan(
        &self,
        start: &Point3<f64>,
        object_pose: &Isometry3<f64>,
        _via_points: &[ViaPoint],
    ) -> Result<Trajectory, LqtError> {
        if !start.coords.iter().all(|v| v.is_finite()) {
            return Err(LqtError::input("start", "expected finite coordinates"));
        }
        let y0 = object_pose.inverse_transform_point(start).coords;
        let runner = DmpRunner {
            dmp: self.clone(),
            y0,
        };
        let tau = self.dt * (self.n_steps - 1) as f64;
        let mut state = runner.initial_state();
        let mut positions = Vec::with_capacity(self.n_steps);
        let mut velocities = Vec::with_capacity(self.n_steps);
        for t in 0..self.n_steps {
            if t > 0 {
                runner.step(&mut state);
            }
            positions.push(object_pose.transform_point(&Point3::new(state[0], state[1], state[2])));
            velocities.push(
                object_pose.transform_vector(&(Vector3::new(state[3], state[4], state[5]) / tau)),
            );
        }
        let start_state = runner.initial_state();
        Ok(Trajectory::from_parts(
            self.dt,
            positions,
            velocities,
            plan_orientations(&self.demo_rotations, object_pose, None),
            *object_pose,
            start_state,
            Policy::Dmp(runner),
        ))
    }
}
