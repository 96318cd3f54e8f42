//! RLDS's backward check and Logic-LfD's TAMP fallback on a hand-grounded blocks world.

use crate::lfd::testing::blocks_task;
use crate::lfd::DemoTrace;
use crate::lfd::{ControlParams, Controller, Decision, FailReason, TaskBuilder};
use crate::lfd::{LfdError, Method, Mode};
use crate::plan::{NoClock, Operator, Task};
use crate::tamp::{BindFailure, Binder, Binding};

/// Five blocks; the demonstration stacks `a` on `b` on `c` and never touches `d` and `e`.
fn tower() -> (Task, DemoTrace) {
    let task = blocks_task(
        &["a", "b", "c", "d", "e"],
        &[
            "(handempty)",
            "(ontable a)",
            "(ontable b)",
            "(ontable c)",
            "(ontable d)",
            "(ontable e)",
            "(clear a)",
            "(clear b)",
            "(clear c)",
            "(clear d)",
            "(clear e)",
        ],
        &["(on a b)", "(on b c)"],
    );
    let demo: Vec<String> = ["(pick b)", "(stack b c)", "(pick a)", "(stack a b)"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let trace = DemoTrace::derive(&task, &demo).expect("the demonstration applies");
    (task, trace)
}

struct SameTask(Task);

impl TaskBuilder for SameTask {
    fn build(&self, _: &[crate::pddl::ObjectDecl], _: &[String]) -> Result<Task, LfdError> {
        Ok(self.0.clone())
    }
}

/// Refuses the first `fail` calls, then binds anything.
struct FailFirst {
    fail: usize,
    calls: usize,
}

impl Binder for FailFirst {
    fn bind(&mut self, _: &Task, ops: &[usize], _: usize) -> Result<Vec<Binding>, BindFailure> {
        self.calls += 1;
        if self.calls <= self.fail {
            return Err(BindFailure {
                action: 0,
                reason: Some("refused".into()),
                blockers: vec![],
            });
        }
        Ok(vec![Binding::default(); ops.len()])
    }

    fn moves_body(&self, _: &Operator, _: &str) -> bool {
        false
    }
}

fn facts(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

fn decide(c: &mut Controller, task: &Task, s: &[String], binder: &mut dyn Binder) -> Decision {
    c.decide(s, &[], &SameTask(task.clone()), binder, &NoClock, 0)
}

/// `b` on `c` as after the demonstration's second action, but `d` stacked on `e`: no
/// demonstration state equals it, yet the demonstration's last two actions reach the goal.
const MOVED_ASIDE: [&str; 9] = [
    "(handempty)",
    "(on b c)",
    "(ontable c)",
    "(clear b)",
    "(ontable a)",
    "(clear a)",
    "(on d e)",
    "(ontable e)",
    "(clear d)",
];

#[test]
fn rlds_joins_where_the_remaining_demonstration_applies() {
    let (task, trace) = tower();
    let seen: std::collections::BTreeSet<String> = facts(&MOVED_ASIDE).into_iter().collect();
    assert!(
        trace.states.iter().all(|l| *l != seen),
        "no demonstration state equals it"
    );
    let mut c = controller(Method::Rlds, &task, trace, ControlParams::default());
    let d = decide(
        &mut c,
        &task,
        &facts(&MOVED_ASIDE),
        &mut FailFirst { fail: 0, calls: 0 },
    );
    assert_eq!(
        d,
        Decision::Execute {
            index: 0,
            action: "(pick a)".into()
        }
    );
    assert_eq!(c.matched_k(), Some(2));
    assert_eq!(c.plan_names(), ["(pick a)", "(stack a b)"]);
}

#[test]
fn rlds_fails_when_no_remaining_demonstration_applies() {
    let (task, trace) = tower();
    // `a` on `d`: the demonstration picks `a` from the table, so no suffix applies.
    let s = facts(&[
        "(handempty)",
        "(on b c)",
        "(ontable c)",
        "(clear b)",
        "(on a d)",
        "(ontable d)",
        "(clear a)",
        "(ontable e)",
        "(clear e)",
    ]);
    let mut c = controller(Method::Rlds, &task, trace, ControlParams::default());
    let d = decide(&mut c, &task, &s, &mut FailFirst { fail: 0, calls: 0 });
    assert!(
        matches!(d, Decision::Failed(FailReason::NoDemoStateMatches { .. })),
        "{d:?}"
    );
}

fn controller(method: Method, task: &Task, trace: DemoTrace, params: ControlParams) -> Controller {
    Controller::new(method, Mode::Paper, params, trace, task.clone(), vec![])
}

fn logic_lfd(task: &Task, trace: DemoTrace, tamp_fallback: bool) -> Controller {
    let params = ControlParams {
        max_skeletons: 2,
        tamp_fallback,
        ..ControlParams::default()
    };
    controller(Method::LogicLfd, task, trace, params)
}

#[test]
fn logic_lfd_without_fallback_fails_when_no_skeleton_binds() {
    let (task, trace) = tower();
    let mut c = logic_lfd(&task, trace, false);
    let mut binder = FailFirst { fail: 2, calls: 0 };
    let d = decide(&mut c, &task, &facts(&MOVED_ASIDE), &mut binder);
    assert!(
        matches!(d, Decision::Failed(FailReason::NoPlan { .. })),
        "{d:?}"
    );
    assert_eq!(binder.calls, 2, "both skeletons tried, nothing else");
    assert!(c.replans().is_empty());
}

#[test]
fn logic_lfd_fallback_plans_from_scratch_and_is_logged() {
    let (task, trace) = tower();
    let mut c = logic_lfd(&task, trace, true);
    let mut binder = FailFirst { fail: 2, calls: 0 };
    let d = decide(&mut c, &task, &facts(&MOVED_ASIDE), &mut binder);
    assert!(matches!(d, Decision::Execute { .. }), "{d:?}");
    assert_eq!(binder.calls, 3, "two skeletons, then TAMP from scratch");
    let r = c.replans().last().expect("logged");
    assert!(r.fallback);
    assert_eq!(r.k, None);
    // A skeleton that binds at once is not a fallback.
    let (task, trace) = tower();
    let mut c = logic_lfd(&task, trace, true);
    decide(
        &mut c,
        &task,
        &facts(&MOVED_ASIDE),
        &mut FailFirst { fail: 0, calls: 0 },
    );
    assert!(!c.replans()[0].fallback);
}
