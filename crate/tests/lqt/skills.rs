//! Skills (object frame, via-points, feedback execution) and the classic DMP.

use logic_lfd::lqt::{Dmp, DmpParams, GripperEvent, MotionSkill, Skill, SkillParams, ViaPoint};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

/// A 1 s approach in the object frame: from above and behind, down onto the object, T = 100.
fn demo_segment() -> Vec<Point3<f64>> {
    (0..100)
        .map(|t| {
            let s = t as f64 / 99.0;
            let e = s * s * (3.0 - 2.0 * s);
            Point3::new(
                -0.3 * (1.0 - e),
                0.1 * libm::sin(std::f64::consts::PI * e),
                0.3 - 0.28 * e,
            )
        })
        .collect()
}

fn max_dist(a: &[Point3<f64>], b: &[Point3<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

fn moved_pose() -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(0.4, -0.2, 0.05),
        UnitQuaternion::from_euler_angles(0.0, 0.0, 0.7),
    )
}

#[test]
fn skill_reproduces_demo_and_reaches_goal() {
    let demo = demo_segment();
    let skill = Skill::learn(&demo, 0.01, SkillParams::default()).unwrap();
    let tr = skill.plan(&demo[0], &Isometry3::identity(), &[]).unwrap();
    assert_eq!(tr.len(), 100);
    let goal_err = (tr.positions[99] - demo[99]).norm();
    let shape_err = max_dist(&tr.positions, &demo);
    assert!(goal_err < 1e-3, "goal error {goal_err}");
    assert!(shape_err < 0.01, "shape error {shape_err}");
    assert!(
        tr.velocities[99].norm() < 0.02,
        "final speed {}",
        tr.velocities[99].norm()
    );
}

/// A new object pose reuses the demo's shape: planning is equivariant under the object pose.
#[test]
fn skill_follows_object_pose() {
    let demo = demo_segment();
    let skill = Skill::learn(&demo, 0.01, SkillParams::default()).unwrap();
    let pose = moved_pose();
    let base = skill.plan(&demo[0], &Isometry3::identity(), &[]).unwrap();
    let moved = skill.plan(&(pose * demo[0]), &pose, &[]).unwrap();
    let mapped: Vec<_> = base.positions.iter().map(|p| pose * p).collect();
    assert!(max_dist(&moved.positions, &mapped) < 1e-9);
    // a new start too: still ends on the (moved) goal
    let other = skill.plan(&Point3::new(0.0, 0.3, 0.4), &pose, &[]).unwrap();
    assert!((other.positions[99] - pose * demo[99]).norm() < 2e-3);
    // orientation follows the object's rotation
    assert!(other.orientations[99].angle_to(&pose.rotation) < 1e-12);
}

#[test]
fn skill_passes_via_point() {
    let demo = demo_segment();
    let skill = Skill::learn(&demo, 0.01, SkillParams::default()).unwrap();
    let via = ViaPoint {
        phase: 0.5,
        position: Vector3::new(-0.1, -0.1, 0.2),
        weight: None,
        velocity: None,
    };
    let tr = skill
        .plan(&demo[0], &Isometry3::identity(), std::slice::from_ref(&via))
        .unwrap();
    let at = tr.positions[50];
    let e = (at.coords - via.position).norm();
    assert!(e < 2e-3, "via error {e}");
    assert!((tr.positions[99] - demo[99]).norm() < 2e-3);
    // without the via-point the path is far from it
    let free = skill.plan(&demo[0], &Isometry3::identity(), &[]).unwrap();
    assert!((free.positions[50].coords - via.position).norm() > 0.05);
}

/// Execute with a push of the end effector at step 40 (5 cm), and the object moved at step 60.
#[test]
fn feedback_controller_absorbs_push_and_object_move() {
    let demo = demo_segment();
    let lqt = Skill::learn(&demo, 0.01, SkillParams::default())
        .unwrap()
        .with_gripper_event(GripperEvent::Close);
    let dmp = Dmp::learn(&demo, 0.01, DmpParams::default()).unwrap();
    for (name, skill) in [("lqt", &lqt as &dyn MotionSkill), ("dmp", &dmp)] {
        let tr = skill.plan(&demo[0], &Isometry3::identity(), &[]).unwrap();
        let mut ctl = tr.controller();
        let mut measured = tr.positions[0];
        let new_pose = Isometry3::translation(0.05, 0.0, 0.0);
        for t in 0..160 {
            if t == 40 {
                measured += Vector3::new(0.0, 0.05, 0.0);
            }
            if t == 60 {
                ctl.retarget(&new_pose);
            }
            measured = ctl.step(Some(&measured));
        }
        assert!(ctl.is_done());
        let e = (measured - new_pose * demo[99]).norm();
        assert!(e < 0.01, "{name}: final error {e}");
    }
    assert_eq!(
        lqt.plan(&demo[0], &Isometry3::identity(), &[])
            .unwrap()
            .gripper_event,
        Some(GripperEvent::Close)
    );
}

#[test]
fn lqt_trajectory_control_matches_gains() {
    let demo = demo_segment();
    let skill = Skill::learn(&demo, 0.01, SkillParams::default()).unwrap();
    let pose = moved_pose();
    let tr = skill.plan(&(pose * demo[0]), &pose, &[]).unwrap();
    // stepping the controller without measurements reproduces the planned positions
    let mut ctl = tr.controller();
    for t in 1..100 {
        let p = ctl.step(None);
        assert!((p - tr.positions[t]).norm() < 1e-9, "step {t}");
    }
    let u = tr.control(0, &[0.0; 9]).unwrap();
    assert!(u.iter().all(|v| v.is_finite()));
    assert!(tr.control(99, &[0.0; 9]).is_err());
}

#[test]
fn dmp_reproduces_demo_and_reaches_new_goal() {
    let demo = demo_segment();
    let dmp = Dmp::learn(&demo, 0.01, DmpParams::default()).unwrap();
    let tr = dmp.plan(&demo[0], &Isometry3::identity(), &[]).unwrap();
    let shape_err = max_dist(&tr.positions, &demo);
    assert!(shape_err < 0.01, "dmp shape error {shape_err}");
    let pose = moved_pose();
    let moved = dmp.plan(&Point3::new(0.1, 0.2, 0.35), &pose, &[]).unwrap();
    let e = (moved.positions[99] - pose * demo[99]).norm();
    assert!(e < 0.01, "dmp new goal error {e}");
}

#[test]
fn a_skill_round_trips_through_json_and_bad_input_is_refused() {
    let demo = demo_segment();
    let skill = Skill::learn(&demo, 0.01, SkillParams::default()).unwrap();
    let json = serde_json::to_string(&skill).unwrap();
    let back: Skill = serde_json::from_str(&json).unwrap();
    let a = skill.plan(&demo[0], &moved_pose(), &[]).unwrap();
    let b = back.plan(&demo[0], &moved_pose(), &[]).unwrap();
    assert!(max_dist(&a.positions, &b.positions) < 1e-12);
    let tr_json = serde_json::to_string(&a).unwrap();
    let tr_back: logic_lfd::lqt::Trajectory = serde_json::from_str(&tr_json).unwrap();
    assert!(max_dist(&tr_back.positions, &a.positions) < 1e-12);
    // inconsistent JSON is an error, not a later panic
    let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
    v["demo_rotations"].as_array_mut().unwrap().pop();
    assert!(serde_json::from_value::<Skill>(v).is_err());
    let mut v: serde_json::Value = serde_json::from_str(&tr_json).unwrap();
    v["policy"]["LqtCp"]["kc"].as_array_mut().unwrap().pop();
    assert!(serde_json::from_value::<logic_lfd::lqt::Trajectory>(v).is_err());
    let dmp = Dmp::learn(&demo, 0.01, DmpParams::default()).unwrap();
    let dj = serde_json::to_string(&dmp).unwrap();
    let dback: Dmp = serde_json::from_str(&dj).unwrap();
    let p1 = dmp.plan(&demo[0], &moved_pose(), &[]).unwrap();
    let p2 = dback.plan(&demo[0], &moved_pose(), &[]).unwrap();
    assert!(max_dist(&p1.positions, &p2.positions) < 1e-12);
    let mut v: serde_json::Value = serde_json::from_str(&dj).unwrap();
    v["weights"].as_array_mut().unwrap().pop();
    assert!(serde_json::from_value::<Dmp>(v).is_err());

    assert!(Skill::learn(&demo[..2], 0.01, SkillParams::default()).is_err());
    let bad = SkillParams {
        tracked_derivative: 3,
        ..SkillParams::default()
    };
    assert!(Skill::learn(&demo, 0.01, bad).is_err());
    let via = ViaPoint {
        phase: 1.5,
        position: Vector3::zeros(),
        weight: None,
        velocity: None,
    };
    assert!(skill
        .plan(&demo[0], &Isometry3::identity(), &[via])
        .is_err());
    assert!(Dmp::learn(&demo, f64::NAN, DmpParams::default()).is_err());
}
