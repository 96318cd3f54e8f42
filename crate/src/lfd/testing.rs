//! A hand-grounded blocks world for unit tests (no parser needed): one arm, actions
//! `pick`/`place`/`stack`/`unstack` as in the paper's B1.

use crate::plan::{Condition, Goal, Operator, State, Task};

/// Builds the grounded blocks task over `blocks` with the given initial and goal facts.
pub(crate) fn blocks_task(blocks: &[&str], init: &[&str], goal: &[&str]) -> Task {
    let mut facts: Vec<String> = vec!["(handempty)".into()];
    for b in blocks {
        facts.push(format!("(ontable {b})"));
        facts.push(format!("(clear {b})"));
        facts.push(format!("(holding {b})"));
        for c in blocks {
            if b != c {
                facts.push(format!("(on {b} {c})"));
            }
        }
    }
    let id = |name: &str| facts.iter().position(|f| f == name).expect(name) as u32;
    let mut ops = Vec::new();
    for b in blocks {
        let (ot, cl, ho, he) = (
            id(&format!("(ontable {b})")),
            id(&format!("(clear {b})")),
            id(&format!("(holding {b})")),
            id("(handempty)"),
        );
        ops.push(Operator {
            name: format!("(pick {b})"),
            pre: vec![ot, cl, he],
            pre_neg: vec![],
            add: vec![ho],
            del: vec![ot, cl, he],
            cost: 1,
        });
        ops.push(Operator {
            name: format!("(place {b})"),
            pre: vec![ho],
            pre_neg: vec![],
            add: vec![ot, cl, he],
            del: vec![ho],
            cost: 1,
        });
        for c in blocks {
            if b == c {
                continue;
            }
            let on = id(&format!("(on {b} {c})"));
            let clc = id(&format!("(clear {c})"));
            ops.push(Operator {
                name: format!("(stack {b} {c})"),
                pre: vec![ho, clc],
                pre_neg: vec![],
                add: vec![on, cl, he],
                del: vec![ho, clc],
                cost: 1,
            });
            ops.push(Operator {
                name: format!("(unstack {b} {c})"),
                pre: vec![on, cl, he],
                pre_neg: vec![],
                add: vec![ho, clc],
                del: vec![on, cl, he],
                cost: 1,
            });
        }
    }
    let n = facts.len();
    let init = State::from_facts(n, init.iter().map(|f| id(f)));
    let goal = Goal {
        alternatives: vec![Condition {
            pos: goal.iter().map(|f| id(f)).collect(),
            neg: vec![],
        }],
        terminal_cost: 0,
    };
    Task::new(facts, ops, init, goal, vec![], false)
}

/// The B1 template: A, B, C, D on the table; goal A on B on C on D; demo stacks bottom-up.
pub(crate) fn b1_template() -> (Task, Vec<String>) {
    let blocks = ["a", "b", "c", "d"];
    let task = blocks_task(
        &blocks,
        &[
            "(handempty)",
            "(ontable a)",
            "(ontable b)",
            "(ontable c)",
            "(ontable d)",
            "(clear a)",
            "(clear b)",
            "(clear c)",
            "(clear d)",
        ],
        &["(on a b)", "(on b c)", "(on c d)"],
    );
    let demo = [
        "(pick c)",
        "(stack c d)",
        "(pick b)",
        "(stack b c)",
        "(pick a)",
        "(stack a b)",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    (task, demo)
}

/// A state of `task` from fact names.
pub(crate) fn state(task: &Task, facts: &[&str]) -> State {
    State::from_facts(
        task.facts.len(),
        facts.iter().map(|f| task.fact_id(f).expect(f)),
    )
}
