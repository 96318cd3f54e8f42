//! Multi-goal search: prioritised optimality against brute force, first-reached semantics,
//! start states that already satisfy goals.

use crate::search::{
    brute_force_cost, brute_force_length, random_blocksworld, random_goal, random_task, replay,
    runner, OPTIMAL, SATISFICING,
};
use logic_lfd::plan::{
    search, search_multi_goal, Algorithm, Goal, HeuristicKind, MultiGoalMode, MultiGoalResult,
    MultiGoalSearch, NoClock, SearchConfig, SearchOutcome, State, Task,
};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Checks the plan replays from `start` into a state of the reported goal; returns `cost + c_k`.
fn check(task: &Task, start: &State, goals: &[Goal], r: &MultiGoalResult) -> Option<u64> {
    match &r.outcome {
        SearchOutcome::Plan(p) => {
            let end = replay(task, start, p).unwrap_or_else(|e| panic!("invalid plan: {e}"));
            let k = r.goal_index.expect("a plan names its goal");
            assert!(goals[k].holds(&end), "plan does not reach goal {k}");
            // The reported goal is the cheapest one holding at the end.
            let cheapest = goals
                .iter()
                .filter(|g| g.holds(&end))
                .map(|g| g.terminal_cost)
                .min();
            assert_eq!(Some(goals[k].terminal_cost), cheapest);
            assert_eq!(r.total_cost, Some(p.cost + goals[k].terminal_cost));
            r.total_cost
        }
        SearchOutcome::Unsolvable => {
            assert_eq!((r.goal_index, r.total_cost), (None, None));
            None
        }
        SearchOutcome::BudgetExhausted { .. } => panic!("no budget was set"),
    }
}

fn random_goals(task: &Task, seed: u64) -> Vec<Goal> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let k = rng.random_range(1..=4);
    (0..k)
        .map(|_| {
            let c = rng.random_range(0..6);
            random_goal(&mut rng, task.facts.len(), c)
        })
        .collect()
}

#[test]
fn prioritised_is_optimal_and_never_worse_than_first_reached() {
    runner(150)
        .run(&(any::<u64>(), any::<bool>()), |(seed, unit)| {
            let task = random_task(seed, unit);
            let goals = random_goals(&task, seed ^ 0xabc);
            let mut rng = Pcg64Mcg::seed_from_u64(seed);
            // Start anywhere reachable or the initial state.
            let start = if rng.random_bool(0.5) {
                task.init.clone()
            } else {
                let (states, _) = crate::search::reachable(&task, &task.init);
                states[rng.random_range(0..states.len())].clone()
            };
            let best = brute_force_cost(&task, &start, &goals);
            let shortest = brute_force_length(&task, &start, &goals);
            let zero: Vec<Goal> = goals
                .iter()
                .map(|g| Goal {
                    terminal_cost: 0,
                    ..g.clone()
                })
                .collect();
            let cheapest_any = brute_force_cost(&task, &start, &zero);
            for (alg, h) in OPTIMAL {
                let cfg = SearchConfig::new(alg, h);
                let p = search_multi_goal(
                    &task,
                    &start,
                    &goals,
                    MultiGoalMode::Prioritised,
                    &cfg,
                    &NoClock,
                );
                let pv = check(&task, &start, &goals, &p);
                prop_assert_eq!(pv, best, "prioritised {} {} seed {}", alg, h, seed);
                let f = search_multi_goal(
                    &task,
                    &start,
                    &goals,
                    MultiGoalMode::FirstReached,
                    &cfg,
                    &NoClock,
                );
                let fv = check(&task, &start, &goals, &f);
                prop_assert_eq!(fv.is_some(), pv.is_some());
                if let (Some(pv), Some(fv)) = (pv, fv) {
                    prop_assert!(pv <= fv, "prioritised {} > first-reached {}", pv, fv);
                }
                // First-reached: bfs reaches some goal in the fewest steps, ucs/A* most cheaply.
                let fp = f.plan().map(|p| (p.len() as u64, p.cost));
                if alg == Algorithm::Bfs {
                    prop_assert_eq!(fp.map(|x| x.0), shortest, "bfs seed {}", seed);
                } else {
                    prop_assert_eq!(fp.map(|x| x.1), cheapest_any, "{} {} seed {}", alg, h, seed);
                }
            }
            for (alg, h) in SATISFICING {
                let cfg = SearchConfig::new(alg, h);
                for mode in [MultiGoalMode::Prioritised, MultiGoalMode::FirstReached] {
                    let r = search_multi_goal(&task, &start, &goals, mode, &cfg, &NoClock);
                    let v = check(&task, &start, &goals, &r);
                    prop_assert_eq!(v.is_some(), best.is_some(), "{} {} seed {}", alg, h, seed);
                }
            }
            Ok(())
        })
        .unwrap();
}

/// Demo-like goals on blocksworld: `L_0..L_N` the states along a plan, `c_k = N − k`.
fn demo_goals(task: &Task) -> (Vec<State>, Vec<Goal>) {
    let r = search(
        task,
        &SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut),
        &NoClock,
    );
    let plan = r.outcome.plan().expect("solvable").clone();
    let mut states = vec![task.init.clone()];
    for &o in &plan.operators {
        let s = task.operators[o].apply(states.last().unwrap());
        states.push(s);
    }
    let n = plan.len() as u64;
    let goals = states
        .iter()
        .enumerate()
        .map(|(k, s)| Goal {
            alternatives: vec![logic_lfd::plan::Condition {
                pos: s.facts().collect(),
                neg: vec![],
            }],
            terminal_cost: n - k as u64,
        })
        .collect();
    (states, goals)
}

#[test]
fn start_in_a_demo_state_returns_the_empty_plan_with_the_closest_goal() {
    for seed in 0..4 {
        let task = random_blocksworld(5, 40 + seed).task;
        let (states, goals) = demo_goals(&task);
        for (k, s) in states.iter().enumerate() {
            for mode in [MultiGoalMode::FirstReached, MultiGoalMode::Prioritised] {
                for (alg, h) in OPTIMAL.into_iter().chain(SATISFICING) {
                    let cfg = SearchConfig::new(alg, h);
                    let r = search_multi_goal(&task, s, &goals, mode, &cfg, &NoClock);
                    assert_eq!(r.plan().map(|p| p.len()), Some(0), "{alg} {h} {mode:?}");
                    // Demo states are distinct, so exactly goal k holds.
                    assert_eq!(r.goal_index, Some(k), "{alg} {h} {mode:?}");
                    assert_eq!(r.total_cost, Some(goals[k].terminal_cost));
                }
            }
        }
    }
}

#[test]
fn prioritised_repairs_to_the_cheapest_demo_suffix() {
    // From random perturbed states, prioritised A* equals the brute-force optimum of
    // cost-to-L_k + (N − k), and first-reached never beats it.
    for seed in 0..6 {
        let task = random_blocksworld(5, 60 + seed).task;
        let (_, goals) = demo_goals(&task);
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let (all, _) = crate::search::reachable(&task, &task.init);
        for _ in 0..3 {
            let start = all[rng.random_range(0..all.len())].clone();
            let best = brute_force_cost(&task, &start, &goals);
            let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut);
            let p = search_multi_goal(
                &task,
                &start,
                &goals,
                MultiGoalMode::Prioritised,
                &cfg,
                &NoClock,
            );
            assert_eq!(check(&task, &start, &goals, &p), best);
            let f = search_multi_goal(
                &task,
                &start,
                &goals,
                MultiGoalMode::FirstReached,
                &SearchConfig::new(Algorithm::Bfs, HeuristicKind::Blind),
                &NoClock,
            );
            assert!(check(&task, &start, &goals, &f) >= best);
        }
    }
}

#[test]
fn unreachable_goals_are_unsolvable() {
    let task = random_blocksworld(3, 1).task;
    // Two blocks on the same block at once never holds.
    let on = |x: usize, y: usize| task.fact_id(&format!("(on b{x} b{y})")).unwrap();
    let goals = [Goal {
        alternatives: vec![logic_lfd::plan::Condition {
            pos: vec![on(0, 2), on(1, 2)],
            neg: vec![],
        }],
        terminal_cost: 2,
    }];
    for mode in [MultiGoalMode::FirstReached, MultiGoalMode::Prioritised] {
        for (alg, h) in OPTIMAL.into_iter().chain(SATISFICING) {
            let r = search_multi_goal(
                &task,
                &task.init,
                &goals,
                mode,
                &SearchConfig::new(alg, h),
                &NoClock,
            );
            assert_eq!(r.outcome, SearchOutcome::Unsolvable, "{alg} {h} {mode:?}");
        }
    }
}

#[test]
fn a_compiled_search_answers_many_starts_as_fresh_searches_do() {
    // One `MultiGoalSearch` reused from many starts (its heuristic templates kept between runs)
    // returns what a search compiled for each start returns, and with the last demonstration
    // state as lower bound prioritised A* still meets the brute-force optimum.
    for seed in 0..4 {
        let task = random_blocksworld(5, 80 + seed).task;
        let (_, goals) = demo_goals(&task);
        let last = goals.len() - 1;
        let (all, _) = crate::search::reachable(&task, &task.init);
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        for mode in [MultiGoalMode::FirstReached, MultiGoalMode::Prioritised] {
            let plain = MultiGoalSearch::new(&task, &goals, mode);
            let bounded = MultiGoalSearch::new(&task, &goals, mode).with_lower_bound(last);
            for _ in 0..6 {
                let start = all[rng.random_range(0..all.len())].clone();
                for (alg, h) in OPTIMAL.into_iter().chain(SATISFICING) {
                    let cfg = SearchConfig::new(alg, h);
                    let fresh = search_multi_goal(&task, &start, &goals, mode, &cfg, &NoClock);
                    let again = plain.run(&start, &cfg, &NoClock);
                    assert_eq!(again.outcome, fresh.outcome, "{alg} {h} {mode:?}");
                    assert_eq!(again.goal_index, fresh.goal_index);
                    check(&task, &start, &goals, &again);
                    let b = bounded.run(&start, &cfg, &NoClock);
                    let total = check(&task, &start, &goals, &b);
                    if mode == MultiGoalMode::Prioritised && cfg.is_optimal() {
                        assert_eq!(total, brute_force_cost(&task, &start, &goals), "{alg} {h}");
                    }
                }
            }
        }
    }
}
