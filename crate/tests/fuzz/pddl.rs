//! PDDL domain/problem, extending the token-level mutation tests of `tests/pddl` (IPC files) with
//! *structural* edits on the three benchmark domains: whole s-expressions deleted, swapped,
//! duplicated or moved into another list, names replaced by other names of the same file, and
//! pathological nesting. Asserts no panic, errors located inside the text (`file:line:col`), and
//! that whatever parses also grounds (or fails with a typed error) without panicking.

use logic_lfd::pddl::{parse_domain, parse_problem, PddlError};
use proptest::prelude::*;

use super::{domain_file, no_panic, runner};

const BENCHES: [&str; 3] = ["b1-tower", "b2-workspace-reach", "b3-dual-arm"];

fn in_bounds(text: &str, e: &PddlError) -> bool {
    let lines: Vec<&str> = text.split('\n').collect();
    e.line >= 1
        && e.line <= lines.len()
        && e.col >= 1
        && e.col <= lines[e.line - 1].chars().count() + 1
}

/// Byte ranges of every balanced `( … )` of the text (comments are not special here: an edit
/// that cuts a comment is just another mutation).
fn lists(text: &str) -> Vec<(usize, usize)> {
    let mut open = Vec::new();
    let mut out = Vec::new();
    for (i, c) in text.char_indices() {
        match c {
            '(' => open.push(i),
            ')' => {
                if let Some(s) = open.pop() {
                    out.push((s, i + 1));
                }
            }
            _ => {}
        }
    }
    out
}

/// Byte ranges of every name (a run of non-space, non-paren characters).
fn names(text: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in text
        .char_indices()
        .chain(std::iter::once((text.len(), ' ')))
    {
        let sep = c == '(' || c == ')' || c.is_whitespace();
        match (start, sep) {
            (None, false) => start = Some(i),
            (Some(s), true) => {
                out.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    out
}

#[derive(Clone, Debug)]
enum Edit {
    /// Delete the i-th list.
    DeleteList(usize),
    /// Put a copy of list j right after list i.
    CopyList(usize, usize),
    /// Swap the texts of lists i and j (when they do not overlap).
    SwapLists(usize, usize),
    /// Replace name i by name j.
    Rename(usize, usize),
    /// Wrap list i in `n` more parentheses.
    Nest(usize, u16),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        1 => any::<usize>().prop_map(Edit::DeleteList),
        1 => (any::<usize>(), any::<usize>()).prop_map(|(i, j)| Edit::CopyList(i, j)),
        1 => (any::<usize>(), any::<usize>()).prop_map(|(i, j)| Edit::SwapLists(i, j)),
        3 => (any::<usize>(), any::<usize>()).prop_map(|(i, j)| Edit::Rename(i, j)),
        1 => (any::<usize>(), 1u16..300).prop_map(|(i, n)| Edit::Nest(i, n)),
    ]
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut t = text.to_string();
    for e in edits {
        let ls = lists(&t);
        let ns = names(&t);
        if ls.is_empty() || ns.is_empty() {
            break;
        }
        let l = |i: usize| ls[i % ls.len()];
        let n = |i: usize| ns[i % ns.len()];
        match *e {
            Edit::DeleteList(i) => {
                let (s, e) = l(i);
                t.replace_range(s..e, "");
            }
            Edit::CopyList(i, j) => {
                let (_, e) = l(i);
                let (s2, e2) = l(j);
                let copy = format!(" {}", &t[s2..e2]);
                t.insert_str(e, &copy);
            }
            Edit::SwapLists(i, j) => {
                let (a, b) = (l(i), l(j));
                let (first, second) = if a.0 < b.0 { (a, b) } else { (b, a) };
                if first.1 <= second.0 {
                    let x = t[first.0..first.1].to_string();
                    let y = t[second.0..second.1].to_string();
                    t.replace_range(second.0..second.1, &x);
                    t.replace_range(first.0..first.1, &y);
                }
            }
            Edit::Rename(i, j) => {
                let (s, e) = n(i);
                let (s2, e2) = n(j);
                let name = t[s2..e2].to_string();
                t.replace_range(s..e, &name);
            }
            Edit::Nest(i, k) => {
                let (s, e) = l(i);
                t.insert_str(e, &")".repeat(k as usize));
                t.insert_str(s, &"(".repeat(k as usize));
            }
        }
    }
    t
}

fn check_domain_then_problem(dom: &str, prob: &str) -> Result<(), TestCaseError> {
    match no_panic("parse_domain", || parse_domain(dom, "m.pddl"))? {
        Err(e) => {
            prop_assert!(in_bounds(dom, &e), "domain error out of bounds: {e}");
            prop_assert!(e.to_string().starts_with("m.pddl:"));
        }
        Ok(d) => match no_panic("parse_problem", || parse_problem(prob, "p.pddl", &d))? {
            Err(e) => prop_assert!(in_bounds(prob, &e), "problem error out of bounds: {e}"),
            Ok(p) => {
                let _ = no_panic("ground", || logic_lfd::plan::ground(&d, &p))?;
            }
        },
    }
    Ok(())
}

#[test]
fn structurally_mutated_benchmark_domains_never_panic_and_errors_are_located() {
    let files: Vec<(String, String)> = BENCHES
        .iter()
        .map(|b| {
            (
                domain_file(b, "domain.pddl"),
                domain_file(b, "problem.pddl"),
            )
        })
        .collect();
    runner(700, 14)
        .run(
            &(0..files.len(), prop::collection::vec(edit(), 1..4)),
            |(k, edits)| {
                let dom = apply(&files[k].0, &edits);
                check_domain_then_problem(&dom, &files[k].1)
            },
        )
        .unwrap();
}

#[test]
fn structurally_mutated_benchmark_problems_never_panic_and_errors_are_located() {
    let files: Vec<(String, String)> = BENCHES
        .iter()
        .map(|b| {
            (
                domain_file(b, "domain.pddl"),
                domain_file(b, "problem.pddl"),
            )
        })
        .collect();
    runner(900, 15)
        .run(
            &(0..files.len(), prop::collection::vec(edit(), 1..4)),
            |(k, edits)| {
                let prob = apply(&files[k].1, &edits);
                check_domain_then_problem(&files[k].0, &prob)
            },
        )
        .unwrap();
}

/// Pathological nesting (`((((…))))` 100 000 deep, unclosed or closed) is refused with a located
/// error, not a stack overflow (which would abort the process, and freeze a page's worker).
#[test]
fn deeply_nested_pddl_is_refused_without_stack_overflow() {
    for (name, text) in [
        ("unclosed", "(".repeat(100_000)),
        (
            "closed",
            format!("{}{}", "(".repeat(100_000), ")".repeat(100_000)),
        ),
        (
            "inside a domain",
            format!(
                "(define (domain d) (:predicates (p)) (:action a :parameters () :precondition {}(p){} :effect (p)))",
                "(and ".repeat(50_000),
                ")".repeat(50_000)
            ),
        ),
    ] {
        // A thread with a small stack, as a browser worker or a small CLI stack would have.
        let t = text.clone();
        let r = std::thread::Builder::new()
            .stack_size(1 << 20)
            .spawn(move || parse_domain(&t, "deep.pddl").map(|_| ()))
            .unwrap()
            .join();
        let r = r.unwrap_or_else(|_| panic!("{name}: the parser panicked"));
        if let Err(e) = r {
            assert!(in_bounds(&text, &e), "{name}: {e}");
        }
        let plan = text.clone();
        let r = std::thread::Builder::new()
            .stack_size(1 << 20)
            .spawn(move || logic_lfd::plan::parse_plan(&plan, "deep.plan").map(|_| ()))
            .unwrap()
            .join();
        assert!(r.is_ok(), "{name}: parse_plan panicked");
    }
}
