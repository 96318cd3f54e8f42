//! The hook: its blade pushes what it sweeps into, a turned stroke ends at the reach radius, it
//! stops rather than push one block into another, and whether it can pull a block depends on the
//! stroke, not on how the hand is tilted now.

use logic_lfd::sim::demo;
use logic_lfd::sim::geometry;
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::{handleable, hook_can_pull};
use logic_lfd::sim::{GripperCommand, World};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::{facts, holding};

#[test]
fn the_hook_pushes_a_block_its_blade_sweeps_into() {
    // Hold the hook in place of the demo's contact pose behind b, then pull towards the base.
    let (mut w, _) = holding(Benchmark::B2, "hook");
    let bp = w.body_pose("b").unwrap();
    // Teleport to the contact pose (lifted first so nothing is swept on the way).
    let (tc, tp) = at_stroke_start(&mut w, &bp);
    let before = w.body_pose("b").unwrap().translation.vector;
    let mut pushed = false;
    stroke(&mut w, &tc, &tp, |_, events| pushed |= !events.is_empty());
    assert!(pushed);
    let after = w.body_pose("b").unwrap().translation.vector;
    let r = |v: Vector3<f64>| libm::hypot(v.x, v.y);
    assert!(
        (r(after) - 0.6).abs() < 0.01 && r(before) > 0.9,
        "{before} -> {after}"
    );
    assert!((after.y - before.y).abs() < 0.05 && (after.z - before.z).abs() < 1e-9);
    assert!(facts(&w).contains(&"(inreach panda b)".to_string()));
}

#[test]
fn a_turned_pull_stroke_brings_the_block_to_the_reach_radius_along_its_line() {
    let base = Isometry3::identity();
    let block = Isometry3::translation(0.9, 0.2, 0.03);
    let reach = demo::PULL_TARGET_RADIUS;
    let radial = demo::pull_hook_poses(&base, &block, reach);
    let same = demo::pull_hook_poses_turned(&base, &block, reach, 0.0).unwrap();
    assert!((radial.0.translation.vector - same.0.translation.vector).norm() < 1e-12);
    assert!((radial.1.translation.vector - same.1.translation.vector).norm() < 1e-12);
    for turn in [0.35, -0.35, 0.7, -0.7] {
        let (contact, pulled) = demo::pull_hook_poses_turned(&base, &block, reach, turn).unwrap();
        let stroke = pulled.translation.vector - contact.translation.vector;
        let end = block.translation.vector + stroke;
        let r = (end.x * end.x + end.y * end.y).sqrt();
        assert!(
            r <= reach && r > reach - 0.011,
            "turn {turn}: ends at radius {r}"
        );
        // The hook is yawed along the turned line and strokes straight back along it.
        let yaw = libm::atan2(0.2, 0.9) + turn;
        let x = contact.rotation * Vector3::x();
        assert!((libm::atan2(x.y, x.x) - yaw).abs() < 1e-9);
        assert!(stroke.normalize().dot(&x) < -0.999_999);
    }
    // A line that never comes within reach of the base has no stroke.
    assert!(demo::pull_hook_poses_turned(&base, &block, reach, 1.5).is_none());
}

#[test]
fn the_hook_stops_rather_than_push_a_block_into_another() {
    let (mut w, _) = holding(Benchmark::B2, "hook");
    let bp = w.body_pose("b").unwrap();
    // Block a stands 15 cm in front of b, on the line b is pulled along.
    let b = bp.translation.vector;
    let u = Vector3::new(b.x, b.y, 0.0).normalize();
    let in_front = b - u * 0.15;
    w.move_block("a", Vector3::new(in_front.x, in_front.y, 0.03))
        .unwrap_or_else(|e| panic!("{e}"));
    let (tc, tp) = at_stroke_start(&mut w, &bp);
    let mut stopped = false;
    stroke(&mut w, &tc, &tp, |w, _| {
        stopped |= w.arm_blocked_by(0).is_some()
    });
    assert!(stopped, "the stroke was never stopped");
    let a = w.body_pose("a").unwrap().translation.vector;
    let b = w.body_pose("b").unwrap().translation.vector;
    assert!((a - b).norm() > 0.058, "b was driven into a: {a} {b}");
    assert!(!w.snapshot().bodies.iter().any(|x| x.lost));
}

#[test]
fn a_hook_that_turns_during_its_stroke_pushes_the_block_instead_of_stopping() {
    let (mut w, _) = holding(Benchmark::B2, "hook");
    let bp = w.body_pose("b").unwrap();
    let (tc, tp) = at_stroke_start(&mut w, &bp);
    // The hand yaws by −3° over the stroke, as the arm's tracking does near its limits: the
    // blade turns into b as well as dragging it (a translation alone would leave it inside).
    let turned = tc.rotation * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -0.05);
    let mut stopped = None;
    for k in 1..=400 {
        let s = (k as f64 / 300.0).min(1.0);
        let p = tc.translation.vector.lerp(&tp.translation.vector, s);
        let r = tc.rotation.slerp(&turned, s);
        w.command_arm(
            0,
            Isometry3::from_parts(Translation3::from(p), r),
            GripperCommand::Close,
        )
        .unwrap();
        w.step();
        w.check_invariants().unwrap();
        stopped = stopped.or(w.arm_blocked_by(0).map(str::to_string));
    }
    assert_eq!(stopped, None, "the stroke was stopped");
    assert!(facts(&w).contains(&"(inreach panda b)".to_string()));
}

/// Drives the TCP from `tc` to `tp` in a straight line over 300 ticks (100 more to settle),
/// checking the invariants after every step; `each` sees the world and the step's events.
fn stroke(
    w: &mut World,
    tc: &Isometry3<f64>,
    tp: &Isometry3<f64>,
    mut each: impl FnMut(&World, &[logic_lfd::sim::WorldEvent]),
) {
    for k in 1..=400 {
        let s = (k as f64 / 300.0).min(1.0);
        let p = tc.translation.vector.lerp(&tp.translation.vector, s);
        w.command_arm(
            0,
            Isometry3::from_parts(Translation3::from(p), tc.rotation),
            GripperCommand::Close,
        )
        .unwrap();
        let events = w.step();
        w.check_invariants().unwrap();
        each(w, &events);
    }
}

/// Puts arm 0 (holding the hook) at the contact pose of the pull stroke of a block at `bp`;
/// returns the TCP poses at contact and pulled.
fn at_stroke_start(w: &mut World, bp: &Isometry3<f64>) -> (Isometry3<f64>, Isometry3<f64>) {
    let base = w.arm_base(0).unwrap();
    let (contact, pulled) = demo::pull_hook_poses(&base, bp, 0.6);
    let tc = geometry::tcp_for_body_pose(w, 0, &contact);
    let tp = geometry::tcp_for_body_pose(w, 0, &pulled);
    let sol = w.reachable(0, &tc).unwrap();
    w.set_joints(0, sol.joints).unwrap();
    w.check_invariants().unwrap();
    (tc, tp)
}

#[test]
fn the_hook_pulls_only_along_strokes_clear_of_the_shelf_and_within_the_arms_reach() {
    let mut w = Benchmark::B2.scene();
    // The template's far block: the radial stroke is clear.
    assert!(hook_can_pull(&w, 0, "hook", "b"));
    assert_eq!(handleable(&w, "b"), Ok(()));
    // Right behind the shelf, 0.73 m out: every stroke towards the base drags b into the shelf
    // or lowers the blade onto it.
    w.move_block("b", Vector3::new(0.38, -0.625, 0.03)).unwrap();
    assert!(!hook_can_pull(&w, 0, "hook", "b"));
    assert!(handleable(&w, "b").is_err());
    // The same distance out on the open table is fine.
    w.move_block("b", Vector3::new(0.73, 0.0, 0.03)).unwrap();
    assert!(hook_can_pull(&w, 0, "hook", "b"));
    // 1.15 m out the hook still reaches the block on the table, but the hand cannot come down
    // from the stroke's lifted pose.
    w.move_block("b", Vector3::new(1.14, -0.14, 0.03)).unwrap();
    assert!(!hook_can_pull(&w, 0, "hook", "b"));
}

#[test]
fn whether_the_hook_can_pull_does_not_depend_on_how_the_carrying_hand_is_tilted_now() {
    // Found by the soak.
    // Derived from the hand's pose of the moment, the hook's grasp of a hand tilted 7° mid-motion
    // would make a block at the edge of the stroke's reach count as pullable.
    let (mut w, _) = holding(Benchmark::B2, "hook");
    let level = w.joints(0).unwrap();
    let mut tilted = level;
    tilted[5] += 0.12;
    let (mut pullable, mut differ) = (0, vec![]);
    for i in 0..8 {
        for j in 0..8 {
            let p = Vector3::new(0.80 + 0.05 * i as f64, -0.30 + 0.1 * j as f64, 0.03);
            if w.move_block("b", p).is_err() {
                continue;
            }
            w.set_joints(0, level).unwrap();
            let a = hook_can_pull(&w, 0, "hook", "b");
            w.set_joints(0, tilted).unwrap();
            let b = hook_can_pull(&w, 0, "hook", "b");
            pullable += a as usize;
            if a != b {
                differ.push(p);
            }
        }
    }
    assert!(pullable > 5 && pullable < 60, "{pullable} of 64 pullable");
    assert!(
        differ.is_empty(),
        "the answer changes with the tilt at {differ:?}"
    );
}
