//! Random tasks: the optimal configurations match brute force, the heuristics are ordered and
//! admissible on every reachable state, and satisficing plans are valid, on random propositional
//! tasks and random blocksworld.

use logic_lfd::plan::{
    search, Algorithm, HeuristicEvaluator, HeuristicKind, NoClock, SearchConfig, SearchOutcome,
};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::cases::{random_blocksworld, random_case, random_goal, random_task, Case};
use super::{brute_force_cost, brute_force_length, reachable, runner, OPTIMAL, SATISFICING};

/// The (cost, length) a configuration achieved, checking plan validity.
fn run_checked(case: &Case, alg: Algorithm, h: HeuristicKind) -> Option<(u64, usize)> {
    let cfg = SearchConfig::new(alg, h);
    let r = search(&case.task, &cfg, &NoClock);
    match &r.outcome {
        SearchOutcome::Plan(p) => {
            case.assert_valid(p);
            assert_eq!(r.stats.plan_cost, Some(p.cost));
            assert_eq!(r.stats.plan_length, Some(p.len()));
            Some((p.cost, p.len()))
        }
        SearchOutcome::Unsolvable => None,
        SearchOutcome::BudgetExhausted { .. } => panic!("no budget was set"),
    }
}

#[test]
fn optimal_configs_match_brute_force_on_random_tasks() {
    runner(150)
        .run(&(any::<u64>(), any::<bool>()), |(seed, unit)| {
            let case = random_case(seed, unit);
            let task = &case.task;
            let goals = [task.goal.clone()];
            let best = brute_force_cost(task, &task.init, &goals);
            let shortest = brute_force_length(task, &task.init, &goals);
            for (alg, h) in OPTIMAL {
                let got = run_checked(&case, alg, h);
                if alg == Algorithm::Bfs {
                    prop_assert_eq!(got.map(|g| g.1 as u64), shortest, "bfs seed {}", seed);
                } else {
                    prop_assert_eq!(got.map(|g| g.0), best, "{} {} seed {}", alg, h, seed);
                }
            }
            for (alg, h) in SATISFICING {
                let got = run_checked(&case, alg, h);
                prop_assert_eq!(got.is_some(), best.is_some(), "{} {} seed {}", alg, h, seed);
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn heuristics_are_ordered_and_admissible_on_all_states() {
    runner(60)
        .run(&(any::<u64>(), any::<bool>()), |(seed, unit)| {
            let task = random_task(seed, unit);
            let mut rng = Pcg64Mcg::seed_from_u64(seed ^ 0x5eed);
            // Two goals with terminal costs exercise the artificial goal operators.
            let c = rng.random_range(0..4);
            let goals = [
                task.goal.clone(),
                random_goal(&mut rng, task.facts.len(), c),
            ];
            let mut ev: Vec<HeuristicEvaluator> = HeuristicKind::ALL
                .iter()
                .map(|&k| HeuristicEvaluator::new(&task, &goals, k))
                .collect();
            let (states, _) = reachable(&task, &task.init);
            for s in &states {
                let hstar = brute_force_cost(&task, s, &goals);
                let v: Vec<Option<u64>> = ev.iter_mut().map(|e| e.value(s)).collect();
                let [blind, hmax, hadd, hff, lmcut] = [v[0], v[1], v[2], v[3], v[4]];
                // Dead ends: every relaxation-based heuristic agrees, and only on true dead ends.
                prop_assert_eq!(hmax.is_none(), hadd.is_none());
                prop_assert_eq!(hmax.is_none(), hff.is_none());
                prop_assert_eq!(hmax.is_none(), lmcut.is_none());
                if hstar.is_some() {
                    prop_assert!(
                        hmax.is_some(),
                        "hmax proved a solvable state dead, seed {}",
                        seed
                    );
                }
                let Some(hs) = hstar else { continue };
                for (name, h) in [("blind", blind), ("hmax", hmax), ("lmcut", lmcut)] {
                    prop_assert!(
                        h.unwrap() <= hs,
                        "{} = {:?} > h* = {} seed {}",
                        name,
                        h,
                        hs,
                        seed
                    );
                }
                prop_assert!(
                    hmax <= lmcut,
                    "hmax {:?} > lmcut {:?} seed {}",
                    hmax,
                    lmcut,
                    seed
                );
                prop_assert!(
                    hmax <= hadd,
                    "hmax {:?} > hadd {:?} seed {}",
                    hmax,
                    hadd,
                    seed
                );
                prop_assert!(hmax <= hff && hff <= hadd, "hff {:?} seed {}", hff, seed);
            }
            Ok(())
        })
        .unwrap();
}

/// LM-cut bound to a search start drops operators h² proves inapplicable from that start: on
/// every state reachable from it the value stays admissible, dominates h_max, and proves dead
/// ends only where there are no plans.
#[test]
fn lmcut_for_a_search_start_is_admissible_on_its_reachable_states() {
    runner(60)
        .run(&(any::<u64>(), any::<bool>()), |(seed, unit)| {
            let task = random_task(seed, unit);
            let goals = [task.goal.clone()];
            let mut pruned =
                HeuristicEvaluator::for_search(&task, &goals, HeuristicKind::LmCut, &task.init);
            let mut hmax = HeuristicEvaluator::new(&task, &goals, HeuristicKind::HMax);
            let (states, _) = reachable(&task, &task.init);
            for s in &states {
                let Some(hs) = brute_force_cost(&task, s, &goals) else {
                    continue;
                };
                let (v, m) = (pruned.value(s), hmax.value(s));
                prop_assert!(v.is_some(), "solvable state proved dead, seed {}", seed);
                prop_assert!(v.unwrap() <= hs, "{:?} > h* {} seed {}", v, hs, seed);
                prop_assert!(m <= v, "hmax {:?} > {:?} seed {}", m, v, seed);
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn optimal_configs_agree_on_random_blocksworld() {
    for seed in 0..12 {
        let n = 4 + (seed as usize % 2);
        let case = random_blocksworld(n, seed);
        let task = &case.task;
        let best = brute_force_cost(task, &task.init, std::slice::from_ref(&task.goal));
        for (alg, h) in OPTIMAL {
            let got = run_checked(&case, alg, h).map(|g| g.0);
            assert_eq!(got, best, "{alg} {h} on {n} blocks, seed {seed}");
        }
    }
}

#[test]
fn satisficing_plans_are_valid_on_larger_blocksworld() {
    for seed in 0..6 {
        let case = random_blocksworld(9, 100 + seed);
        for (alg, h) in SATISFICING {
            if alg == Algorithm::Astar {
                continue;
            }
            assert!(
                run_checked(&case, alg, h).is_some(),
                "{alg} {h} failed, seed {seed}"
            );
        }
    }
}
