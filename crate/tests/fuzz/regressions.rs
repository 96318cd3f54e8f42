//! Regression tests for inputs found by `logic-lfd fuzz`: each is named after the behaviour it
//! protects, regenerates its input from the saved `<target>-<seed>-<index>` and replays it
//! through the same oracle.

use logic_lfd::experiments::fuzz::{base_inputs, check_catching, generate, FuzzTarget};

/// Regenerates input `index` of a `logic-lfd fuzz --target T --seed S --max-edits K` run.
fn input(target: FuzzTarget, seed: u64, index: u64, max_edits: usize) -> String {
    generate(
        target,
        &base_inputs(target).unwrap(),
        seed,
        index,
        max_edits,
    )
}

/// The generator is stable: a saved `<target>-<seed>-<index>` name regenerates the same input,
/// so a regression test may name its input by seed and index instead of embedding it.
#[test]
fn fuzz_inputs_are_regenerated_from_their_name() {
    for t in [
        FuzzTarget::Pddl,
        FuzzTarget::Plan,
        FuzzTarget::Scene,
        FuzzTarget::WorldOps,
    ] {
        let a = input(t, 2026, 17, 4);
        assert_eq!(a, input(t, 2026, 17, 4));
        assert!(check_catching(t, &a).is_ok(), "{t:?}");
    }
}
