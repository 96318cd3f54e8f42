//! Search test tasks: PDDL cases checked by replay and by the lifted validator, random
//! propositional tasks and goals, random blocksworld, and the shared IPC benchmarks.

use logic_lfd::pddl::{Domain, Problem};
use logic_lfd::plan::{validate_names, Condition, Goal, Plan, Task};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::assert_valid;

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

/// The shared IPC benchmark folder.
pub fn ipc(path: &str) -> std::path::PathBuf {
    std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/ipc")).join(path)
}

/// Parses and grounds an IPC problem.
pub fn ipc_case(domain: &str, problem: &str) -> Case {
    let read = |p: &str| std::fs::read_to_string(ipc(p)).unwrap();
    Case::from_text(&read(domain), &read(problem))
}
