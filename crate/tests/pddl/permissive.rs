//! PDDL that Fast Downward, VAL and pyperplan read and that is easy to refuse by mistake: names
//! written against a variable, and a type declared under a parent and again under a subtype of
//! it. What stays unsupported is still refused by name.

use logic_lfd::pddl::{parse_domain, parse_problem};

/// Zenotravel-like: `(aircraft?a)` with no space before the variable.
const TIGHT: &str = "(define (domain tight) (:requirements :strips)
  (:predicates (aircraft ?a) (at ?a ?c) (city ?c))
  (:action fly :parameters (?a ?from ?to)
    :precondition (and (aircraft?a) (city?from) (city ?to) (at ?a?from))
    :effect (and (at ?a ?to) (not (at ?a ?from)))))";

#[test]
fn a_name_ends_where_a_variable_starts() {
    let tight = parse_domain(TIGHT, "tight.pddl").expect("read as FD reads it");
    let spaced = parse_domain(
        &TIGHT
            .replace("(aircraft?a)", "(aircraft ?a)")
            .replace("(city?from)", "(city ?from)")
            .replace("?a?from", "?a ?from"),
        "spaced.pddl",
    )
    .unwrap();
    assert_eq!(
        format!("{:?}", tight.actions[0].precondition).replace(char::is_numeric, ""),
        format!("{:?}", spaced.actions[0].precondition).replace(char::is_numeric, ""),
        "the same formula, spans aside"
    );
    let p = parse_problem(
        "(define (problem p) (:domain tight) (:objects plane c1 c2)
           (:init (aircraft plane) (city c1) (city c2) (at plane c1)) (:goal (at plane c2)))",
        "p.pddl",
        &tight,
    )
    .unwrap();
    assert_eq!(p.objects.len(), 3);
}

/// IPC-2006 storage's declaration: `area` under `object`, then under `surface`.
const STORAGE_TYPES: &str = "(:types hoist surface place area - object
        container depot - place
        storearea transitarea - area
        area crate - surface)";

fn with_types(types: &str) -> String {
    format!(
        "(define (domain typed) (:requirements :strips :typing) {types}
           (:predicates (on ?c - crate ?s - surface) (in ?x - area ?p - place))
           (:action noop :parameters (?c - crate ?a - storearea)
             :precondition (on ?c ?a) :effect (not (on ?c ?a))))"
    )
}

#[test]
fn a_type_redeclared_under_a_subtype_takes_the_most_specific_parent() {
    let d = parse_domain(&with_types(STORAGE_TYPES), "storage.pddl").expect("storage's types");
    let t = |n: &str| d.type_index(n).unwrap_or_else(|| panic!("type {n}"));
    assert!(d.is_subtype(t("area"), t("surface")));
    assert!(d.is_subtype(t("storearea"), t("surface")), "through area");
    assert!(d.is_subtype(t("crate"), t("surface")));
    assert!(!d.is_subtype(t("place"), t("surface")));
    // Declared twice under the same parent: one declaration.
    let d = parse_domain(
        &with_types(
            "(:types surface place area crate - object storearea - area area - surface crate - surface crate - surface)",
        ),
        "twice.pddl",
    )
    .unwrap();
    assert!(d.is_subtype(
        d.type_index("crate").unwrap(),
        d.type_index("surface").unwrap()
    ));
}

#[test]
fn two_unrelated_parents_are_refused_by_name() {
    let text =
        with_types("(:types surface place area crate - object storearea - area storearea - place)");
    let e = parse_domain(&text, "two.pddl").expect_err("multiple inheritance");
    assert!(
        e.message
            .contains("type `storearea` is declared under both `area` and `place`"),
        "{e}"
    );
    // Located at the second declaration.
    let at = text.rfind("storearea - place").unwrap();
    let line = text[..at].matches('\n').count() + 1;
    let col = at - text[..at].rfind('\n').map_or(0, |n| n + 1) + 1;
    assert_eq!((e.line, e.col), (line, col), "{e}");
}

#[test]
fn a_cycle_through_redeclared_types_is_refused() {
    let e = parse_domain(
        &with_types("(:types surface place area crate storearea - object a - b b - c c - a)"),
        "cycle.pddl",
    )
    .expect_err("a cycle");
    assert!(e.message.contains("cycle"), "{e}");
}

#[test]
fn past_the_types_the_unsupported_construct_is_named() {
    let text = with_types(STORAGE_TYPES).replace(
        "(in ?x - area ?p - place)",
        "(in ?x - (either storearea crate) ?p - place)",
    );
    let e = parse_domain(&text, "storage.pddl").expect_err("union types");
    assert!(e.message.contains("`either`"), "{e}");
}
