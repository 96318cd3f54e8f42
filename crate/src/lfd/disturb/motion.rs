//! Motion-level disturbances of a moving arm (L1 during a motion, paper §IV-B): the body the arm
//! approaches moved on its support, or the arm's hand pushed. Neither changes a fact; the
//! learned skill's feedback (u_t = −K̃_t x̃_t) and the executor's re-anchoring absorb them.

use nalgebra::{Isometry3, Translation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use crate::sim::World;

use super::scene::{centre, facts, Before, MOTION_TRIES};
use super::{shift_one_of, DemoTrace, Injection, Level, TcpPush};

/// An arm in the middle of a move, as a mid-motion disturbance sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct Moving {
    /// The arm's index.
    pub arm: usize,
    /// The body its motion approaches (a grasp's or a pull's object; `None` while it carries
    /// its load to a placement).
    pub approached: Option<String>,
}

/// Range of a push of a moving arm's hand (m): a shove of a few centimetres.
const PUSH_SHIFT: std::ops::Range<f64> = 0.02..0.05;
/// Largest elevation of a push's direction above or below the horizontal (rad): a shove from
/// the side, not a blow from above.
const PUSH_ELEVATION: f64 = 0.5;
/// A push is kept only when the IK puts the TCP this close to the pushed position (m).
const PUSH_ACCURACY: f64 = 0.001;
/// A motion-level disturbance (L1) while arm `moving.arm` moves: the body it approaches is
/// moved by 2–5 cm on its support, or its hand is pushed by 2–5 cm (seeded choice; the other
/// when the first is impossible). The facts are unchanged; the skill's feedback and the
/// executor's re-anchoring absorb it. Deterministic in `seed`.
pub fn inject_during_motion(
    world: &mut World,
    trace: &DemoTrace,
    moving: &Moving,
    seed: u64,
) -> Result<Injection, String> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let before = Before::of(world, trace);
    let target: Vec<String> = moving
        .approached
        .iter()
        .filter(|b| before.blocks.contains(b))
        .cloned()
        .collect();
    let push_first = target.is_empty() || rng.random_bool(0.5);
    for push in [push_first, !push_first] {
        let done = if push {
            push_tcp(world, &before, moving.arm, &mut rng).map(|p| {
                let held = world.held_by(moving.arm).map(str::to_string);
                Injection {
                    level: Level::L1,
                    description: format!(
                        "L1: pushed the hand of {} by {:.0} mm while it moved; the facts are unchanged",
                        p.arm, p.displacement_mm
                    ),
                    moved: held
                        .and_then(|h| centre(world, &h).map(|c| (h, c)))
                        .into_iter()
                        .collect(),
                    during: None,
                    push: Some(p),
                }
            })
        } else {
            shift_one_of(world, &before, &target, &mut rng)
        };
        if let Some(i) = done {
            return Ok(i);
        }
    }
    Err(
        "L1: neither the approached body nor the hand can be moved without changing the facts"
            .into(),
    )
}

/// The hand of arm `arm` pushed by 2–5 cm in a seeded, mostly horizontal direction: the joints
/// jump to the IK solution nearest them, the load follows; kept only when the arm's links and
/// load sweep through nothing on the way, the world's invariants hold and the facts are
/// unchanged.
fn push_tcp(world: &mut World, before: &Before, arm: usize, rng: &mut Pcg64Mcg) -> Option<TcpPush> {
    let (tcp, q0) = (world.tcp_pose(arm)?, world.joints(arm)?);
    if world.check_invariants().is_err() {
        return None;
    }
    let from = tcp.translation.vector;
    for _ in 0..MOTION_TRIES {
        let az = rng.random_range(0.0..std::f64::consts::TAU);
        let el = rng.random_range(-PUSH_ELEVATION..PUSH_ELEVATION);
        let r = rng.random_range(PUSH_SHIFT);
        let dir = Vector3::new(
            libm::cos(el) * libm::cos(az),
            libm::cos(el) * libm::sin(az),
            libm::sin(el),
        );
        let goal = Isometry3::from_parts(Translation3::from(from + dir * r), tcp.rotation);
        let Ok(sol) = world.reachable_near(arm, &goal) else {
            continue;
        };
        if world.joint_move_hits(arm, &q0, &sol.joints, &[]).is_some() {
            continue;
        }
        let saved = world.clone();
        if world.set_joints(arm, sol.joints).is_ok() {
            let to = world.tcp_pose(arm).map_or(from, |p| p.translation.vector);
            if ((to - from).norm() - r).abs() <= PUSH_ACCURACY
                && world.check_invariants().is_ok()
                && facts(world) == before.facts
            {
                return Some(TcpPush {
                    arm: world.arm_names()[arm].to_string(),
                    from: from.into(),
                    to: to.into(),
                    displacement_mm: (to - from).norm() * 1e3,
                });
            }
        }
        *world = saved;
    }
    None
}
