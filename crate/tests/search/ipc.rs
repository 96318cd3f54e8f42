//! The shared IPC benchmarks: optimal configurations agree on small problems, satisficing plans
//! are valid on blocks, gripper and logistics.

use logic_lfd::plan::{search, Algorithm, HeuristicKind, NoClock, SearchConfig, SearchOutcome};

use super::cases::{ipc, ipc_case};
use super::OPTIMAL;

/// Problem file names of an IPC folder, sorted.
fn ipc_problems(dir: &str) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(ipc(dir))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".pddl") && n != "domain.pddl")
        .collect();
    v.sort();
    v
}

#[test]
fn optimal_configs_agree_on_small_ipc_problems() {
    let cases: Vec<(&str, Vec<String>)> = vec![
        (
            "blocks",
            ipc_problems("blocks")
                .into_iter()
                .filter(|p| p.contains("-4-") || p.contains("-5-") || p.contains("-6-"))
                .collect(),
        ),
        ("gripper", vec!["prob01.pddl".into()]),
        ("logistics00", vec!["probLOGISTICS-4-0.pddl".into()]),
        ("depot-typed", vec!["p01.pddl".into()]),
    ];
    let mut compared = 0;
    for (dir, problems) in cases {
        for prob in problems {
            let case = ipc_case(&format!("{dir}/domain.pddl"), &format!("{dir}/{prob}"));
            let task = &case.task;
            let mut costs = Vec::new();
            for (alg, h) in OPTIMAL {
                let cfg = SearchConfig {
                    max_nodes: Some(20_000),
                    ..SearchConfig::new(alg, h)
                };
                let r = search(task, &cfg, &NoClock);
                match &r.outcome {
                    SearchOutcome::Plan(p) => {
                        case.assert_valid(p);
                        costs.push((alg, h, p.cost));
                    }
                    SearchOutcome::BudgetExhausted { .. } => {}
                    SearchOutcome::Unsolvable => panic!("{dir}/{prob} {alg} {h}: unsolvable"),
                }
            }
            // LM-cut solves every one of these within the budget.
            assert!(
                costs.iter().any(|c| c.1 == HeuristicKind::LmCut),
                "{dir}/{prob}"
            );
            for w in costs.windows(2) {
                assert_eq!(w[0].2, w[1].2, "{dir}/{prob}: {:?}", costs);
            }
            compared += costs.len();
        }
    }
    assert!(compared > 40);
}

#[test]
fn satisficing_plans_are_valid_on_ipc_blocks_gripper_logistics() {
    let mut solved = std::collections::BTreeMap::new();
    let mut total = 0;
    for dir in ["blocks", "gripper", "logistics00"] {
        for prob in ipc_problems(dir) {
            let case = ipc_case(&format!("{dir}/domain.pddl"), &format!("{dir}/{prob}"));
            total += 1;
            for (alg, h) in [
                (Algorithm::LazyGbfs, HeuristicKind::HFf),
                (Algorithm::Gbfs, HeuristicKind::HFf),
                (Algorithm::LazyGbfs, HeuristicKind::HAdd),
            ] {
                let cfg = SearchConfig {
                    max_nodes: Some(3_000),
                    ..SearchConfig::new(alg, h)
                };
                let r = search(&case.task, &cfg, &NoClock);
                let n = solved.entry(format!("{alg} {h}")).or_insert(0usize);
                match &r.outcome {
                    SearchOutcome::Plan(p) => {
                        case.assert_valid(p);
                        *n += 1;
                    }
                    SearchOutcome::BudgetExhausted { .. } => {}
                    SearchOutcome::Unsolvable => panic!("{dir}/{prob} {alg} {h}: unsolvable"),
                }
            }
        }
    }
    // Lazy GBFS with preferred operators solves every problem within the small budget (83 of
    // 83); eager GBFS, without them, most (77 of 83).
    for (config, n) in &solved {
        if config.starts_with("lazy") {
            assert_eq!(*n, total, "{config}: {solved:?} of {total}");
        } else {
            assert!(n * 10 >= total * 9, "{config}: {solved:?} of {total}");
        }
    }
    assert_eq!(solved.len(), 3);
}
