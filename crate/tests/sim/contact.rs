//! Grasps, releases and contact: a block let go over nothing is lost, a grasp turns away from a
//! neighbour, an open hand around a block rises first, the release check, and a carried block
//! stops at one the other arm holds.

use logic_lfd::sim::geometry;
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::GripperCommand;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::{facts, holding};

#[test]
fn a_block_released_over_nothing_is_lost_and_the_invariants_say_so() {
    let mut w = Benchmark::B1.scene();
    // Closing on nothing grasps nothing.
    let home = w.tcp_pose(0).unwrap();
    w.command_arm(0, home, GripperCommand::Close).unwrap();
    let ev = w.step();
    assert!(
        ev.iter()
            .any(|e| e.to_string().contains("closed on nothing")),
        "{ev:?}"
    );
    assert_eq!(w.held_by(0), None);
    // Grasp a, carry it beyond the table's edge (y < -0.6), release.
    w.command_arm(0, home, GripperCommand::Open).unwrap();
    for _ in 0..30 {
        w.step();
    }
    let g = geometry::grasp_pose(&w, 0, "a").unwrap();
    w.set_joints(0, w.reachable(0, &g).unwrap().joints).unwrap();
    w.command_arm(0, g, GripperCommand::Close).unwrap();
    w.step();
    assert_eq!(w.held_by(0), Some("a"));
    let out = Isometry3::from_parts(Translation3::new(0.3, -0.68, 0.15), g.rotation);
    w.set_joints(0, w.reachable(0, &out).unwrap().joints)
        .unwrap();
    w.check_invariants().unwrap();
    w.command_arm(0, out, GripperCommand::Open).unwrap();
    let ev = w.step();
    assert!(
        ev.iter()
            .any(|e| matches!(e, logic_lfd::sim::WorldEvent::Lost { body, .. } if body == "a")),
        "{ev:?}"
    );
    assert!(w.is_lost("a"));
    let v = w.check_invariants().unwrap_err();
    assert!(v
        .iter()
        .any(|x| matches!(x, logic_lfd::sim::Violation::Lost { body } if body == "a")));
    assert!(
        !facts(&w).iter().any(|f| f.contains(" a")),
        "a lost has no facts"
    );
}

#[test]
fn the_grasp_turns_a_quarter_when_a_neighbour_stands_in_the_hand_s_way() {
    let w = Benchmark::B1.scene();
    let a = w.body_pose("a").unwrap();
    let g0 = geometry::grasp_pose(&w, 0, "a").unwrap();
    let boxes = geometry::boxes_except(&w, &["a"]);
    let clear = geometry::clear_grasp_at(&w, 0, "a", &a, &boxes, 0.1).unwrap();
    assert_eq!(
        clear, g0,
        "nothing in the way: the grasp closest to the arm's heading"
    );
    // A block 2.5 cm from a along the fingers' closing axis.
    let axis = g0.rotation * Vector3::y();
    let p = a.translation.vector + axis * 0.085;
    let mut w = w;
    w.move_block("b", Vector3::new(p.x, p.y, 0.03)).unwrap();
    let boxes = geometry::boxes_except(&w, &["a"]);
    assert!(geometry::hand_hits(&g0, &boxes), "the hand would hit b");
    let turned = geometry::clear_grasp_at(&w, 0, "a", &a, &boxes, 0.1).unwrap();
    assert!(!geometry::hand_hits(&turned, &boxes));
    let angle = (g0.rotation.inverse() * turned.rotation).angle();
    assert!(
        (angle - std::f64::consts::FRAC_PI_2).abs() < 1e-6,
        "{angle}"
    );
    assert_eq!(turned.translation, g0.translation);
}

#[test]
fn an_empty_hand_left_around_a_block_rises_first() {
    let (mut w, g) = holding(Benchmark::B1, "a");
    assert_eq!(geometry::rise_first(&w, 0, 0.1), None, "the hand holds a");
    w.command_arm(0, g, GripperCommand::Open).unwrap();
    for _ in 0..40 {
        w.step();
    }
    assert_eq!(w.held_by(0), None);
    let up = geometry::rise_first(&w, 0, 0.1).expect("the open hand is around a");
    let tcp = w.tcp_pose(0).unwrap();
    assert!((up.translation.vector - tcp.translation.vector - Vector3::z() * 0.1).norm() < 1e-12);
    let sol = w.reachable(0, &up).unwrap();
    w.set_joints(0, sol.joints).unwrap();
    assert_eq!(geometry::rise_first(&w, 0, 0.1), None, "10 cm above a");
}

#[test]
fn release_check_says_when_letting_go_would_lose_the_load() {
    assert_eq!(
        Benchmark::B1.scene().release_check(0),
        Ok(()),
        "nothing held"
    );
    let (mut w, g) = holding(Benchmark::B1, "a");
    assert_eq!(w.release_check(0), Ok(()), "a rests where it was grasped");
    // Over the floor, 10 cm beyond the table's far edge.
    let (_, hi) = w.body_aabb("table").unwrap();
    let out = Isometry3::from_parts(Translation3::new(0.4, hi.y + 0.1, 0.15), g.rotation);
    let sol = w.reachable(0, &out).unwrap();
    w.set_joints(0, sol.joints).unwrap();
    let why = w.release_check(0).unwrap_err();
    assert!(!why.is_empty());
    assert_eq!(w.held_by(0), Some("a"), "the check lets go of nothing");
}

#[test]
fn a_block_carried_into_one_the_other_arm_holds_stops_at_contact() {
    // Found by the soak.
    // The contact stop covers bodies held by the other arm: in B3 the left arm carrying a must
    // not press it into the b the right arm holds.
    let mut w = Benchmark::B3.scene();
    w.move_block("a", Vector3::new(0.38, 0.09, 0.03)).unwrap();
    w.move_block("b", Vector3::new(0.38, -0.06, 0.03)).unwrap();
    for (arm, body) in [(0, "a"), (1, "b")] {
        let g = geometry::grasp_pose(&w, arm, body).unwrap();
        w.set_joints(arm, w.reachable(arm, &g).unwrap().joints)
            .unwrap();
        w.command_arm(arm, g, GripperCommand::Close).unwrap();
        w.step();
        assert_eq!(w.held_by(arm), Some(body));
        let up = Isometry3::from_parts(
            Translation3::new(0.0, 0.0, 0.12),
            UnitQuaternion::identity(),
        ) * g;
        w.set_joints(arm, w.reachable(arm, &up).unwrap().joints)
            .unwrap();
        w.command_arm(arm, up, GripperCommand::Close).unwrap();
    }
    w.check_invariants().unwrap();
    // The left arm carries a straight through where b hangs.
    let from = w.tcp_pose(0).unwrap();
    let mut stopped = false;
    for k in 1..=200 {
        let s = (k as f64 / 150.0).min(1.0);
        let mut to = from;
        to.translation.vector.y = from.translation.vector.y - 0.2 * s;
        w.command_arm(0, to, GripperCommand::Close).unwrap();
        w.step();
        w.check_invariants().unwrap();
        stopped |= w.arm_blocked_by(0) == Some("b");
    }
    assert!(stopped, "the left arm never reported b in its way");
    assert_eq!(w.held_by(1), Some("b"));
}
