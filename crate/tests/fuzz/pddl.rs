//! PDDL domain/problem, extending the token-level mutation tests of `tests/pddl` (IPC files) with
//! *structural* edits on the three benchmark domains and problems (the library's mutator,
//! `experiments::fuzz::PddlEdit`): whole s-expressions deleted, swapped, duplicated or moved,
//! names replaced by other names of the same file, pathological nesting, character edits.
//! Asserts no panic, errors located inside the text (`file:line:col`), and that whatever parses
//! also grounds (or fails with a typed error) without panicking.

use logic_lfd::experiments::fuzz::{pddl_error_in_bounds as in_bounds, FuzzTarget};
use logic_lfd::pddl::parse_domain;

use super::run_target;

#[test]
fn structurally_mutated_benchmark_domains_and_problems_never_panic_and_errors_are_located() {
    let (accepted, refused) = run_target(FuzzTarget::Pddl, 1600, 14, 3);
    assert!(
        accepted > 0 && refused > 0,
        "{accepted} accepted, {refused} refused"
    );
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
