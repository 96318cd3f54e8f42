//! Planner benchmarks: the paper's B1 tower (4 blocks, goal a on b on c on d) from every start,
//! and end-to-end (parse + ground + search) lazy GBFS with h_FF on IPC blocks problems.

// `criterion_group!` generates an undocumented function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use logic_lfd::pddl::{parse_domain, parse_problem};
use logic_lfd::plan::{
    ground, search, search_multi_goal, Algorithm, HeuristicKind, MultiGoalMode, NoClock,
    SearchConfig, State, Task,
};
use std::hint::black_box;

const BLOCKS_DOMAIN: &str = include_str!("../../tests/data/ipc/blocks/domain.pddl");

const TOWER_PROBLEM: &str = "(define (problem b1-tower) (:domain BLOCKS)
  (:objects a b c d)
  (:init (clear a) (clear b) (clear c) (clear d)
         (ontable a) (ontable b) (ontable c) (ontable d) (handempty))
  (:goal (and (on a b) (on b c) (on c d))))";

fn tower_task() -> Task {
    let d = parse_domain(BLOCKS_DOMAIN, "domain.pddl").expect("domain");
    let p = parse_problem(TOWER_PROBLEM, "tower.pddl", &d).expect("problem");
    ground(&d, &p).expect("ground")
}

/// Every state reachable from the initial one (all 4-block configurations, hand full or empty).
fn all_states(task: &Task) -> Vec<State> {
    let mut seen = std::collections::HashSet::from([task.init.clone()]);
    let mut states = vec![task.init.clone()];
    let mut i = 0;
    while i < states.len() {
        let s = states[i].clone();
        for op in &task.operators {
            if op.applicable(&s) {
                let t = op.apply(&s);
                if seen.insert(t.clone()) {
                    states.push(t);
                }
            }
        }
        i += 1;
    }
    states
}

fn tower(c: &mut Criterion) {
    let task = tower_task();
    let starts = all_states(&task);
    let goals = [task.goal.clone()];
    let mut g = c.benchmark_group("b1_tower_4_blocks");
    for (alg, h) in [
        (Algorithm::Astar, HeuristicKind::LmCut),
        (Algorithm::LazyGbfs, HeuristicKind::HFf),
        (Algorithm::Bfs, HeuristicKind::Blind),
    ] {
        let cfg = SearchConfig::new(alg, h);
        // Mean per start = reported time / number of starts.
        g.bench_function(format!("{alg}_{h}_all_{}_starts", starts.len()), |b| {
            b.iter(|| {
                for s in &starts {
                    let r = search_multi_goal(
                        &task,
                        s,
                        &goals,
                        MultiGoalMode::FirstReached,
                        &cfg,
                        &NoClock,
                    );
                    black_box(r.goal_index);
                }
            })
        });
    }
    // The hardest start for the tower: the reversed tower d on c on b on a.
    let d = parse_domain(BLOCKS_DOMAIN, "domain.pddl").expect("domain");
    let reversed = TOWER_PROBLEM.replace(
        "(:init (clear a) (clear b) (clear c) (clear d)
         (ontable a) (ontable b) (ontable c) (ontable d) (handempty))",
        "(:init (clear d) (on d c) (on c b) (on b a) (ontable a) (handempty))",
    );
    g.bench_function("astar_lmcut_reversed_tower_end_to_end", |b| {
        b.iter(|| {
            let p = parse_problem(&reversed, "reversed.pddl", &d).expect("problem");
            let t = ground(&d, &p).expect("ground");
            black_box(
                search(&t, &SearchConfig::default(), &NoClock)
                    .stats
                    .plan_length,
            )
        })
    });
    g.finish();
}

fn ipc_blocks_gbfs(c: &mut Criterion) {
    let mut g = c.benchmark_group("ipc_blocks_lazy_gbfs_hff_end_to_end");
    g.sample_size(20);
    let d_text = BLOCKS_DOMAIN;
    for name in ["probBLOCKS-10-0", "probBLOCKS-14-0", "probBLOCKS-17-0"] {
        let path = format!(
            "{}/../tests/data/ipc/blocks/{name}.pddl",
            env!("CARGO_MANIFEST_DIR")
        );
        let p_text = std::fs::read_to_string(&path).expect("IPC problem");
        let cfg = SearchConfig::new(Algorithm::LazyGbfs, HeuristicKind::HFf);
        g.bench_function(name, |b| {
            b.iter(|| {
                let d = parse_domain(d_text, "domain.pddl").expect("domain");
                let p = parse_problem(&p_text, name, &d).expect("problem");
                let t = ground(&d, &p).expect("ground");
                black_box(search(&t, &cfg, &NoClock).stats.plan_length)
            })
        });
    }
    g.finish();
}

criterion_group!(benches, tower, ipc_blocks_gbfs);
criterion_main!(benches);
