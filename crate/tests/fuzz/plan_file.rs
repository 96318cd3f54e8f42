//! Plan files for `validate` (`plan::parse_plan` + `plan::validate`): mutated plans never panic;
//! a parse error or a malformed step is located inside the plan text; a precondition failure
//! names a 1-based step that exists and its location; a valid report applied every step
//! (oracle: `experiments::fuzz::check_plan_against`).

use logic_lfd::experiments::fuzz::{check_plan_against, mutate_plan, FuzzTarget, PlanEdit};
use logic_lfd::pddl::{parse_domain, parse_problem};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};

use super::{no_panic, run_target, runner};

fn rooms(file: &str) -> String {
    let p = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/pddl/rooms");
    std::fs::read_to_string(format!("{p}/{file}")).unwrap()
}

#[test]
fn mutated_benchmark_demo_plans_never_panic_and_failures_are_located() {
    let (accepted, refused) = run_target(FuzzTarget::Plan, 2800, 12, 4);
    assert!(
        accepted > 0 && refused > 0,
        "{accepted} accepted, {refused} refused"
    );
}

/// The same mutator and oracle on a plan with action costs (`rooms`).
#[test]
fn mutated_plans_with_costs_never_panic_and_failures_are_located() {
    let d = parse_domain(&rooms("domain.pddl"), "d.pddl").unwrap();
    let p = parse_problem(&rooms("p-costs.pddl"), "p.pddl", &d).unwrap();
    let plan = rooms("plan-costs.plan");
    runner(700, 20)
        .run(&any::<u64>(), |seed| {
            let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
            let k = rng.random_range(1..=4);
            let edits: Vec<PlanEdit> = (0..k).map(|_| PlanEdit::random(&mut rng)).collect();
            let text = mutate_plan(&plan, &edits);
            match no_panic("validate", || check_plan_against(&d, &p, &text))? {
                Ok(_) => Ok(()),
                Err(m) => Err(TestCaseError::fail(format!("{m}\nplan: {text}"))),
            }
        })
        .unwrap();
}
