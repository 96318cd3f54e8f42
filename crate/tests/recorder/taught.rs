//! Taught tasks (`recorder::taught`): loading checks a taught demo completely, and taught tasks
//! run closed loop with Logic-LfD from random worlds to their goals, keeping the world's
//! invariants every tick.

use std::path::PathBuf;

use logic_lfd::recorder::Edit;
use logic_lfd::recorder::Recorder;
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::{SceneGraph, World};

use super::{drag, run_to_outcome};

/// A taught demo is checked completely on load: not a taught demo, an action that does not
/// apply, a goal that does not hold at the end — each refused with the key.
#[test]
fn loading_a_taught_demo_checks_it() {
    use logic_lfd::recorder::taught;
    let mut rec = Recorder::for_benchmark(Benchmark::B1).unwrap();
    rec.push(&drag("c", "d")).unwrap();
    let json = serde_json::to_string(&rec.finish().unwrap().demo).unwrap();
    let (_, info) = taught::load(&json, None).unwrap();
    assert_eq!(info.actions, ["(pick panda c)", "(stack panda c d)"]);
    assert_eq!(info.states.len(), 3);
    assert!(info.goal.contains(&"(on c d)".to_string()));

    let scripted = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../domains/b1-tower/demo.json"),
    )
    .unwrap();
    let e = taught::load(&scripted, None).unwrap_err().to_string();
    assert!(e.contains("not a taught demonstration"), "{e}");
    let swapped = json.replace("(stack panda c d)", "(stack panda c a)");
    let e = taught::load(&swapped, None).unwrap_err().to_string();
    assert!(e.starts_with("goal[") || e.starts_with("actions"), "{e}");
    let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
    v["goal"] = serde_json::json!(["(on d c)"]);
    let e = taught::load(&v.to_string(), None).unwrap_err().to_string();
    assert!(e.contains("goal[0]: (on d c) does not hold"), "{e}");
    assert!(taught::load("{", None)
        .unwrap_err()
        .to_string()
        .contains("line 1"));
}

/// A taught task (the reverse tower c on b on a, not B1's order) runs closed loop with Logic-LfD
/// from a seeded random initial world to success under an L3 disturbance (facts changed to an
/// unseen state), through `recorder::taught` (what the page's Run does); its log replays exactly.
#[test]
fn taught_reverse_tower_runs_to_success_under_l3() {
    use logic_lfd::recorder::taught::{self, TaughtRunOptions};

    let mut rec = Recorder::for_benchmark(Benchmark::B1).unwrap();
    rec.push(&drag("b", "a")).unwrap();
    rec.push(&drag("c", "b")).unwrap();
    rec.set_goal(vec!["(on b a)".into(), "(on c b)".into()])
        .unwrap();
    let taught = rec.finish().unwrap();
    let demo_json = serde_json::to_string(&taught.demo).unwrap();
    let opts = TaughtRunOptions {
        seed: 5,
        random: true,
        ..TaughtRunOptions::default()
    };
    // The random initial world differs from the taught one, and is the same for the same seed.
    let scene = taught::random_scene(&demo_json, 5, None).unwrap();
    assert_eq!(scene, taught::random_scene(&demo_json, 5, None).unwrap());
    let w = World::from_json(&scene).unwrap();
    assert_ne!(
        SceneGraph::from_world(&w).facts,
        SceneGraph::from_world(&Benchmark::B1.scene()).facts
    );
    let mut s = taught::session(&demo_json, &opts, None).unwrap();
    let injected = run_to_outcome(&mut s, Some(2));
    assert!(injected, "no L3 disturbance could be injected");
    assert_eq!(
        s.outcome(),
        Some(&Ok(())),
        "the taught task did not succeed"
    );
    let facts = SceneGraph::from_world(s.world());
    assert!(facts.contains("(on b a)") && facts.contains("(on c b)"));
    // The episode of a taught task replays exactly.
    let log = s.log().canonical();
    let again = taught::replay(&s.episode_json(), None).unwrap();
    assert_eq!(again.log().canonical(), log);
}

/// B3: a taught hand-over (b from the left table to the right one through the middle region) is
/// a valid taught task: it loads, a random initial world can be drawn, and Logic-LfD runs it from
/// that world to the taught goal.
#[test]
fn taught_b3_hand_over_runs_from_a_random_world() {
    use logic_lfd::recorder::taught::{self, TaughtRunOptions};
    let mut rec = Recorder::for_benchmark(Benchmark::B3).unwrap();
    for p in [[0.38, 0.0], [0.42, -0.62]] {
        rec.push(&Edit::Drag {
            body: "b".into(),
            onto: None,
            position: Some(p),
            yaw: None,
            arm: None,
        })
        .unwrap();
    }
    let t = rec.finish().unwrap();
    let goal: Vec<String> = t
        .demo
        .goal
        .iter()
        .filter(|f| f.contains(" b "))
        .cloned()
        .collect();
    assert!(!goal.is_empty(), "{:?}", t.demo.goal);
    let mut demo = t.demo.clone();
    demo.goal = goal.clone();
    let json = serde_json::to_string(&demo).unwrap();
    let (_, info) = taught::load(&json, None).unwrap();
    assert_eq!(info.arms, ["left", "left", "right", "right"]);
    let mut s = taught::session(
        &json,
        &TaughtRunOptions {
            seed: 2,
            random: true,
            ..TaughtRunOptions::default()
        },
        None,
    )
    .unwrap();
    run_to_outcome(&mut s, None);
    assert_eq!(s.outcome(), Some(&Ok(())), "{:?}", s.log().result);
    let facts = SceneGraph::from_world(s.world());
    for g in &goal {
        assert!(facts.contains(g), "{g}");
    }
}
