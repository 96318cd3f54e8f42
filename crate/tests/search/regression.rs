//! Goal regression agrees with replay: on random tasks with negative preconditions and or-goals,
//! for every state and random operator sequences, the regressed goal holds exactly when the
//! sequence applies and ends in the goal.

use logic_lfd::plan::{reaches_goal, regress, replay, State};
use std::sync::atomic::{AtomicUsize, Ordering};

use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::cases::random_task;
use super::runner;

#[test]
fn regression_agrees_with_replay_on_every_state() {
    // Both answers occur, so the agreement is not vacuous.
    let reached = AtomicUsize::new(0);
    let missed = AtomicUsize::new(0);
    runner(120)
        .run(&(any::<u64>(), any::<bool>()), |(seed, unit)| {
            let task = random_task(seed, unit);
            let n = task.facts.len();
            let mut rng = Pcg64Mcg::seed_from_u64(seed ^ 0x7e9e);
            let m = task.operators.len();
            for _ in 0..12 {
                let len = rng.random_range(0..=5usize);
                let ops: Vec<usize> = if m == 0 {
                    vec![]
                } else {
                    (0..len).map(|_| rng.random_range(0..m)).collect()
                };
                let regressed: Vec<_> = task
                    .goal
                    .alternatives
                    .iter()
                    .map(|c| regress(&task, c, &ops))
                    .collect();
                for bits in 0u32..(1 << n) {
                    let mut s = State::empty(n);
                    for f in 0..n as u32 {
                        if bits >> f & 1 == 1 {
                            s.insert(f);
                        }
                    }
                    let by_replay = replay(&task, &s, &ops).is_ok_and(|e| task.goal.holds(&e));
                    let by_regression = regressed.iter().flatten().any(|c| c.holds(&s));
                    prop_assert_eq!(by_replay, by_regression, "seed {} ops {:?}", seed, ops);
                    prop_assert_eq!(by_replay, reaches_goal(&task, &s, &ops));
                    let counter = if by_replay { &reached } else { &missed };
                    counter.fetch_add(1, Ordering::Relaxed);
                }
            }
            Ok(())
        })
        .unwrap();
    assert!(reached.load(Ordering::Relaxed) > 0 && missed.load(Ordering::Relaxed) > 0);
}

#[test]
fn regression_of_a_blocks_plan_needs_its_first_preconditions() {
    // b1 on b0 to b0 on b1: the goal regresses through the optimal plan to a condition that
    // contains the first action's preconditions, and every fact of it is needed.
    let case = super::cases::blocksworld(2, &[vec![0, 1]], &[vec![1, 0]]);
    let task = &case.task;
    let plan = logic_lfd::plan::search(
        task,
        &logic_lfd::plan::SearchConfig::new(
            logic_lfd::plan::Algorithm::Astar,
            logic_lfd::plan::HeuristicKind::LmCut,
        ),
        &logic_lfd::plan::NoClock,
    );
    let logic_lfd::plan::SearchOutcome::Plan(p) = plan.outcome else {
        panic!("the two-block task is solvable");
    };
    let ops = &p.operators;
    assert!(reaches_goal(task, &task.init, ops));
    let c = regress(task, &task.goal.alternatives[0], ops).expect("a valid plan regresses");
    let first = &task.operators[ops[0]];
    for f in &first.pre {
        assert!(
            c.pos.contains(f),
            "{} is needed first",
            task.facts[*f as usize]
        );
    }
    for &f in &c.pos {
        let mut s = task.init.clone();
        s.remove(f);
        assert!(
            !reaches_goal(task, &s, ops),
            "without {}",
            task.facts[f as usize]
        );
    }
}
