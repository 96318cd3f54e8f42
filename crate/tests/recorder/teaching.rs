//! Teaching: a taught tower in another order is a valid demo reaching its goal, undo rewinds a
//! segment, quick mode covers the hand-over and the hook pull, and the skills learned from a
//! taught demo (drag or gripper mode) fit the recorded motion.

use std::process::Command;

use logic_lfd::pddl::{parse_domain, parse_problem};
use logic_lfd::plan::{parse_plan, validate};
use logic_lfd::recorder::Edit;
use logic_lfd::recorder::GripperState;
use logic_lfd::recorder::Recorder;
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::{demo, SceneGraph};

use super::{domain_file, drag, grasp_yaw, gripper};

/// A taught 3-block tower in another order than B1 (c on b on a): valid actions, the final state
/// is the taught goal, the demo replays to it, skills are learned, and the CLI gives the same.
#[test]
fn taught_reverse_tower_is_a_valid_demo_reaching_its_goal() {
    let b = Benchmark::B1;
    let mut rec = Recorder::for_benchmark(b).unwrap();
    rec.push(&drag("b", "a")).unwrap();
    rec.push(&drag("c", "b")).unwrap();
    let actions: Vec<String> = rec.segments().iter().map(|s| s.action.clone()).collect();
    assert_eq!(
        actions,
        [
            "(pick panda b)",
            "(stack panda b a)",
            "(pick panda c)",
            "(stack panda c b)"
        ]
    );
    rec.set_goal(vec!["(on b a)".into(), "(ON C B)".into()])
        .unwrap();
    assert!(rec.set_goal(vec!["(on x y)".into()]).is_err());
    rec.set_goal(vec!["(on b a)".into(), "(on c b)".into()])
        .unwrap();
    let taught = rec.finish().unwrap();
    assert_eq!(taught.demo.goal, ["(on b a)", "(on c b)"]);
    assert_eq!(taught.skills.len(), 8);
    for f in &taught.skills {
        assert!(f.goal_error < 0.01, "{f:?}");
    }
    // The plan is valid in the PDDL model and reaches the taught goal.
    let domain = parse_domain(b.domain_pddl(), "domain.pddl").unwrap();
    let problem_text = format!(
        "(define (problem taught) (:domain b1-tower) (:objects panda - arm a b c d - block) \
         (:init {}) (:goal (and {})))",
        taught.demo.initial_facts.join(" "),
        taught.demo.goal.join(" ")
    );
    let problem = parse_problem(&problem_text, "taught.pddl", &domain).unwrap();
    let plan = parse_plan(&actions.join("\n"), "plan").unwrap();
    assert!(validate(&domain, &problem, &plan).is_valid());
    // demo.json round trip and replay in the simulator.
    let json = serde_json::to_string(&taught.demo).unwrap();
    let d = demo::from_json(&json).unwrap();
    let mut world = b.scene();
    demo::replay(&mut world, &d, |_, _, _| Ok(())).unwrap();
    let facts = SceneGraph::from_world(&world);
    assert!(facts.contains("(on b a)") && facts.contains("(on c b)"));
    // The raw recording of the same session, through the CLI.
    let raw = rec.recording();
    let dir = std::env::temp_dir();
    let rec_file = dir.join(format!("taught-{}.json", std::process::id()));
    let out_file = dir.join(format!("taught-demo-{}.json", std::process::id()));
    std::fs::write(&rec_file, raw.to_json()).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
        .args(["demo", "segment"])
        .arg(&rec_file)
        .arg("--domain")
        .arg(domain_file(b))
        .arg("-o")
        .arg(&out_file)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let cli: demo::Demonstration =
        demo::from_json(&std::fs::read_to_string(&out_file).unwrap()).unwrap();
    assert_eq!(cli.plan(), actions);
    let _ = std::fs::remove_file(&rec_file);
    let _ = std::fs::remove_file(&out_file);
}

/// Undo removes the last segment and rewinds the world to the end of the one before.
#[test]
fn undo_rewinds_to_the_previous_segment() {
    let mut rec = Recorder::for_benchmark(Benchmark::B1).unwrap();
    rec.push(&drag("b", "a")).unwrap();
    let after_first = rec.demo_states();
    rec.push(&drag("c", "b")).unwrap();
    assert_eq!(rec.segments().len(), 4);
    let removed = rec.undo_last_segment().unwrap().unwrap();
    assert_eq!(removed.action, "(stack panda c b)");
    assert_eq!(rec.segments().len(), 3);
    assert_eq!(rec.world().held_by(0), Some("c"));
    let removed = rec.undo_last_segment().unwrap().unwrap();
    assert_eq!(removed.action, "(pick panda c)");
    assert_eq!(rec.demo_states(), after_first);
    assert!(rec.facts().contains(&"(on b a)".to_string()));
    // Teach something else from there.
    rec.push(&drag("d", "b")).unwrap();
    let taught = rec.finish().unwrap();
    assert_eq!(
        taught.demo.demo.plan(),
        [
            "(pick panda b)",
            "(stack panda b a)",
            "(pick panda d)",
            "(stack panda d b)"
        ]
    );
}

/// Quick mode in B3 (hand-over through the middle region) and B2 (hook pull) segment into the
/// benchmark's actions.
#[test]
fn quick_mode_covers_the_hand_over_and_the_hook_pull() {
    let mut rec = Recorder::for_benchmark(Benchmark::B3).unwrap();
    // The left arm cannot put b on the right table.
    assert!(rec
        .push(&Edit::Drag {
            body: "b".into(),
            onto: None,
            position: Some([0.42, -0.62]),
            yaw: None,
            arm: None
        })
        .is_err());
    assert!(rec.segments().is_empty());
    rec.push(&Edit::Drag {
        body: "b".into(),
        onto: None,
        position: Some([0.38, 0.0]),
        yaw: None,
        arm: None,
    })
    .unwrap();
    rec.push(&Edit::Drag {
        body: "b".into(),
        onto: None,
        position: Some([0.42, -0.62]),
        yaw: None,
        arm: None,
    })
    .unwrap();
    let plan: Vec<String> = rec.segments().iter().map(|s| s.action.clone()).collect();
    assert_eq!(
        plan,
        [
            "(pick left b left-table)",
            "(place left b handover)",
            "(pick right b handover)",
            "(place right b right-table)"
        ]
    );

    let mut rec = Recorder::for_benchmark(Benchmark::B2).unwrap();
    rec.push(&Edit::Pull {
        body: "b".into(),
        hook: None,
        arm: None,
    })
    .unwrap();
    let plan: Vec<String> = rec.segments().iter().map(|s| s.action.clone()).collect();
    assert_eq!(
        plan,
        [
            "(pick panda hook)",
            "(pull panda hook b)",
            "(place panda hook)"
        ]
    );
    assert!(rec.facts().contains(&"(inreach panda b)".to_string()));
}

/// Segment boundaries fall where the hand rests, not mid-lift (a cut mid-lift leaves the skills
/// learned from a taught B1 demo 100–260 mm off the recorded motion). Every action's skill, and
/// every approach/retreat skill the loop learns, must reproduce its recorded motion within 3 mm
/// (RMS) and end within 3 mm of it.
#[test]
fn skills_learned_from_a_taught_demo_fit_the_recorded_motion() {
    let mut rec = Recorder::for_benchmark(Benchmark::B1).unwrap();
    rec.push(&drag("c", "b")).unwrap();
    rec.push(&drag("a", "c")).unwrap();
    let taught_demo = rec.finish().unwrap();
    let parts = &taught_demo.skills;
    assert_eq!(parts.len(), 8, "{parts:?}");
    for f in parts {
        eprintln!(
            "{:32} T = {:4}  rms {:6.2} mm  goal {:6.2} mm",
            f.action,
            f.steps,
            f.rms_error * 1e3,
            f.goal_error * 1e3
        );
    }
    for f in parts {
        assert!(f.rms_error < 0.003 && f.goal_error < 0.003, "{f:?}");
    }
    // Each retreat ends at rest after the lift: the last samples are still, not mid-lift.
    for a in &taught_demo.demo.demo.actions {
        let n = a.samples.len();
        let last = a.samples[n - 1];
        let before = a.samples[n - 2];
        let v = ((last[0] - before[0]).powi(2)
            + (last[1] - before[1]).powi(2)
            + (last[2] - before[2]).powi(2))
        .sqrt();
        assert!(v < 1e-3, "{}: still moving {v} m/step at its end", a.action);
    }
}

/// A pick and place taught in gripper mode the way the page's handle does it (the handle jumps
/// to a few poses, the arm follows by IK at its joint-speed limits, G closes and opens) is
/// segmented into (pick panda c), (stack panda c d), and the skills learned from it fit its
/// motion within 3 mm RMS. The arm interpolates towards each commanded pose: jumping to it at
/// its joint speed limits would leave fits of 20–410 mm.
#[test]
fn gripper_mode_pick_and_place_is_segmented_and_learned() {
    let mut rec = Recorder::for_benchmark(Benchmark::B1).unwrap();
    let (c, yaw) = grasp_yaw(rec.world(), "c");
    let (d, _) = grasp_yaw(rec.world(), "d");
    let high = 0.25;
    let on_d = d[2] + 0.06 + 0.004;
    for (p, g, secs) in [
        ([c[0], c[1], high], GripperState::Open, 1.5),
        (c, GripperState::Open, 1.0),
        (c, GripperState::Closed, 0.5),
        ([c[0], c[1], high], GripperState::Closed, 1.0),
        ([d[0], d[1], high], GripperState::Closed, 1.5),
        ([d[0], d[1], on_d], GripperState::Closed, 1.0),
        ([d[0], d[1], on_d], GripperState::Open, 0.5),
        ([d[0], d[1], high], GripperState::Open, 1.0),
    ] {
        rec.push(&gripper(p, yaw, g, secs)).unwrap();
    }
    let actions: Vec<String> = rec.segments().iter().map(|s| s.action.clone()).collect();
    assert_eq!(actions, ["(pick panda c)", "(stack panda c d)"]);
    let taught = rec.finish().unwrap();
    for f in &taught.skills {
        eprintln!(
            "{:32} T = {:4}  rms {:6.2} mm  goal {:6.2} mm",
            f.action,
            f.steps,
            f.rms_error * 1e3,
            f.goal_error * 1e3
        );
    }
    assert_eq!(taught.skills.len(), 4);
    for f in &taught.skills {
        assert!(f.rms_error < 0.003 && f.goal_error < 0.003, "{f:?}");
    }
}
