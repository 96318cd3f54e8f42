//! The lifted plan validator and the `validate` CLI: valid plans, the first failing step with its
//! false literals, goal not reached, malformed plans at line:col, and agreement with grounding.

use std::path::{Path, PathBuf};
use std::process::Command;

use logic_lfd::pddl::{parse_domain, parse_problem, Domain, Problem};
use logic_lfd::plan::{ground, parse_plan, validate, validate_names, Outcome, ValidationReport};
use rand::{Rng, SeedableRng};

use crate::ground::{data_dir, ipc_dir};

fn load(dir: &Path, problem: &str) -> (Domain, Problem) {
    let d = parse_domain(
        &std::fs::read_to_string(dir.join("domain.pddl")).unwrap(),
        "domain.pddl",
    )
    .unwrap();
    let p = parse_problem(
        &std::fs::read_to_string(dir.join(problem)).unwrap(),
        problem,
        &d,
    )
    .unwrap();
    (d, p)
}

/// blocks-4-0: init all four on the table; goal (on d c) (on c b) (on b a). Written by hand.
const BLOCKS_4_0: &str = "; hand-written
(pick-up b)
(stack b a)
(pick-up c)
(stack c b)
(pick-up d)
(stack d c)
";

fn check(text: &str) -> ValidationReport {
    let (d, p) = load(&ipc_dir().join("blocks"), "probBLOCKS-4-0.pddl");
    validate(&d, &p, &parse_plan(text, "plan.txt").unwrap())
}

#[test]
fn hand_written_blocks_plan_is_valid() {
    let r = check(BLOCKS_4_0);
    assert!(r.is_valid(), "{r}");
    assert_eq!((r.cost, r.steps_applied), (6, 6));
    assert_eq!(r.to_string(), "Plan valid, cost 6");
}

#[test]
fn an_invalid_plan_names_its_first_failing_step_and_its_false_literals() {
    // Without the first pick-up, step 1 (stack b a) lacks (holding b).
    let r = check(&BLOCKS_4_0.replace("(pick-up b)\n", ""));
    match &r.outcome {
        Outcome::PreconditionFalse {
            step,
            action,
            location,
            false_literals,
        } => {
            assert_eq!((*step, action.as_str()), (1, "(stack b a)"));
            assert_eq!(location, "plan.txt:2:1");
            assert_eq!(false_literals, &["(holding b)"]);
        }
        o => panic!("{o:?}"),
    }
    assert_eq!(r.steps_applied, 0);
    // Picking up c while holding b: step 2 lacks (handempty) only.
    let r = check(&BLOCKS_4_0.replace("(stack b a)\n(pick-up c)", "(pick-up c)\n(stack b a)"));
    match &r.outcome {
        Outcome::PreconditionFalse {
            step,
            false_literals,
            ..
        } => {
            assert_eq!(*step, 2);
            assert_eq!(false_literals, &["(handempty)"]);
        }
        o => panic!("{o:?}"),
    }
    assert_eq!((r.steps_applied, r.cost), (1, 1));
    assert!(
        r.to_string()
            .contains("step 2 (pick-up c) is not applicable: false precondition(s): (handempty)"),
        "{r}"
    );
    // Stacking onto a covered block: both literals reported.
    let r = check("(pick-up b)\n(stack b a)\n(pick-up c)\n(stack c a)\n");
    match &r.outcome {
        Outcome::PreconditionFalse {
            step,
            false_literals,
            ..
        } => {
            assert_eq!(*step, 4);
            assert_eq!(false_literals, &["(clear a)"]);
        }
        o => panic!("{o:?}"),
    }
}

#[test]
fn goal_not_reached_lists_false_goal_literals() {
    let r = check(&BLOCKS_4_0.replace("(pick-up d)\n(stack d c)\n", ""));
    assert_eq!(
        r.outcome,
        Outcome::GoalNotReached {
            false_literals: vec!["(on d c)".into()]
        }
    );
    assert_eq!((r.steps_applied, r.cost), (4, 4));
    let r = check("");
    assert_eq!(
        r.outcome,
        Outcome::GoalNotReached {
            false_literals: vec!["(on d c)".into(), "(on c b)".into(), "(on b a)".into()]
        }
    );
}

#[test]
fn malformed_steps_are_located() {
    let cases = [
        ("(pick-up b)\n  (fly b)\n", (2, 4), "unknown action `fly`"),
        (
            "(pick-up b c)\n",
            (1, 1),
            "action `pick-up` takes 1 argument(s), found 2",
        ),
        ("(pick-up b)\n(stack b  z)\n", (2, 11), "unknown object `z`"),
    ];
    for (text, (line, col), msg) in cases {
        match check(text).outcome {
            Outcome::Malformed(e) => {
                assert_eq!(
                    (e.file.as_str(), e.line, e.col),
                    ("plan.txt", line, col),
                    "{e}"
                );
                assert!(e.message.contains(msg), "{e}");
            }
            o => panic!("{text}: {o:?}"),
        }
    }
    for (text, (line, col)) in [
        ("(pick-up b\n(stack b a)", (1, 1)),
        ("(pick-up b)\nstack b a\n", (2, 1)),
        ("()", (1, 1)),
    ] {
        let e = parse_plan(text, "plan.txt").unwrap_err();
        assert_eq!((e.line, e.col), (line, col), "{e}");
    }
}

#[test]
fn the_validator_sums_function_costs_and_prints_false_or_equality_and_negated_literals() {
    let dir = data_dir().join("rooms");
    let (d, p) = load(&dir, "p-costs.pddl");
    let plan = std::fs::read_to_string(dir.join("plan-costs.plan")).unwrap();
    let r = validate(&d, &p, &parse_plan(&plan, "plan-costs.plan").unwrap());
    assert!(r.is_valid(), "{r}");
    assert_eq!(r.cost, 9); // 3 + 0 + 2 + 4
                           // Entering the locked room: the negative precondition is the false literal.
    let r = validate_names(&d, &p, &["(move hall r1)".into(), "(move r1 r2)".into()]);
    match &r.outcome {
        Outcome::PreconditionFalse {
            step,
            false_literals,
            ..
        } => {
            assert_eq!(*step, 2);
            assert_eq!(false_literals, &["(not (locked r2))"]);
        }
        o => panic!("{o:?}"),
    }
    // No door: the whole `or` is printed; equality violated: `(not (= …))` printed.
    let r = validate_names(&d, &p, &["(move hall r2)".into()]);
    match &r.outcome {
        Outcome::PreconditionFalse { false_literals, .. } => {
            assert_eq!(
                false_literals,
                &["(or (door hall r2) (door r2 hall))", "(not (locked r2))"]
            )
        }
        o => panic!("{o:?}"),
    }
    let r = validate_names(&d, &p, &["(move hall hall)".into()]);
    match &r.outcome {
        Outcome::PreconditionFalse { false_literals, .. } => {
            assert_eq!(
                false_literals,
                &[
                    "(not (= hall hall))",
                    "(or (door hall hall) (door hall hall))"
                ]
            )
        }
        o => panic!("{o:?}"),
    }
    // A key is not a room: a type error, located.
    match validate_names(&d, &p, &["(move hall k1)".into()]).outcome {
        Outcome::Malformed(e) => assert!(
            e.message
                .contains("`k1` of `move` has type `key`, expected `room`"),
            "{e}"
        ),
        o => panic!("{o:?}"),
    }
    // The unit-cost problem counts steps.
    let (d, p) = load(&dir, "p-unit.pddl");
    let r = validate_names(&d, &p, &["(move hall r1)".into(), "(take k1 r1)".into()]);
    assert!(r.is_valid(), "{r}");
    assert_eq!(r.cost, 2);
}

/// Seeded random walks on the grounded task, replayed by the lifted validator: every grounded
/// step must be applicable at the lifted level, and the grounded goal test must agree with the
/// validator's (regression guard for grounding and validation drifting apart).
#[test]
fn grounding_and_lifted_validation_agree_on_random_walks() {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(11);
    let cases = [
        (ipc_dir().join("blocks"), "probBLOCKS-5-1.pddl"),
        (ipc_dir().join("depot-typed"), "p01.pddl"),
        (ipc_dir().join("logistics00"), "probLOGISTICS-4-0.pddl"),
        (ipc_dir().join("gripper"), "prob01.pddl"),
        (data_dir().join("rooms"), "p-costs.pddl"),
        (data_dir().join("rooms"), "p-unit.pddl"),
    ];
    for (dir, prob) in cases {
        let (d, p) = load(&dir, prob);
        let t = ground(&d, &p).unwrap();
        for _walk in 0..20 {
            let mut s = t.init.clone();
            let mut plan = Vec::new();
            let mut cost = 0u64;
            for _ in 0..30 {
                let app: Vec<_> = t.operators.iter().filter(|o| o.applicable(&s)).collect();
                if app.is_empty() {
                    break;
                }
                let o = app[rng.random_range(0..app.len())];
                s = o.apply(&s);
                cost += u64::from(o.cost);
                plan.push(o.name.clone());
                let r = validate_names(&d, &p, &plan);
                assert_eq!(r.steps_applied, plan.len(), "{prob}: {r}");
                assert_eq!(r.cost, cost, "{prob}");
                assert_eq!(r.is_valid(), t.goal.holds(&s), "{prob}: {r}");
            }
        }
        // And a lifted-applicable step the grounding dropped must not exist: every action the
        // validator accepts from init is a grounded operator applicable in init.
        for o in t.operators.iter().filter(|o| o.applicable(&t.init)) {
            assert_eq!(
                validate_names(&d, &p, std::slice::from_ref(&o.name)).steps_applied,
                1
            );
        }
    }
}

// ---- CLI -------------------------------------------------------------------------------------

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
}

fn tmp(name: &str, contents: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("logic-lfd-validate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, contents).unwrap();
    p
}

fn run(domain: &Path, problem: &Path, plan: &Path, json: bool) -> (i32, String, String) {
    let mut c = bin();
    c.arg("validate").arg(domain).arg(problem).arg(plan);
    if json {
        c.arg("--json");
    }
    let out = c.output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn cli_validate_exits_with_a_code_per_verdict_and_locates_bad_input() {
    let dir = ipc_dir().join("blocks");
    let (dom, prob) = (dir.join("domain.pddl"), dir.join("probBLOCKS-4-0.pddl"));
    let good = tmp("good.plan", BLOCKS_4_0.as_bytes());
    let (code, out, err) = run(&dom, &prob, &good, false);
    assert_eq!(
        (code, out.trim(), err.as_str()),
        (0, "Plan valid, cost 6", "")
    );

    let bad = tmp(
        "bad.plan",
        BLOCKS_4_0.replace("(pick-up b)\n", "").as_bytes(),
    );
    let (code, out, _) = run(&dom, &prob, &bad, false);
    assert_eq!(code, 5);
    assert!(out.contains("bad.plan:2:1: step 1 (stack b a) is not applicable: false precondition(s): (holding b)"), "{out}");
    let (code, out, _) = run(&dom, &prob, &bad, true);
    assert_eq!(code, 5);
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["valid"], false);
    assert_eq!(j["failure"]["step"], 1);
    assert_eq!(j["failure"]["false_literals"][0], "(holding b)");

    let short = tmp("short.plan", b"(pick-up b)\n(stack b a)\n");
    let (code, out, _) = run(&dom, &prob, &short, false);
    assert_eq!(code, 5);
    assert!(
        out.contains("the goal does not hold: false goal literal(s): (on d c) (on c b)"),
        "{out}"
    );

    // Bad input: exit 2 with file:line:col on stderr, nothing on stdout, never a panic.
    let missing = dir.join("no-such-problem.pddl");
    let (code, out, err) = run(&dom, &missing, &good, false);
    assert_eq!(code, 2);
    assert!(out.is_empty());
    assert!(
        err.starts_with(&format!("{}:1:1: cannot read file", missing.display())),
        "{err}"
    );
    let unreadable = std::env::temp_dir(); // a directory cannot be read as a file
    let (code, _, err) = run(&dom, &prob, &unreadable, false);
    assert_eq!(code, 2);
    assert!(err.contains(":1:1: cannot read file"), "{err}");
    let bad_pddl = tmp("bad-domain.pddl", b"(define (domain blocks)\n  (:predicates (on ?x ?y))\n  (:action a :effect (forall (?x) (on ?x ?x))))\n");
    let (code, _, err) = run(&bad_pddl, &prob, &good, false);
    assert_eq!(code, 2);
    assert!(
        err.starts_with(&format!(
            "{}:3:23: `forall` is not supported",
            bad_pddl.display()
        )),
        "{err}"
    );
    let latin1 = tmp("latin1.plan", b"(pick-up b)\n(stack b \xe9)\n");
    let (code, _, err) = run(&dom, &prob, &latin1, false);
    assert_eq!(code, 2);
    assert!(
        err.contains("latin1.plan:2:10: invalid UTF-8 byte 0xe9"),
        "{err}"
    );
    let unknown = tmp("unknown.plan", b"(pick-up b)\n(teleport b)\n");
    let (code, _, err) = run(&dom, &prob, &unknown, false);
    assert_eq!(code, 2);
    assert!(
        err.contains("unknown.plan:2:2: unknown action `teleport`"),
        "{err}"
    );
    let no_args = bin().arg("validate").output().unwrap();
    assert_eq!(no_args.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(good.parent().unwrap());
}
