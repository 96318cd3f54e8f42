//! PDDL front end: refusals by name with line:col, located errors for wrong input, case
//! insensitivity, and property tests that mutate IPC files (never a panic, errors in bounds).

use logic_lfd::pddl::{decode_source, parse_domain, parse_problem, Domain, Formula, PddlError};

use crate::ground::{data_dir, ipc_dir};

mod brackets;
mod permissive;

fn read(path: &std::path::Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The `; expect LINE:COL NAME` first line of a refusal vector.
fn expectation(text: &str) -> (usize, usize, String) {
    let first = text.lines().next().unwrap();
    let rest = first
        .strip_prefix("; expect ")
        .expect("first line `; expect L:C NAME`");
    let (pos, name) = rest.split_once(' ').unwrap();
    let (l, c) = pos.split_once(':').unwrap();
    (l.parse().unwrap(), c.parse().unwrap(), name.to_string())
}

#[test]
fn every_refused_construct_is_named_at_its_location() {
    let dir = data_dir().join("refused");
    let base = parse_domain(&read(&dir.join("base-domain.pddl")), "base-domain.pddl").unwrap();
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|f| f != "base-domain.pddl")
        .collect();
    files.sort();
    assert!(files.len() >= 20, "{files:?}");
    for f in files {
        let text = read(&dir.join(&f));
        let (line, col, name) = expectation(&text);
        let err = if f.starts_with("problem-") {
            parse_problem(&text, &f, &base).map(|_| ())
        } else {
            parse_domain(&text, &f).map(|_| ())
        }
        .expect_err(&f);
        assert_eq!(err.file, f);
        assert!(
            err.message.contains(&format!("`{name}`")),
            "{f}: message does not name `{name}`: {err}"
        );
        assert_eq!((err.line, err.col), (line, col), "{f}: {err}");
        assert!(err.to_string().starts_with(&format!("{f}:{line}:{col}: ")));
    }
}

fn domain_err(text: &str) -> PddlError {
    parse_domain(text, "d.pddl").expect_err("expected an error")
}

fn at(e: &PddlError) -> (usize, usize) {
    (e.line, e.col)
}

const DOM: &str = "(define (domain d)
  (:requirements :strips :typing :equality :negative-preconditions)
  (:types block - object table)
  (:constants t0 - table)
  (:predicates (on ?x - block ?y - object) (clear ?x - object) (free))
  (:action move :parameters (?x - block ?y - object)
    :precondition (and (clear ?x) (clear ?y) (not (= ?x ?y)))
    :effect (and (on ?x ?y) (not (clear ?y)))))";

/// 1-based (line, column) of the `nth` (0-based) occurrence of `needle` in `text`: the oracle
/// for where an error must point.
fn loc(text: &str, needle: &str, nth: usize) -> (usize, usize) {
    let (i, _) = text
        .match_indices(needle)
        .nth(nth)
        .unwrap_or_else(|| panic!("`{needle}` not in text"));
    let before = &text[..i];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().unwrap().chars().count() + 1;
    (line, col)
}

#[test]
fn wrong_domains_are_located() {
    // (what, replacement of `(clear ?x)` in the precondition, token the error points at, message)
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "undeclared predicate",
            "(held ?x)",
            "held",
            "undeclared predicate `held`",
        ),
        (
            "wrong arity",
            "(on ?x)",
            "(on ?x)",
            "predicate `on` takes 2 argument(s), found 1",
        ),
        (
            "undeclared variable",
            "(clear ?z)",
            "?z",
            "undeclared variable `?z`",
        ),
        (
            "undeclared constant",
            "(clear c9)",
            "c9",
            "undeclared object or constant `c9`",
        ),
        (
            "type mismatch",
            "(on t0 ?y)",
            "t0 ?y",
            "argument `t0` of `on` has type `table`, expected `block`",
        ),
    ];
    for (what, replace, token, msg) in cases {
        let text = DOM.replace(
            "(clear ?x) (clear ?y) (not",
            &format!("{replace} (clear ?y) (not"),
        );
        let e = domain_err(&text);
        assert_eq!(at(&e), loc(&text, token, 0), "{what}: {e}");
        assert!(e.message.contains(msg), "{what}: {e}");
    }
    let ok = parse_domain(DOM, "d.pddl").unwrap();
    assert_eq!(ok.actions.len(), 1);
    assert!(matches!(ok.actions[0].precondition, Formula::And(ref v, _) if v.len() == 3));

    let text = DOM.replace("(free))", "(free) (clear ?z))");
    let e = domain_err(&text);
    assert_eq!(at(&e), loc(&text, "clear ?z", 0));
    let (l, c) = loc(&text, "clear", 0);
    assert!(
        e.message.contains(&format!(
            "duplicate predicate `clear` (first declared at {l}:{c})"
        )),
        "{e}"
    );
    let text = DOM.replace("?y - object)\n", "?y - thing)\n");
    let e = domain_err(&text);
    assert_eq!(at(&e), loc(&text, "thing", 0));
    assert!(e.message.contains("undeclared type `thing`"), "{e}");
    let text = DOM.replace("(:constants t0 - table)", "(:constants t0 t0 - table)");
    let e = domain_err(&text);
    assert_eq!(at(&e), loc(&text, "t0", 1));
    assert!(e.message.contains("duplicate constant `t0`"), "{e}");
    let e = domain_err(&DOM.replace(":parameters (?x - block ?y", ":parameters (?x - block ?x"));
    assert!(e.message.contains("duplicate parameter `?x`"), "{e}");
    let e = domain_err(&DOM.replace("(:types block - object table)", "(:types a - b b - a)"));
    assert!(e.message.contains("cycle"), "{e}");
    let text = DOM.replace(":effect", ":effects");
    let e = domain_err(&text);
    assert_eq!(at(&e), loc(&text, ":effects", 0));
    assert!(e.message.contains("unknown action key `:effects`"), "{e}");
    let text = format!("{DOM})");
    let e = domain_err(&text);
    let (l, c) = loc(&text, "))))))", 0);
    assert_eq!(at(&e), (l, c + 5));
    assert!(e.message.contains("unmatched `)`"), "{e}");
    let e = domain_err(&DOM[..DOM.len() - 1]);
    assert!(e.message.contains("opened at 1:1 is not closed"), "{e}");
    let e = domain_err(&DOM.replace("(domain d)", "(problem d)"));
    assert!(e.message.contains("this is a problem file"), "{e}");
    let e = domain_err(&DOM.replace("(:predicates", "(:predicates (x)) (:predicates"));
    assert!(e.message.contains("duplicate section `:predicates`"), "{e}");
}

fn dom() -> Domain {
    parse_domain(DOM, "d.pddl").unwrap()
}

fn problem_err(text: &str) -> PddlError {
    parse_problem(text, "p.pddl", &dom()).expect_err("expected an error")
}

const PROB: &str = "(define (problem p) (:domain D)
  (:objects a b - block)
  (:init (clear a) (clear b) (clear t0))
  (:goal (and (on a b) (not (on b a)))))";

#[test]
fn wrong_problems_are_located() {
    let p = parse_problem(PROB, "p.pddl", &dom()).unwrap();
    assert_eq!(p.objects.len(), 2);
    assert_eq!(p.init.len(), 3);
    let text = PROB.replace("(:domain D)", "(:domain e)");
    let e = problem_err(&text);
    assert_eq!(at(&e), loc(&text, "e)", 0));
    assert!(
        e.message.contains("domain `e`, but the domain is `d`"),
        "{e}"
    );
    let text = PROB.replace("(clear b) (clear t0)", "(clear b) (clear z)");
    let e = problem_err(&text);
    assert_eq!(at(&e), loc(&text, "z)", 0));
    assert!(
        e.message.contains("undeclared object or constant `z`"),
        "{e}"
    );
    let text = PROB.replace("(on a b)", "(on t0 b)");
    let e = problem_err(&text);
    assert_eq!(at(&e), loc(&text, "t0", 1));
    assert!(e.message.contains("type `table`, expected `block`"), "{e}");
    let e = problem_err(&PROB.replace("a b - block", "a b a - block"));
    let (l, c) = loc(PROB, "a b - block", 0);
    assert!(
        e.message
            .contains(&format!("duplicate object `a` (first declared at {l}:{c})")),
        "{e}"
    );
    let e = problem_err(&PROB.replace("a b - block", "a b t0 - block"));
    assert!(e.message.contains("already a constant"), "{e}");
    let e = problem_err(&PROB.replace("(:goal (and (on a b) (not (on b a))))", ""));
    assert_eq!(at(&e), (1, 1));
    assert!(e.message.contains("missing section `(:goal …)`"), "{e}");
    let e = problem_err(&PROB.replace("(:init (clear a) (clear b) (clear t0))", ""));
    assert!(e.message.contains("missing section `(:init …)`"), "{e}");
    let e = problem_err(&PROB.replace("(:domain D)", ""));
    assert!(
        e.message.contains("missing section `(:domain NAME)`"),
        "{e}"
    );
    let e = problem_err(&PROB.replace("(on a b)", "(on a b c)"));
    assert!(e.message.contains("takes 2 argument(s), found 3"), "{e}");
    let text = PROB.replace("(:objects a b - block)", "(:objects a b - bloc)");
    let e = problem_err(&text);
    assert_eq!(at(&e), loc(&text, "bloc)", 0));
}

#[test]
fn pddl_is_read_case_insensitively_with_comments_anywhere() {
    let d = parse_domain(
        "; header\n(DEFINE (DOMAIN Mixed) ; c\n (:REQUIREMENTS :STRIPS :Typing)\n (:TYPES Block)\n \
         (:PREDICATES (On ?X - BLOCK ?y - block)) ; c\n (:ACTION Go :PARAMETERS (?A - Block) \
         :EFFECT (AND (NOT (on ?a ?A)))))",
        "m.pddl",
    )
    .unwrap();
    assert_eq!(d.name.text, "mixed");
    assert_eq!(d.actions[0].name.text, "go");
    let p = parse_problem(
        "(define (problem x) (:DOMAIN MIXED) (:OBJECTS A - BLOCK) (:INIT (ON A a)) (:GOAL (AND)))",
        "x.pddl",
        &d,
    )
    .unwrap();
    assert_eq!(p.objects[0].name.text, "a");
}

#[test]
fn invalid_utf8_is_reported_at_the_file_layer() {
    let mut bytes = read(&ipc_dir().join("gripper/domain.pddl")).into_bytes();
    bytes[40] = 0xC3; // a lone lead byte
    bytes[41] = b'(';
    let e = decode_source(bytes, "g.pddl").unwrap_err();
    assert_eq!(e.file, "g.pddl");
    assert!(e.message.contains("invalid UTF-8"), "{e}");
}

mod mutations {
    //! Property tests: mutated IPC files never panic the parser, and every error is located
    //! within the text.
    use super::*;
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

    /// Every (line, col) must point into the text or just past its end.
    fn in_bounds(text: &str, e: &PddlError) -> bool {
        let lines: Vec<&str> = text.split('\n').collect();
        e.line >= 1
            && e.line <= lines.len()
            && e.col >= 1
            && e.col <= lines[e.line - 1].chars().count() + 1
    }

    fn corpus() -> Vec<(String, String)> {
        ["blocks-typed", "gripper", "logistics00", "depot-typed"]
            .iter()
            .map(|d| {
                let dir = ipc_dir().join(d);
                let probs: Vec<_> = std::fs::read_dir(&dir)
                    .unwrap()
                    .map(|e| e.unwrap().path())
                    .filter(|p| !p.ends_with("domain.pddl"))
                    .collect();
                let mut probs: Vec<_> = probs.into_iter().map(|p| read(&p)).collect();
                probs.sort_by_key(|p| p.len());
                (read(&dir.join("domain.pddl")), probs.swap_remove(0))
            })
            .collect()
    }

    /// Splits text into tokens (parentheses, words) with the whitespace kept.
    fn tokens(text: &str) -> Vec<String> {
        let mut out = Vec::new();
        let mut cur = String::new();
        for ch in text.chars() {
            if ch == '(' || ch == ')' || ch.is_whitespace() {
                if !cur.is_empty() {
                    out.push(std::mem::take(&mut cur));
                }
                out.push(ch.to_string());
            } else {
                cur.push(ch);
            }
        }
        if !cur.is_empty() {
            out.push(cur);
        }
        out
    }

    #[derive(Clone, Debug)]
    enum Edit {
        Delete(usize),
        Insert(usize, &'static str),
        Duplicate(usize),
        Truncate(usize),
        Byte(usize, u8),
    }

    fn edit() -> impl Strategy<Value = Edit> {
        let words = prop::sample::select(vec![
            "(",
            ")",
            "-",
            "?x",
            ":init",
            "and",
            "not",
            "or",
            "=",
            "forall",
            ";",
            "\u{e9}",
            "object",
            "(either a b)",
            "1.5",
            "-3",
            ":action",
            "(increase (total-cost) 2)",
            "?",
        ]);
        prop_oneof![
            any::<usize>().prop_map(Edit::Delete),
            (any::<usize>(), words).prop_map(|(i, w)| Edit::Insert(i, w)),
            any::<usize>().prop_map(Edit::Duplicate),
            any::<usize>().prop_map(Edit::Truncate),
            (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Edit::Byte(i, b)),
        ]
    }

    fn apply(text: &str, edits: &[Edit]) -> Vec<u8> {
        let mut toks = tokens(text);
        let mut bytes_edits = Vec::new();
        for e in edits {
            let n = toks.len().max(1);
            match e {
                Edit::Delete(i) if !toks.is_empty() => {
                    toks.remove(i % n);
                }
                Edit::Insert(i, w) => toks.insert(i % (toks.len() + 1), format!(" {w} ")),
                Edit::Duplicate(i) if !toks.is_empty() => {
                    let t = toks[i % n].clone();
                    toks.insert(i % n, t);
                }
                Edit::Truncate(i) => toks.truncate(i % (toks.len() + 1)),
                Edit::Byte(i, b) => bytes_edits.push((*i, *b)),
                _ => {}
            }
        }
        let mut bytes = toks.concat().into_bytes();
        for (i, b) in bytes_edits {
            if !bytes.is_empty() {
                let n = bytes.len();
                bytes[i % n] = b;
            }
        }
        bytes
    }

    fn check(
        bytes: Vec<u8>,
        parse: impl FnOnce(&str) -> Result<(), PddlError>,
    ) -> Result<(), TestCaseError> {
        match decode_source(bytes.clone(), "m.pddl") {
            Err(e) => {
                // The error points at the first bad byte: the end of the valid prefix.
                let valid =
                    std::str::from_utf8(&bytes).map_or_else(|u| u.valid_up_to(), |s| s.len());
                let prefix = std::str::from_utf8(&bytes[..valid]).unwrap();
                prop_assert!(in_bounds(prefix, &e), "{e}");
                prop_assert!(e.message.contains("invalid UTF-8"), "{e}");
            }
            Ok(text) => {
                if let Err(e) = parse(&text) {
                    prop_assert!(in_bounds(&text, &e), "{e} out of bounds");
                    prop_assert_eq!(e.file.as_str(), "m.pddl");
                }
            }
        }
        Ok(())
    }

    fn runner() -> TestRunner {
        TestRunner::new_with_rng(
            Config {
                cases: 96,
                failure_persistence: None,
                ..Config::default()
            },
            TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]),
        )
    }

    #[test]
    fn mutated_domains_never_panic_and_errors_are_in_bounds() {
        let corpus = corpus();
        runner()
            .run(
                &(0..corpus.len(), prop::collection::vec(edit(), 1..4)),
                |(k, edits)| {
                    let bytes = apply(&corpus[k].0, &edits);
                    let mut problem_error = None;
                    check(bytes, |t| {
                        let d = parse_domain(t, "m.pddl")?;
                        problem_error = parse_problem(&corpus[k].1, "p.pddl", &d).err();
                        Ok(())
                    })?;
                    // A mutated domain that still parses must still take its problem or refuse
                    // it with an error located in the problem.
                    if let Some(e) = problem_error {
                        prop_assert!(in_bounds(&corpus[k].1, &e), "{e} out of bounds");
                        prop_assert_eq!(e.file.as_str(), "p.pddl");
                    }
                    Ok(())
                },
            )
            .unwrap();
    }

    #[test]
    fn mutated_problems_never_panic_ground_or_error_in_bounds() {
        let corpus = corpus();
        let domains: Vec<Domain> = corpus
            .iter()
            .map(|(d, _)| parse_domain(d, "d.pddl").unwrap())
            .collect();
        runner()
            .run(
                &(0..corpus.len(), prop::collection::vec(edit(), 1..4)),
                |(k, edits)| {
                    let bytes = apply(&corpus[k].1, &edits);
                    check(bytes, |t| {
                        let p = parse_problem(t, "m.pddl", &domains[k])?;
                        // Whatever parses must ground (or fail with a typed error).
                        let _ = logic_lfd::plan::ground(&domains[k], &p);
                        Ok(())
                    })
                },
            )
            .unwrap();
    }
}
