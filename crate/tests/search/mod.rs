//! Search and heuristics: optimality against brute force, admissibility, plan validity, budgets.
//! This module holds the configurations and the plan checks its test files share; the task
//! generators and the brute-force references are shared with `multigoal` too.

mod brute_force;
mod cases;
mod cli;
mod edge_cases;
mod ipc;
mod random_tasks;
mod regression;
mod relevance;

pub use brute_force::{brute_force_cost, brute_force_length, reachable};
pub use cases::{random_blocksworld, random_goal, random_task};

use logic_lfd::plan::{Algorithm, HeuristicKind, Plan, State, Task};
use proptest::test_runner::{Config as PtConfig, RngAlgorithm, TestRng, TestRunner};

/// The optimal configurations that must agree on cost (bfs only on unit-cost tasks).
pub const OPTIMAL: [(Algorithm, HeuristicKind); 5] = [
    (Algorithm::Bfs, HeuristicKind::Blind),
    (Algorithm::Ucs, HeuristicKind::Blind),
    (Algorithm::Astar, HeuristicKind::Blind),
    (Algorithm::Astar, HeuristicKind::HMax),
    (Algorithm::Astar, HeuristicKind::LmCut),
];

/// Satisficing configurations.
pub const SATISFICING: [(Algorithm, HeuristicKind); 6] = [
    (Algorithm::Gbfs, HeuristicKind::HFf),
    (Algorithm::Gbfs, HeuristicKind::HAdd),
    (Algorithm::LazyGbfs, HeuristicKind::HFf),
    (Algorithm::LazyGbfs, HeuristicKind::HAdd),
    (Algorithm::Astar, HeuristicKind::HAdd),
    (Algorithm::Astar, HeuristicKind::HFf),
];

/// A seeded proptest runner (deterministic, no persistence files).
pub fn runner(cases: u32) -> TestRunner {
    TestRunner::new_with_rng(
        PtConfig {
            cases,
            failure_persistence: None,
            ..PtConfig::default()
        },
        TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    )
}

/// Replays `plan` from `start` with `Operator::apply`; the final state, or a message.
pub fn replay(task: &Task, start: &State, plan: &Plan) -> Result<State, String> {
    let mut s = start.clone();
    let mut cost = 0u64;
    for (i, &o) in plan.operators.iter().enumerate() {
        let op = &task.operators[o];
        if !op.applicable(&s) {
            return Err(format!("step {i}: {} not applicable", op.name));
        }
        cost += op.cost as u64;
        s = op.apply(&s);
    }
    if cost != plan.cost {
        return Err(format!(
            "plan cost {} but operators sum to {cost}",
            plan.cost
        ));
    }
    Ok(s)
}

/// Asserts that `plan` is applicable from the initial state and reaches the task goal.
pub fn assert_valid(task: &Task, plan: &Plan) {
    let end = replay(task, &task.init, plan).unwrap_or_else(|e| panic!("invalid plan: {e}"));
    assert!(task.goal.holds(&end), "plan does not reach the goal");
}
