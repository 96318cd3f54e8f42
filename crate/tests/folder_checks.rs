//! A task folder is checked before anything runs, and every message names the file and the
//! place at fault: a demonstration step with an unknown object, a malformed `motions.json` fact
//! or `demo.json`, a scene body the problem does not declare (or one it declares that the scene
//! lacks), a scene that contradicts `:init`, bodies out of reach or too close for a grasp from
//! above. The shipped folders check clean.

use std::path::Path;

use logic_lfd::lfd::{Session, SessionOptions, SessionParams};
use logic_lfd::sim::{check_sources, Benchmark, Finding, TaskFolder, MIN_GAP_MM};
use serde_json::{json, Value};

fn shipped(name: &str) -> TaskFolder {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../domains")
        .join(name);
    TaskFolder::read(&dir).unwrap()
}

/// B1 in the paper's naming, given as `./mine` (a folder of the user's own).
fn mine() -> TaskFolder {
    TaskFolder::new("mine", shipped("b1-paper-naming").files)
}

fn with_file(mut f: TaskFolder, name: &str, text: String) -> TaskFolder {
    f.files.insert(name.into(), text);
    f
}

fn scene_value(f: &TaskFolder) -> Value {
    serde_json::from_str(&f.files["scene.json"]).unwrap()
}

fn with_scene(f: TaskFolder, scene: &Value) -> TaskFolder {
    with_file(
        f,
        "scene.json",
        serde_json::to_string_pretty(scene).unwrap(),
    )
}

/// Index of body `name` in the scene's `bodies`.
fn body_index(scene: &Value, name: &str) -> usize {
    scene["bodies"]
        .as_array()
        .unwrap()
        .iter()
        .position(|b| b["name"] == name)
        .unwrap()
}

/// The error of starting a session on the folder.
fn refusal(f: &TaskFolder) -> String {
    let options: SessionOptions = serde_json::from_value(json!({ "benchmark": "b1" })).unwrap();
    let sources = f.sources().unwrap();
    match Session::with_sources(options, &sources, None, None, SessionParams::default()) {
        Ok(_) => panic!("the folder was accepted"),
        Err(e) => e.to_string(),
    }
}

fn findings(f: &TaskFolder) -> Vec<Finding> {
    check_sources(&f.sources().unwrap())
}

#[test]
fn the_shipped_folders_and_benchmarks_check_clean() {
    for name in [
        "b1-tower",
        "b2-workspace-reach",
        "b3-dual-arm",
        "b1-paper-naming",
    ] {
        let found = findings(&shipped(name));
        assert!(found.is_empty(), "{name}: {found:#?}");
    }
    for b in Benchmark::ALL {
        let found = check_sources(&b.sources().unwrap());
        assert!(found.is_empty(), "{b:?}: {found:#?}");
    }
}

#[test]
fn a_demonstration_step_with_an_unknown_object_names_the_file_the_step_and_the_object() {
    let demo: Value = serde_json::from_str(&mine().files["demo.json"]).unwrap();
    let mut demo = demo;
    demo["actions"][2]["action"] = json!("(pick-up bleu2 panda)");
    let f = with_file(mine(), "demo.json", demo.to_string());
    let e = refusal(&f);
    assert!(
        e.starts_with(
            "./mine/demo.json: actions[2] (step 3) `(pick-up bleu2 panda)`: unknown object `bleu2`"
        ),
        "{e}"
    );
    assert!(e.contains("(the task's objects: panda a b c d)"), "{e}");
}

#[test]
fn a_motions_fact_of_the_wrong_form_says_what_was_expected_with_the_file() {
    let text = mine().files["motions.json"].replace(
        r#""clear": { "predicate": "clear", "args": ["body"] }"#,
        r#""clear": "(clear ?b)""#,
    );
    let f = with_file(mine(), "motions.json", text);
    let e = refusal(&f);
    assert!(
        e.starts_with("./mine/motions.json:9:25: facts.clear: "),
        "{e}"
    );
    assert!(e.contains("expected a predicate name"), "{e}");
    assert!(
        e.contains(
            r#"{"predicate": "on", "args": ["body", "below"]}, got the string "(clear ?b)""#
        ),
        "{e}"
    );
    assert!(!e.contains("untagged"), "{e}");
}

#[test]
fn a_trailing_comma_in_demo_json_is_reported_as_a_syntax_error_at_its_line_and_column() {
    let f = with_file(
        mine(),
        "demo.json",
        "{\"actions\": [\n  \"(pick-up c panda)\",\n  \"(put-on c d panda)\",\n]}\n".into(),
    );
    let e = refusal(&f);
    assert_eq!(e, "./mine/demo.json:4:1: trailing comma");
}

#[test]
fn a_misspelt_scene_body_is_named_in_the_scene_with_the_problems_objects() {
    let mut scene = scene_value(&mine());
    let i = body_index(&scene, "c");
    scene["bodies"][i]["name"] = json!("cc");
    let e = refusal(&with_scene(mine(), &scene));
    assert!(
        e.starts_with(&format!(
            "./mine/scene.json: bodies[{i}].name: the block `cc` is not an object of the problem: \
             ./mine/problem.pddl declares panda a b c d; did you mean `c`?"
        )),
        "{e}"
    );
    // The problem's `c` is missing from the scene too, at its line in problem.pddl.
    assert!(
        e.contains("; ./mine/problem.pddl:4:23: `c` is a block"),
        "{e}"
    );
    assert!(!e.contains("problem.pddl:3:"), "{e}");
}

#[test]
fn a_scene_that_contradicts_init_lists_the_facts_that_differ_naming_both_files() {
    // c stands on d in the scene; the problem's :init has it on the table.
    let mut scene = scene_value(&mine());
    let c = body_index(&scene, "c");
    let d = body_index(&scene, "d");
    let p = scene["bodies"][d]["pose"]["position"].clone();
    scene["bodies"][c]["pose"]["position"] = json!([p[0], p[1], 0.09]);
    let e = refusal(&with_scene(mine(), &scene));
    assert!(
        e.starts_with("./mine/problem.pddl:6:5: :init and ./mine/scene.json disagree"),
        "{e}"
    );
    assert!(
        e.contains("in :init but not seen in the scene: (clear d) (on-table c); seen in the scene but not in :init: (on-block c d)"),
        "{e}"
    );
}

#[test]
fn a_scene_body_or_region_the_problem_does_not_declare_is_refused_by_name_and_path() {
    let mut scene = scene_value(&mine());
    let mut extra = scene["bodies"][body_index(&scene, "a")].clone();
    extra["name"] = json!("e");
    extra["pose"]["position"] = json!([0.30, 0.25, 0.03]);
    scene["bodies"].as_array_mut().unwrap().push(extra);
    let n = scene["bodies"].as_array().unwrap().len() - 1;
    let e = refusal(&with_scene(mine(), &scene));
    assert!(
        e.starts_with(&format!(
            "./mine/scene.json: bodies[{n}].name: the block `e` is not an object of the problem"
        )),
        "{e}"
    );

    let mut scene = scene_value(&mine());
    scene["regions"] =
        json!([{ "name": "tray", "min": [0.3, 0.3], "max": [0.5, 0.5], "color": "#cccccc" }]);
    let e = refusal(&with_scene(mine(), &scene));
    assert!(
        e.starts_with("./mine/scene.json: regions[0].name: the region `tray` is not an object"),
        "{e}"
    );

    // A block the problem declares (a block per motions.json's `(block ?b)`) that the scene lacks.
    let mut scene = scene_value(&mine());
    let d = body_index(&scene, "d");
    scene["bodies"].as_array_mut().unwrap().remove(d);
    let e = refusal(&with_scene(mine(), &scene));
    assert!(
        e.starts_with("./mine/problem.pddl:4:25: `d` is a block (as motions.json declares blocks), but ./mine/scene.json has no block of that name (its blocks: a b c)"),
        "{e}"
    );
}

#[test]
fn a_body_no_arm_reaches_is_found_with_the_arms_reach() {
    let mut scene = scene_value(&mine());
    let a = body_index(&scene, "a");
    scene["bodies"][a]["pose"]["position"] = json!([0.85, -0.5, 0.03]);
    // Widen the table so the block still stands on it.
    let t = body_index(&scene, "table");
    scene["bodies"][t]["shape"]["half_extents"] = json!([0.9, 0.9, 0.02]);
    let found = findings(&with_scene(mine(), &scene));
    assert_eq!(found.len(), 1, "{found:#?}");
    let f = &found[0];
    assert_eq!(
        (f.file.as_str(), f.path.clone()),
        ("./mine/scene.json", format!("bodies[{a}].pose.position"))
    );
    assert!(
        f.message
            .starts_with("no arm can work `a` at (0.850, -0.500)"),
        "{f}"
    );
    assert!(
        f.message
            .contains("panda reaches 0.25–0.70 m from its base, `a` is 0.99 m from it"),
        "{f}"
    );
}

/// B1's folder with block `c` hemmed in: `d` beside it and `b` in front of it (further from the
/// arm), each `gap` m from its faces.
fn hemmed_in(gap: f64) -> TaskFolder {
    let mut scene = scene_value(&mine());
    let (x, y) = (0.45, 0.05);
    for (name, at) in [
        ("c", [x, y]),
        ("d", [x, y + 0.06 + gap]),
        ("b", [x + 0.06 + gap, y]),
    ] {
        let i = body_index(&scene, name);
        scene["bodies"][i]["pose"]["position"] = json!([at[0], at[1], 0.03]);
    }
    with_scene(mine(), &scene)
}

#[test]
fn blocks_too_close_for_a_grasp_from_above_are_named_as_a_pair_with_their_gap() {
    let found = findings(&hemmed_in(0.03));
    assert_eq!(found.len(), 1, "{found:#?}");
    let f = &found[0];
    let scene = scene_value(&mine());
    assert_eq!(
        f.path,
        format!("bodies[{}].pose.position", body_index(&scene, "c"))
    );
    assert!(
        f.message.starts_with("a grasp of `c` from above hits `d` (the hand) at every grasp angle: they stand 30 mm apart"),
        "{f}"
    );
    assert!(
        f.message.contains(&format!("at least {MIN_GAP_MM} mm")),
        "{f}"
    );
    // One neighbour alone leaves the other axis free for the hand.
    let mut scene = scene_value(&mine());
    let (c, d) = (body_index(&scene, "c"), body_index(&scene, "d"));
    scene["bodies"][c]["pose"]["position"] = json!([0.45, 0.05, 0.03]);
    scene["bodies"][d]["pose"]["position"] = json!([0.45, 0.12, 0.03]);
    let found = findings(&with_scene(mine(), &scene));
    assert!(found.is_empty(), "{found:#?}");
}

#[test]
fn the_advised_gap_is_the_smallest_that_checks_clean() {
    // Every gap from the advised one up (in 5 mm steps to 15 cm, where `b` is still in reach) is
    // clear; 5 mm less is not.
    let clear = |mm: u32| findings(&hemmed_in(f64::from(mm) / 1000.0)).is_empty();
    for mm in (MIN_GAP_MM..=150).step_by(5) {
        assert!(clear(mm), "{mm} mm");
    }
    assert!(!clear(MIN_GAP_MM - 5));
}

fn cli(args: &[&str]) -> (Option<i32>, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn shipped_dir(name: &str) -> String {
    format!("{}/../domains/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn scene_check_with_a_domain_prints_each_finding_and_exits_2_until_clean() {
    let dir = shipped_dir("b1-paper-naming");
    let (code, out, err) = cli(&["scene", "check", "--domain", &dir]);
    assert_eq!(code, Some(0), "{out}{err}");
    assert!(out.trim_end().ends_with(": ok"), "{out}");

    // A folder on disk with a misspelt body and a crowded corner.
    let tmp = std::env::temp_dir().join(format!("logic-lfd-folder-check-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let mut f = hemmed_in(0.02);
    let mut scene = scene_value(&f);
    let a = body_index(&scene, "a");
    scene["bodies"][a]["name"] = json!("aa");
    f = with_scene(f, &scene);
    for (name, text) in &f.files {
        std::fs::write(tmp.join(name), text).unwrap();
    }
    let (code, out, err) = cli(&["scene", "check", "--domain", tmp.to_str().unwrap()]);
    std::fs::remove_dir_all(&tmp).unwrap();
    assert_eq!(code, Some(2), "{out}{err}");
    let scene_file = tmp.join("scene.json").display().to_string();
    let lines: Vec<&str> = out.lines().collect();
    assert!(
        lines.iter().any(|l| l.starts_with(&format!(
            "{scene_file}: bodies[{a}].name: the block `aa` is not an object of the problem"
        ))),
        "{out}"
    );
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with(&format!("{scene_file}: bodies["))
                && l.contains("stand 20 mm apart")),
        "{out}"
    );
}

#[test]
fn scene_facts_and_disturb_with_a_domain_read_the_folders_scene() {
    let dir = shipped_dir("b1-paper-naming");
    let (code, out, err) = cli(&["scene", "facts", "--domain", &dir]);
    assert_eq!(code, Some(0), "{err}");
    let facts: Vec<&str> = out.lines().collect();
    for f in ["(on-table a)", "(clear d)", "(empty panda)", "(block c)"] {
        assert!(facts.contains(&f), "{out}");
    }
    let (code, out, err) = cli(&[
        "scene", "disturb", "--domain", &dir, "--level", "l2", "--seed", "3",
    ]);
    assert_eq!(code, Some(0), "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    let d = v["disturbance"]["description"].as_str().unwrap();
    assert!(d.starts_with("L2: moved "), "{d}");
    assert!(d.ends_with(": a state of the demonstration"), "{d}");
}
