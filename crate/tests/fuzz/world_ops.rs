//! World operations from the page (drags, new blocks) and the session's perturb API: random
//! sequences of requests, hostile ones included. A refused request leaves the world's snapshot
//! byte-identical (nothing partially applied); an accepted one leaves a world whose invariants
//! hold (oracle: `experiments::fuzz::check`, target `world-ops`).

use logic_lfd::experiments::fuzz::{FuzzTarget, WorldOp};
use logic_lfd::lfd::{Session, SessionOptions};
use logic_lfd::sim::Benchmark;
use proptest::prelude::*;
use rand::SeedableRng;

use super::{no_panic, run_target, runner};

#[test]
fn refused_world_operations_change_nothing_accepted_ones_keep_the_invariants() {
    let (accepted, refused) = run_target(FuzzTarget::WorldOps, 400, 16, 3);
    assert!(
        accepted > 0 && refused > 0,
        "{accepted} accepted, {refused} refused"
    );
}

#[test]
fn a_refused_session_perturb_changes_neither_world_nor_log() {
    let s = std::cell::RefCell::new(
        Session::new(SessionOptions {
            benchmark: Benchmark::B1,
            method: Default::default(),
            mode: Default::default(),
            seed: 3,
            skill: Default::default(),
            blocks: None,
        })
        .unwrap(),
    );
    runner(200, 17)
        .run(&any::<u64>(), |seed| {
            let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
            let (body, to) = match WorldOp::random(&mut rng) {
                WorldOp::Move { body, to }
                | WorldOp::MoveYaw { body, to, .. }
                | WorldOp::Add { body, at: to, .. } => (body, to.map(|c| c.value())),
            };
            let mut s = s.borrow_mut();
            let before = s.episode_json();
            match no_panic("Session::perturb", || s.perturb(&body, to))? {
                Err(_) => prop_assert!(s.episode_json() == before, "a refused drag was applied"),
                Ok(_) => {
                    prop_assert!(s.world().check_invariants().is_ok());
                    // Put the world back for the next case.
                    *s = Session::new(s.options().clone()).unwrap();
                }
            }
            Ok(())
        })
        .unwrap();
}
