//! Episode JSON (replay, `logic-lfd run --replay`): mutated episode logs never panic the parser
//! or the replay; a refusal is located (serde's `line L column C`, or the scene's key path); an
//! accepted log replays to a world whose invariants hold or ends with a stated outcome.

use logic_lfd::lfd::session::{BenchmarkId, EpisodeLog, Session, SessionError, SessionOptions};
use logic_lfd::plan::NoClock;
use proptest::prelude::*;

use super::{json_edit, mutate_json, no_panic, runner};

/// A short B1 episode (300 ticks) with a drag and an injection, as JSON.
fn short_episode() -> String {
    let mut s = Session::new(SessionOptions {
        benchmark: BenchmarkId::B1,
        method: Default::default(),
        mode: Default::default(),
        seed: 11,
        skill: Default::default(),
    })
    .unwrap();
    s.run_to_end(120, &NoClock);
    let _ = s.inject("l1");
    s.run_to_end(120, &NoClock);
    let _ = s.perturb("a", [0.40, -0.20, 0.1]);
    s.run_to_end(60, &NoClock);
    s.episode_json()
}

fn located(msg: &str) -> bool {
    (msg.contains(" line ") && msg.contains(" column ")) || msg.starts_with("scene: ")
}

#[test]
fn mutated_episode_json_never_panics_and_parse_errors_are_located() {
    let ep = short_episode();
    runner(2000, 18)
        .run(&prop::collection::vec(json_edit(), 1..4), |edits| {
            let text = String::from_utf8_lossy(&mutate_json(&ep, &edits)).into_owned();
            if let Err(e) = no_panic("parse", || serde_json::from_str::<EpisodeLog>(&text))? {
                prop_assert!(e.line() >= 1, "{e}");
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn mutated_episode_json_replays_without_panic() {
    let ep = short_episode();
    runner(120, 19)
        .run(&prop::collection::vec(json_edit(), 1..3), |edits| {
            let text = String::from_utf8_lossy(&mutate_json(&ep, &edits)).into_owned();
            // Only logs that still parse reach the (expensive) replay; keep their length bounded.
            let Ok(log) = serde_json::from_str::<EpisodeLog>(&text) else {
                return Ok(());
            };
            if log.ticks > 2_000 {
                return Ok(());
            }
            match no_panic("Session::replay", || Session::replay(&text))? {
                Err(SessionError::Scene(e)) => prop_assert!(!e.path.is_empty(), "{e}"),
                Err(e) => prop_assert!(located(&e.to_string()) || !e.to_string().is_empty()),
                Ok(s) => {
                    let _ = no_panic("episode_json", || s.episode_json())?;
                }
            }
            Ok(())
        })
        .unwrap();
}
