//! Scenes and user moves: snapshots round-trip, bad scene JSON names the body and the field (also
//! through `logic-lfd scene`), and user moves are refused unchanged or settle onto a support.

use logic_lfd::sim::Benchmark;
use logic_lfd::sim::World;
use logic_lfd::sim::WorldSnapshot;
use nalgebra::Vector3;

use super::{b1_with, facts};

#[test]
fn snapshot_round_trip_is_identity() {
    for b in Benchmark::ALL {
        let w = b.scene();
        let s1 = w.snapshot();
        let json = serde_json::to_string(&s1).unwrap();
        let s2: WorldSnapshot = serde_json::from_str(&json).unwrap();
        let w2 = World::from_snapshot(&s2).unwrap();
        assert_eq!(w2.snapshot(), s1, "{b:?}");
    }
}

#[test]
fn bad_scene_json_names_the_body_and_the_field() {
    let good = Benchmark::B1.scene().to_json();
    let e = World::from_json("{ not json").unwrap_err();
    assert!(e.path.starts_with("line 1"), "{e}");
    // Overlapping blocks.
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    let i = s.bodies.iter().position(|b| b.name == "b").unwrap();
    let a = s.bodies.iter().position(|b| b.name == "a").unwrap();
    s.bodies[i].pose.position = s.bodies[a].pose.position;
    let e = World::from_snapshot(&s).unwrap_err();
    assert!(
        e.to_string().contains("\"a\"") && e.to_string().contains("interpenetrate"),
        "{e}"
    );
    // A block in the air.
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.bodies[i].pose.position[2] = 0.3;
    let e = World::from_snapshot(&s).unwrap_err();
    assert!(
        e.path.contains("\"b\"") && e.path.ends_with(".pose") && e.message.contains("in the air"),
        "{e}"
    );
    // Unknown held body; bad quaternion; duplicate name; joint out of limits; unknown predicate.
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.arms[0].holding = Some("zz".into());
    assert!(World::from_snapshot(&s)
        .unwrap_err()
        .to_string()
        .contains("arms[0] \"panda\".holding"));
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.bodies[i].pose.quaternion = [0.0; 4];
    assert!(World::from_snapshot(&s)
        .unwrap_err()
        .path
        .ends_with("\"b\".pose.quaternion"));
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.bodies[i].name = "a".into();
    assert!(World::from_snapshot(&s)
        .unwrap_err()
        .message
        .contains("already used"));
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.arms[0].joints[3] = 0.5;
    assert!(World::from_snapshot(&s)
        .unwrap_err()
        .path
        .ends_with("joints[3]"));
    // And the good one loads.
    World::from_json(&good).unwrap();
}

#[test]
fn cli_scene_prints_the_facts_and_check_locates_a_bad_body() {
    let exe = env!("CARGO_BIN_EXE_logic-lfd");
    let scene = format!(
        "{}/../domains/b1-tower/scene.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let out = std::process::Command::new(exe)
        .args(["scene", "facts", &scene])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(text.lines().count(), 9, "{text}");
    assert!(text.contains("(ontable a)"));
    // A block in the air: exit 2, the message names the file, the body and the field.
    let mut s: WorldSnapshot =
        serde_json::from_str(&std::fs::read_to_string(&scene).unwrap()).unwrap();
    s.bodies[2].pose.position[2] = 0.5;
    let dir = std::env::temp_dir().join(format!("logic-lfd-sim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.json");
    std::fs::write(&bad, serde_json::to_string(&s).unwrap()).unwrap();
    let out = std::process::Command::new(exe)
        .args(["scene", "check", bad.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("bad.json: bodies[2]")
            && err.contains(".pose: ")
            && err.contains("in the air"),
        "{err}"
    );
    assert!(!err.contains("panicked"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn user_moves_that_interpenetrate_or_float_are_refused_and_change_nothing() {
    let mut w = Benchmark::B1.scene();
    let before = w.snapshot();
    // Into block b.
    let bp = w.body_pose("b").unwrap().translation.vector;
    let e = w
        .move_block("a", bp + Vector3::new(0.02, 0.0, 0.0))
        .unwrap_err();
    assert!(e.reason.contains("interpenetrate b"), "{e}");
    // Off the table: nothing under it.
    let e = w.move_block("a", Vector3::new(2.0, 0.0, 0.2)).unwrap_err();
    assert!(e.reason.contains("fall"), "{e}");
    // Half over the edge of block d: would tip over.
    let dp = w.body_pose("d").unwrap().translation.vector;
    let e = w
        .move_block("a", dp + Vector3::new(0.045, 0.0, 0.2))
        .unwrap_err();
    assert!(e.reason.contains("tip"), "{e}");
    // Into the table top.
    let e = w
        .move_block("a", Vector3::new(0.4, -0.25, 0.0))
        .unwrap_err();
    assert!(e.reason.contains("table"), "{e}");
    // Fixed bodies and unknown names.
    assert!(w.move_block("table", Vector3::new(0.0, 0.0, 0.5)).is_err());
    assert!(w.move_block("zz", Vector3::new(0.0, 0.0, 0.5)).is_err());
    assert_eq!(w.snapshot(), before);
    // An accepted move settles onto the support below.
    let out = w.move_block("a", dp + Vector3::new(0.0, 0.0, 0.3)).unwrap();
    assert_eq!(out.support, "d");
    assert!((out.to[2] - 0.09).abs() < 1e-6, "{out:?}");
    w.check_invariants().unwrap();
}

#[test]
fn moving_a_block_from_under_another_lets_the_upper_one_settle() {
    let mut w = b1_with(&[("c", [0.55, 0.26, 0.3])]);
    assert!(facts(&w).contains(&"(on c d)".to_string()));
    let out = w.move_block("d", Vector3::new(0.40, 0.40, 0.1)).unwrap();
    assert_eq!(out.also_moved.len(), 1, "{out:?}");
    assert!((out.also_moved[0].1[2] - 0.03).abs() < 1e-6);
    let f = facts(&w);
    assert!(
        f.contains(&"(ontable c)".to_string()) && f.contains(&"(ontable d)".to_string()),
        "{f:?}"
    );
    w.check_invariants().unwrap();
}

#[test]
fn a_block_dragged_under_an_overhang_rests_on_the_table_below_it() {
    // c stands on d and overhangs the spot by 4 mm. Dropped there, a rests on the table with
    // its top touching c's underside: what lies above a block's centre cannot hold it up. The
    // settle probe starts 5 mm above the drop, where c is; counting c "in the way" would refuse
    // the drag and lose a block let go there (a pick under the overhang, undone).
    let mut w = b1_with(&[
        ("a", [0.30, 0.25, 0.03]),
        ("d", [0.4637, -0.2166, 0.03]),
        ("c", [0.456, -0.1988, 0.09]),
    ]);
    w.move_block("a", Vector3::new(0.40, -0.25, 0.03))
        .expect("a rests under the overhang");
    let a = w.body_pose("a").unwrap().translation.vector;
    assert!((a.z - 0.03).abs() < 1e-6, "a at {a:?}");
    assert_eq!(w.check_invariants(), Ok(()));
    let f = facts(&w);
    assert!(
        f.contains(&"(ontable a)".to_string()) && f.contains(&"(on c d)".to_string()),
        "{f:?}"
    );
}
