//! The closed-loop soak at CI size (`logic-lfd soak --episodes 8 --seed 2026`); the README reports
//! the large run.

use logic_lfd::experiments::soak::{soak, SoakParams};

#[test]
fn a_small_soak_is_clean() {
    let p = SoakParams {
        episodes: 8,
        seed: 2026,
        ..SoakParams::default()
    };
    let r = soak(&p).unwrap();
    assert_eq!(r.episodes, 8);
    assert!(r.disturbances > 0, "no disturbance was applied: {r:?}");
    assert!(r.plans_checked >= r.episodes, "{r:?}");
    assert!(r.invariant_checks > 1000, "{r:?}");
    assert_eq!(r.panics, 0, "{:#?}", r.findings);
    assert_eq!(r.partial_applies, 0, "{:#?}", r.findings);
    assert_eq!(r.invalid_plans, 0, "{:#?}", r.findings);
    // Every episode ends with a stated outcome, each counted once.
    let stated = r.successes
        + r.legitimate_failures.values().sum::<usize>()
        + r.budget_exhausted
        + r.unexplained_failures;
    assert_eq!(stated, r.episodes, "{r:?}");
    // And every guarantee holds: no invariant violation, replays identical, no unexplained end.
    assert_eq!(r.invariant_violations, 0, "{:#?}", r.findings);
    assert_eq!(r.replay_mismatches, 0, "{:#?}", r.findings);
    assert!(r.is_clean(), "{:#?}", r.findings);
}

#[test]
fn a_small_soak_on_8_and_12_block_towers_is_clean() {
    for (n, episodes) in [(8, 2), (12, 1)] {
        let p = SoakParams {
            episodes,
            seed: 2026,
            blocks: Some(n),
            ..SoakParams::default()
        };
        let r = soak(&p).unwrap();
        assert_eq!(r.episodes, episodes);
        assert!(
            r.disturbances > 0,
            "N = {n}: no disturbance was applied: {r:?}"
        );
        assert!(r.invariant_checks > 500, "N = {n}: {r:?}");
        assert_eq!(r.invalid_plans, 0, "N = {n}: {:#?}", r.findings);
        assert_eq!(r.invariant_violations, 0, "N = {n}: {:#?}", r.findings);
        assert!(r.is_clean(), "N = {n}: {:#?}", r.findings);
    }
}
