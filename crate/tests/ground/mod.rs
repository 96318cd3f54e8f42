//! Grounding: every IPC benchmark grounds; fact and operator counts match hand counts; the
//! project's own small domains exercise negative preconditions, equality, or, costs, unreachability.

use logic_lfd::pddl::{parse_domain, parse_problem};
use logic_lfd::plan::{ground, Task};

pub(crate) fn ipc_dir() -> std::path::PathBuf {
    std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/ipc"))
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
fn gripper_prob01_grounds_to_the_counted_facts_and_operators() {
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
fn depot_p01_folds_the_facts_no_operator_changes_into_statics() {
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

fn rooms(problem: &str) -> Task {
    ground_files(&data_dir().join("rooms"), problem)
}

fn names(t: &Task, ids: &[u32]) -> Vec<String> {
    ids.iter().map(|&f| t.facts[f as usize].clone()).collect()
}

fn op<'t>(t: &'t Task, name: &str) -> &'t logic_lfd::plan::Operator {
    t.operators
        .iter()
        .find(|o| o.name == name)
        .unwrap_or_else(|| panic!("no operator {name}"))
}

/// Hand count for rooms/p-costs (see the file): reachable rooms hall, r1, r2 (r3 has no door).
/// move: (hall r1), (r1 r2) from `(door ?a ?b)`, (r1 hall), (r2 r1) from `(door ?b ?a)`, and
/// not (r2 r2) although `(door r2 r2)` holds, because of `(not (= ?a ?b))`: 4. take k1 r1: 1
/// (k2 lies in unreachable r3). unlock k1 ?a r2 from r1 and, through the self-loop door, from r2
/// itself (relaxed: `(at r2)` is reachable, `(locked r2)` initial): 2. wait (?a ?a) for the 3
/// reachable rooms (`(= ?a ?b)`): 3. Total 10.
/// Fluents: at ×3, visited ×3, has k1, key-at k1 r1, locked r2 = 9. Static: 3 doors, opens,
/// key-at k2 r3 (never taken) = 5.
#[test]
fn rooms_grounds_action_costs_negative_preconditions_equality_and_or() {
    let t = rooms("p-costs.pddl");
    assert_eq!(t.facts.len(), 9, "{:?}", t.facts);
    assert_eq!(
        t.operators.len(),
        10,
        "{:?}",
        t.operators.iter().map(|o| &o.name).collect::<Vec<_>>()
    );
    assert_eq!(t.static_facts.len(), 5, "{:?}", t.static_facts);
    assert!(t.static_facts.contains(&"(key-at k2 r3)".to_string()));
    assert!(t.uses_costs);
    let costs: Vec<(&str, u32)> = t
        .operators
        .iter()
        .map(|o| (o.name.as_str(), o.cost))
        .collect();
    for (n, c) in [
        ("(move hall r1)", 3),
        ("(move r1 hall)", 3),
        ("(move r1 r2)", 4),
        ("(move r2 r1)", 4),
        ("(take k1 r1)", 0),
        ("(unlock k1 r1 r2)", 2),
        ("(wait r2 r2)", 1),
    ] {
        assert!(costs.contains(&(n, c)), "{n} cost {c}: {costs:?}");
    }
    assert!(!costs
        .iter()
        .any(|(n, _)| *n == "(move r2 r2)" || *n == "(wait hall r1)"));
    // Negative precondition kept where the fact is fluent, dropped where it can never hold.
    assert_eq!(names(&t, &op(&t, "(move r1 r2)").pre_neg), ["(locked r2)"]);
    assert!(op(&t, "(move hall r1)").pre_neg.is_empty());
    // Static `(opens k1 r2)` and `(door r1 r2)` folded out of the precondition.
    assert_eq!(
        names(&t, &op(&t, "(unlock k1 r1 r2)").pre),
        ["(at r1)", "(locked r2)", "(has k1)"] // facts in predicate declaration order
    );
    // Goal (at r2) ∧ ((has k1) ∨ (visited r3)): the r3 alternative is unreachable, dropped.
    assert_eq!(t.goal.alternatives.len(), 1);
    assert_eq!(
        names(&t, &t.goal.alternatives[0].pos),
        ["(at r2)", "(has k1)"]
    );
}

/// Without a metric every action costs 1; an or-goal gives two alternatives; a negative goal
/// literal becomes `Condition::neg`; a true `(= r1 r1)` disappears.
#[test]
fn without_a_metric_actions_cost_one_and_an_or_goal_keeps_its_alternatives() {
    let t = rooms("p-unit.pddl");
    assert!(!t.uses_costs);
    assert!(t.operators.iter().all(|o| o.cost == 1));
    let alts = &t.goal.alternatives;
    assert_eq!(alts.len(), 2);
    assert_eq!(names(&t, &alts[0].pos), ["(at r2)"]);
    assert_eq!(names(&t, &alts[0].neg), ["(locked r2)"]);
    assert_eq!(names(&t, &alts[1].pos), ["(has k1)"]);
    assert_eq!(names(&t, &alts[1].neg), ["(at hall)"]);
}

#[test]
fn unreachable_goal_gives_no_alternative() {
    let t = rooms("p-unreachable.pddl");
    assert!(t.goal.alternatives.is_empty());
    assert!(!t.goal.holds(&t.init));
}

#[test]
fn missing_cost_value_is_located_in_the_domain() {
    let dir = data_dir().join("rooms");
    let d = parse_domain(
        &std::fs::read_to_string(dir.join("domain.pddl")).unwrap(),
        "domain.pddl",
    )
    .unwrap();
    let ptext = std::fs::read_to_string(dir.join("p-missing-cost.pddl")).unwrap();
    let p = parse_problem(&ptext, "p-missing-cost.pddl", &d).unwrap();
    let e = ground(&d, &p).unwrap_err().to_string();
    assert!(e.starts_with("domain.pddl:14:53: "), "{e}");
    assert!(
        e.contains("no value for `(dist r1 r2)`") && e.contains("(move r1 r2)"),
        "{e}"
    );
}

#[test]
fn state_from_names_accepts_fluents_and_statics_only() {
    let t = rooms("p-costs.pddl");
    let s = t
        .state_from_names(&[
            "( AT  R1 )".to_string(),
            "(door hall r1)".into(),
            "(has k1)".into(),
        ])
        .unwrap();
    assert_eq!(t.state_names(&s), ["(at r1)", "(has k1)"]);
    let e = t.state_from_names(&["(at r3)".to_string()]).unwrap_err();
    assert!(e.to_string().contains("(at r3)"), "{e}");
    assert_eq!(t.state_from_names(&t.state_names(&t.init)).unwrap(), t.init);
}

/// A precondition whose DNF explodes is refused with a typed error, not an out-of-memory.
#[test]
fn exploding_dnf_is_a_typed_error() {
    let ors = "(or (p) (q)) ".repeat(13); // 2^13 disjuncts
    let d = parse_domain(
        &format!("(define (domain d) (:predicates (p) (q)) (:action a :precondition (and {ors}) :effect (not (p))))"),
        "d.pddl",
    )
    .unwrap();
    let p = parse_problem(
        "(define (problem x) (:domain d) (:init (p)) (:goal (q)))",
        "x.pddl",
        &d,
    )
    .unwrap();
    let e = ground(&d, &p).unwrap_err();
    assert!(
        matches!(e, logic_lfd::plan::GroundError::TooLarge(..)),
        "{e}"
    );
    assert!(
        e.to_string()
            .contains("precondition of `a` has more than 4096 disjuncts"),
        "{e}"
    );
}

/// Re-grounding from an observed state reaches facts the original init could not.
#[test]
fn regrounding_from_an_observed_state_reaches_facts_the_init_could_not() {
    let dir = data_dir().join("rooms");
    let d = parse_domain(
        &std::fs::read_to_string(dir.join("domain.pddl")).unwrap(),
        "domain.pddl",
    )
    .unwrap();
    let p = parse_problem(
        &std::fs::read_to_string(dir.join("p-unreachable.pddl")).unwrap(),
        "p.pddl",
        &d,
    )
    .unwrap();
    assert!(ground(&d, &p).unwrap().goal.alternatives.is_empty());
    let observed: Vec<String> = ["(AT r3)", "(door hall r1)", "(door r1 r2)"]
        .map(String::from)
        .to_vec();
    let q = p.with_init(&d, &observed).unwrap();
    let t = ground(&d, &q).unwrap();
    assert_eq!(t.goal.alternatives.len(), 1);
    assert!(t.goal.holds(&t.init));
    let e = p
        .with_init(&d, &["(at r1)".into(), "(at k1)".into()])
        .unwrap_err();
    assert_eq!((e.file.as_str(), e.line, e.col), ("<init>", 2, 5), "{e}");
}
