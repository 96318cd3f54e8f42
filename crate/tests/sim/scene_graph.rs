//! The scene graph reads each benchmark's predicates from geometry: on, ontable, clear, holding,
//! handempty, onshelf, inreach and regions.

use logic_lfd::sim::Benchmark;
use logic_lfd::sim::GripperCommand;
use nalgebra::{Isometry3, Translation3, Vector3};

use super::{b1_with, facts, holding};

#[test]
fn scene_graph_reports_on_ontable_clear_from_geometry() {
    // c on d, b on c (dropped from above: they settle).
    let w = b1_with(&[("c", [0.55, 0.26, 0.3]), ("b", [0.551, 0.262, 0.4])]);
    w.check_invariants().unwrap();
    let f = facts(&w);
    for want in [
        "(on c d)",
        "(on b c)",
        "(ontable d)",
        "(ontable a)",
        "(clear a)",
        "(clear b)",
        "(handempty panda)",
    ] {
        assert!(f.contains(&want.to_string()), "{want} missing in {f:?}");
    }
    for not in [
        "(clear c)",
        "(clear d)",
        "(ontable c)",
        "(ontable b)",
        "(on c b)",
    ] {
        assert!(!f.contains(&not.to_string()), "{not} wrongly in {f:?}");
    }
    assert_eq!(f.len(), 7, "{f:?}");
}

#[test]
fn scene_graph_reports_holding_and_handempty() {
    let (mut w, g) = holding(Benchmark::B1, "a");
    let f = facts(&w);
    assert!(f.contains(&"(holding panda a)".to_string()), "{f:?}");
    assert!(!f.contains(&"(handempty panda)".to_string()));
    assert!(
        !f.iter()
            .any(|s| s.contains(" a)") && !s.starts_with("(holding")),
        "{f:?}"
    );
    // Lift and release over b: a lands on b.
    let bp = w.body_pose("b").unwrap().translation.vector;
    let up = Isometry3::from_parts(Translation3::new(bp.x, bp.y, 0.2), g.rotation);
    for _ in 0..300 {
        w.command_arm(0, up, GripperCommand::Close).unwrap();
        w.step();
        w.check_invariants().unwrap();
    }
    assert_eq!(w.held_by(0), Some("a"), "still held after moving");
    let ev = {
        w.command_arm(0, up, GripperCommand::Open).unwrap();
        w.step()
    };
    assert!(
        ev.iter().any(|e| e.to_string().contains("onto b")),
        "{ev:?}"
    );
    let f = facts(&w);
    assert!(
        f.contains(&"(on a b)".to_string()) && f.contains(&"(handempty panda)".to_string()),
        "{f:?}"
    );
    w.check_invariants().unwrap();
}

#[test]
fn scene_graph_reports_onshelf_and_inreach_in_b2() {
    let mut w = Benchmark::B2.scene();
    let f = facts(&w);
    assert!(f.contains(&"(inreach panda a)".to_string()));
    assert!(
        !f.contains(&"(inreach panda b)".to_string()),
        "b starts out of reach"
    );
    // Drop a onto the shelf; pull b in by hand: onshelf a, inreach b.
    w.move_block("a", Vector3::new(0.30, -0.50, 0.3)).unwrap();
    w.move_block("b", Vector3::new(0.60, 0.05, 0.1)).unwrap();
    let f = facts(&w);
    for want in [
        "(onshelf a)",
        "(inreach panda a)",
        "(inreach panda b)",
        "(ontable b)",
        "(ontable hook)",
        "(inreach panda hook)",
    ] {
        assert!(f.contains(&want.to_string()), "{want} missing in {f:?}");
    }
    assert!(!f.contains(&"(ontable a)".to_string()));
}

#[test]
fn scene_graph_reports_regions_in_b3() {
    let mut w = Benchmark::B3.scene();
    w.move_block("a", Vector3::new(0.38, 0.0, 0.1)).unwrap();
    w.move_block("b", Vector3::new(0.45, -0.6, 0.1)).unwrap();
    let f = facts(&w);
    for want in [
        "(at a handover)",
        "(at b right-table)",
        "(ontable a)",
        "(handempty left)",
        "(handempty right)",
    ] {
        assert!(f.contains(&want.to_string()), "{want} missing in {f:?}");
    }
    w.move_block("a", Vector3::new(0.45, -0.6, 0.3)).unwrap();
    let f = facts(&w);
    assert!(
        f.contains(&"(on a b)".to_string()) && f.contains(&"(at a right-table)".to_string()),
        "{f:?}"
    );
}
