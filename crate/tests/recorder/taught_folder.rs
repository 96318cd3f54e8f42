//! Teaching in a task folder's workcell: the recorder on the folder's scene, domain and motions,
//! a taught demo that names its folder's world, and the taught task run closed loop with that
//! folder, refused without it or with another folder.

use std::path::PathBuf;

use logic_lfd::recorder::taught::{self, TaughtRunOptions};
use logic_lfd::recorder::{Edit, Recorder};
use logic_lfd::sim::{SceneGraph, TaskFolder};

use super::{drag, run_to_outcome};

fn folder(name: &str) -> TaskFolder {
    TaskFolder::read(
        &PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../domains")
            .join(name),
    )
    .unwrap()
}

fn drag_to(body: &str, xy: [f64; 2]) -> Edit {
    Edit::Drag {
        body: body.into(),
        onto: None,
        position: Some(xy),
        yaw: None,
        arm: None,
    }
}

/// A task taught in the sorting folder's workcell (r2 into the red tray, b1 into the blue one)
/// is checked against that folder's domain, and runs closed loop from a random world of it
/// through an L3 disturbance to the taught goal; its log replays exactly with the folder.
#[test]
fn a_task_taught_in_a_folder_runs_with_that_folder() {
    let sorting = folder("sorting");
    let mut rec = Recorder::for_folder(&sorting, None).unwrap();
    let r = rec.push(&drag_to("r2", [0.39, 0.32])).unwrap();
    assert_eq!(
        r.new_segments
            .iter()
            .map(|s| s.action.as_str())
            .collect::<Vec<_>>(),
        ["(unstack panda r2 b2 pile)", "(place panda r2 red-tray)"]
    );
    rec.push(&drag_to("b1", [0.39, -0.32])).unwrap();
    rec.set_goal(vec!["(at r2 red-tray)".into(), "(at b1 blue-tray)".into()])
        .unwrap();
    let json = serde_json::to_string(&rec.finish().unwrap().demo).unwrap();

    let (_, info) = taught::load(&json, Some(&sorting)).unwrap();
    assert_eq!(info.benchmark, None);
    assert_eq!(info.folder.as_deref(), Some(sorting.dir.as_str()));
    assert_eq!(info.actions.len(), 4);
    // The demo's world is the folder's: without it, or in another folder, it is refused by name.
    let e = taught::load(&json, None).unwrap_err().to_string();
    assert!(
        e.contains("world `sorting` is none of the benchmarks") && e.contains("task folder"),
        "{e}"
    );
    let e = taught::load(&json, Some(&folder("shelf-tower")))
        .unwrap_err()
        .to_string();
    assert!(e.contains("is not the world"), "{e}");

    let opts = TaughtRunOptions {
        seed: 4,
        random: true,
        ..TaughtRunOptions::default()
    };
    let mut s = taught::session(&json, &opts, Some(&sorting)).unwrap();
    let injected = run_to_outcome(&mut s, Some(1));
    assert!(injected, "no L3 disturbance could be injected");
    assert_eq!(s.outcome(), Some(&Ok(())), "{:?}", s.log().result);
    let facts = SceneGraph::from_world(s.world());
    assert!(facts.contains("(at r2 red-tray)") && facts.contains("(at b1 blue-tray)"));
    let again = taught::replay(&s.episode_json(), Some(&sorting)).unwrap();
    assert_eq!(again.log().canonical(), s.log().canonical());
}

/// A folder that reuses B1's world under its own domain (B1 in the paper's names): its taught
/// demo names B1's world, yet without the folder it is refused for its domain, not misread.
#[test]
fn a_folder_demo_in_a_benchmark_world_is_not_taken_for_the_benchmark() {
    let naming = folder("b1-paper-naming");
    let mut rec = Recorder::for_folder(&naming, None).unwrap();
    rec.push(&drag("c", "b")).unwrap();
    let json = serde_json::to_string(&rec.finish().unwrap().demo).unwrap();
    let (_, info) = taught::load(&json, Some(&naming)).unwrap();
    assert!(
        info.actions
            .iter()
            .all(|a| a.starts_with("(pick-up ") || a.starts_with("(put-on ")),
        "{:?}",
        info.actions
    );
    let e = taught::load(&json, None).unwrap_err().to_string();
    assert!(
        e.contains("domain `b1-paper-naming` is not B1's `b1-tower`") && e.contains("task folder"),
        "{e}"
    );
    // …and a B1 demo is not read in that folder, whose world has B1's name.
    let mut rec = Recorder::for_benchmark(logic_lfd::sim::Benchmark::B1).unwrap();
    rec.push(&drag("c", "b")).unwrap();
    let b1 = serde_json::to_string(&rec.finish().unwrap().demo).unwrap();
    let e = taught::load(&b1, Some(&naming)).unwrap_err().to_string();
    assert!(
        e.contains("domain `b1-tower` is not the domain `b1-paper-naming` of the task folder"),
        "{e}"
    );
}
