//! Read-only queries of the world: names, poses, kinds and bounds of bodies, the state of the
//! arms, inverse kinematics from an arm's joints, overlaps and heights for planners.

use super::{World, WorldParams};
use crate::sim::panda::DOF;
use crate::sim::BodyKind;
use crate::sim::Motions;
use crate::sim::{ArmModel, ArmPart, IkParams, IkSolution, Unreachable};
use nalgebra::{Isometry3, Point3, Vector3};
use parry3d_f64::shape::{Capsule, Cuboid};
use std::sync::Arc;

/// An inverse kinematics of an [`ArmModel`]: (model, base, target, seed joints, parameters).
type IkSolver = fn(
    &ArmModel,
    &Isometry3<f64>,
    &Isometry3<f64>,
    &[f64; DOF],
    &IkParams,
) -> Result<IkSolution, Unreachable>;

impl World {
    /// The world reading the domain declared by `motions` (its facts, objects and actions).
    pub fn with_motions(mut self, motions: Arc<Motions>) -> World {
        self.motions = motions;
        self
    }

    /// What the domain's predicates and actions mean in this world: a shipped benchmark's world
    /// loads with that benchmark's declaration, any other with none (the scene graph then
    /// reports nothing) until [`World::with_motions`].
    pub fn motions(&self) -> &Motions {
        &self.motions
    }

    /// The shared declaration, to hand to another world.
    pub fn motions_arc(&self) -> Arc<Motions> {
        Arc::clone(&self.motions)
    }

    /// Scene name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The fixed step (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The tunables.
    pub fn params(&self) -> &WorldParams {
        &self.params
    }

    /// Mutable tunables.
    pub fn params_mut(&mut self) -> &mut WorldParams {
        &mut self.params
    }

    /// Arm names in order (the index used by [`World::command_arm`]).
    pub fn arm_names(&self) -> Vec<&str> {
        self.arms.iter().map(|a| a.name.as_str()).collect()
    }

    /// Index of the arm called `name`.
    pub fn arm_index(&self, name: &str) -> Option<usize> {
        self.arms.iter().position(|a| a.name == name)
    }

    /// Names of the blocks (kind [`BodyKind::Block`]), in body order.
    pub fn block_names(&self) -> Vec<&str> {
        self.bodies
            .iter()
            .filter(|b| b.kind == BodyKind::Block)
            .map(|b| b.name.as_str())
            .collect()
    }

    /// Names of the hooks (kind [`BodyKind::Hook`]), in body order.
    pub fn hook_names(&self) -> Vec<String> {
        self.bodies
            .iter()
            .filter(|b| b.kind == BodyKind::Hook)
            .map(|b| b.name.clone())
            .collect()
    }

    /// Names of the table regions.
    pub fn region_names(&self) -> Vec<&str> {
        self.regions.iter().map(|r| r.name.as_str()).collect()
    }

    pub(crate) fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// Pose of the body called `name`.
    pub fn body_pose(&self, name: &str) -> Option<Isometry3<f64>> {
        self.body_index(name).map(|i| self.bodies[i].pose)
    }

    /// Kind of the body called `name`.
    pub fn body_kind(&self, name: &str) -> Option<BodyKind> {
        self.body_index(name).map(|i| self.bodies[i].kind)
    }

    /// World-frame bounding box `(min, max)` of the body called `name`.
    pub fn body_aabb(&self, name: &str) -> Option<(Vector3<f64>, Vector3<f64>)> {
        self.body_index(name).map(|i| self.bodies[i].aabb())
    }

    /// World-frame bounding boxes `(min, max)` of every body of `kind`, in the world's order.
    pub fn aabbs_of(&self, kind: BodyKind) -> Vec<(Vector3<f64>, Vector3<f64>)> {
        self.bodies
            .iter()
            .filter(|b| b.kind == kind)
            .map(|b| b.aabb())
            .collect()
    }

    /// Whether the body fell off (lost).
    pub fn is_lost(&self, name: &str) -> bool {
        self.body_index(name).is_some_and(|i| self.bodies[i].lost)
    }

    /// The body held by arm `arm`, if any.
    pub fn held_by(&self, arm: usize) -> Option<&str> {
        self.arms
            .get(arm)
            .and_then(|a| a.holding.map(|(i, _)| self.bodies[i].name.as_str()))
    }

    /// The held body's pose in the TCP frame of arm `arm` (the grasp), if holding.
    pub fn grasp_transform(&self, arm: usize) -> Option<Isometry3<f64>> {
        self.arms.get(arm).and_then(|a| a.holding.map(|(_, g)| g))
    }

    /// The arm's current joint angles.
    pub fn joints(&self, arm: usize) -> Option<[f64; DOF]> {
        self.arms.get(arm).map(|a| a.joints)
    }

    /// The arm's base pose.
    pub fn arm_base(&self, arm: usize) -> Option<Isometry3<f64>> {
        self.arms.get(arm).map(|a| a.base)
    }

    /// The arm's current tool-centre-point pose (between the fingertips).
    pub fn tcp_pose(&self, arm: usize) -> Option<Isometry3<f64>> {
        self.arms.get(arm).map(|a| a.tcp())
    }

    /// The TCP pose of arm `arm` at its ready posture.
    pub fn ready_tcp(&self, arm: usize) -> Option<Isometry3<f64>> {
        self.arms
            .get(arm)
            .map(|a| a.model.forward_kinematics(&a.base, &a.model.ready()))
    }

    /// The solids of arm `arm` at joints `q` (world frame) and how many leading ones are its
    /// base's ([`ArmModel::arm_parts`]); none for an unknown arm.
    pub(crate) fn arm_parts(&self, arm: usize, q: &[f64; DOF]) -> (Vec<ArmPart>, usize) {
        match self.arms.get(arm) {
            Some(a) => (a.model.arm_parts(&a.base, q), a.model.base_parts()),
            None => (vec![], 0),
        }
    }

    /// The arm's kinematic model.
    pub fn arm_model(&self, arm: usize) -> Option<&Arc<ArmModel>> {
        self.arms.get(arm).map(|a| &a.model)
    }

    /// The arm's finger opening (m).
    pub fn gripper_opening(&self, arm: usize) -> Option<f64> {
        self.arms.get(arm).map(|a| a.gripper_opening)
    }

    /// The arm's link capsules `(a, b, radius)` in the world frame (for collision checks).
    pub fn arm_capsules(&self, arm: usize) -> Vec<Capsule> {
        self.arms
            .get(arm)
            .map(|a| {
                crate::sim::geometry::arm_drawing(a)
                    .0
                    .iter()
                    .map(|(p, q, r)| Capsule::new(Point3::from(*p), Point3::from(*q), *r))
                    .collect()
            })
            .unwrap_or_default()
    }

    /// The parry boxes of the body called `name`, posed in the world (for collision checks).
    pub fn body_shapes(&self, name: &str) -> Vec<(Isometry3<f64>, Cuboid)> {
        self.body_index(name)
            .map(|i| self.bodies[i].world_parts().map(|(p, c)| (p, *c)).collect())
            .unwrap_or_default()
    }

    /// Inverse kinematics for a TCP pose of arm `arm`, warm-started from its current joints, with
    /// seeded restarts: `Ok` with the joint angles, or `Err` with the best residual.
    pub fn reachable(&self, arm: usize, pose: &Isometry3<f64>) -> Result<IkSolution, Unreachable> {
        let Some(a) = self.arms.get(arm) else {
            return Err(Unreachable {
                best_joints: ArmModel::panda().ready(),
                position_error: f64::INFINITY,
                orientation_error: f64::INFINITY,
            });
        };
        a.model
            .inverse_kinematics(&a.base, pose, &a.joints, &self.params.planning_ik)
    }

    /// Like [`World::reachable`], the solution with the most room to the joint limits
    /// ([`ArmModel::inverse_kinematics_with_room`] from the arm's joints; the executor's joint-space
    /// recovery).
    pub fn reachable_with_room(
        &self,
        arm: usize,
        pose: &Isometry3<f64>,
    ) -> Result<IkSolution, Unreachable> {
        self.solve_from_joints(arm, pose, ArmModel::inverse_kinematics_with_room)
    }

    /// The solution nearest the arm's joints ([`ArmModel::inverse_kinematics_near`]: from them
    /// alone, a joint at a limit held there while the others reach the pose).
    pub fn reachable_near(
        &self,
        arm: usize,
        pose: &Isometry3<f64>,
    ) -> Result<IkSolution, Unreachable> {
        self.solve_from_joints(arm, pose, ArmModel::inverse_kinematics_near)
    }

    /// `solve` (an IK of the arm's [`ArmModel`]) for arm `arm` from its joints, with the planning IK's
    /// parameters; [`World::reachable`] for an unknown arm.
    fn solve_from_joints(
        &self,
        arm: usize,
        pose: &Isometry3<f64>,
        solve: IkSolver,
    ) -> Result<IkSolution, Unreachable> {
        let Some(a) = self.arms.get(arm) else {
            return self.reachable(arm, pose);
        };
        solve(&a.model, &a.base, pose, &a.joints, &self.params.planning_ik)
    }

    /// The deepest overlap (m) body `name` would have at `pose` with another body that is not
    /// lost (bodies held by arms included), and that body's name; `None` when it would touch
    /// nothing.
    pub fn overlap_at(&self, name: &str, pose: &Isometry3<f64>) -> Option<(f64, String)> {
        let bi = self.body_index(name)?;
        let mut probe = self.bodies[bi].clone();
        probe.pose = *pose;
        let mut best: Option<(f64, String)> = None;
        for (j, o) in self.bodies.iter().enumerate() {
            if j == bi || o.lost {
                continue;
            }
            let d = probe.penetration(o);
            if d > 0.0 && best.as_ref().is_none_or(|(b, _)| d > *b) {
                best = Some((d, o.name.clone()));
            }
        }
        best
    }

    /// The highest top face (m) of the bodies (not lost, `except` left out) whose
    /// horizontal bounds meet the rectangle `[lo, hi]` (x, y); the floor height if none.
    pub fn highest_top_in(&self, lo: [f64; 2], hi: [f64; 2], except: &str) -> f64 {
        let mut top = self.floor_z;
        for b in &self.bodies {
            if b.lost || b.name == except {
                continue;
            }
            let (blo, bhi) = b.aabb();
            if blo.x <= hi[0] && bhi.x >= lo[0] && blo.y <= hi[1] && bhi.y >= lo[1] {
                top = top.max(bhi.z);
            }
        }
        top
    }

    /// Names of the bodies standing (directly or through others) on body `name`, bottom first.
    pub fn resting_on(&self, name: &str) -> Vec<String> {
        self.body_index(name)
            .map(|bi| {
                self.stack_above(bi)
                    .into_iter()
                    .map(|j| self.bodies[j].name.clone())
                    .collect()
            })
            .unwrap_or_default()
    }

    /// The body that stopped the body held by `arm` at the last step (contact stop), if any.
    pub fn arm_blocked_by(&self, arm: usize) -> Option<&str> {
        self.arms.get(arm).and_then(|a| a.blocked_by.as_deref())
    }

    /// Whether a gripper holds body `bi`.
    pub(super) fn is_held(&self, bi: usize) -> bool {
        self.arms
            .iter()
            .any(|a| a.holding.is_some_and(|(j, _)| j == bi))
    }
}
