//! World operations from the page (drags, new blocks) and the session's perturb API: random
//! sequences of requests, hostile ones included. A refused request leaves the world's snapshot
//! byte-identical (nothing partially applied); an accepted one leaves a world whose invariants
//! hold.

use logic_lfd::lfd::session::{BenchmarkId, Session, SessionOptions};
use logic_lfd::sim::benchmark::Benchmark;
use logic_lfd::sim::World;
use nalgebra::Vector3;
use proptest::prelude::*;

use super::{no_panic, runner};

#[derive(Clone, Debug)]
enum Op {
    Move(usize, [f64; 3]),
    MoveYaw(usize, [f64; 3], f64),
    Add(usize, usize, [f64; 3]),
}

const NAMES: [&str; 12] = [
    "a", "b", "c", "d", "hook", "table", "shelf", "panda", "e", "", "A", "<b>",
];
const COLORS: [&str; 4] = ["#123456", "red", "#12345", "#GGGGGG"];

fn coord() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => -0.4f64..1.2,
        1 => prop::sample::select(vec![f64::NAN, f64::INFINITY, -f64::INFINITY, 1e12, -1e12, 0.0]),
    ]
}

fn point() -> impl Strategy<Value = [f64; 3]> {
    (
        coord(),
        coord(),
        prop_oneof![3 => 0.0f64..0.4, 1 => coord()],
    )
        .prop_map(|(x, y, z)| [x, y, z])
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        4 => (any::<usize>(), point()).prop_map(|(i, p)| Op::Move(i, p)),
        1 => (any::<usize>(), point(), coord()).prop_map(|(i, p, y)| Op::MoveYaw(i, p, y)),
        1 => (any::<usize>(), any::<usize>(), point()).prop_map(|(i, c, p)| Op::Add(i, c, p)),
    ]
}

fn snap(w: &World) -> String {
    serde_json::to_string(&w.snapshot()).unwrap()
}

#[test]
fn refused_world_operations_change_nothing_accepted_ones_keep_the_invariants() {
    let worlds = [
        Benchmark::B1.scene(),
        Benchmark::B2.scene(),
        Benchmark::B3.scene(),
    ];
    runner(300, 16)
        .run(
            &(0..3usize, prop::collection::vec(op(), 1..10)),
            |(k, ops)| {
                let mut w = worlds[k].clone();
                for op in ops {
                    let before = snap(&w);
                    let r = no_panic("world operation", || match op {
                        Op::Move(i, p) => w
                            .move_block(NAMES[i % NAMES.len()], Vector3::from(p))
                            .map(|_| ()),
                        Op::MoveYaw(i, p, y) => w
                            .move_block_to(NAMES[i % NAMES.len()], Vector3::from(p), y)
                            .map(|_| ()),
                        Op::Add(i, c, p) => w
                            .add_block(
                                NAMES[i % NAMES.len()],
                                COLORS[c % COLORS.len()],
                                Vector3::from(p),
                                0.3,
                            )
                            .map(|_| ()),
                    })?;
                    match r {
                        Err(refused) => {
                            prop_assert!(!refused.reason.is_empty());
                            prop_assert!(snap(&w) == before, "refused {refused} changed the world");
                        }
                        Ok(()) => {
                            let v = w.check_invariants();
                            prop_assert!(v.is_ok(), "accepted {op:?} broke invariants: {v:?}");
                        }
                    }
                }
                Ok(())
            },
        )
        .unwrap();
}

#[test]
fn a_refused_session_perturb_changes_neither_world_nor_log() {
    let s = std::cell::RefCell::new(
        Session::new(SessionOptions {
            benchmark: BenchmarkId::B1,
            method: Default::default(),
            mode: Default::default(),
            seed: 3,
            skill: Default::default(),
        })
        .unwrap(),
    );
    runner(200, 17)
        .run(&(any::<usize>(), point()), |(i, p)| {
            let mut s = s.borrow_mut();
            let before = s.episode_json();
            match no_panic("Session::perturb", || s.perturb(NAMES[i % NAMES.len()], p))? {
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
