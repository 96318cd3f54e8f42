//! Search and heuristics: optimality against brute force, admissibility, plan validity, budgets.

use logic_lfd::pddl::{Domain, Problem};
use logic_lfd::plan::{
    search, validate_names, Algorithm, Budget, Clock, Condition, Goal, HeuristicEvaluator,
    HeuristicKind, NoClock, Operator, Plan, SearchConfig, SearchOutcome, State, Task,
};
use proptest::prelude::*;
use proptest::test_runner::{Config as PtConfig, RngAlgorithm, TestRng, TestRunner};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::cell::Cell;
use std::collections::{BinaryHeap, HashMap};

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

// ----------------------------------------------------------------------------------------------
// Generators.

fn cond(pos: Vec<u32>) -> Condition {
    Condition { pos, neg: vec![] }
}

/// A PDDL task: the parsed domain and problem (for the lifted validator) and the grounded task.
pub struct Case {
    /// The parsed domain.
    pub domain: Domain,
    /// The parsed problem.
    pub problem: Problem,
    /// The grounded task.
    pub task: Task,
}

impl Case {
    /// Parses and grounds PDDL text.
    pub fn from_text(domain: &str, problem: &str) -> Case {
        let d = logic_lfd::pddl::parse_domain(domain, "domain.pddl").unwrap();
        let p = logic_lfd::pddl::parse_problem(problem, "problem.pddl", &d).unwrap();
        let task = logic_lfd::plan::ground(&d, &p).unwrap();
        Case {
            domain: d,
            problem: p,
            task,
        }
    }

    /// Asserts that `plan` is valid: by `Operator::apply` replay on the task and by the lifted
    /// validator on the PDDL domain and problem (same cost).
    pub fn assert_valid(&self, plan: &Plan) {
        assert_valid(&self.task, plan);
        let names: Vec<String> = plan
            .names(&self.task)
            .into_iter()
            .map(String::from)
            .collect();
        let report = validate_names(&self.domain, &self.problem, &names);
        assert!(report.is_valid(), "lifted validator: {report}");
        assert_eq!(report.cost, plan.cost, "lifted validator cost");
    }
}

/// The IPC blocks domain (4 operators, untyped).
pub fn blocks_domain() -> String {
    std::fs::read_to_string(ipc("blocks/domain.pddl")).unwrap()
}

/// An n-block IPC blocksworld problem from `init` towers to `goal` towers (each tower listed
/// bottom to top, blocks `b0..`).
pub fn blocksworld(n: usize, init: &[Vec<usize>], goal: &[Vec<usize>]) -> Case {
    let mut text = String::from("(define (problem bw) (:domain BLOCKS) (:objects");
    for i in 0..n {
        text += &format!(" b{i}");
    }
    text += ") (:init (handempty)";
    for t in init {
        text += &format!(" (ontable b{}) (clear b{})", t[0], t.last().unwrap());
        for w in t.windows(2) {
            text += &format!(" (on b{} b{})", w[1], w[0]);
        }
    }
    text += ") (:goal (and";
    for t in goal {
        for w in t.windows(2) {
            text += &format!(" (on b{} b{})", w[1], w[0]);
        }
    }
    text += ")))";
    Case::from_text(&blocks_domain(), &text)
}

/// Random towers of blocks `0..n`.
pub fn random_towers(n: usize, rng: &mut Pcg64Mcg) -> Vec<Vec<usize>> {
    let mut blocks: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        blocks.swap(i, rng.random_range(0..=i));
    }
    let mut towers: Vec<Vec<usize>> = Vec::new();
    for x in blocks {
        match towers.last_mut() {
            Some(t) if rng.random_bool(0.6) => t.push(x),
            _ => towers.push(vec![x]),
        }
    }
    towers
}

/// A random blocksworld problem with `n` blocks.
pub fn random_blocksworld(n: usize, seed: u64) -> Case {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let init = random_towers(n, &mut rng);
    let goal = random_towers(n, &mut rng);
    blocksworld(n, &init, &goal)
}

fn random_condition(rng: &mut Pcg64Mcg, n: usize, neg: bool) -> Condition {
    let mut c = Condition::default();
    for f in 0..n as u32 {
        let r: f64 = rng.random();
        if r < 0.25 {
            c.pos.push(f);
        } else if neg && r < 0.33 {
            c.neg.push(f);
        }
    }
    c
}

fn pddl_conjunction(c: &Condition) -> String {
    let mut t = String::from("(and");
    for f in &c.pos {
        t += &format!(" (p{f})");
    }
    for f in &c.neg {
        t += &format!(" (not (p{f}))");
    }
    t + ")"
}

/// A random propositional PDDL task over `n ≤ 7` facts with negative preconditions, an
/// or-goal and (unless `unit_cost`) action costs 0..=3.
pub fn random_case(seed: u64, unit_cost: bool) -> Case {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let n = rng.random_range(3..=7usize);
    let m = rng.random_range(2..=12usize);
    let mut d = String::from("(define (domain rnd) (:requirements :strips :negative-preconditions :disjunctive-preconditions");
    d += if unit_cost { ")" } else { " :action-costs)" };
    d += " (:predicates";
    for f in 0..n {
        d += &format!(" (p{f})");
    }
    d += ")";
    if !unit_cost {
        d += " (:functions (total-cost) - number)";
    }
    for i in 0..m {
        let pre = random_condition(&mut rng, n, true);
        let mut eff = String::from("(and");
        for f in 0..n {
            let r: f64 = rng.random();
            if r < 0.3 {
                eff += &format!(" (p{f})");
            } else if r < 0.55 {
                eff += &format!(" (not (p{f}))");
            }
        }
        if !unit_cost {
            eff += &format!(" (increase (total-cost) {})", rng.random_range(0..=3));
        }
        eff += ")";
        d += &format!(
            " (:action op{i} :parameters () :precondition {} :effect {eff})",
            pddl_conjunction(&pre)
        );
    }
    d += ")";
    let mut p = String::from("(define (problem r) (:domain rnd) (:init");
    for f in 0..n {
        if rng.random_bool(0.4) {
            p += &format!(" (p{f})");
        }
    }
    if !unit_cost {
        p += " (= (total-cost) 0)";
    }
    p += ") (:goal (or";
    for _ in 0..rng.random_range(1..=2) {
        p += " ";
        p += &pddl_conjunction(&random_condition(&mut rng, n, true));
    }
    p += "))";
    if !unit_cost {
        p += " (:metric minimize (total-cost))";
    }
    p += ")";
    Case::from_text(&d, &p)
}

/// The grounded task of [`random_case`].
pub fn random_task(seed: u64, unit_cost: bool) -> Task {
    random_case(seed, unit_cost).task
}

/// A random DNF goal with 1–2 alternatives.
pub fn random_goal(rng: &mut Pcg64Mcg, n: usize, terminal_cost: u64) -> Goal {
    let k = rng.random_range(1..=2);
    Goal {
        alternatives: (0..k).map(|_| random_condition(rng, n, true)).collect(),
        terminal_cost,
    }
}

// ----------------------------------------------------------------------------------------------
// Brute force.

/// All states reachable from `start` (breadth-first), and the successor lists.
pub fn reachable(task: &Task, start: &State) -> (Vec<State>, Vec<Vec<(usize, u64)>>) {
    let mut index: HashMap<State, usize> = HashMap::from([(start.clone(), 0)]);
    let mut states = vec![start.clone()];
    let mut succ = Vec::new();
    let mut i = 0;
    while i < states.len() {
        let s = states[i].clone();
        let mut out = Vec::new();
        for op in &task.operators {
            if op.applicable(&s) {
                let t = op.apply(&s);
                let j = *index.entry(t.clone()).or_insert_with(|| {
                    states.push(t);
                    states.len() - 1
                });
                out.push((j, op.cost as u64));
            }
        }
        succ.push(out);
        i += 1;
    }
    (states, succ)
}

/// `min_k (cost of a cheapest path from s to a G_k state + c_k)` by Dijkstra, `None` if no goal
/// is reachable.
pub fn brute_force_cost(task: &Task, start: &State, goals: &[Goal]) -> Option<u64> {
    let (states, succ) = reachable(task, start);
    let mut dist = vec![u64::MAX; states.len()];
    let mut heap = BinaryHeap::from([std::cmp::Reverse((0u64, 0usize))]);
    dist[0] = 0;
    let mut best: Option<u64> = None;
    while let Some(std::cmp::Reverse((d, i))) = heap.pop() {
        if d > dist[i] {
            continue;
        }
        for g in goals {
            if g.holds(&states[i]) {
                let v = d + g.terminal_cost;
                best = Some(best.map_or(v, |b: u64| b.min(v)));
            }
        }
        for &(j, c) in &succ[i] {
            if d + c < dist[j] {
                dist[j] = d + c;
                heap.push(std::cmp::Reverse((d + c, j)));
            }
        }
    }
    best
}

/// Fewest steps from `start` to any goal state (breadth-first), `None` if unreachable.
pub fn brute_force_length(task: &Task, start: &State, goals: &[Goal]) -> Option<u64> {
    let unit: Vec<Operator> = task
        .operators
        .iter()
        .map(|o| Operator {
            cost: 1,
            ..o.clone()
        })
        .collect();
    let t = Task::new(
        task.facts.clone(),
        unit,
        task.init.clone(),
        task.goal.clone(),
        vec![],
        false,
    );
    let zero: Vec<Goal> = goals
        .iter()
        .map(|g| Goal {
            alternatives: g.alternatives.clone(),
            terminal_cost: 0,
        })
        .collect();
    brute_force_cost(&t, start, &zero)
}

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

// ----------------------------------------------------------------------------------------------
// Tests.

#[test]
fn names_parse_and_print() {
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

// ----------------------------------------------------------------------------------------------
// IPC benchmarks and the CLI.

/// The shared IPC benchmark folder.
pub fn ipc(path: &str) -> std::path::PathBuf {
    std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/ipc")).join(path)
}

/// Parses and grounds an IPC problem.
pub fn ipc_case(domain: &str, problem: &str) -> Case {
    let read = |p: &str| std::fs::read_to_string(ipc(p)).unwrap();
    Case::from_text(&read(domain), &read(problem))
}

/// Problem file names of an IPC folder, sorted.
fn ipc_problems(dir: &str) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(ipc(dir))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".pddl") && n != "domain.pddl")
        .collect();
    v.sort();
    v
}

#[test]
fn optimal_configs_agree_on_small_ipc_problems() {
    let cases: Vec<(&str, Vec<String>)> = vec![
        (
            "blocks",
            ipc_problems("blocks")
                .into_iter()
                .filter(|p| p.contains("-4-") || p.contains("-5-") || p.contains("-6-"))
                .collect(),
        ),
        ("gripper", vec!["prob01.pddl".into()]),
        ("logistics00", vec!["probLOGISTICS-4-0.pddl".into()]),
        ("depot-typed", vec!["p01.pddl".into()]),
    ];
    let mut compared = 0;
    for (dir, problems) in cases {
        for prob in problems {
            let case = ipc_case(&format!("{dir}/domain.pddl"), &format!("{dir}/{prob}"));
            let task = &case.task;
            let mut costs = Vec::new();
            for (alg, h) in OPTIMAL {
                let cfg = SearchConfig {
                    max_nodes: Some(20_000),
                    ..SearchConfig::new(alg, h)
                };
                let r = search(task, &cfg, &NoClock);
                match &r.outcome {
                    SearchOutcome::Plan(p) => {
                        case.assert_valid(p);
                        costs.push((alg, h, p.cost));
                    }
                    SearchOutcome::BudgetExhausted { .. } => {}
                    SearchOutcome::Unsolvable => panic!("{dir}/{prob} {alg} {h}: unsolvable"),
                }
            }
            // LM-cut solves every one of these within the budget.
            assert!(
                costs.iter().any(|c| c.1 == HeuristicKind::LmCut),
                "{dir}/{prob}"
            );
            for w in costs.windows(2) {
                assert_eq!(w[0].2, w[1].2, "{dir}/{prob}: {:?}", costs);
            }
            compared += costs.len();
        }
    }
    assert!(compared > 40);
}

#[test]
fn satisficing_plans_are_valid_on_ipc_blocks_gripper_logistics() {
    let mut solved = 0;
    let mut total = 0;
    for dir in ["blocks", "gripper", "logistics00"] {
        for prob in ipc_problems(dir) {
            let case = ipc_case(&format!("{dir}/domain.pddl"), &format!("{dir}/{prob}"));
            for (alg, h) in [
                (Algorithm::LazyGbfs, HeuristicKind::HFf),
                (Algorithm::Gbfs, HeuristicKind::HFf),
                (Algorithm::LazyGbfs, HeuristicKind::HAdd),
            ] {
                let cfg = SearchConfig {
                    max_nodes: Some(3_000),
                    ..SearchConfig::new(alg, h)
                };
                let r = search(&case.task, &cfg, &NoClock);
                total += 1;
                match &r.outcome {
                    SearchOutcome::Plan(p) => {
                        case.assert_valid(p);
                        solved += 1;
                    }
                    SearchOutcome::BudgetExhausted { .. } => {}
                    SearchOutcome::Unsolvable => panic!("{dir}/{prob} {alg} {h}: unsolvable"),
                }
            }
        }
    }
    // Lazy GBFS with h_FF and preferred operators solves nearly all within the small budget.
    assert!(solved * 10 >= total * 8, "solved {solved} of {total}");
}

/// A domain where the goal room cannot be entered: `(move ?from ?to)` needs `(door ?from ?to)`.
const ONE_WAY_DOMAIN: &str = "(define (domain one-way)
  (:requirements :strips :negative-preconditions)
  (:predicates (at ?r) (door ?a ?b))
  (:action move :parameters (?a ?b)
    :precondition (and (at ?a) (door ?a ?b) (not (at ?b)))
    :effect (and (not (at ?a)) (at ?b))))";

const ONE_WAY_PROBLEM: &str = "(define (problem trapped) (:domain one-way)
  (:objects r1 r2 r3)
  (:init (at r1) (door r1 r2) (door r2 r1) (door r3 r1))
  (:goal (at r3)))";

fn run_cli(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn temp_files(tag: &str, files: &[(&str, &str)]) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("logic-lfd-search-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}

#[test]
fn cli_plan_exit_codes_and_output() {
    let dir = temp_files(
        "exit",
        &[
            ("domain.pddl", ONE_WAY_DOMAIN),
            ("problem.pddl", ONE_WAY_PROBLEM),
            (
                "bad.pddl",
                "(define (problem p) (:domain one-way)\n  (:init (at r9)",
            ),
        ],
    );
    let d = dir.join("domain.pddl");
    let d = d.to_str().unwrap();
    let p = dir.join("problem.pddl");
    let p = p.to_str().unwrap();
    // Proved unsolvable: exit 3, for the default and a satisficing configuration.
    for extra in [
        &[][..],
        &["--search", "lazy-gbfs", "--heuristic", "hff"][..],
    ] {
        let mut args = vec!["plan", d, p];
        args.extend_from_slice(extra);
        let (code, _, err) = run_cli(&args);
        assert_eq!(code, 3, "{err}");
        assert!(err.contains("unsolvable"), "{err}");
    }
    // Bad input: exit 2 with a located message.
    let bad = dir.join("bad.pddl");
    let (code, _, err) = run_cli(&["plan", d, bad.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("bad.pddl:"), "{err}");
    let (code, _, _) = run_cli(&["plan", d, p, "--heuristic", "ff"]);
    assert_eq!(code, 2);
    // Budget exhausted: exit 4.
    let bd = ipc("blocks/domain.pddl");
    let bp = ipc("blocks/probBLOCKS-8-0.pddl");
    let (bd, bp) = (bd.to_str().unwrap(), bp.to_str().unwrap());
    let (code, out, err) = run_cli(&["plan", bd, bp, "--max-nodes", "5", "--json"]);
    assert_eq!(code, 4, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["status"], "budget");
    assert_eq!(j["expanded"], 5);
    // A plan: IPC text, then the cost line; the JSON agrees and the plan replays.
    let bp = ipc("blocks/probBLOCKS-5-0.pddl");
    let bp = bp.to_str().unwrap();
    let (code, out, _) = run_cli(&["plan", bd, bp]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().filter(|l| !l.starts_with(';')).collect();
    assert!(out.contains(&format!("; cost = {} (unit cost)", lines.len())));
    let (code, out, _) = run_cli(&[
        "plan",
        bd,
        bp,
        "--search",
        "lazy-gbfs",
        "--heuristic",
        "hff",
        "--json",
    ]);
    assert_eq!(code, 0);
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    let case = ipc_case("blocks/domain.pddl", "blocks/probBLOCKS-5-0.pddl");
    let task = &case.task;
    let names: Vec<String> = j["plan"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap().to_string())
        .collect();
    let ops: Vec<usize> = names
        .iter()
        .map(|n| task.operators.iter().position(|o| &o.name == n).unwrap())
        .collect();
    let cost = ops.len() as u64;
    assert_valid(
        task,
        &Plan {
            operators: ops,
            cost,
        },
    );
    assert_eq!(j["length"], names.len());
    for key in [
        "cost",
        "expanded",
        "generated",
        "evaluated",
        "time_secs",
        "search",
        "heuristic",
    ] {
        assert!(!j[key].is_null(), "{key}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cli_bench_planner_prints_tables() {
    let blocks = ipc("blocks");
    let (code, out, err) = run_cli(&[
        "bench",
        "planner",
        blocks.to_str().unwrap(),
        "--configs",
        "astar:lmcut,lazy-gbfs:hff",
        "--filter",
        "BLOCKS-4-",
        "--time-limit",
        "10",
        "--markdown",
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.matches(":lmcut | solved |").count(), 3, "{out}");
    assert_eq!(out.matches(":hff | solved |").count(), 3, "{out}");
    assert!(out.contains("| astar:lmcut | blocks | 3/3 |"), "{out}");
    assert!(out.contains("| lazy-gbfs:hff | blocks | 3/3 |"), "{out}");
    let dir = temp_files(
        "bench",
        &[
            ("domain.pddl", ONE_WAY_DOMAIN),
            ("trapped.pddl", ONE_WAY_PROBLEM),
        ],
    );
    let (code, out, err) = run_cli(&["bench", "planner", dir.to_str().unwrap(), "--markdown"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("| trapped | lazy-gbfs:hff | unsolvable |"),
        "{out}"
    );
    let (code, _, _) = run_cli(&["bench", "planner", "--configs", "astar:ff"]);
    assert_eq!(code, 2);
    std::fs::remove_dir_all(&dir).ok();
}
