//! What every configuration handles: names that parse and print, unsolvable tasks and empty
//! goals proved unsolvable, node and time budgets, progress reports of a long search, a start
//! state that satisfies the goal, goal facts out of range.

use logic_lfd::plan::{
    search, Algorithm, Budget, Clock, Condition, Goal, HeuristicKind, NoClock, Operator, Plan,
    SearchConfig, SearchOutcome, State, Task, PROGRESS_EVERY,
};
use std::cell::Cell;

use super::cases::{blocksworld, random_blocksworld};
use super::{OPTIMAL, SATISFICING};

#[test]
fn algorithm_and_heuristic_names_parse_back_and_unknown_names_are_refused() {
    for a in Algorithm::ALL {
        assert_eq!(a.name().parse::<Algorithm>().unwrap(), a);
    }
    for h in HeuristicKind::ALL {
        assert_eq!(h.name().parse::<HeuristicKind>().unwrap(), h);
    }
    let e = "dfs".parse::<Algorithm>().unwrap_err();
    assert!(e.to_string().contains("bfs|ucs|astar|gbfs|lazy-gbfs"));
    assert!("ff".parse::<HeuristicKind>().is_err());
}

fn cond(pos: Vec<u32>) -> Condition {
    Condition { pos, neg: vec![] }
}

/// Two rooms, a one-way door: the goal room cannot be reached again once left.
fn one_way_task() -> Task {
    let facts = vec!["(in a)".into(), "(in b)".into(), "(in c)".into()];
    let mv = |a: u32, b: u32| Operator {
        name: format!("(move {a} {b})"),
        pre: vec![a],
        pre_neg: vec![],
        add: vec![b],
        del: vec![a],
        cost: 1,
    };
    // a → b, b → a; c is unreachable (only c → a).
    Task::new(
        facts,
        vec![mv(0, 1), mv(1, 0), mv(2, 0)],
        State::from_facts(3, [0]),
        Goal {
            alternatives: vec![cond(vec![2])],
            terminal_cost: 0,
        },
        vec![],
        false,
    )
}

/// A goal needing a negative literal the relaxation ignores: unsolvable, not a relaxed dead end.
fn negative_goal_task() -> Task {
    let ops = vec![Operator {
        name: "(toggle)".into(),
        pre: vec![0],
        pre_neg: vec![],
        add: vec![1],
        del: vec![],
        cost: 1,
    }];
    Task::new(
        vec!["(a)".into(), "(b)".into()],
        ops,
        State::from_facts(2, [0]),
        Goal {
            alternatives: vec![Condition {
                pos: vec![1],
                neg: vec![0],
            }],
            terminal_cost: 0,
        },
        vec![],
        false,
    )
}

#[test]
fn unsolvable_tasks_are_proved_unsolvable_by_every_config() {
    for task in [one_way_task(), negative_goal_task()] {
        for (alg, h) in OPTIMAL.into_iter().chain(SATISFICING) {
            let r = search(&task, &SearchConfig::new(alg, h), &NoClock);
            assert_eq!(r.outcome, SearchOutcome::Unsolvable, "{alg} {h}");
        }
    }
}

#[test]
fn goal_without_alternatives_is_unsolvable() {
    let mut task = one_way_task();
    task.goal = Goal::default();
    for (alg, h) in OPTIMAL.into_iter().chain(SATISFICING) {
        let r = search(&task, &SearchConfig::new(alg, h), &NoClock);
        assert_eq!(r.outcome, SearchOutcome::Unsolvable, "{alg} {h}");
    }
}

/// A clock that advances one second each time it is read.
struct SteppingClock(Cell<f64>);

impl Clock for SteppingClock {
    fn now_secs(&self) -> f64 {
        let t = self.0.get();
        self.0.set(t + 1.0);
        t
    }
}

#[test]
fn budgets_stop_the_search() {
    let task = random_blocksworld(8, 7).task;
    for (alg, h) in OPTIMAL.into_iter().chain(SATISFICING) {
        let cfg = SearchConfig {
            max_nodes: Some(3),
            ..SearchConfig::new(alg, h)
        };
        let r = search(&task, &cfg, &NoClock);
        assert_eq!(
            r.outcome,
            SearchOutcome::BudgetExhausted {
                which: Budget::Nodes
            },
            "{alg} {h}"
        );
        assert!(r.stats.expanded <= 3);
        let cfg = SearchConfig {
            time_limit_secs: Some(5.0),
            ..SearchConfig::new(alg, h)
        };
        let r = search(&task, &cfg, &SteppingClock(Cell::new(0.0)));
        assert_eq!(
            r.outcome,
            SearchOutcome::BudgetExhausted {
                which: Budget::Time
            },
            "{alg} {h}"
        );
    }
}

/// A clock that never advances and keeps every progress report.
#[derive(Default)]
struct ProgressLog(std::cell::RefCell<Vec<u64>>);

impl Clock for ProgressLog {
    fn now_secs(&self) -> f64 {
        0.0
    }

    fn progress(&self, expanded: u64) {
        self.0.borrow_mut().push(expanded);
    }
}

#[test]
fn a_long_search_reports_its_expansions_as_it_goes() {
    let task = random_blocksworld(8, 7).task;
    let mut reported = 0;
    for (alg, h) in OPTIMAL.into_iter().chain(SATISFICING) {
        let cfg = SearchConfig {
            max_nodes: Some(5 * PROGRESS_EVERY + 10),
            ..SearchConfig::new(alg, h)
        };
        let log = ProgressLog::default();
        let r = search(&task, &cfg, &log);
        let seen = log.0.into_inner();
        // One report per PROGRESS_EVERY expansions, in order, each the count at that moment.
        let want: Vec<u64> = (1..=r.stats.expanded / PROGRESS_EVERY)
            .map(|i| i * PROGRESS_EVERY)
            .collect();
        let mut dedup = seen.clone();
        dedup.dedup();
        assert_eq!(dedup, want, "{alg} {h}: {} expanded", r.stats.expanded);
        reported += want.len();
    }
    assert!(
        reported > 0,
        "no configuration searched long enough to report"
    );
}

#[test]
fn start_state_satisfying_the_goal_gives_the_empty_plan() {
    let towers = vec![vec![2, 0], vec![1, 3]];
    let case = blocksworld(4, &towers, &towers);
    for (alg, h) in OPTIMAL.into_iter().chain(SATISFICING) {
        let r = search(&case.task, &SearchConfig::new(alg, h), &NoClock);
        assert_eq!(r.outcome, SearchOutcome::Plan(Plan::default()), "{alg} {h}");
        case.assert_valid(r.outcome.plan().unwrap());
    }
}

#[test]
fn out_of_range_goal_facts_never_hold() {
    let mut task = one_way_task();
    task.goal = Goal {
        alternatives: vec![cond(vec![99]), cond(vec![1])],
        terminal_cost: 0,
    };
    for (alg, h) in OPTIMAL.into_iter().chain(SATISFICING) {
        let r = search(&task, &SearchConfig::new(alg, h), &NoClock);
        assert_eq!(r.stats.plan_length, Some(1), "{alg} {h}");
    }
}
