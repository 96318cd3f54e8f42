//! Logic-LfD on domains that are not the robot's: every IPC domain of `tests/data/ipc` and the
//! example domains of `domains/`, with a planner-found (IPC) or hand-written demonstration and
//! seeded random perturbations of it.
//!
//! Properties, for every perturbed state S_C:
//! * every merged plan (both modes, an optimal and a satisficing search) replays on the lifted
//!   validator from S_C to the goal, and is `prefix ⧺ a_{k+1} … a_N` with the prefix ending in L_k;
//! * LogicIn is the latest k with L_k ⊆ S_C (checked by set inclusion on fact names);
//! * with A* + LM-cut, prioritised mode is never costlier than paper mode;
//! * on small tasks, prioritised + A* returns `min_k (cost to reach L_k or G + c_k)` as found by
//!   Dijkstra over every reachable state whenever LogicIn does not hold (when it does, the
//!   paper's rule follows the demonstration: its cost is c_k, never below the minimum).

mod folder_replay;
mod gallery;
mod paper_naming;

use std::collections::BTreeSet;

use logic_lfd::plan::{parse_plan, replay};
use logic_lfd::prelude::*;

use crate::search::brute_force_cost;

fn ipc(path: &str) -> String {
    read(&format!(
        "{}/../tests/data/ipc/{path}",
        env!("CARGO_MANIFEST_DIR")
    ))
}

fn repo(path: &str) -> String {
    read(&format!("{}/../{path}", env!("CARGO_MANIFEST_DIR")))
}

fn read(path: &str) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A demonstration found by the planner (A* + LM-cut): the IPC convention of a plan file.
fn planned_demo(domain: &str, problem: &str) -> String {
    let d = logic_lfd::pddl::parse_domain(domain, "domain.pddl").unwrap();
    let p = logic_lfd::pddl::parse_problem(problem, "problem.pddl", &d).unwrap();
    let task = logic_lfd::plan::ground(&d, &p).unwrap();
    let r = logic_lfd::plan::search(
        &task,
        &SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut),
        &NoClock,
    );
    let plan = r.outcome.plan().expect("the IPC problem is solvable");
    plan.names(&task).join("\n")
}

/// (name, Logic-LfD instance) for every domain under test.
fn cases() -> Vec<(String, LogicLfd)> {
    let mut out = vec![];
    for (dir, problems) in [
        ("blocks", &["probBLOCKS-4-0", "probBLOCKS-5-1"][..]),
        ("blocks-typed", &["probBLOCKS-4-2"][..]),
        ("gripper", &["prob01"][..]),
        ("logistics00", &["probLOGISTICS-4-0"][..]),
        ("depot-typed", &["p01"][..]),
    ] {
        let domain = ipc(&format!("{dir}/domain.pddl"));
        for p in problems {
            let problem = ipc(&format!("{dir}/{p}.pddl"));
            let demo = planned_demo(&domain, &problem);
            let lfd = LogicLfd::new(&domain, &problem, &demo)
                .unwrap_or_else(|e| panic!("{dir}/{p}: {e}"));
            out.push((format!("{dir}/{p}"), lfd));
        }
    }
    for dir in ["kitchen", "delivery"] {
        let f = |n: &str| repo(&format!("domains/{dir}/{n}"));
        let src = |n: &str| Source::new(n, f(n));
        let lfd = LogicLfd::named(&src("domain.pddl"), &src("problem.pddl"), &src("demo.plan"))
            .unwrap_or_else(|e| panic!("{dir}: {e}"));
        out.push((dir.to_string(), lfd));
    }
    out
}

/// The latest k whose L_k (by fact names) is a subset of the state's fluents and from which the
/// demonstration's suffix a_{k+1} … a_N replays to the goal on the lifted validator (with negative
/// preconditions a superset of L_k may block the suffix).
fn latest_subset(lfd: &LogicLfd, s: &State) -> Option<usize> {
    let names: BTreeSet<String> = lfd.names(s).into_iter().collect();
    let demo = lfd.demo_actions();
    lfd.demo_states()
        .iter()
        .enumerate()
        .rev()
        .find_map(|(k, l)| {
            (l.is_subset(&names) && lfd.validate(s, &demo[k..]).unwrap().is_valid()).then_some(k)
        })
}

/// Checks one merged plan from `s`; returns its cost.
fn check_merged(name: &str, lfd: &LogicLfd, s: &State, p: &LfdPlan) -> u64 {
    let report = lfd.validate(s, &p.names).unwrap();
    assert!(report.is_valid(), "{name}: {report}");
    assert!(lfd.reaches_goal(s, &p.ops), "{name}: grounded replay");
    assert_eq!(p.prefix().len() + p.suffix().len(), p.names.len());
    let demo = lfd.demo_actions();
    match p.k {
        Some(k) => {
            assert_eq!(
                p.suffix(),
                &demo[k..],
                "{name}: the suffix is the demo after L_{k}"
            );
            let mid = replay(lfd.task(), s, &p.ops[..p.prefix_len]).unwrap();
            let lk = lfd.demo_state(k).expect("L_k is a state of the task");
            assert!(
                lk.facts().all(|f| mid.contains(f)),
                "{name}: the prefix ends in L_{k}"
            );
        }
        None => assert!(p.suffix().is_empty(), "{name}: G directly"),
    }
    p.cost
}

#[test]
fn merged_plans_on_every_ipc_and_example_domain_are_valid_and_join_the_demo() {
    let optimal = SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut);
    let satisficing = SearchConfig::new(Algorithm::LazyGbfs, HeuristicKind::HFf);
    for (name, lfd) in cases() {
        let states = lfd.perturb(8, 0x5eed ^ name.len() as u64, 6);
        assert_eq!(states.len(), 8, "{name}");
        let mut searched = 0;
        for (i, st) in states.iter().enumerate() {
            let s = &st.state;
            let tag = format!("{name} #{i}");
            assert_eq!(lfd.logic_in(s), latest_subset(&lfd, s), "{tag}: LogicIn");
            let mut costs = vec![];
            for cfg in [&optimal, &satisficing] {
                for mode in [Mode::Paper, Mode::Prioritised] {
                    let p = lfd
                        .replan(s, mode, cfg, &NoClock)
                        .unwrap_or_else(|e| panic!("{tag} {mode:?}: {e}"));
                    if let Some(k) = lfd.logic_in(s) {
                        assert_eq!((p.k, p.prefix_len), (Some(k), 0), "{tag}: LogicIn's suffix");
                    } else {
                        searched += 1;
                    }
                    costs.push(check_merged(&tag, &lfd, s, &p));
                }
            }
            // costs: [paper A*, prioritised A*, paper GBFS, prioritised GBFS].
            assert!(costs[1] <= costs[0], "{tag}: prioritised {costs:?}");
        }
        assert!(searched > 0, "{name}: no perturbed state needed a search");
    }
}

/// Whether at most `cap` states are reachable from the initial state.
fn small(task: &logic_lfd::plan::Task, cap: usize) -> bool {
    let mut seen = std::collections::HashSet::from([task.init.clone()]);
    let mut queue = vec![task.init.clone()];
    while let Some(s) = queue.pop() {
        for op in task.operators.iter().filter(|o| o.applicable(&s)) {
            let t = op.apply(&s);
            if seen.insert(t.clone()) {
                if seen.len() > cap {
                    return false;
                }
                queue.push(t);
            }
        }
    }
    true
}

#[test]
fn prioritised_optimal_search_equals_brute_force_on_small_tasks() {
    let optimal = SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut);
    let mut compared = 0;
    for (name, lfd) in cases() {
        if !small(lfd.task(), 20_000) {
            continue;
        }
        for (i, st) in lfd.perturb(8, 11, 5).iter().enumerate() {
            let s = &st.state;
            let p = lfd
                .replan(s, Mode::Prioritised, &optimal, &NoClock)
                .unwrap();
            let best = brute_force_cost(lfd.task(), s, &lfd.spec().goals).unwrap();
            match lfd.logic_in(s) {
                None => {
                    assert_eq!(p.cost, best, "{name} #{i}: cost + c_k");
                    compared += 1;
                }
                Some(k) => {
                    assert_eq!(p.cost, lfd.spec().goals[k].terminal_cost, "{name} #{i}");
                    assert!(p.cost >= best, "{name} #{i}");
                }
            }
        }
    }
    assert!(compared >= 10, "only {compared} states were compared");
}

#[test]
fn logic_in_on_each_demo_state_is_the_latest_state_it_contains() {
    for (name, lfd) in cases() {
        for k in 0..lfd.demo_states().len() {
            let lk = lfd.demo_state(k).unwrap();
            let latest = latest_subset(&lfd, lk).unwrap();
            assert!(latest >= k, "{name}: L_{k} ⊆ L_{k}");
            assert_eq!(lfd.logic_in(lk), Some(latest), "{name}: L_{k}");
        }
    }
}

#[test]
fn a_demo_that_does_not_apply_names_the_step_and_the_false_precondition() {
    let domain = ipc("gripper/domain.pddl");
    let problem = ipc("gripper/prob01.pddl");
    let demo = planned_demo(&domain, &problem);
    // The first pick dropped: the drop of that ball (at some later line n) fails.
    let lines: Vec<&str> = demo.lines().collect();
    let first_pick = lines.iter().position(|l| l.starts_with("(pick")).unwrap();
    let ball = lines[first_pick].split_whitespace().nth(1).unwrap();
    let drop = lines
        .iter()
        .position(|l| l.starts_with("(drop") && l.contains(ball))
        .unwrap();
    let mut broken = lines.clone();
    broken.remove(first_pick);
    let e = LogicLfd::new(&domain, &problem, &broken.join("\n")).unwrap_err();
    let text = e.to_string();
    assert!(
        text.starts_with(&format!(
            "demo.plan:{drop}:1: demonstration step {drop} `(drop {ball} "
        )),
        "{text}"
    );
    assert!(
        text.contains(&format!("false precondition (carry {ball} ")),
        "{text}"
    );
    // A demonstration that stops early misses the goal, named by its false goal literals.
    let short = demo.lines().take(2).collect::<Vec<_>>().join("\n");
    let e = LogicLfd::new(&domain, &problem, &short).unwrap_err();
    assert!(
        matches!(e, LfdError::DemoMissesGoal { ref false_literals } if !false_literals.is_empty())
    );
    // Parse errors keep their location.
    let e = LogicLfd::new(&domain, &problem, "(pick ball1 rooma left)\n(fly)").unwrap_err();
    assert!(e.to_string().starts_with("demo.plan:"), "{e}");
}

#[test]
fn states_are_read_with_or_without_statics_and_bad_atoms_are_named() {
    let f = |n: &str| repo(&format!("domains/delivery/{n}"));
    let lfd = LogicLfd::new(&f("domain.pddl"), &f("problem.pddl"), &f("demo.plan")).unwrap();
    let facts = f("disturbed.facts");
    let s = lfd.state_in("disturbed.facts", &facts).unwrap();
    assert!(!s.is_regrounded(), "fluents of the task: no re-grounding");
    // With every static fact added the state is the same, in the same task.
    let with_statics = format!("{facts}\n{}", lfd.static_facts().join("\n"));
    let same = lfd.state(&with_statics).unwrap();
    assert!(!same.is_regrounded());
    assert_eq!(same.state(), s.state());
    // An object the problem does not have: located at the object.
    let e = lfd.state("; S_C\n(at nowhere-object depot)").unwrap_err();
    assert!(e.to_string().starts_with("state:2:"), "{e}");
    // A static atom the problem does not make true is a state too, of a task of its own.
    let statics = lfd.static_facts();
    let some_static = statics.first().expect("the delivery map is static");
    let (pred, args) = logic_lfd::plan::fact_args(some_static);
    let swapped = format!(
        "({pred} {})",
        args.iter().rev().cloned().collect::<Vec<_>>().join(" ")
    );
    if !statics.contains(&swapped) {
        let observed = lfd.state(&format!("{facts}\n{swapped}")).unwrap();
        assert!(observed.is_regrounded());
        assert!(
            observed.names().contains(&swapped),
            "{:?}",
            observed.names()
        );
    }
}

#[test]
fn a_plan_prefix_gives_the_state_after_it_and_a_wrong_step_is_named() {
    let f = |n: &str| repo(&format!("domains/kitchen/{n}"));
    let lfd = LogicLfd::new(&f("domain.pddl"), &f("problem.pddl"), &f("demo.plan")).unwrap();
    let demo = f("demo.plan");
    let steps = parse_plan(&demo, "demo.plan").unwrap();
    // The first three demonstrated actions lead to L_3.
    let three: Vec<String> = steps.iter().take(3).map(|s| s.text()).collect();
    let s = lfd.state_after("prefix.plan", &three.join("\n")).unwrap();
    assert_eq!(Some(&s), lfd.demo_state(3));
    let reversed: Vec<String> = three.iter().rev().cloned().collect();
    let e = lfd
        .state_after("prefix.plan", &reversed.join("\n"))
        .unwrap_err();
    assert!(
        matches!(e, LfdError::PrefixNotApplicable { step: 1, .. }),
        "{e}"
    );
    assert!(e.to_string().starts_with("prefix.plan:1:1: step 1 "), "{e}");
}

#[test]
fn a_budget_is_reported_as_such() {
    let f = |n: &str| repo(&format!("domains/kitchen/{n}"));
    let lfd = LogicLfd::new(&f("domain.pddl"), &f("problem.pddl"), &f("demo.plan")).unwrap();
    let s = lfd.state(&f("disturbed.facts")).unwrap();
    assert_eq!(s.logic_in(), None, "the example disturbance needs a search");
    let mut cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut);
    cfg.max_nodes = Some(1);
    let e = s.replan(Mode::Paper, &cfg, &NoClock).unwrap_err();
    assert!(matches!(e, LfdError::Budget(_)), "{e}");
}
