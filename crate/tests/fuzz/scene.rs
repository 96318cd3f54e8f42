//! Scene JSON (`World::from_json`): mutated benchmark scenes never panic; a refusal names a JSON
//! key path (`bodies[2] "c".pose.quaternion`) or `line L column C`; an accepted scene is a valid
//! world (invariants hold) that round-trips through its snapshot (oracle:
//! `experiments::fuzz::check`, target `scene`).

use logic_lfd::experiments::fuzz::FuzzTarget;

use super::run_target;

#[test]
fn mutated_scenes_never_panic_refusals_are_located_accepted_scenes_are_valid() {
    let (accepted, refused) = run_target(FuzzTarget::Scene, 1500, 11, 3);
    assert!(
        accepted > 0 && refused > 0,
        "{accepted} accepted, {refused} refused"
    );
}
