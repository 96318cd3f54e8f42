//! Disturbance injection and the Table I task generator (`sim::disturb`, `sim::tasks`).

use logic_lfd::sim::benchmark::Benchmark;
use logic_lfd::sim::demo;
use logic_lfd::sim::{SceneGraph, World};

mod disturbances {
    //! Every injector delivers its promise.
    use super::*;
    use logic_lfd::sim::disturb::{self, Level};
    use std::collections::BTreeSet;

    fn fset(w: &World) -> BTreeSet<String> {
        SceneGraph::from_world(w).to_strings().into_iter().collect()
    }

    #[test]
    fn every_level_keeps_its_promise_on_every_benchmark() {
        for b in Benchmark::ALL {
            let states = demo::demo_states(b).unwrap();
            assert_eq!(states.len(), demo::committed(b).unwrap().actions.len() + 1);
            for seed in 0..4 {
                for level in Level::ALL {
                    let mut w = b.scene();
                    let before = fset(&w);
                    let nblocks = w.block_names().len();
                    let d = disturb::inject(&mut w, b, level, &states, seed)
                        .unwrap_or_else(|e| panic!("{b:?} {level:?} seed {seed}: {e}"));
                    w.check_invariants()
                        .unwrap_or_else(|v| panic!("{b:?} {level:?}: {v:?}"));
                    let after = fset(&w);
                    assert_eq!(d.facts_after, after.iter().cloned().collect::<Vec<_>>());
                    assert_eq!(d.facts_before, before.iter().cloned().collect::<Vec<_>>());
                    assert!(!d.description.is_empty());
                    match level {
                        Level::L1 => {
                            assert_eq!(after, before, "{b:?} L1 seed {seed}");
                            assert!(!d.moves.is_empty());
                        }
                        Level::L2 => {
                            assert_ne!(after, before, "{b:?} L2 seed {seed}");
                            assert!(states.contains(&after), "{b:?} L2 seed {seed}: {after:?}");
                        }
                        Level::L3 => {
                            assert!(!states.contains(&after), "{b:?} L3 seed {seed}: {after:?}");
                        }
                        Level::L4 => {
                            assert_eq!(w.block_names().len(), nblocks + 1);
                            assert_eq!(d.added.len(), 1);
                            let e = &d.added[0];
                            assert!(
                                after.iter().any(|f| f.contains(&format!(" {e}"))),
                                "{after:?}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn injection_is_deterministic_in_its_seed() {
        let states = demo::demo_states(Benchmark::B3).unwrap();
        let run = |seed| {
            let mut w = Benchmark::B3.scene();
            disturb::inject(&mut w, Benchmark::B3, Level::L3, &states, seed).unwrap();
            w.snapshot()
        };
        assert_eq!(run(5), run(5));
        assert_ne!(run(5), run(6));
    }
}

mod task_generator {
    //! Table I tasks: the promised level, valid worlds, solvable PDDL problems.
    use super::*;
    use logic_lfd::plan::{self, NoClock, SearchConfig, SearchOutcome};
    use logic_lfd::sim::disturb::Level;
    use logic_lfd::sim::tasks;

    #[test]
    fn generated_tasks_load_and_their_problems_parse_and_are_solvable() {
        for b in Benchmark::ALL {
            let ts = tasks::generate_table1(b, 12, 3).unwrap_or_else(|e| panic!("{b:?}: {e}"));
            assert_eq!(ts.len(), 12);
            let dom = logic_lfd::pddl::parse_domain(b.domain_pddl(), "domain.pddl").unwrap();
            for t in &ts {
                assert_eq!(t.level, Level::ALL[t.index % 4]);
                let w = World::from_snapshot(&t.scene)
                    .unwrap_or_else(|e| panic!("{}: {e}", t.description));
                w.check_invariants().unwrap();
                let blocks = w.block_names().len();
                let want = b.blocks().len() + usize::from(t.level == Level::L4);
                assert_eq!(blocks, want, "{b:?} {:?}", t.level);
                let prob = logic_lfd::pddl::parse_problem(&t.problem_pddl, "task.pddl", &dom)
                    .unwrap_or_else(|e| panic!("{}\n{e}", t.problem_pddl));
                let task = plan::ground(&dom, &prob).unwrap();
                // The problem's init is the scene graph of the world.
                assert_eq!(
                    task.state_names(&task.state_from_names(&t.facts).unwrap()),
                    task.state_names(&task.init)
                );
                let r = plan::search(&task, &SearchConfig::default(), &NoClock);
                assert!(
                    matches!(r.outcome, SearchOutcome::Plan(_)),
                    "{b:?} {}: {:?}",
                    t.description,
                    r.outcome
                );
            }
        }
    }

    #[test]
    fn task_generation_is_deterministic() {
        let a = tasks::generate(Benchmark::B1, Level::L3, 3, 9).unwrap();
        let b = tasks::generate(Benchmark::B1, Level::L3, 3, 9).unwrap();
        assert_eq!(a, b);
        assert_ne!(
            a[0].facts,
            tasks::generate(Benchmark::B1, Level::L3, 1, 10).unwrap()[0].facts
        );
    }
}
