//! Load errors of the JSON documents a user hands in (scenes, demonstrations, taught
//! demonstrations, episode logs) name the JSON path of the value at fault, what was expected, and its line and column —
//! in the library (what the page shows) and in the CLI.

use std::process::Command;

use logic_lfd::lfd::{Session, SessionOptions};
use logic_lfd::recorder::Edit;
use logic_lfd::recorder::{taught, Recorder};
use logic_lfd::sim::Benchmark;
use serde_json::json;

/// `text` pretty-printed with `value` set at `pointer`, and the 1-based line and column where
/// the value starts.
fn with_value_at(text: &str, pointer: &str, value: serde_json::Value) -> (String, usize, usize) {
    let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
    *v.pointer_mut(pointer).unwrap() = value.clone();
    let out = serde_json::to_string_pretty(&v).unwrap();
    let needle = value.to_string();
    let (i, line) = out
        .lines()
        .enumerate()
        .find(|(_, l)| l.contains(&needle))
        .unwrap();
    // serde_json reports the column of the value's last character.
    let column = line.find(&needle).unwrap() + needle.len();
    (out, i + 1, column)
}

fn b1_options() -> SessionOptions {
    serde_json::from_value(json!({ "benchmark": "b1", "seed": 1 })).unwrap()
}

#[test]
fn a_scene_with_a_wrong_type_deep_inside_names_its_path() {
    let scene = Benchmark::B1.sources().unwrap().scene;
    let (bad, line, column) = with_value_at(&scene, "/bodies/2/pose/position/1", json!("x"));
    let e = Session::from_scene(b1_options(), &bad, None)
        .err()
        .unwrap()
        .to_string();
    assert_eq!(
        e,
        format!(
            "scene: bodies[2].pose.position[1]: invalid type: string \"x\", expected f64 at line {line} column {column}"
        )
    );
}

#[test]
fn a_taught_demo_with_a_wrong_type_deep_inside_names_its_path() {
    let mut rec = Recorder::for_benchmark(Benchmark::B1).unwrap();
    rec.push(&Edit::Drag {
        body: "c".into(),
        onto: Some("d".into()),
        position: None,
        yaw: None,
        arm: None,
    })
    .unwrap();
    let json = serde_json::to_string(&rec.finish().unwrap().demo).unwrap();
    let (bad, line, column) = with_value_at(&json, "/scene/bodies/3/pose/position/0", json!(true));
    let e = taught::load(&bad, None).unwrap_err().to_string();
    assert_eq!(
        e,
        format!(
            "scene.bodies[3].pose.position[0]: invalid type: boolean `true`, expected f64 at line {line} column {column}"
        )
    );
}

#[test]
fn an_episode_log_with_a_wrong_type_names_its_path() {
    let mut s = Session::new(b1_options()).unwrap();
    s.cancel();
    let log = s.episode_json();
    let (bad, line, column) = with_value_at(&log, "/scene/bodies/2/pose/position/1", json!("x"));
    let e = Session::replay(&bad).err().unwrap().to_string();
    assert_eq!(
        e,
        format!(
            "episode: scene.bodies[2].pose.position[1]: invalid type: string \"x\", expected f64 at line {line} column {column}"
        )
    );
    let (bad, line, column) = with_value_at(&log, "/events/0/tick", json!("soon"));
    let e = Session::replay(&bad).err().unwrap().to_string();
    assert_eq!(
        e,
        format!(
            "episode: events[0].tick: invalid type: string \"soon\", expected u64 at line {line} column {column}"
        )
    );
}

#[test]
fn an_episode_event_with_a_bad_field_names_its_path_inside_the_event() {
    let mut s = Session::new(b1_options()).unwrap();
    let d = s.world().body_pose("d").unwrap().translation.vector;
    s.perturb("a", [d.x, d.y, d.z + 0.1]).unwrap();
    let log = s.episode_json();
    // The log as written (tag first) and with its keys sorted (tag no longer first) both replay.
    Session::replay(&log).unwrap();
    let v: serde_json::Value = serde_json::from_str(&log).unwrap();
    assert_eq!(v["events"][0]["event"], "perturb");
    Session::replay(&serde_json::to_string_pretty(&v).unwrap()).unwrap();

    let (bad, line, column) = with_value_at(&log, "/events/0/position/1", json!("ahead"));
    let e = Session::replay(&bad).err().unwrap().to_string();
    assert_eq!(
        e,
        format!(
            "episode: events[0].position[1]: invalid type: string \"ahead\", expected f64 at line {line} column {column}"
        )
    );
    let (bad, line, column) = with_value_at(&log, "/events/0/event", json!("shove"));
    let e = Session::replay(&bad).err().unwrap().to_string();
    assert_eq!(
        e,
        format!(
            "episode: events[0].event: unknown variant `shove`, expected one of `perturb`, `inject`, `cancel` at line {line} column {column}"
        )
    );
    let mut v = v;
    v["events"][0].as_object_mut().unwrap().remove("body");
    let e = Session::replay(&serde_json::to_string_pretty(&v).unwrap())
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.starts_with("episode: events[0]: missing field `body` at line "),
        "{e}"
    );
}

/// B1's demo.json with a string where a sample's coordinate belongs, and where it is.
fn b1_demo_with_a_bad_sample() -> (String, usize, usize) {
    let demo = Benchmark::B1.sources().unwrap().demo;
    with_value_at(&demo, "/actions/2/samples/5/1", json!("x"))
}

#[test]
fn a_demo_with_a_wrong_type_deep_inside_names_its_path() {
    let files = Benchmark::B1.sources().unwrap();
    let (bad, line, column) = b1_demo_with_a_bad_sample();
    let e = Session::from_scene(b1_options(), &files.scene, Some(&bad))
        .err()
        .unwrap()
        .to_string();
    assert_eq!(
        e,
        format!(
            "demo: actions[2].samples[5][1]: invalid type: string \"x\", expected f64 at line {line} column {column}"
        )
    );
    // A demo without trajectories (the actions only) is still a demo.
    let d: serde_json::Value = serde_json::from_str(&files.demo).unwrap();
    let names: Vec<_> = d["actions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a["action"].clone())
        .collect();
    let plain = json!({ "actions": names }).to_string();
    let s = Session::from_scene(b1_options(), &files.scene, Some(&plain)).unwrap();
    assert_eq!(s.frame().demo.len(), names.len());
}

#[test]
fn the_cli_names_the_path_in_a_domain_directorys_demo() {
    let files = Benchmark::B1.sources().unwrap();
    let (bad, line, column) = b1_demo_with_a_bad_sample();
    let dir =
        std::env::temp_dir().join(format!("logic-lfd-load-errors-demo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in [
        ("domain.pddl", &files.domain),
        ("problem.pddl", &files.problem),
        ("motions.json", &files.motions),
        ("scene.json", &files.scene),
        ("demo.json", &bad),
    ] {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let out = Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
        .args(["run", "--domain"])
        .arg(&dir)
        .output()
        .unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    let want = format!(
        "{}: actions[2].samples[5][1]: invalid type: string \"x\", expected f64 at line {line} column {column}",
        dir.join("demo.json").display()
    );
    assert!(stderr.contains(&want), "{stderr}");
}

#[test]
fn the_cli_prints_the_file_the_path_and_the_position() {
    let scene = Benchmark::B1.sources().unwrap().scene;
    let (bad, line, column) = with_value_at(&scene, "/bodies/2/pose/position/1", json!("x"));
    let dir = std::env::temp_dir().join(format!("logic-lfd-load-errors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad-scene.json");
    std::fs::write(&file, bad).unwrap();
    let want = format!(
        "{}: bodies[2].pose.position[1]: invalid type: string \"x\", expected f64 at line {line} column {column}",
        file.display()
    );
    let out = Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
        .args(["scene", "check"])
        .arg(&file)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(String::from_utf8_lossy(&out.stderr).trim(), want);
    let out = Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
        .args(["run", "--benchmark", "b1", "--scene"])
        .arg(&file)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&want.replacen(": bodies", ": scene: bodies", 1)),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
