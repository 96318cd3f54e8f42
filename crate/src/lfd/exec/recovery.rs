//! Recoveries of an arm that cannot go straight on: the transit over what is in the way, the
//! undoing of a lift stopped at the start, unwinding a joint at its limit, rising by way of the
//! ready posture, and the route of a joint-space recovery.

use nalgebra::{Isometry3, Translation3};

use super::steps::{no_transit, Via};
use super::{ActionExec, Running};
use crate::sim::World;
use crate::tamp::transit_height;
use crate::tamp::ActionKind;

impl ActionExec {
    /// When the planned segment `r` would sweep a carried body into another body, or a learned
    /// approach's path (the skill's shape, not the straight line the streams certify) would
    /// sweep the hand through a block, the TCP height of a safe transit (the held body's bottom,
    /// or the hand, 3 cm above every top between start and goal); `None` when the path is
    /// clear, the via is a pull stroke or a transit itself, or a transit was already inserted
    /// for this phase.
    pub(super) fn transit_height(&self, world: &World, via: &Via, r: &Running) -> Option<f64> {
        if no_transit(via) || self.transit_at.is_some() {
            return None;
        }
        let n = r.traj.len();
        let path: Vec<Isometry3<f64>> = (0..n)
            .step_by(4)
            .chain(std::iter::once(n - 1))
            .map(|t| {
                let s = (t as f64 / (n.max(2) - 1) as f64).clamp(0.0, 1.0);
                let rot = r.traj.start_rotation().slerp(&r.goal.rotation, s);
                Isometry3::from_parts(Translation3::from(r.traj.planned(t)), rot)
            })
            .collect();
        let held = world.held_by(self.arm).map(str::to_string);
        let load_hits = held.as_ref().is_some_and(|held| {
            let tol = world.params().penetration_tolerance;
            world.grasp_transform(self.arm).is_some_and(|g| {
                path.iter().any(|tcp| {
                    world
                        .overlap_at(held, &(tcp * g))
                        .is_some_and(|(d, _)| d > LOAD_OVERLAP_OF_TOLERANCE * tol)
                })
            })
        });
        if load_hits {
            return transit_height(world, self.arm, &r.goal);
        }
        if !via.is_learned_approach() || world.hand_path_hits(&path, &[self.kind.body()]).is_none()
        {
            return None;
        }
        // The hand's transit only where the arm reaches above the goal (near the base, the
        // learned path may reach a goal the transit's corner cannot).
        let z = transit_height(world, self.arm, &r.goal)?;
        let mut over = r.goal;
        over.translation.z = z;
        world.reachable(self.arm, &over).is_ok().then_some(z)
    }
}

/// Why the lift of the body that `arm` just grasped (action `kind`, move `via`, the TCP's height
/// `grasped_z` at the grasp) is stuck: the simulator stopped it at another body before it rose
/// [`STUCK_LIFT`] above where it was grasped. `None` if it is not.
pub(super) fn stuck_lift(
    world: &World,
    arm: usize,
    kind: &ActionKind,
    via: &Via,
    grasped_z: Option<f64>,
) -> Option<String> {
    let (ActionKind::Grasp { body, .. }, Via::Up { .. }) = (kind, via) else {
        return None;
    };
    if world.held_by(arm) != Some(body.as_str()) {
        return None;
    }
    let by = world.arm_blocked_by(arm)?;
    let at = grasped_z?;
    let z = world.tcp_pose(arm)?.translation.z;
    (z - at < STUCK_LIFT).then(|| format!("cannot lift {body}: {by} is in its way"))
}

/// How far a body must have risen from where it was grasped for a stopped lift to be carried
/// on (by a transit) rather than undone (m).
const STUCK_LIFT: f64 = 0.01;

/// A planned path of a carried body counts as hitting another body where it goes deeper into it
/// than this fraction of the world's penetration tolerance.
const LOAD_OVERLAP_OF_TOLERANCE: f64 = 0.5;

/// How much more room to its joint limits ([`ArmModel::limit_margin`]) an unwound posture must
/// leave than the arm's posture now.
///
/// [`ArmModel::limit_margin`]: crate::sim::ArmModel::limit_margin
const UNWIND_GAIN: f64 = 1e-3;

/// The joints that reach arm `arm`'s TCP pose `tcp` with the most room to their limits, if they
/// leave more room than the arm's joints now and the straight joint-space move there is clear
/// ([`World::joint_move_hits`]; `touches` may be touched).
pub(super) fn unwound(
    world: &World,
    arm: usize,
    tcp: &Isometry3<f64>,
    touches: &str,
) -> Option<[f64; crate::sim::panda::DOF]> {
    let model = world.arm_model(arm)?;
    let now = world.joints(arm)?;
    let sol = world.reachable_with_room(arm, tcp).ok()?.joints;
    (model.limit_margin(&sol) > model.limit_margin(&now) + UNWIND_GAIN
        && world.joint_move_hits(arm, &now, &sol, &[touches]).is_none())
    .then_some(sol)
}

/// The ready posture, as a way for arm `arm` to rise to `goal`'s height when it cannot rise
/// where it is (a hand folded inside the minimum reach, a wrist at its limit): if the ready TCP
/// is at least that high and the joint-space move there is clear ([`World::joint_move_hits`];
/// `touches` may be touched). The transit's next leg, across and down to its goal, starts from
/// there, higher than the height it needs.
pub(super) fn rise_by_ready(
    world: &World,
    arm: usize,
    goal: &Isometry3<f64>,
    touches: &str,
) -> Option<[f64; crate::sim::panda::DOF]> {
    let model = world.arm_model(arm)?;
    let ready = model.ready();
    let now = world.joints(arm)?;
    let base = world.arm_base(arm)?;
    let high = model.forward_kinematics(&base, &ready).translation.z >= goal.translation.z;
    (high
        && world
            .joint_move_hits(arm, &now, &ready, &[touches])
            .is_none())
    .then_some(ready)
}
