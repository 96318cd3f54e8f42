//! `logic-lfd lfd`: the annotated plan text and the JSON agree, every merged plan replays from
//! S_C (grounded and lifted, independently of the binary), bad input exits 2 with its location,
//! search outcomes exit 3 and 4, and the perturbation study is deterministic.

use logic_lfd::pddl::Source;
use std::path::{Path, PathBuf};

use logic_lfd::prelude::LogicLfd;
use serde_json::Value;

use crate::support::cli::run_cli;

fn domain_dir(name: &str) -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../domains")).join(name)
}

fn ipc(path: &str) -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/ipc")).join(path)
}

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("logic-lfd-lfd-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(p: &Path) -> String {
    p.to_str().unwrap().to_string()
}

/// A domain, a problem and a demonstration plan on disk.
struct Task {
    domain: PathBuf,
    problem: PathBuf,
    demo: PathBuf,
}

impl Task {
    fn example(name: &str) -> Self {
        let dir = domain_dir(name);
        Task {
            domain: dir.join("domain.pddl"),
            problem: dir.join("problem.pddl"),
            demo: dir.join("demo.plan"),
        }
    }

    /// `logic-lfd lfd DOMAIN PROBLEM DEMO extra…`.
    fn run(&self, extra: &[&str]) -> (i32, String, String) {
        let (d, p, m) = (text(&self.domain), text(&self.problem), text(&self.demo));
        let mut args = vec!["lfd", &d, &p, &m];
        args.extend_from_slice(extra);
        run_cli(&args)
    }

    fn json(&self, extra: &[&str]) -> Value {
        let mut args = extra.to_vec();
        args.push("--json");
        let (code, out, err) = self.run(&args);
        assert_eq!(code, 0, "{err}");
        serde_json::from_str(&out).unwrap()
    }

    fn lfd(&self) -> LogicLfd {
        let read = |p: &Path| Source::new(text(p), std::fs::read_to_string(p).unwrap());
        let (d, p, m) = (read(&self.domain), read(&self.problem), read(&self.demo));
        LogicLfd::named(&d, &p, &m).unwrap()
    }
}

fn strings(v: &Value) -> Vec<String> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap().to_string())
        .collect()
}

/// Replays `plan` from the state `facts` with the grounded task and with the lifted validator.
fn assert_replays(lfd: &LogicLfd, facts: &[String], plan: &[String]) {
    let observed = lfd.state(&facts.join("\n")).unwrap();
    let (own, s) = (observed.lfd(), observed.state());
    let ops: Vec<usize> = plan
        .iter()
        .map(|n| {
            let ops = &own.task().operators;
            ops.iter().position(|o| &o.name == n).expect(n)
        })
        .collect();
    assert!(own.reaches_goal(s, &ops), "grounded replay: {plan:?}");
    let report = observed.validate(plan).unwrap();
    assert!(report.is_valid(), "{report}");
}

/// Runs text and JSON on the same input and checks they say the same, and that the plan replays.
fn check_text_and_json(task: &Task, extra: &[&str]) -> Value {
    let j = task.json(extra);
    let (code, out, err) = task.run(extra);
    assert_eq!(code, 0, "{err}");
    let plan: Vec<String> = out
        .lines()
        .filter(|l| !l.starts_with(';'))
        .map(|l| l.split(';').next().unwrap().trim().to_string())
        .collect();
    assert_eq!(plan, strings(&j["plan"]));
    let new = out.lines().filter(|l| l.ends_with("; new")).count();
    assert_eq!(new, j["prefix"].as_array().unwrap().len());
    assert_eq!(
        j["prefix"].as_array().unwrap().len() + j["suffix"].as_array().unwrap().len(),
        plan.len()
    );
    assert!(
        out.contains(&format!("; cost = {} (unit cost)", j["cost"])),
        "{out}"
    );
    let n = j["demo_actions"].as_array().unwrap().len();
    assert_eq!(j["demo_states"].as_array().unwrap().len(), n + 1);
    assert!(out.contains(&format!("; L_{n} ")), "{out}");
    match j["k"].as_u64() {
        Some(k) => assert!(out.contains(&format!("; matched: L_{k} ")), "{out}"),
        None => assert!(out.contains("; matched: G "), "{out}"),
    }
    assert_eq!(j["valid"], true);
    assert_eq!(j["status"], "solved");
    assert_replays(&task.lfd(), &strings(&j["state"]), &plan);
    j
}

#[test]
fn lfd_joins_the_kitchen_demonstration_from_a_disturbed_or_interrupted_state() {
    let task = Task::example("kitchen");
    let facts = text(&task.demo.with_file_name("disturbed.facts"));
    let j = check_text_and_json(&task, &["--state", &facts]);
    assert_eq!(j["logic_in"], Value::Null);
    assert_eq!(j["source"], "multi-goal");
    let after = text(&task.demo.with_file_name("interrupted.plan"));
    let j = check_text_and_json(&task, &["--after", &after, "--mode", "prioritised"]);
    assert_eq!(j["mode"], "prioritised");
    // The problem's initial state is L_0: the plan is the whole demonstration.
    let j = check_text_and_json(&task, &[]);
    assert_eq!(
        (j["logic_in"].as_u64(), j["k"].as_u64()),
        (Some(0), Some(0))
    );
    assert_eq!(j["plan"], j["demo_actions"]);
}

#[test]
fn lfd_joins_the_delivery_demonstration_with_each_search() {
    let task = Task::example("delivery");
    let facts = text(&task.demo.with_file_name("disturbed.facts"));
    for search in [&["--search", "lazy-gbfs", "--heuristic", "hff"][..], &[]] {
        let mut args = vec!["--state", &facts];
        args.extend_from_slice(search);
        check_text_and_json(&task, &args);
    }
    let after = text(&task.demo.with_file_name("interrupted.plan"));
    check_text_and_json(&task, &["--after", &after]);
}

#[test]
fn lfd_on_ipc_blocks_reads_back_the_states_its_study_draws() {
    let dir = temp_dir("blocks");
    let domain = ipc("blocks/domain.pddl");
    let problem = ipc("blocks/probBLOCKS-6-0.pddl");
    let (code, plan, err) = run_cli(&["plan", &text(&domain), &text(&problem)]);
    assert_eq!(code, 0, "{err}");
    let task = Task {
        domain,
        problem,
        demo: dir.join("demo.plan"),
    };
    std::fs::write(&task.demo, plan).unwrap();
    let study = task.json(&[
        "--perturb",
        "6",
        "--seed",
        "5",
        "--search",
        "lazy-gbfs",
        "--heuristic",
        "hff",
    ]);
    let states = study["states"].as_array().unwrap();
    assert_eq!(states.len(), 6);
    for (i, s) in states.iter().enumerate() {
        assert_eq!(s["valid"], true, "state {i}");
        let file = dir.join(format!("state-{i}.facts"));
        std::fs::write(&file, strings(&s["facts"]).join("\n")).unwrap();
        let j = check_text_and_json(&task, &["--state", &text(&file)]);
        assert_eq!(j["state"], s["facts"]);
        assert_eq!(j["logic_in"], s["logic_in"]);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn lfd_refuses_bad_input_with_its_location() {
    let task = Task::example("kitchen");
    let dir = temp_dir("bad");
    // An unknown object in the state file: exit 2 at its line and column.
    let bad = dir.join("bad.facts");
    std::fs::write(&bad, "(robot-at chef counter)\n  (robot-at chef garage)\n").unwrap();
    let (code, out, err) = task.run(&["--state", &text(&bad), "--json"]);
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty(), "{out}");
    assert!(err.contains(&format!("{}:2:18:", text(&bad))), "{err}");
    assert!(err.contains("`garage`"), "{err}");
    // A demonstration step whose precondition is false: the step and the false literal.
    let demo = std::fs::read_to_string(&task.demo).unwrap();
    let broken = demo.replace("(pick chef carrot fridge)\n", "");
    let wrong = Task {
        demo: dir.join("demo.plan"),
        ..Task::example("kitchen")
    };
    std::fs::write(&wrong.demo, broken).unwrap();
    let (code, _, err) = wrong.run(&[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains(&text(&wrong.demo)), "{err}");
    assert!(
        err.contains("step 4 `(place chef carrot counter)`"),
        "{err}"
    );
    assert!(err.contains("(holding chef carrot)"), "{err}");
    // A prefix step that does not apply.
    let prefix = dir.join("prefix.plan");
    std::fs::write(
        &prefix,
        "(move chef counter fridge)\n(pick chef carrot fridge)\n",
    )
    .unwrap();
    let (code, _, err) = task.run(&["--after", &text(&prefix)]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(":2:1:") && err.contains("(pick chef carrot fridge)"),
        "{err}"
    );
    assert!(err.contains("(not (closed fridge))"), "{err}");
    // --state and --after conflict; a mode that does not exist; a missing file.
    let facts = text(&task.demo.with_file_name("disturbed.facts"));
    let (code, _, _) = task.run(&["--state", &facts, "--after", &text(&prefix)]);
    assert_eq!(code, 2);
    let (code, _, _) = task.run(&["--mode", "greedy"]);
    assert_eq!(code, 2);
    let (code, _, _) = task.run(&["--perturb", "2", "--state", &facts]);
    assert_eq!(code, 2);
    let (code, _, err) = task.run(&["--state", &text(&dir.join("missing.facts"))]);
    assert_eq!(code, 2);
    assert!(err.contains("missing.facts:1:1:"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Rooms with one-way doors: r4 is a dead end.
const ROOMS_DOMAIN: &str = "(define (domain rooms) (:requirements :strips)
  (:predicates (at ?r) (door ?a ?b))
  (:action go :parameters (?a ?b) :precondition (and (at ?a) (door ?a ?b))
    :effect (and (at ?b) (not (at ?a)))))";
const ROOMS_PROBLEM: &str = "(define (problem p) (:domain rooms) (:objects r1 r2 r3 r4)
  (:init (at r1) (door r1 r2) (door r2 r3) (door r1 r4))
  (:goal (at r3)))";

#[test]
fn lfd_exits_3_when_proved_unsolvable_and_4_on_an_exhausted_budget() {
    let dir = temp_dir("outcomes");
    let task = Task {
        domain: dir.join("domain.pddl"),
        problem: dir.join("problem.pddl"),
        demo: dir.join("demo.plan"),
    };
    std::fs::write(&task.domain, ROOMS_DOMAIN).unwrap();
    std::fs::write(&task.problem, ROOMS_PROBLEM).unwrap();
    std::fs::write(&task.demo, "(go r1 r2)\n(go r2 r3)\n").unwrap();
    let dead_end = dir.join("dead-end.facts");
    std::fs::write(&dead_end, "(at r4)").unwrap();
    let (code, out, _) = task.run(&["--state", &text(&dead_end), "--json"]);
    assert_eq!(code, 3);
    let j: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        (j["status"].as_str(), &j["plan"]),
        (Some("unsolvable"), &Value::Null)
    );
    let (code, _, err) = task.run(&["--state", &text(&dead_end)]);
    assert_eq!(code, 3);
    assert!(err.contains("no plan"), "{err}");
    // The disturbed kitchen needs more than one expansion to reach a demonstration state.
    let kitchen = Task::example("kitchen");
    let facts = text(&kitchen.demo.with_file_name("disturbed.facts"));
    let (code, out, _) = kitchen.run(&["--state", &facts, "--max-nodes", "1", "--json"]);
    assert_eq!(code, 4);
    let j: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["status"], "budget");
    let (code, _, err) = kitchen.run(&["--state", &facts, "--max-nodes", "1"]);
    assert_eq!(code, 4);
    assert!(err.contains("exhausted"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn lfd_perturbation_study_is_deterministic_and_every_merged_plan_replays() {
    let task = Task::example("kitchen");
    // Greedy searches and a short optimality budget: the study's bookkeeping is under test here,
    // not A* from scratch (seconds per kitchen state).
    let args = [
        "--perturb",
        "10",
        "--seed",
        "3",
        "--search",
        "lazy-gbfs",
        "--heuristic",
        "hff",
        "--optimal-time-limit",
        "0.3",
    ];
    let first = task.json(&args);
    let second = task.json(&args);
    let stable = |j: &Value| -> Vec<Value> {
        j["states"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| {
                let keys = [
                    "index",
                    "from_k",
                    "steps",
                    "facts",
                    "logic_in",
                    "k",
                    "prefix_len",
                ];
                keys.iter().map(|k| s[*k].clone()).collect()
            })
            .collect()
    };
    assert_eq!(stable(&first), stable(&second));
    assert_eq!(
        (first["seed"].as_u64(), first["count"].as_u64()),
        (Some(3), Some(10))
    );
    let lfd = task.lfd();
    for s in first["states"].as_array().unwrap() {
        assert_eq!(s["valid"], true);
        assert_eq!(s["lfd_status"], "solved");
        assert!(s["merged_len"].as_u64() >= s["optimal_len"].as_u64());
        assert!(lfd.state(&strings(&s["facts"]).join("\n")).is_ok());
    }
    let summary = &first["summary"];
    assert_eq!(summary["lfd_solved"], 10);
    for key in ["median_lfd_ms", "median_scratch_ms"] {
        assert!(summary[key].is_number(), "{key}");
    }
    // The ratios exist exactly when they are defined: a non-zero Logic-LfD time, and states
    // whose optimum was proved within the (wall-clock) budget.
    assert_eq!(
        summary["speedup"].is_number(),
        summary["median_lfd_ms"].as_f64() > Some(0.0),
        "{summary}"
    );
    assert_eq!(
        summary["median_length_ratio"].is_number(),
        summary["length_compared"].as_u64() > Some(0),
        "{summary}"
    );
    // The text table: a header, one line per state, the summary.
    let (code, out, err) = task.run(&args);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().count(), 1 + 1 + 10 + 3, "{out}");
    assert!(out.contains("solved: Logic-LfD 10/10"), "{out}");
}
