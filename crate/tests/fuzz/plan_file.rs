//! Plan files for `validate` (`plan::parse_plan` + `plan::validate`): mutated plans never panic;
//! a parse error or a malformed step is located inside the plan text; a precondition failure
//! names a 1-based step that exists and its location; a valid report applied every step.

use logic_lfd::pddl::{parse_domain, parse_problem, Domain, PddlError, Problem};
use logic_lfd::plan::{parse_plan, validate, Outcome};
use proptest::prelude::*;

use super::{domain_file, no_panic, runner};

fn rooms(file: &str) -> String {
    let p = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/pddl/rooms");
    std::fs::read_to_string(format!("{p}/{file}")).unwrap()
}

/// (domain, problem, plan text) triples: the rooms plan with costs and every benchmark demo.
fn corpus() -> Vec<(Domain, Problem, String)> {
    let mut out = Vec::new();
    let d = parse_domain(&rooms("domain.pddl"), "d.pddl").unwrap();
    let p = parse_problem(&rooms("p-costs.pddl"), "p.pddl", &d).unwrap();
    out.push((d, p, rooms("plan-costs.plan")));
    for b in ["b1-tower", "b2-workspace-reach", "b3-dual-arm"] {
        let d = parse_domain(&domain_file(b, "domain.pddl"), "d.pddl").unwrap();
        let p = parse_problem(&domain_file(b, "problem.pddl"), "p.pddl", &d).unwrap();
        let demo = logic_lfd::lfd::session::demo_actions(&domain_file(b, "demo.json")).unwrap();
        out.push((d, p, demo.join("\n") + "\n"));
    }
    out
}

fn in_bounds(text: &str, e: &PddlError) -> bool {
    let lines: Vec<&str> = text.split('\n').collect();
    e.line >= 1
        && e.line <= lines.len()
        && e.col >= 1
        && e.col <= lines[e.line - 1].chars().count() + 1
}

#[derive(Clone, Debug)]
enum Edit {
    /// Delete the i-th character.
    Delete(usize),
    /// Insert a fragment before the i-th character.
    Insert(usize, &'static str),
    /// Swap two lines.
    SwapLines(usize, usize),
    /// Duplicate a line.
    DupLine(usize),
    /// Cut the text.
    Truncate(usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    let frag = prop::sample::select(vec![
        "(",
        ")",
        " ",
        "\n",
        ";",
        "x",
        "(stack a b)",
        "(pick panda zz)",
        "()",
        "((",
        "-",
        "?x",
        "é",
        "\t",
        "(unstack a a)",
        "panda",
        "hall",
    ]);
    prop_oneof![
        any::<usize>().prop_map(Edit::Delete),
        (any::<usize>(), frag).prop_map(|(i, f)| Edit::Insert(i, f)),
        (any::<usize>(), any::<usize>()).prop_map(|(i, j)| Edit::SwapLines(i, j)),
        any::<usize>().prop_map(Edit::DupLine),
        any::<usize>().prop_map(Edit::Truncate),
    ]
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for e in edits {
        let n = chars.len();
        match e {
            Edit::Delete(i) if n > 0 => {
                chars.remove(i % n);
            }
            Edit::Insert(i, f) => {
                let at = i % (n + 1);
                chars.splice(at..at, f.chars());
            }
            Edit::Truncate(i) => chars.truncate(i % (n + 1)),
            Edit::SwapLines(i, j) | Edit::DupLine(i @ j) if n > 0 => {
                let s: String = chars.iter().collect();
                let mut lines: Vec<String> = s.split('\n').map(str::to_string).collect();
                let m = lines.len();
                if matches!(e, Edit::DupLine(_)) {
                    let l = lines[i % m].clone();
                    lines.insert(i % m, l);
                } else {
                    lines.swap(i % m, j % m);
                }
                chars = lines.join("\n").chars().collect();
            }
            _ => {}
        }
    }
    chars.into_iter().collect()
}

#[test]
fn mutated_plans_never_panic_and_failures_are_located() {
    let corpus = corpus();
    runner(3500, 12)
        .run(
            &(0..corpus.len(), prop::collection::vec(edit(), 1..5)),
            |(k, edits)| {
                let (d, p, plan) = &corpus[k];
                let text = apply(plan, &edits);
                let steps = match no_panic("parse_plan", || parse_plan(&text, "m.plan"))? {
                    Err(e) => {
                        prop_assert!(in_bounds(&text, &e), "parse error out of bounds: {e}");
                        prop_assert_eq!(e.file.as_str(), "m.plan");
                        return Ok(());
                    }
                    Ok(s) => s,
                };
                let report = no_panic("validate", || validate(d, p, &steps))?;
                match &report.outcome {
                    Outcome::Valid => prop_assert_eq!(report.steps_applied, steps.len()),
                    Outcome::Malformed(e) => {
                        prop_assert!(in_bounds(&text, e), "malformed step out of bounds: {e}");
                        prop_assert_eq!(e.file.as_str(), "m.plan");
                    }
                    Outcome::PreconditionFalse {
                        step,
                        location,
                        false_literals,
                        ..
                    } => {
                        prop_assert!(*step >= 1 && *step <= steps.len());
                        prop_assert_eq!(report.steps_applied, step - 1);
                        prop_assert!(location.starts_with("m.plan:"), "{}", location);
                        prop_assert!(!false_literals.is_empty());
                    }
                    Outcome::GoalNotReached { false_literals } => {
                        prop_assert_eq!(report.steps_applied, steps.len());
                        prop_assert!(!false_literals.is_empty());
                    }
                }
                Ok(())
            },
        )
        .unwrap();
}
