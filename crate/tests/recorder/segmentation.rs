//! Segmentation: recordings of the scripted demos give back their actions and replay to the goal;
//! what the PDDL model cannot explain (a teleport, two blocks in one grasp, a release in mid-air)
//! is refused where it happens; `logic-lfd demo segment` segments a file and names bad fields.

use std::process::Command;

use logic_lfd::recorder::recording_from_demo;
use logic_lfd::recorder::GripperState;
use logic_lfd::recorder::{RawRecording, Recorder, RecorderError};
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::{demo, SceneGraph};

use super::{data, domain_file, drag, grasp_yaw, gripper, segment};

/// Segmenting a recording replayed from each benchmark's scripted demo gives back its actions.
#[test]
fn segmentation_reproduces_each_scripted_demo() {
    for b in Benchmark::ALL {
        let d = demo::committed(b).unwrap();
        let rec = recording_from_demo(b, &d).unwrap();
        let taught = segment(&rec, b).unwrap_or_else(|e| panic!("{}: {e}", b.as_str()));
        let got: Vec<&str> = taught.demo.demo.plan();
        assert_eq!(got, d.plan(), "{}", b.as_str());
        assert_eq!(taught.states.len(), d.actions.len() + 1);
        for g in b.goal() {
            assert!(
                taught.demo.goal.contains(&g.to_string()),
                "{}: goal {g}",
                b.as_str()
            );
        }
        // Every sample is somewhere: the actions cover the recording without gaps.
        let n: usize = taught
            .demo
            .demo
            .actions
            .iter()
            .map(|a| a.samples.len())
            .sum();
        assert_eq!(n, rec.samples.len(), "{}", b.as_str());
    }
}

/// A segmented demo replays in the simulator to the same final facts (anchor frames are right).
#[test]
fn segmented_b1_demo_replays_to_the_goal() {
    let b = Benchmark::B1;
    let d = demo::committed(b).unwrap();
    let rec = recording_from_demo(b, &d).unwrap();
    let taught = segment(&rec, b).unwrap();
    let mut world = b.scene();
    demo::replay(&mut world, &taught.demo.demo, |_, _, _| Ok(())).unwrap();
    let facts = SceneGraph::from_world(&world);
    for g in b.goal() {
        assert!(facts.facts.contains(&g), "{g} after replay");
    }
}

/// A block moved by hand onto another one (a teleport) is refused with the time of the move and
/// the unexplained facts; the CLI exits 2 with that message and writes nothing.
#[test]
fn teleported_block_is_rejected_with_its_time() {
    let text = std::fs::read_to_string(data("teleport-b1.json")).unwrap();
    let rec = RawRecording::from_json(&text).unwrap();
    let err = segment(&rec, Benchmark::B1).unwrap_err();
    match &err {
        RecorderError::Unexplained {
            t, added, removed, ..
        } => {
            assert!((t - 0.5).abs() < 0.011, "t = {t}");
            assert!(added.contains(&"(on c d)".to_string()), "{added:?}");
            assert!(removed.contains(&"(ontable c)".to_string()), "{removed:?}");
        }
        other => panic!("expected an unexplained change, got {other}"),
    }
    let msg = err.to_string();
    assert!(msg.starts_with("at t = 0.50 s: the change "), "{msg}");
    let out_file = std::env::temp_dir().join(format!("teleport-{}.json", std::process::id()));
    let _ = std::fs::remove_file(&out_file);
    let out = Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
        .args(["demo", "segment"])
        .arg(data("teleport-b1.json"))
        .arg("--domain")
        .arg(domain_file(Benchmark::B1))
        .arg("-o")
        .arg(&out_file)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("teleport-b1.json: at t = 0.50 s:"),
        "{stderr}"
    );
    assert!(stderr.contains("+(on c d)"), "{stderr}");
    assert!(!out_file.exists(), "nothing is saved half-made");
}

/// Grasping the lower block of a stack (two blocks in one grasp) is refused at the grasp.
#[test]
fn grasping_under_a_stacked_block_is_rejected_at_the_grasp() {
    let mut rec = Recorder::for_benchmark(Benchmark::B1).unwrap();
    rec.push(&drag("c", "d")).unwrap();
    let (p, yaw) = grasp_yaw(rec.world(), "d");
    rec.push(&gripper([p[0], p[1], 0.25], yaw, GripperState::Open, 1.0))
        .unwrap();
    rec.push(&gripper(p, yaw, GripperState::Open, 1.0)).unwrap();
    let t_close = rec.time();
    let before = rec.segments();
    let err = rec
        .push(&gripper(p, yaw, GripperState::Closed, 0.3))
        .unwrap_err();
    match &err {
        RecorderError::Unexplained {
            t, added, removed, ..
        } => {
            assert!((t - t_close).abs() < 0.011, "t = {t}, close at {t_close}");
            assert!(added.contains(&"(holding panda d)".to_string()));
            assert!(removed.contains(&"(on c d)".to_string()));
        }
        other => panic!("expected an unexplained change, got {other}"),
    }
    // Atomic: the refused edit left nothing behind.
    assert_eq!(rec.segments(), before);
    assert_eq!(rec.time(), t_close);
    assert!(rec.world().held_by(0).is_none());
}

/// Opening the gripper high above the table (a release in mid-air) is refused at the release.
#[test]
fn release_in_mid_air_is_rejected_at_the_release() {
    let mut rec = Recorder::for_benchmark(Benchmark::B1).unwrap();
    let (p, yaw) = grasp_yaw(rec.world(), "a");
    rec.push(&gripper([p[0], p[1], 0.2], yaw, GripperState::Open, 1.5))
        .unwrap();
    rec.push(&gripper(p, yaw, GripperState::Open, 1.0)).unwrap();
    let ev = rec
        .push(&gripper(p, yaw, GripperState::Closed, 0.3))
        .unwrap();
    assert_eq!(ev.new_segments.len(), 1);
    assert_eq!(ev.new_segments[0].action, "(pick panda a)");
    rec.push(&gripper([p[0], p[1], 0.2], yaw, GripperState::Closed, 1.0))
        .unwrap();
    let t_open = rec.time();
    let err = rec
        .push(&gripper([p[0], p[1], 0.2], yaw, GripperState::Open, 0.3))
        .unwrap_err();
    match &err {
        RecorderError::Physics { t, message } => {
            assert!((t - t_open).abs() < 0.011, "t = {t}, open at {t_open}");
            assert!(message.contains("in mid-air"), "{message}");
        }
        other => panic!("expected a physics error, got {other}"),
    }
    assert_eq!(rec.world().held_by(0), Some("a"));
    // The model says the recording is unfinished while a block is held.
    assert!(matches!(rec.finish(), Err(RecorderError::Refused(_))));
}

/// A hand-written recording file (sparse samples) segments through the CLI; malformed files
/// give `file: key.path: message` and exit 2.
#[test]
fn cli_segments_a_file_and_names_bad_fields() {
    let out = Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
        .args(["demo", "segment"])
        .arg(data("b1-stack-c-on-d.json"))
        .arg("--domain")
        .arg(domain_file(Benchmark::B1))
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let d = demo::from_json(&String::from_utf8_lossy(&out.stdout)).unwrap();
    assert_eq!(d.plan(), ["(pick panda c)", "(stack panda c d)"]);

    let out = Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
        .args(["demo", "segment"])
        .arg(data("bad-gripper.json"))
        .arg("--domain")
        .arg(domain_file(Benchmark::B1))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("bad-gripper.json: samples[1].gripper: expected \"open\" or \"closed\""),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"));

    let bad = [
        (
            r#"{"benchmark":"b9","samples":[]}"#,
            "benchmark: unknown benchmark",
        ),
        (r#"{"benchmark":"b1"}"#, "samples: missing"),
        (
            r#"{"benchmark":"b1","samples":[{"t":1,"arm":0,"pose":{"position":[0,0,0.3],"yaw":0},"gripper":"open"},{"t":0.5,"arm":0,"pose":{"position":[0,0,0.3],"yaw":0},"gripper":"open"}]}"#,
            "samples[1].t: goes back in time",
        ),
        (
            r#"{"benchmark":"b1","samples":[{"t":0,"arm":0,"pose":{"position":[0,0],"yaw":0},"gripper":"open"}]}"#,
            "samples[0].pose.position: expected [x, y, z]",
        ),
        (
            r#"{"benchmark":"b1","samples":[{"t":0,"arm":7,"pose":{"position":[0,0,0.3],"yaw":0},"gripper":"open"}]}"#,
            "samples[0].arm: no such arm 7",
        ),
        (r#"{"benchmark": "#, "line 1 column"),
    ];
    for (text, want) in bad {
        let err = match RawRecording::from_json(text) {
            Err(e) => e,
            Ok(r) => segment(&r, Benchmark::B1).unwrap_err(),
        };
        assert!(err.to_string().contains(want), "{text}: {err}");
    }
    // Nothing demonstrated: refused, not an empty demo.
    let r = RawRecording::from_json(
        r#"{"benchmark":"b1","samples":[{"t":0,"arm":0,"pose":{"position":[0.3,0,0.3],"yaw":0},"gripper":"open"}]}"#,
    )
    .unwrap();
    assert!(matches!(
        segment(&r, Benchmark::B1),
        Err(RecorderError::Refused(_))
    ));
}
