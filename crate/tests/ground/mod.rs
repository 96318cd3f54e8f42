//! Grounding: every IPC benchmark grounds; fact and operator counts match hand counts; the
//! project's own small domains exercise negative preconditions, equality, or, costs, unreachability.

use logic_lfd::pddl::{parse_domain, parse_problem};
use logic_lfd::plan::{ground, Task};

pub(crate) fn ipc_dir() -> std::path::PathBuf {
    std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/ipc"))
}

#[allow(dead_code)]
pub(crate) fn data_dir() -> std::path::PathBuf {
    std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/pddl"))
}

/// Parses and grounds `dir/domain.pddl` with `dir/problem`.
pub(crate) fn ground_files(dir: &std::path::Path, problem: &str) -> Task {
    let dpath = dir.join("domain.pddl");
    let ppath = dir.join(problem);
    let dtext = std::fs::read_to_string(&dpath).unwrap();
    let ptext = std::fs::read_to_string(&ppath).unwrap();
    let d = parse_domain(&dtext, &dpath.display().to_string()).unwrap_or_else(|e| panic!("{e}"));
    let p =
        parse_problem(&ptext, &ppath.display().to_string(), &d).unwrap_or_else(|e| panic!("{e}"));
    ground(&d, &p).unwrap_or_else(|e| panic!("{e}"))
}

fn ground_ipc(domain: &str, problem: &str) -> Task {
    ground_files(&ipc_dir().join(domain), problem)
}

/// Grounds in-memory texts.
#[allow(dead_code)]
pub(crate) fn ground_text(domain: &str, problem: &str) -> Task {
    let d = parse_domain(domain, "d.pddl").unwrap_or_else(|e| panic!("{e}"));
    let p = parse_problem(problem, "p.pddl", &d).unwrap_or_else(|e| panic!("{e}"));
    ground(&d, &p).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_ipc_problem_parses_and_grounds() {
    let mut n = 0;
    for dom in [
        "blocks",
        "blocks-typed",
        "gripper",
        "logistics00",
        "depot-typed",
    ] {
        let dir = ipc_dir().join(dom);
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|f| f.ends_with(".pddl") && f != "domain.pddl")
            .collect();
        files.sort();
        for f in files {
            let t = ground_files(&dir, &f);
            assert!(!t.operators.is_empty(), "{dom}/{f}: no operators");
            assert_eq!(t.goal.alternatives.len(), 1, "{dom}/{f}");
            assert!(!t.goal.holds(&t.init), "{dom}/{f}: goal holds initially");
            n += 1;
        }
    }
    assert_eq!(n, 207);
}

/// Blocks with n blocks (no inequality in the domain, so `(stack a a)` is relaxed-reachable):
/// facts `on` n², `ontable`, `clear`, `holding` n each, `handempty` 1; operators pick-up and
/// put-down n each, stack and unstack n² each.
#[test]
fn blocks_counts_match_the_formula() {
    for (file, n) in [("probBLOCKS-4-0.pddl", 4usize), ("probBLOCKS-9-1.pddl", 9)] {
        for dom in ["blocks", "blocks-typed"] {
            let t = ground_ipc(dom, file);
            assert_eq!(t.facts.len(), n * n + 3 * n + 1, "{dom}/{file}");
            assert_eq!(t.operators.len(), 2 * n * n + 2 * n, "{dom}/{file}");
            assert!(t.static_facts.is_empty());
        }
    }
    // blocks-4-0: objects declared D B A C; facts by predicate then object declaration order.
    let t = ground_ipc("blocks", "probBLOCKS-4-0.pddl");
    assert_eq!(t.facts[0], "(on d d)");
    assert_eq!(t.facts[1], "(on d b)");
    assert_eq!(t.facts.last().unwrap(), "(holding c)");
    assert!(t.fact_id("(handempty)").is_some());
    assert_eq!(t.init.len(), 9); // 4 clear, 4 ontable, handempty
    let names: Vec<&str> = t.operators.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(
        &names[..4],
        ["(pick-up d)", "(pick-up b)", "(pick-up a)", "(pick-up c)"]
    );
    assert!(names.contains(&"(stack a b)") && names.contains(&"(unstack c c)"));
    let stack = t
        .operators
        .iter()
        .find(|o| o.name == "(stack a b)")
        .unwrap();
    let ids = |v: &[u32]| {
        v.iter()
            .map(|&f| t.facts[f as usize].clone())
            .collect::<Vec<_>>()
    };
    assert_eq!(ids(&stack.pre), ["(clear b)", "(holding a)"]);
    assert_eq!(ids(&stack.add), ["(on a b)", "(clear a)", "(handempty)"]);
    assert_eq!(ids(&stack.del), ["(clear b)", "(holding a)"]);
    assert_eq!(stack.cost, 1);
    assert_eq!(t.goal.alternatives[0].pos.len(), 3);
}

/// Gripper prob01 (2 rooms, 4 balls, 2 grippers): `room`, `ball`, `gripper` are static (8 facts);
/// fluents at-robby 2 + at 4·2 + free 2 + carry 4·2 = 20; operators move 2·2 + pick 4·2·2 +
/// drop 4·2·2 = 36.
#[test]
fn gripper_prob01_counts() {
    let t = ground_ipc("gripper", "prob01.pddl");
    assert_eq!(t.facts.len(), 20);
    assert_eq!(t.operators.len(), 36);
    assert_eq!(t.static_facts.len(), 8);
    assert!(t.static_facts.contains(&"(room rooma)".to_string()));
    assert!(t
        .operators
        .iter()
        .any(|o| o.name == "(pick ball1 rooma left)"));
    assert!(!t.operators.iter().any(|o| o.name == "(move ball1 rooma)"));
}

/// Depot p01 (1 depot, 2 distributors → 3 places; 2 trucks; 3 pallets, 2 crates, 3 hoists):
/// hoists and pallets never move, so their `at` facts are static; drive 2·3·3 = 18 operators.
#[test]
fn depot_p01_folds_facts_no_operator_changes() {
    let t = ground_ipc("depot-typed", "p01.pddl");
    assert!(t.static_facts.contains(&"(at hoist0 depot0)".to_string()));
    assert!(t.static_facts.contains(&"(at pallet0 depot0)".to_string()));
    assert!(t.fact_id("(at hoist0 depot0)").is_none());
    let drives = t
        .operators
        .iter()
        .filter(|o| o.name.starts_with("(drive "))
        .count();
    assert_eq!(drives, 18);
    // A hoist only lifts where it stands: no (lift hoist0 … distributor0).
    assert!(!t
        .operators
        .iter()
        .any(|o| o.name.starts_with("(lift hoist0") && o.name.ends_with("distributor0)")));
}

#[test]
fn grounding_is_deterministic() {
    let a = ground_ipc("logistics00", "probLOGISTICS-6-0.pddl");
    let b = ground_ipc("logistics00", "probLOGISTICS-6-0.pddl");
    assert_eq!(a.facts, b.facts);
    assert_eq!(a.operators, b.operators);
    assert_eq!(a.init, b.init);
}
