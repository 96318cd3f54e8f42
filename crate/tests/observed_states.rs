//! Any observed state is a state: facts no action adds and static facts that differ from the
//! problem's `:init` are kept (the problem is re-grounded with the state as its `:init`), LogicIn
//! and replanning run on the state as observed, every plan replays on the lifted validator from
//! it, malformed atoms are still refused at their `line:col` (exit 2), and a state from which the
//! goal can no longer be reached exits 3 naming the goal literals.

use std::path::{Path, PathBuf};

use logic_lfd::prelude::*;
use serde_json::Value;

use crate::support::cli::run_cli;

fn sorting() -> PathBuf {
    Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/pddl/sorting"
    ))
    .to_path_buf()
}

fn example(name: &str) -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../domains")).join(name)
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap()
}

fn load(dir: &Path) -> LogicLfd {
    let f = |n: &str| read(&dir.join(n));
    LogicLfd::new(&f("domain.pddl"), &f("problem.pddl"), &f("demo.plan")).unwrap()
}

fn astar() -> SearchConfig {
    SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut)
}

fn temp_file(tag: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("logic-lfd-observed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(tag);
    std::fs::write(&file, text).unwrap();
    file
}

/// `logic-lfd lfd` on a task folder and a state file: exit code, stdout, stderr.
fn lfd_cli(dir: &Path, state: &Path, extra: &[&str]) -> (i32, String, String) {
    let path = |n: &str| dir.join(n).display().to_string();
    let (d, p, m, s) = (
        path("domain.pddl"),
        path("problem.pddl"),
        path("demo.plan"),
        state.display().to_string(),
    );
    let mut args = vec!["lfd", &d, &p, &m, "--state", &s];
    args.extend_from_slice(extra);
    run_cli(&args)
}

#[test]
fn a_cube_in_a_tray_of_another_colour_is_kept_and_the_plan_takes_it_out() {
    let dir = sorting();
    let lfd = load(&dir);
    // Nothing puts a cube into a tray of another colour: the grounded task has no such fact.
    assert_eq!(lfd.task().fact_id("(in blue-cube red-tray)"), None);
    let file = dir.join("blue-in-red-tray.facts");
    let s = lfd
        .state_in("blue-in-red-tray.facts", &read(&file))
        .unwrap();
    assert!(s.is_regrounded());
    assert!(s.names().contains(&"(in blue-cube red-tray)".to_string()));
    // The re-grounded task knows the operator the observed fact enables.
    let applicable: Vec<&str> = s.applicable().collect();
    assert_eq!(
        applicable,
        [
            "(pick-from-tray red-cube red-tray)",
            "(pick-from-tray blue-cube red-tray)"
        ]
    );
    assert_eq!(s.logic_in(), None);
    let expected = [
        "(pick-from-tray blue-cube red-tray)",
        "(put-in-tray blue-cube blue-tray blue)",
    ];
    for mode in [Mode::Paper, Mode::Prioritised] {
        let p = s.replan(mode, &astar(), &NoClock).unwrap();
        assert_eq!(p.names, expected, "{mode:?}");
        assert!(s.validate(&p.names).unwrap().is_valid(), "{mode:?}");
    }
    // Paper mode joins L_3 (blue cube in hand, red cube sorted) after one new action.
    let p = s.replan(Mode::Paper, &astar(), &NoClock).unwrap();
    assert_eq!((p.k, p.prefix_len), (Some(3), 1));

    let (code, out, err) = lfd_cli(&dir, &file, &["--json"]);
    assert_eq!(code, 0, "{err}");
    let j: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        (&j["regrounded"], &j["valid"], &j["k"]),
        (&Value::Bool(true), &Value::Bool(true), &Value::from(3))
    );
    assert_eq!(j["plan"], serde_json::json!(expected));
    assert!(j["state"]
        .as_array()
        .unwrap()
        .contains(&Value::from("(in blue-cube red-tray)")));
    let (code, out, err) = lfd_cli(&dir, &file, &[]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("re-grounded with S_C as its :init"), "{out}");
    assert!(
        out.contains("; replayed from S_C on the lifted domain: valid"),
        "{out}"
    );
}

#[test]
fn demonstration_states_are_matched_by_name_in_a_regrounded_task() {
    let lfd = load(&example("delivery"));
    // No parcel but the return has a destination: nothing delivers the return.
    let extra = "(delivered return1)";
    assert_eq!(lfd.task().fact_id(extra), None);
    for k in [0, 5] {
        let l_k: Vec<&str> = lfd.demo_states()[k].iter().map(String::as_str).collect();
        let s = lfd.state(&format!("{}\n{extra}", l_k.join("\n"))).unwrap();
        assert!(s.is_regrounded());
        assert_eq!(s.logic_in(), Some(k));
        let p = s.replan(Mode::Paper, &astar(), &NoClock).unwrap();
        assert_eq!((p.k, p.source), (Some(k), PlanSource::LogicIn));
        assert_eq!(p.names, lfd.demo_actions()[k..]);
        assert!(s.validate(&p.names).unwrap().is_valid());
    }
}

#[test]
fn known_fluents_keep_the_task_and_a_changed_static_fact_regrounds() {
    let dir = example("kitchen");
    let lfd = load(&dir);
    let disturbed = read(&dir.join("disturbed.facts"));
    let known = lfd.state(&disturbed).unwrap();
    assert!(!known.is_regrounded());
    // The static facts as in the problem: still the problem's own task.
    let statics = lfd.static_facts().join("\n");
    assert!(!lfd
        .state(&format!("{disturbed}\n{statics}"))
        .unwrap()
        .is_regrounded());
    // The counter and the stove are no longer neighbours: every other adjacency is listed.
    let cut = ["(adjacent counter stove)", "(adjacent stove counter)"];
    let adjacency: Vec<&str> = lfd
        .static_facts()
        .iter()
        .map(String::as_str)
        .filter(|f| f.starts_with("(adjacent ") && !cut.contains(f))
        .collect();
    let text = format!("{disturbed}\n{}", adjacency.join("\n"));
    let s = lfd.state(&text).unwrap();
    assert!(s.is_regrounded());
    let walk = "(move chef counter stove)";
    assert!(known.applicable().any(|a| a == walk));
    assert!(!s.applicable().any(|a| a == walk));
    assert!(s.applicable().any(|a| a == "(move chef counter sink)"));
    let known_plan = known.replan(Mode::Paper, &astar(), &NoClock).unwrap();
    assert!(known_plan.names.iter().any(|a| a == walk));
    for mode in [Mode::Paper, Mode::Prioritised] {
        let p = s.replan(mode, &astar(), &NoClock).unwrap();
        let moves: Vec<&String> = p.names.iter().filter(|a| a.starts_with("(move ")).collect();
        assert!(
            moves.iter().all(|a| !cut.contains(&&a[..]) && *a != walk),
            "{mode:?}: {moves:?}"
        );
        assert!(s.validate(&p.names).unwrap().is_valid(), "{mode:?}");
    }
    // The plan made on the problem's map walks the missing edge: invalid on the observed map.
    assert!(!s.validate(&known_plan.names).unwrap().is_valid());
    let file = temp_file("cut-stove.facts", &text);
    let (code, out, err) = lfd_cli(&dir, &file, &["--json"]);
    assert_eq!(code, 0, "{err}");
    let j: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        (&j["regrounded"], &j["valid"]),
        (&Value::Bool(true), &Value::Bool(true))
    );
}

#[test]
fn malformed_atoms_are_still_refused_at_their_line_and_column() {
    let dir = example("kitchen");
    let cases = [
        ("(hand-empty chef)\n(flying chef)\n", "2:2:", "flying"),
        (
            "(hand-empty chef)\n  (robot-at chef garage)\n",
            "2:18:",
            "garage",
        ),
        ("(hand-empty chef counter)\n", "1:1:", "hand-empty"),
        (
            "(hand-empty chef)\n(robot-at carrot counter)\n",
            "2:11:",
            "carrot",
        ),
    ];
    for (i, (text, at, names)) in cases.into_iter().enumerate() {
        let file = temp_file(&format!("bad-{i}.facts"), text);
        let (code, out, err) = lfd_cli(&dir, &file, &[]);
        assert_eq!(code, 2, "{text}: {err}");
        assert!(out.is_empty(), "{out}");
        assert!(
            err.contains(&format!("{}:{at}", file.display())),
            "{text}: {err}"
        );
        assert!(err.contains(names), "{text}: {err}");
        let lfd = load(&dir);
        let e = lfd.state(text).unwrap_err();
        assert!(matches!(e, LfdError::Input(_)), "{e}");
    }
}

#[test]
fn a_goal_no_action_can_reach_from_the_state_exits_3_with_the_literals() {
    let dir = example("delivery");
    let lfd = load(&dir);
    // The van stands in the old town, where no road leads: it can never leave.
    let stuck =
        read(&dir.join("disturbed.facts")).replace("(at van1 depot)", "(at van1 church-lane)");
    assert_eq!(lfd.task().fact_id("(at van1 church-lane)"), None);
    let s = lfd.state(&stuck).unwrap();
    assert!(s.is_regrounded());
    let lost = [
        "(delivered p2)",
        "(delivered p4)",
        "(parcel-at return1 depot)",
        "(at van1 depot)",
    ];
    assert_eq!(s.unreachable_goal_literals(), lost);
    let e = s.replan(Mode::Paper, &astar(), &NoClock).unwrap_err();
    assert!(matches!(e, LfdError::NoPlan(_)), "{e}");
    assert!(e.to_string().contains(&lost.join(" ")), "{e}");

    let file = temp_file("van-in-old-town.facts", &stuck);
    let (code, _, err) = lfd_cli(&dir, &file, &[]);
    assert_eq!(code, 3, "{err}");
    assert!(err.contains("(at van1 depot)"), "{err}");
    let (code, out, _) = lfd_cli(&dir, &file, &["--json"]);
    assert_eq!(code, 3);
    let j: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["status"], "unsolvable");
    assert!(
        j["message"]
            .as_str()
            .unwrap()
            .contains("(parcel-at return1 depot)"),
        "{j}"
    );
}
