//! Budgets (Rust side): every search honours its node budget and its time budget measured with
//! the caller's clock, and an exhausted budget is a stated outcome, not a hang; a session under a
//! tiny planning or simulated-time budget ends with a stated reason.

use std::cell::Cell;

use logic_lfd::experiments::{run_episode, EpisodeSpec};
use logic_lfd::lfd::FailReason;
use logic_lfd::lfd::Level;
use logic_lfd::lfd::SessionParams;
use logic_lfd::lfd::{Method, Mode};
use logic_lfd::pddl::{parse_domain, parse_problem};
use logic_lfd::plan::{
    ground, search, search_multi_goal, Algorithm, Budget, Clock, HeuristicKind, MultiGoalMode,
    NoClock, SearchConfig, SearchOutcome, Task,
};
use logic_lfd::sim::Benchmark;

/// A clock that advances by `step` seconds every time it is read.
struct SteppingClock {
    t: Cell<f64>,
    step: f64,
}

impl Clock for SteppingClock {
    fn now_secs(&self) -> f64 {
        let t = self.t.get() + self.step;
        self.t.set(t);
        t
    }
}

/// IPC blocksworld with 9 blocks: large enough that no configuration solves it in a few nodes.
fn hard_task() -> Task {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/ipc/blocks");
    let d = std::fs::read_to_string(format!("{dir}/domain.pddl")).unwrap();
    let p = std::fs::read_to_string(format!("{dir}/probBLOCKS-9-0.pddl")).unwrap();
    let d = parse_domain(&d, "domain.pddl").unwrap();
    let p = parse_problem(&p, "p.pddl", &d).unwrap();
    ground(&d, &p).unwrap()
}

const CONFIGS: [(Algorithm, HeuristicKind); 5] = [
    (Algorithm::Bfs, HeuristicKind::Blind),
    (Algorithm::Ucs, HeuristicKind::Blind),
    (Algorithm::Astar, HeuristicKind::LmCut),
    (Algorithm::Gbfs, HeuristicKind::HFf),
    (Algorithm::LazyGbfs, HeuristicKind::HFf),
];

#[test]
fn every_search_stops_at_its_node_budget_with_a_stated_outcome() {
    let task = hard_task();
    for (alg, h) in CONFIGS {
        let cfg = SearchConfig {
            max_nodes: Some(5),
            ..SearchConfig::new(alg, h)
        };
        let r = search(&task, &cfg, &NoClock);
        assert_eq!(
            r.outcome,
            SearchOutcome::BudgetExhausted {
                which: Budget::Nodes
            },
            "{alg:?}/{h:?}"
        );
        assert!(
            r.stats.expanded <= 5,
            "{alg:?}: {} expanded",
            r.stats.expanded
        );
    }
}

#[test]
fn every_search_stops_at_its_time_budget_by_the_callers_clock() {
    let task = hard_task();
    for (alg, h) in CONFIGS {
        // Each clock read advances 10 ms; a 0.2 s limit must stop the search after a few reads.
        let clock = SteppingClock {
            t: Cell::new(0.0),
            step: 0.01,
        };
        let cfg = SearchConfig {
            time_limit_secs: Some(0.2),
            ..SearchConfig::new(alg, h)
        };
        let r = search(&task, &cfg, &clock);
        assert_eq!(
            r.outcome,
            SearchOutcome::BudgetExhausted {
                which: Budget::Time
            },
            "{alg:?}/{h:?}"
        );
        assert!(r.stats.time_secs >= 0.2, "{alg:?}: {}", r.stats.time_secs);
    }
}

#[test]
fn multi_goal_search_honours_both_budgets() {
    let task = hard_task();
    let goals = [task.goal.clone()];
    for mode in [MultiGoalMode::FirstReached, MultiGoalMode::Prioritised] {
        let cfg = SearchConfig {
            max_nodes: Some(3),
            ..SearchConfig::new(Algorithm::Astar, HeuristicKind::HMax)
        };
        let r = search_multi_goal(&task, &task.init, &goals, mode, &cfg, &NoClock);
        assert_eq!(
            r.outcome,
            SearchOutcome::BudgetExhausted {
                which: Budget::Nodes
            }
        );
        assert_eq!(r.goal_index, None);
        let clock = SteppingClock {
            t: Cell::new(0.0),
            step: 1.0,
        };
        let cfg = SearchConfig {
            time_limit_secs: Some(0.5),
            ..SearchConfig::new(Algorithm::Astar, HeuristicKind::HMax)
        };
        let r = search_multi_goal(&task, &task.init, &goals, mode, &cfg, &clock);
        assert_eq!(
            r.outcome,
            SearchOutcome::BudgetExhausted {
                which: Budget::Time
            }
        );
    }
}

fn l3_episode() -> EpisodeSpec {
    EpisodeSpec {
        benchmark: Benchmark::B1,
        // L3 leaves the demonstration: the replan must search.
        level: Some(Level::L3),
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed: 1,
        scene: None,
        robots: vec![],
    }
}

#[test]
fn an_optimal_replan_out_of_budget_retries_with_the_satisficing_search() {
    let mut params = SessionParams::default();
    // A* cannot expand past the start; lazy GBFS stops where a goal operator applies.
    params.control.search.max_nodes = Some(1);
    params.control.tamp_fallback = false;
    let r = run_episode(&l3_episode(), params, &NoClock).unwrap();
    assert!(r.success, "{:?}", r.reason);
    assert!(r.log.replans.iter().all(|p| !p.fallback));
    assert!(r.log.replans.iter().any(|p| p.new_actions > 0));
}

#[test]
fn an_episode_out_of_planning_budget_states_it_instead_of_hanging() {
    let mut params = SessionParams::default();
    params.control.search.max_nodes = Some(0);
    let r = run_episode(&l3_episode(), params, &NoClock).unwrap();
    assert!(!r.success);
    match r.reason {
        Some(FailReason::NoPlan { message }) => {
            assert!(
                message.contains("exhausted"),
                "not stated as a budget: {message}"
            )
        }
        Some(FailReason::Budget { .. }) => {}
        other => panic!("expected a stated budget outcome, got {other:?}"),
    }
}

#[test]
fn an_episode_out_of_simulated_time_states_it() {
    let params = SessionParams {
        max_time: 1.0,
        ..SessionParams::default()
    };
    let spec = EpisodeSpec {
        benchmark: Benchmark::B1,
        level: None,
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed: 2,
        scene: None,
        robots: vec![],
    };
    let r = run_episode(&spec, params, &NoClock).unwrap();
    assert!(!r.success);
    assert_eq!(
        r.reason,
        Some(FailReason::Budget {
            what: "simulated time".into()
        })
    );
    assert!(r.execution_s <= 1.0 + 0.02, "{}", r.execution_s);
}
