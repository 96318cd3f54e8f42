//! Tables I and II as the CLI runs them, on a few tasks: Logic-LfD's success is its own when the
//! TAMP fallback is off, every first plan's time splits into search and binding, the markdown
//! says which way the fallback was set; the paper's pattern holds (Logic-LfD and TAMP solve every
//! task, the linear baseline fails where the state differs from the demonstration and RLDS where
//! no demonstration state matches, each for the paper's reason); and the rule that redraws an
//! infeasible Table I state accepts the templates and refuses worlds no arm can work.

use logic_lfd::experiments::{
    infeasible, table1, table1_scene, table1_task_seed, table2, Table2Cell,
};
use logic_lfd::lfd::Level;
use logic_lfd::lfd::Method;
use logic_lfd::lfd::SessionParams;
use logic_lfd::plan::{Clock, NoClock};
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::World;
use nalgebra::Vector3;

/// A clock that moves on by a millisecond every time it is read, so every timed span is
/// non-zero and search and binding get different shares.
struct Ticking(std::cell::Cell<f64>);

impl Clock for Ticking {
    fn now_secs(&self) -> f64 {
        let t = self.0.get() + 1e-3;
        self.0.set(t);
        t
    }
}

fn run(tamp_fallback: bool) -> logic_lfd::experiments::Table1 {
    let mut params = SessionParams::default();
    params.control.tamp_fallback = tamp_fallback;
    let clock = Ticking(std::cell::Cell::new(0.0));
    table1(&[Benchmark::B1], 4, 1, params, &clock, &mut |_| {}).expect("table I runs")
}

#[test]
fn table1_counts_logic_lfd_alone_and_splits_planning_time() {
    let t = run(false);
    assert!(!t.tamp_fallback);
    assert_eq!(t.cells.len(), 4, "linear, tamp and Logic-LfD in both modes");
    for c in &t.cells {
        assert_eq!(c.tasks, 4);
        assert_eq!(c.fallbacks, 0, "{}: the fallback is off", c.method_label());
        if c.method == Method::Linear {
            continue;
        }
        assert_eq!(c.plan_ms.len(), 4, "{}", c.method_label());
        assert_eq!(c.search_ms.len(), 4);
        assert_eq!(c.bind_ms.len(), 4);
        for ((p, s), b) in c.plan_ms.iter().zip(&c.search_ms).zip(&c.bind_ms) {
            assert!(
                (s + b - p).abs() < 1e-6,
                "search + binding = first-plan time"
            );
            assert!(
                *s > 0.0 && *b > 0.0,
                "{}: search {s} ms, binding {b} ms",
                c.method_label()
            );
        }
        assert_eq!(c.successes, 4, "{}: {:?}", c.method_label(), c.failures);
    }
    let md = t.markdown();
    assert!(md.contains("TAMP fallback off"), "{md}");
    assert!(
        md.contains("| logic-lfd (paper) | B1 | 100 % (4/4) |"),
        "{md}"
    );
    assert!(md
        .lines()
        .any(|l| l.starts_with("| logic-lfd (paper)") && l.contains("| off |")));
}

#[test]
fn table1_with_the_fallback_reports_its_count() {
    let t = run(true);
    assert!(t.tamp_fallback);
    let md = t.markdown();
    assert!(md.contains("TAMP fallback on"), "{md}");
    let row = md
        .lines()
        .find(|l| l.starts_with("| logic-lfd (paper)"))
        .expect("a Logic-LfD row");
    let cell = t
        .cells
        .iter()
        .find(|c| c.method_label() == "logic-lfd (paper)")
        .unwrap();
    assert!(row.contains(&format!("| {} |", cell.fallbacks)), "{row}");
}

/// Failure kinds of a blind baseline: an action that cannot run, or a plan that ends short.
const BLIND_FAILURES: [&str; 2] = ["action-failed", "goal-not-reached"];

/// Table I on every benchmark, one task per level: Logic-LfD (both modes) and TAMP solve every
/// task; the linear baseline solves the L1 task (the demonstration's facts) and fails only by
/// executing blindly, at least once where the initial state differs from the demonstration.
#[test]
fn table1_pattern_logic_lfd_and_tamp_solve_every_task_linear_fails_blindly() {
    let mut failed: Vec<String> = vec![];
    let t = table1(
        &Benchmark::ALL,
        4,
        1,
        SessionParams::default(),
        &NoClock,
        &mut |m| {
            if m.contains("failed") {
                failed.push(m.to_string())
            }
        },
    )
    .expect("table I runs");
    assert_eq!(t.cells.len(), 12);
    for c in &t.cells {
        let tag = format!("{:?} {}: {:?}", c.benchmark, c.method_label(), c.failures);
        assert_eq!(c.tasks, 4, "{tag}");
        let failures: usize = c.failures.iter().map(|(_, n)| n).sum();
        assert_eq!(
            c.successes + failures,
            c.tasks,
            "{tag}: a failure without a reason"
        );
        if c.method != Method::Linear {
            assert_eq!(c.successes, 4, "{tag}");
            continue;
        }
        assert!(c.successes < 4, "{tag}: linear solved every task");
        for (kind, _) in &c.failures {
            assert!(BLIND_FAILURES.contains(&kind.as_str()), "{tag}");
        }
    }
    // Task 0 is the L1 task: its facts are the demonstration's, so blind execution works.
    assert!(
        !failed.iter().any(|m| m.contains("task 0 (L1) linear")),
        "{failed:?}"
    );
}

fn successes(c: &Table2Cell) -> usize {
    c.times.len()
}

/// Table II on every benchmark, two trials per cell: Logic-LfD succeeds at every level; RLDS at
/// L1–L2, and at L3–L4 fails because no demonstration state matches; the linear baseline succeeds
/// at L1 and fails blindly at L2–L4 (on B2 it may still succeed: its skills re-target the pull to
/// the moved block, `docs/levels.md`).
#[test]
fn table2_pattern_follows_the_paper() {
    let t = table2(
        &Benchmark::ALL,
        2,
        1,
        SessionParams::default(),
        &NoClock,
        &mut |_| {},
    )
    .expect("table II runs");
    assert_eq!(t.cells.len(), 4 * 3 * 3);
    for c in &t.cells {
        let tag = format!(
            "{:?} {:?} {:?}: {}/{} ({} not injected) {:?}",
            c.level,
            c.method,
            c.benchmark,
            successes(c),
            c.trials,
            c.not_injected,
            c.failures
        );
        let injected = c.trials - c.not_injected;
        assert!(injected > 0, "{tag}: the level was never injected");
        let failures: usize = c.failures.iter().map(|(_, n)| n).sum();
        assert_eq!(successes(c) + failures, injected, "{tag}");
        let kinds_are = |allowed: &[&str]| {
            c.failures
                .iter()
                .all(|(k, _)| allowed.contains(&k.as_str()))
        };
        match (c.method, c.level) {
            (Method::LogicLfd, _) | (_, Level::L1) | (Method::Rlds, Level::L2) => {
                assert_eq!(successes(c), injected, "{tag}")
            }
            (Method::Rlds, _) => {
                assert_eq!(successes(c), 0, "{tag}");
                assert!(kinds_are(&["no-demo-state-matches"]), "{tag}");
            }
            (Method::Linear, _) => {
                if c.benchmark != Benchmark::B2 {
                    assert_eq!(successes(c), 0, "{tag}");
                }
                assert!(kinds_are(&BLIND_FAILURES), "{tag}");
            }
            _ => panic!("{tag}: not a Table II method"),
        }
    }
}

/// The redraw rule accepts every template and refuses a block no arm can grasp: on B1 beyond
/// the arm's reach, on B2 inside the arm's minimum reach (a pull only brings a block nearer).
#[test]
fn infeasible_accepts_the_templates_and_refuses_unworkable_blocks() {
    for b in Benchmark::ALL {
        assert_eq!(infeasible(&b.scene()), None, "{b:?} template");
    }
    let far = |b: Benchmark, at: [f64; 2]| -> World {
        let mut w = b.scene();
        w.move_block_to("a", Vector3::new(at[0], at[1], 0.03), 0.0)
            .expect("the table has room there");
        w
    };
    let why = infeasible(&far(Benchmark::B1, [0.9, 0.55])).expect("beyond reach");
    assert!(why.contains("block a"), "{why}");
    let why = infeasible(&far(Benchmark::B2, [0.12, 0.12])).expect("inside the minimum reach");
    assert!(why.contains("block a"), "{why}");
    // Moved within reach instead, the same block is fine.
    assert_eq!(infeasible(&far(Benchmark::B1, [0.45, 0.35])), None);
}

/// A Table I draw the rule refuses is redrawn: B2's task 18 of seed 1 (an L3 task) takes a
/// second draw, and the draw it keeps is feasible.
#[test]
fn an_infeasible_table1_draw_is_redrawn() {
    let seed = table1_task_seed(Benchmark::B2, 18, 1);
    let (scene, draw) = table1_scene(Benchmark::B2, Level::L3, seed).unwrap();
    assert_eq!(draw, 1);
    let kept = World::from_json(&scene)
        .unwrap()
        .with_motions(Benchmark::B2.motions());
    assert_eq!(infeasible(&kept), None);
    let first = logic_lfd::experiments::initial_scene(Benchmark::B2, Level::L3, seed).unwrap();
    let first = World::from_json(&first)
        .unwrap()
        .with_motions(Benchmark::B2.motions());
    assert!(infeasible(&first).is_some());
}

/// The sweep's parts as the page joins them: each level's report holds that level's tasks alone
/// and the levels add up to the whole table; re-plans count those after the first plan (the
/// linear baseline, which never replans, has none); an episode of one method re-runs as the
/// sweep ran it; failure kinds fall into logic, motion and budget; a Wilson interval holds its rate.
#[test]
fn table1_sweep_parts_add_up_by_level() {
    use logic_lfd::experiments::{failure_group, wilson, Table1Sweep, Table1Task};
    let sweep = Table1Sweep {
        benchmarks: vec![Benchmark::B1],
        tasks: 5,
        seed: 1,
        tamp_fallback: false,
        robots: vec![],
    };
    let items: Vec<Table1Task> = (0..sweep.items())
        .map(|i| sweep.run(i, SessionParams::default(), &NoClock, &mut |_| {}))
        .collect::<Result<_, _>>()
        .expect("the items run");
    let whole = sweep.report(items.clone());
    assert_eq!(whole.cells[0].replans, vec![0; 5], "linear never replans");
    let levels: Vec<_> = Level::ALL
        .iter()
        .map(|&l| sweep.report_level(items.clone(), l))
        .collect();
    assert_eq!(levels[0].cells[0].tasks, 2, "tasks 0 and 4 are at L1");
    for (k, cell) in whole.cells.iter().enumerate() {
        let tasks: usize = levels.iter().map(|t| t.cells[k].tasks).sum();
        let successes: usize = levels.iter().map(|t| t.cells[k].successes).sum();
        assert_eq!((tasks, successes), (cell.tasks, cell.successes));
        assert_eq!(cell.replans.len(), cell.tasks);
    }
    let episode = sweep
        .episode(2, 1, SessionParams::default(), &NoClock)
        .expect("TAMP's episode of task 2");
    assert_eq!(episode.success, items[2].runs[1].success_actions.is_some());
    assert_eq!(episode.replans.saturating_sub(1), items[2].runs[1].replans);
    assert_eq!(failure_group("out-of-reach"), "motion");
    assert_eq!(failure_group("action-failed"), "motion");
    assert_eq!(failure_group("budget"), "budget");
    assert_eq!(failure_group("no-plan"), "logic");
    let (lo, hi) = wilson(3, 10);
    assert!(lo < 0.3 && 0.3 < hi && lo > 0.1 && hi < 0.61, "{lo} {hi}");
    assert_eq!(wilson(0, 0), (0.0, 1.0));
}
