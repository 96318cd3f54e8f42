//! `logic-lfd plan` (exit codes, IPC plan text, JSON) and `logic-lfd bench planner` (tables).

use logic_lfd::plan::Plan;

use super::assert_valid;
use super::cases::{ipc, ipc_case};
use crate::support::cli::run_cli;

/// A domain where the goal room cannot be entered: `(move ?from ?to)` needs `(door ?from ?to)`.
const ONE_WAY_DOMAIN: &str = "(define (domain one-way)
  (:requirements :strips :negative-preconditions)
  (:predicates (at ?r) (door ?a ?b))
  (:action move :parameters (?a ?b)
    :precondition (and (at ?a) (door ?a ?b) (not (at ?b)))
    :effect (and (not (at ?a)) (at ?b))))";

const ONE_WAY_PROBLEM: &str = "(define (problem trapped) (:domain one-way)
  (:objects r1 r2 r3)
  (:init (at r1) (door r1 r2) (door r2 r1) (door r3 r1))
  (:goal (at r3)))";

fn temp_files(tag: &str, files: &[(&str, &str)]) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("logic-lfd-search-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}

#[test]
fn cli_plan_exits_with_a_code_per_outcome_and_prints_a_replayable_plan() {
    let dir = temp_files(
        "exit",
        &[
            ("domain.pddl", ONE_WAY_DOMAIN),
            ("problem.pddl", ONE_WAY_PROBLEM),
            (
                "bad.pddl",
                "(define (problem p) (:domain one-way)\n  (:init (at r9)",
            ),
        ],
    );
    let d = dir.join("domain.pddl");
    let d = d.to_str().unwrap();
    let p = dir.join("problem.pddl");
    let p = p.to_str().unwrap();
    // Proved unsolvable: exit 3, for the default and a satisficing configuration.
    for extra in [
        &[][..],
        &["--search", "lazy-gbfs", "--heuristic", "hff"][..],
    ] {
        let mut args = vec!["plan", d, p];
        args.extend_from_slice(extra);
        let (code, _, err) = run_cli(&args);
        assert_eq!(code, 3, "{err}");
        assert!(err.contains("unsolvable"), "{err}");
    }
    // Bad input: exit 2 with a located message.
    let bad = dir.join("bad.pddl");
    let (code, _, err) = run_cli(&["plan", d, bad.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("bad.pddl:"), "{err}");
    let (code, _, _) = run_cli(&["plan", d, p, "--heuristic", "ff"]);
    assert_eq!(code, 2);
    // Budget exhausted: exit 4.
    let bd = ipc("blocks/domain.pddl");
    let bp = ipc("blocks/probBLOCKS-8-0.pddl");
    let (bd, bp) = (bd.to_str().unwrap(), bp.to_str().unwrap());
    let (code, out, err) = run_cli(&["plan", bd, bp, "--max-nodes", "5", "--json"]);
    assert_eq!(code, 4, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["status"], "budget");
    assert_eq!(j["expanded"], 5);
    // A plan: IPC text, then the cost line; the JSON agrees and the plan replays.
    let bp = ipc("blocks/probBLOCKS-5-0.pddl");
    let bp = bp.to_str().unwrap();
    let (code, out, _) = run_cli(&["plan", bd, bp]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().filter(|l| !l.starts_with(';')).collect();
    assert!(out.contains(&format!("; cost = {} (unit cost)", lines.len())));
    let (code, out, _) = run_cli(&[
        "plan",
        bd,
        bp,
        "--search",
        "lazy-gbfs",
        "--heuristic",
        "hff",
        "--json",
    ]);
    assert_eq!(code, 0);
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    let case = ipc_case("blocks/domain.pddl", "blocks/probBLOCKS-5-0.pddl");
    let task = &case.task;
    let names: Vec<String> = j["plan"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap().to_string())
        .collect();
    let ops: Vec<usize> = names
        .iter()
        .map(|n| task.operators.iter().position(|o| &o.name == n).unwrap())
        .collect();
    let cost = ops.len() as u64;
    assert_valid(
        task,
        &Plan {
            operators: ops,
            cost,
        },
    );
    assert_eq!(j["length"], names.len());
    for key in [
        "cost",
        "expanded",
        "generated",
        "evaluated",
        "time_secs",
        "search",
        "heuristic",
    ] {
        assert!(!j[key].is_null(), "{key}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cli_bench_planner_prints_tables() {
    let blocks = ipc("blocks");
    let (code, out, err) = run_cli(&[
        "bench",
        "planner",
        blocks.to_str().unwrap(),
        "--configs",
        "astar:lmcut,lazy-gbfs:hff",
        "--filter",
        "BLOCKS-4-",
        // A node budget decides what is solved, not the machine's load: the time limit is far
        // beyond what 50 000 expansions take.
        "--max-nodes",
        "50000",
        "--time-limit",
        "600",
        "--markdown",
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.matches(":lmcut | solved |").count(), 3, "{out}");
    assert_eq!(out.matches(":hff | solved |").count(), 3, "{out}");
    assert!(out.contains("| astar:lmcut | blocks | 3/3 |"), "{out}");
    assert!(out.contains("| lazy-gbfs:hff | blocks | 3/3 |"), "{out}");
    let dir = temp_files(
        "bench",
        &[
            ("domain.pddl", ONE_WAY_DOMAIN),
            ("trapped.pddl", ONE_WAY_PROBLEM),
        ],
    );
    let (code, out, err) = run_cli(&["bench", "planner", dir.to_str().unwrap(), "--markdown"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("| trapped | lazy-gbfs:hff | unsolvable |"),
        "{out}"
    );
    let (code, _, _) = run_cli(&["bench", "planner", "--configs", "astar:ff"]);
    assert_eq!(code, 2);
    std::fs::remove_dir_all(&dir).ok();
}
