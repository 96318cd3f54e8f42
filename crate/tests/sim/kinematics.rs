//! Arm kinematics and motion: IK round trips, refusals and restarts, a level path at the joints'
//! speed limits, links stopped at the table top, and what a joint-space move sweeps through.

use logic_lfd::sim::geometry;
use logic_lfd::sim::panda;
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::GripperCommand;
use logic_lfd::sim::{ArmModel, IkParams};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::b1_with;

#[test]
fn ik_round_trip_within_1mm_and_1deg_for_sampled_reachable_poses() {
    let base = Isometry3::identity();
    let params = IkParams::default();
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    let mut solved = 0;
    for _ in 0..60 {
        // Sample a configuration, take its TCP pose: reachable by construction.
        let mut q = [0.0; 7];
        for (k, v) in q.iter_mut().enumerate() {
            let (lo, hi) = (panda::JOINT_LOWER[k], panda::JOINT_UPPER[k]);
            *v = rng.random_range(lo + 0.2 * (hi - lo)..hi - 0.2 * (hi - lo));
        }
        let target = panda::forward_kinematics(&base, &q);
        // Solve from the ready pose, not from q.
        let sol = ArmModel::panda()
            .inverse_kinematics(&base, &target, &panda::READY, &params)
            .unwrap_or_else(|e| panic!("{q:?}: {e}"));
        let got = panda::forward_kinematics(&base, &sol.joints);
        let dp = (got.translation.vector - target.translation.vector).norm();
        let da = (got.rotation * target.rotation.inverse()).angle();
        assert!(dp < 1e-3, "position error {dp}");
        assert!(da < 1f64.to_radians(), "orientation error {da}");
        for k in 0..7 {
            assert!(
                sol.joints[k] >= panda::JOINT_LOWER[k] && sol.joints[k] <= panda::JOINT_UPPER[k]
            );
        }
        solved += 1;
    }
    assert_eq!(solved, 60);
}

#[test]
fn ik_refuses_unreachable_poses_with_a_residual() {
    let base = Isometry3::identity();
    let params = IkParams::default();
    for p in [[1.5, 0.0, 0.3], [0.0, 0.0, 1.6], [0.3, 0.9, -0.2]] {
        let target = Isometry3::from_parts(
            Translation3::new(p[0], p[1], p[2]),
            panda::down_orientation(0.0),
        );
        let err = ArmModel::panda()
            .inverse_kinematics(&base, &target, &panda::READY, &params)
            .unwrap_err();
        assert!(err.position_error > 0.1, "{p:?}: {err}");
        // The best configuration is within limits and really has that residual.
        let got = panda::forward_kinematics(&base, &err.best_joints);
        let dp = (got.translation.vector - target.translation.vector).norm();
        assert!((dp - err.position_error).abs() < 1e-9);
    }
    // World::reachable agrees for B1's arm.
    let w = Benchmark::B1.scene();
    let far = Isometry3::from_parts(
        Translation3::new(1.2, 0.0, 0.03),
        panda::down_orientation(0.0),
    );
    assert!(w.reachable(0, &far).is_err());
    let near = geometry::grasp_pose(&w, 0, "a").unwrap();
    assert!(w.reachable(0, &near).is_ok());
}

#[test]
fn ik_with_room_reaches_above_a_block_at_the_minimum_reach() {
    // Found by the soak.
    // A block 25 cm from the right arm's base (B3), the pre-grasp 10 cm above it. The arm folds
    // its elbow to its limit there, and neither the warm start nor the ready posture with 6
    // restarts each converges, so the streams would refuse a pick the executor makes. More
    // restarts before giving up reach it.
    let base = Isometry3::translation(0.0, -0.45, 0.0);
    let planning = IkParams::default();
    for yaw in [0.0, std::f64::consts::FRAC_PI_2] {
        let target = Isometry3::from_parts(
            Translation3::new(0.2501, -0.4426, 0.13),
            panda::down_orientation(yaw),
        );
        let sol = ArmModel::panda()
            .inverse_kinematics_with_room(&base, &target, &panda::READY, &planning)
            .unwrap_or_else(|e| panic!("yaw {yaw}: {e:?}"));
        let reached = panda::forward_kinematics(&base, &sol.joints);
        assert!((reached.translation.vector - target.translation.vector).norm() < 1e-3);
    }
}

#[test]
fn a_hand_stretching_out_at_the_joints_speed_limits_stays_on_its_level_path() {
    // Found by the soak.
    // A hand carried out to 0.8 m at 0.35 m/s saturates the elbow's speed. Clamping each joint to
    // its speed limit alone would let the shoulder pitch on while the elbow lags, and the hand
    // would sink 5 cm below its level path (the hook's blade into a block).
    let mut w = Benchmark::B2.scene();
    let down = panda::down_orientation(0.1);
    let from = Isometry3::from_parts(Translation3::new(0.33, -0.02, 0.132), down);
    let to = Vector3::new(0.755, 0.28, 0.132);
    let sol = w.reachable(0, &from).unwrap();
    w.set_joints(0, sol.joints).unwrap();
    let steps = ((to - from.translation.vector).norm() / 0.0035).ceil() as usize;
    let mut lowest = f64::INFINITY;
    for k in 1..=steps + 150 {
        let s = (k as f64 / steps as f64).min(1.0);
        let p = from.translation.vector.lerp(&to, s);
        w.command_arm(
            0,
            Isometry3::from_parts(Translation3::from(p), down),
            GripperCommand::Open,
        )
        .unwrap();
        w.step();
        w.check_invariants().unwrap();
        lowest = lowest.min(w.tcp_pose(0).unwrap().translation.z);
    }
    assert!(lowest > 0.132 - 0.01, "the hand sank to {lowest:.3} m");
    let end = w.tcp_pose(0).unwrap().translation.vector;
    assert!((end - to).norm() < 0.004, "the hand stopped at {end}");
}

#[test]
fn an_arm_commanded_through_the_table_stops_at_its_top() {
    let mut w = Benchmark::B1.scene();
    let g = geometry::grasp_pose(&w, 0, "a").unwrap();
    // 25 cm below the table top, well inside the reach of the links.
    let below = Isometry3::from_parts(Translation3::new(0.45, -0.3, -0.25), g.rotation);
    let top = 0.0;
    let mut stopped = false;
    for _ in 0..400 {
        w.command_arm(0, below, GripperCommand::Open).unwrap();
        w.step();
        w.check_invariants().unwrap();
        let q = w.joints(0).unwrap();
        for (i, (a, b, r)) in geometry::link_capsules(&w, 0, &q)
            .into_iter()
            .enumerate()
            .skip(1)
        {
            let low = a.z.min(b.z) - r;
            assert!(
                low > top - 0.0101,
                "link {i} reaches {low:.4} m, into the table"
            );
        }
        stopped |= w.arm_blocked_by(0) == Some("table");
    }
    assert!(stopped, "the arm never reported the table in its way");
    assert!(w.tcp_pose(0).unwrap().translation.z > -0.05);
}

#[test]
fn a_joint_space_move_names_what_it_sweeps_through_and_the_ready_posture_goes_round_it() {
    // A two-block tower between two low hand poses (the hand's arc in joint space keeps its
    // distance from the base axis, 0.583 m), the other blocks far off.
    let aside = [("c", [0.3, 0.45, 0.03]), ("d", [0.25, -0.45, 0.03])];
    let w = b1_with(&[
        aside[0],
        aside[1],
        ("a", [0.583, 0.0, 0.03]),
        ("b", [0.583, 0.0, 0.09]),
    ]);
    let down = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI);
    let low = |y: f64| Isometry3::from_parts(Translation3::new(0.5, y, 0.1), down);
    let ik = |p: &Isometry3<f64>| w.reachable(0, p).expect("reachable").joints;
    let (from, to) = (ik(&low(-0.3)), ik(&low(0.3)));
    // The hand sweeps low from one side of the tower to the other: through the top block.
    let hit = w.joint_move_hits(0, &from, &to, &[]);
    assert!(matches!(hit.as_deref(), Some("a" | "b")), "{hit:?}");
    assert!(w.joint_move_hits(0, &to, &from, &[]).is_some());
    // By way of the ready posture (high above the table) both legs are clear.
    assert_eq!(w.joint_move_hits(0, &from, &panda::READY, &[]), None);
    assert_eq!(w.joint_move_hits(0, &panda::READY, &to, &[]), None);
    // Without the tower the straight move is clear too.
    let clear = b1_with(&[
        aside[0],
        aside[1],
        ("a", [0.25, 0.3, 0.03]),
        ("b", [0.2, -0.3, 0.03]),
    ]);
    assert_eq!(clear.joint_move_hits(0, &from, &to, &[]), None);
    // What overlaps at the start already (the hand around a block it grasps) is not a hit.
    let around = b1_with(&[aside[0], aside[1], ("a", [0.5, -0.3, 0.03])]);
    let at_a = Isometry3::from_parts(Translation3::new(0.5, -0.3, 0.03), down);
    let grasp = ik(&at_a);
    assert_eq!(around.joint_move_hits(0, &grasp, &panda::READY, &[]), None);
    // Coming down to grasp it the hand meets it, unless it is the body the action touches.
    assert_eq!(
        around
            .joint_move_hits(0, &panda::READY, &grasp, &[])
            .as_deref(),
        Some("a")
    );
    assert_eq!(
        around.joint_move_hits(0, &panda::READY, &grasp, &["a"]),
        None
    );
    // A hand already pressing on the table may not press deeper than the simulator lets links
    // (it would stop there), though the overlap was there at the start.
    let at = |z: f64| {
        ik(&Isometry3::from_parts(
            Translation3::new(0.45, 0.3, z),
            down,
        ))
    };
    let (touching, deeper) = (at(-0.02), at(-0.028));
    assert_eq!(
        w.joint_move_hits(0, &touching, &deeper, &[]).as_deref(),
        Some("table")
    );
    assert_eq!(w.joint_move_hits(0, &deeper, &touching, &[]), None);
}

#[test]
fn the_capsule_messages_call_the_hand_is_the_hand_capsule() {
    let w = Benchmark::B1.scene();
    let q = w.joints(0).unwrap();
    let caps = geometry::link_capsules(&w, 0, &q);
    assert_eq!(caps.len(), 7, "six links, then the hand");
    let (a, b, r) = caps[caps.len() - 1];
    let (ha, hb, hr) = logic_lfd::sim::panda::hand_capsule(&w.tcp_pose(0).unwrap());
    assert!((a - ha).norm() < 1e-9 && (b - hb).norm() < 1e-9 && r == hr);
}
