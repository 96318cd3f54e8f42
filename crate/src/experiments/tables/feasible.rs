//! Which Table I initial states no method could solve: the one rule, the same for every method
//! and benchmark, by which a draw is redrawn.

use nalgebra::{Isometry3, Translation3, Vector3};

use crate::sim::demo::{pull_hook_poses, PULL_TARGET_RADIUS};
use crate::sim::geometry::grasp_pose;
use crate::sim::BodyKind;
use crate::sim::Relation;
use crate::sim::World;

/// Why no method could solve a task from `world` (`None`: it is feasible). The rule, the same for
/// every method and benchmark: every block and hook rests on a support (the simulator's
/// invariants hold), and every block can be grasped from above — grasp pose and its approach pose
/// 10 cm above reachable by some arm's IK, and, where the domain has `(inreach r x)`, inside r's
/// reach annulus — or, where the scene has a hook, pulled: the hook is graspable and some arm's
/// pull stroke (the executor's, to `PULL_TARGET_RADIUS`) is reachable at its contact and pulled
/// poses and leaves the block inside the annulus (a pull only brings a block nearer: a block
/// inside the annulus' inner radius can never be picked).
pub fn infeasible(world: &World) -> Option<String> {
    if let Err(v) = world.check_invariants() {
        return Some(format!("the world breaks its invariants: {v:?}"));
    }
    let arms = world.arm_names().len();
    let snap = world.snapshot();
    // Where the domain has `(inreach r x)`, a block is only picked inside r's reach annulus.
    let annulus = world.motions().reports(Relation::InReach);
    let in_annulus = |a: usize, p: &Vector3<f64>| {
        !annulus
            || match (snap.arms.get(a), world.arm_base(a)) {
                (Some(arm), Some(b)) => {
                    let d = libm::hypot(p.x - b.translation.x, p.y - b.translation.y);
                    d >= arm.reach.min_radius && d <= arm.reach.max_radius
                }
                _ => false,
            }
    };
    let reachable = |arm: usize, tcp: &Isometry3<f64>| {
        world.reachable(arm, tcp).is_ok()
            && world
                .reachable(
                    arm,
                    &Isometry3::from_parts(
                        Translation3::from(tcp.translation.vector + Vector3::z() * 0.10),
                        tcp.rotation,
                    ),
                )
                .is_ok()
    };
    let graspable = |body: &str| {
        (0..arms).any(|a| {
            grasp_pose(world, a, body)
                .is_some_and(|g| in_annulus(a, &g.translation.vector) && reachable(a, &g))
        })
    };
    let hooks: Vec<String> = snap
        .bodies
        .iter()
        .filter(|b| b.kind == BodyKind::Hook && !b.lost)
        .map(|b| b.name.clone())
        .collect();
    for h in &hooks {
        if !graspable(h) {
            return Some(format!("the hook {h} cannot be grasped"));
        }
    }
    let pullable = |body: &str| {
        let Some(bp) = world.body_pose(body) else {
            return false;
        };
        hooks.iter().any(|h| {
            (0..arms).any(|a| {
                let (Some(base), Some(hp), Some(g)) = (
                    world.arm_base(a),
                    world.body_pose(h),
                    grasp_pose(world, a, h),
                ) else {
                    return false;
                };
                let grip = g.inverse() * hp;
                let (contact, pulled) = pull_hook_poses(&base, &bp, PULL_TARGET_RADIUS);
                // A pull only brings a block nearer: it must end inside the annulus.
                let moved = bp.translation.vector
                    + (pulled.translation.vector - contact.translation.vector);
                in_annulus(a, &moved)
                    && reachable(a, &(contact * grip.inverse()))
                    && reachable(a, &(pulled * grip.inverse()))
            })
        })
    };
    for b in world.block_names() {
        if world.is_lost(b) {
            return Some(format!("block {b} is lost"));
        }
        if !graspable(b) && !pullable(b) {
            return Some(format!(
                "block {b} can be neither grasped nor pulled into reach"
            ));
        }
    }
    None
}
