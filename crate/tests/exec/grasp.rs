//! Grasps and lifts: the executor flies a transit where a learned approach would hit a tower or
//! the shelf, grasps a block beside the shelf along it, first unwinds an arm wound to a joint
//! limit, and puts back a block whose lift an overhang stops.

use logic_lfd::lfd::{ActionExec, ExecParams, ExecStatus};
use logic_lfd::sim::geometry::{grasp_pose, hand_hits};
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::SceneGraph;
use logic_lfd::tamp::classify;
use logic_lfd::tamp::Binder;
use logic_lfd::tamp::{StreamBinder, StreamParams};
use nalgebra::Vector3;

use crate::support::bench::{
    b1_skills, b1_with_c_overhanging_a, b2_skills, model_and_task, op, saved_world, template,
};
use crate::support::exec::{execute_learned, tick_to_end_watching};

#[test]
fn an_empty_hand_low_beside_a_tower_reaches_its_top_through_a_transit() {
    // a stands on c on d; the open hand waits low beside the tower. The straight way up to the
    // pre-grasp above a swings the hand through c; the grasp is certified with a transit
    // (straight up, across, straight down), and the executor flies it without touching c.
    let mut world = template(Benchmark::B1);
    for (name, z) in [("d", 0.03), ("c", 0.10), ("a", 0.17)] {
        world.move_block(name, Vector3::new(0.55, 0.26, z)).unwrap();
    }
    assert!(SceneGraph::from_world(&world).contains("(on a c)"));
    let low = world.tcp_pose(0).unwrap();
    let low = nalgebra::Isometry3::from_parts(
        nalgebra::Translation3::new(0.60, 0.10, 0.04),
        low.rotation,
    );
    let q = world
        .reachable(0, &low)
        .expect("the low pose is reachable")
        .joints;
    world.set_joints(0, q).unwrap();
    let (_, task) = model_and_task(Benchmark::B1, &world);
    let ops = [op(&task, "(unstack panda a c)")];
    let mut binder = StreamBinder::new(&world, 5, StreamParams::default());
    let bindings = binder.bind(&task, &ops, ops.len()).expect("certified");
    let z = bindings[0].transit.expect("a transit");
    let c_box = world.body_shapes("c");

    let skills = b1_skills();
    let params = ExecParams::default();
    // Ticks during which the hand overlaps c, with and without the transit.
    let run = |transit: Option<f64>| {
        let mut w = world.clone();
        let kind = classify(&task.operators[ops[0]], &w).unwrap();
        let mut exec = ActionExec::new("(unstack panda a c)", kind, &w, &skills, &params);
        if let Some(z) = transit {
            exec = exec.with_transit(z);
        }
        let mut touching = 0;
        let status = tick_to_end_watching(exec, &mut w, &skills, &params, |w| {
            touching += usize::from(hand_hits(&w.tcp_pose(0).unwrap(), &c_box));
        });
        (status, touching, w.held_by(0).map(str::to_string))
    };
    let (status, touching, held) = run(Some(z));
    assert_eq!(status, ExecStatus::Done);
    assert_eq!(held.as_deref(), Some("a"));
    assert_eq!(touching, 0, "the hand touched c on its transit");
    // The learned approach's own path swings the hand through c ...
    let grasp = grasp_pose(&world, 0, "a").unwrap();
    let anchor = world.body_pose("a").unwrap();
    let path = skills.segment("grasp-approach", &low, &grasp, Some(&anchor), 200);
    let through_c = (0..path.len()).any(|t| {
        let tcp = nalgebra::Isometry3::from_parts(path.planned(t).into(), low.rotation);
        hand_hits(&tcp, &c_box)
    });
    assert!(
        through_c,
        "the learned path missed c: the test shows nothing"
    );
    // ... so the executor, given no transit, checks that path and flies one itself.
    let (status, touching, held) = run(None);
    assert_eq!(status, ExecStatus::Done);
    assert_eq!(held.as_deref(), Some("a"));
    assert_eq!(touching, 0, "the hand touched c on the learned path");
}

#[test]
fn an_arm_wound_to_a_joint_limit_unwinds_before_it_picks() {
    // Found by the soak.
    // A learned approach to b beside the shelf, stopped at the shelf, leaves the arm's last joint
    // at its limit; from there the hand would reach b's grasp 55° from the grasp's turn, and
    // every joint-space way to turn it sweeps the shelf. An action whose arm starts with a joint
    // at its limit first moves, up where it rose to, to the joints with the most room for the
    // same TCP pose.
    let mut world = saved_world("b2-arm-wound-b-beside-shelf");
    let wound = world.joints(0).unwrap();
    assert!(
        logic_lfd::sim::ArmModel::panda().limit_margin(&wound) < 1e-3,
        "{wound:?}"
    );
    let (_, task) = model_and_task(Benchmark::B2, &world);
    let status = execute_learned(&mut world, &task, "(pick panda b)", &b2_skills());
    assert_eq!(status, ExecStatus::Done);
    assert_eq!(world.held_by(0), Some("b"));
}

/// B2 with `block` moved to `(x, y)` on the table: the demonstration's `(pick panda block)`
/// executed there with the learned skills grasps it.
fn b2_pick_after_moving(block: &str, x: f64, y: f64) {
    let b = Benchmark::B2;
    let mut world = template(b);
    world
        .move_block_to(block, Vector3::new(x, y, 0.03), 0.0)
        .unwrap();
    let (_, task) = model_and_task(b, &world);
    let pick = format!("(pick panda {block})");
    let status = execute_learned(&mut world, &task, &pick, &b2_skills());
    assert_eq!(status, ExecStatus::Done);
    assert_eq!(world.held_by(0), Some(block));
}

#[test]
fn a_block_beside_the_shelf_is_grasped_with_the_hand_along_the_shelf_not_across_it() {
    // Found by the soak.
    // A block dragged 2 mm from the shelf's side. No grasp keeps the hand clear of the shelf: the
    // one nearest the arm's heading reaches across the shelf (the simulator stops the hand 4 cm
    // above the block), the hand turned along the shelf's face grazes it by 3 mm, which the
    // simulator allows.
    b2_pick_after_moving("a", 0.198, -0.435);
}

#[test]
fn a_learned_approach_that_swings_the_hand_into_the_shelf_flies_over_and_comes_straight_down() {
    // Found by the soak.
    // A block dragged to the shelf's corner. The learned approach curves in from the side and the
    // simulator stops the hand at the shelf; the executor rises, crosses above the grasp and
    // descends straight, as for a carried body.
    b2_pick_after_moving("b", 0.162, -0.616);
}

#[test]
fn a_lift_stopped_by_an_overhang_puts_the_block_back_and_lets_go() {
    // The demonstration's pick executed under the overhang: the simulator stops the lift. The
    // executor lowers a back to where it was, opens and rises, and reports why: the replan
    // starts from a free hand, with a resting (not lost, not left in the gripper).
    let mut world = b1_with_c_overhanging_a();
    let a0 = world.body_pose("a").unwrap().translation.vector;
    let (_, task) = model_and_task(Benchmark::B1, &world);
    let skills = b1_skills();
    let status = execute_learned(&mut world, &task, "(pick panda a)", &skills);
    assert_eq!(
        status,
        ExecStatus::Failed("cannot lift a: c is in its way".into())
    );
    assert_eq!(world.held_by(0), None);
    assert!(!world.is_lost("a"));
    let a = world.body_pose("a").unwrap().translation.vector;
    assert!((a - a0).norm() < 0.002, "a moved from {a0:?} to {a:?}");
    assert!(SceneGraph::from_world(&world).contains("(ontable a)"));
}
