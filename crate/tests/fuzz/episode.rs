//! Episode JSON (replay, `logic-lfd run --replay`): mutated episode logs never panic the parser
//! or the replay; a refusal is located (serde's `line L column C`, or the scene's key path); an
//! accepted log replays (oracle: `experiments::fuzz::check`, target `episode`).

use logic_lfd::experiments::fuzz::FuzzTarget;

use super::run_target;

#[test]
fn mutated_episode_json_never_panics_and_errors_are_located() {
    let (accepted, refused) = run_target(FuzzTarget::Episode, 1500, 18, 3);
    assert!(
        accepted > 0 && refused > 0,
        "{accepted} accepted, {refused} refused"
    );
}
