//! Disturbance injection for the loop (paper §IV-B), defined against the demonstration:
//!
//! ```text
//!   L1  move one free block on its support; S_C unchanged
//!       (during a motion: move the body the arm approaches, or push the arm's hand)
//!   L2  move one clear block (to the table or onto another block) so that S_C = L_k for some k
//!   L3  move one clear block so that no L_k ⊆ S_C (a state the demonstration never visits)
//!   L4  add a new block on top of a clear block so that no L_k ⊆ S_C (it is in the way);
//!       without stacking (B2), put it into an idle arm's empty hand: no grasp can run
//! ```
//!
//! Candidates are tried in a seeded random order through the simulator's own user-move rule
//! ([`World::move_block`]: settles onto the support below, refuses interpenetration), so every
//! injected world satisfies the simulator's invariants (and the move rule refuses a world the
//! scene cannot describe: a block on the hook, on a held block, or on a block where the domain
//! has no `on`). A candidate whose resulting facts do not meet the level's definition, or that
//! leaves the moved or new block where no arm can grasp or pull it
//! ([`crate::sim::handleable`], IK), is undone: an injection never makes
//! the task geometrically impossible; when no candidate qualifies it is refused with the reason.
//!
//! The same injector makes the Table I tasks (applied to the template scene), the disturbances
//! of Table II and of the soak, and those of the page's buttons
//! ([`Session::inject`](super::session::Session::inject)).

use nalgebra::Vector3;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};

use crate::sim::handleable;
use crate::sim::World;
use crate::sim::{BodyKind, BodySnapshot, PoseSnapshot, ShapeSnapshot};
use crate::sim::{Relation, Slot};
use crate::sim::{BLOCK_COLORS, BLOCK_SIZE};

use super::catalogue::Level;
use super::demo::DemoTrace;

pub(super) mod motion;
mod scene;

use scene::{centre, facts, is_about, is_clear, resting_place, table_spot, Before};
use scene::{DROP_HEIGHT, L1_LIFT, L1_SHIFT, MOTION_TRIES, NEW_BLOCK_NAMES};

/// A push of an arm's hand: its tool centre point displaced while the arm moves.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct TcpPush {
    /// The arm pushed.
    pub arm: String,
    /// Where the TCP was (m).
    pub from: [f64; 3],
    /// Where the push left it (m).
    pub to: [f64; 3],
    /// |to − from| (mm).
    pub displacement_mm: f64,
}

/// What an injected disturbance did.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct Injection {
    /// `l1`..`l4`.
    pub level: Level,
    /// What it did, in words.
    pub description: String,
    /// Bodies moved or added: (name, new centre).
    pub moved: Vec<(String, [f64; 3])>,
    /// The action being executed when it came (`None`: the arm was idle).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub during: Option<String>,
    /// The push given to an arm's hand (a mid-motion L1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub push: Option<TcpPush>,
}

/// Injects a disturbance of `level` into `world`; `trace` defines "seen in the
/// demonstration". Deterministic in `seed`.
///
/// `busy` are the arms executing an action now: where the scene has no stacking (B2), the L4
/// block is handed to an idle arm (one not in `busy`, its hand empty).
pub fn inject(
    world: &mut World,
    level: Level,
    trace: &DemoTrace,
    busy: &[usize],
    seed: u64,
) -> Result<Injection, String> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let before = Before::of(world, trace);
    match level {
        Level::L1 => motion_level(world, &before, &mut rng),
        Level::L2 | Level::L3 => task_level(world, level, &before, &mut rng),
        Level::L4 => new_block(world, &before, busy, &mut rng),
    }
}

/// L1: one free block moved by 2–5 cm on its support, the facts unchanged.
fn motion_level(
    world: &mut World,
    before: &Before,
    rng: &mut Pcg64Mcg,
) -> Result<Injection, String> {
    let mut order = before.blocks.clone();
    order.shuffle(rng);
    shift_one_of(world, before, &order, rng)
        .ok_or_else(|| "L1: no block can be moved without changing the facts".into())
}

/// The first of `order` that moves by 2–5 cm on its support with the facts unchanged and stays
/// workable ([`handleable`]).
fn shift_one_of(
    world: &mut World,
    before: &Before,
    order: &[String],
    rng: &mut Pcg64Mcg,
) -> Option<Injection> {
    for b in order {
        let Some(c) = centre(world, b) else { continue };
        for _ in 0..MOTION_TRIES {
            let a = rng.random_range(0.0..std::f64::consts::TAU);
            let r = rng.random_range(L1_SHIFT);
            let target = Vector3::new(
                c[0] + r * libm::cos(a),
                c[1] + r * libm::sin(a),
                c[2] + L1_LIFT,
            );
            let saved = world.clone();
            if world.move_block(b, target).is_ok()
                && facts(world) == before.facts
                && handleable(world, b).is_ok()
            {
                let to = centre(world, b).unwrap_or(c);
                return Some(Injection {
                    level: Level::L1,
                    description: format!(
                        "L1: moved {b} by {:.0} mm; the facts are unchanged",
                        r * 1e3
                    ),
                    moved: vec![(b.clone(), to)],
                    during: None,
                    push: None,
                });
            }
            *world = saved;
        }
    }
    None
}

/// L2 / L3: one clear block moved to the table or onto another clear block, to a state of the
/// demonstration short of the goal (L2) or to one no L_k is a subset of (L3).
fn task_level(
    world: &mut World,
    level: Level,
    before: &Before,
    rng: &mut Pcg64Mcg,
) -> Result<Injection, String> {
    let want_seen = level == Level::L2;
    let trace = before.trace;
    let n = trace.states.len().saturating_sub(1);
    let cur = before.seen_at(&before.facts).first().copied();
    let mut moves: Vec<(String, Option<String>)> = vec![];
    for b in &before.blocks {
        if !is_clear(&before.motions, &before.facts, b) {
            continue;
        }
        // Several table spots per block (a spot is drawn per try).
        for _ in 0..6 {
            moves.push((b.clone(), None));
        }
        for o in &before.blocks {
            if before.has_on && o != b && is_clear(&before.motions, &before.facts, o) {
                moves.push((b.clone(), Some(o.clone())));
            }
        }
    }
    moves.shuffle(rng);
    // L2 prefers going back along the demonstration (work is undone), then any other
    // demonstration state short of the goal.
    let passes: &[u8] = if want_seen { &[0, 1] } else { &[1] };
    for &pass in passes {
        for (b, onto) in &moves {
            let target = match onto {
                Some(o) => {
                    let Some(c) = centre(world, o) else { continue };
                    Vector3::new(c[0], c[1], c[2] + DROP_HEIGHT)
                }
                None => {
                    let Some([x, y]) = table_spot(world, rng, !before.has_on) else {
                        continue;
                    };
                    Vector3::new(x, y, DROP_HEIGHT)
                }
            };
            let saved = world.clone();
            if world.move_block(b, target).is_ok() {
                let after = facts(world);
                // Without stacking (B2) a severe change takes the block out of reach.
                let out_of_reach = before.has_on
                    || !after
                        .iter()
                        .any(|f| is_about(&before.motions, f, Relation::InReach, Slot::Body, b));
                let ok = after != before.facts
                    && if want_seen {
                        before
                            .seen_at(&after)
                            .into_iter()
                            .any(|k| k < n && (pass == 1 || cur.is_some_and(|c| k < c)))
                    } else {
                        !before.seen_subset(&after) && out_of_reach
                    };
                // The moved block stays where an arm can grasp or pull it.
                if ok && handleable(world, b).is_ok() {
                    let to = centre(world, b).unwrap_or([0.0; 3]);
                    // Where it came to rest, not where it was dropped: a table spot can be
                    // over another block.
                    let place = resting_place(world, &after, b);
                    let what = if want_seen {
                        "a state of the demonstration"
                    } else {
                        "a state the demonstration never visits"
                    };
                    return Ok(Injection {
                        level,
                        description: format!(
                            "{}: moved {b} {place}: {what}",
                            level.as_str().to_uppercase()
                        ),
                        moved: vec![(b.clone(), to)],
                        during: None,
                        push: None,
                    });
                }
            }
            *world = saved;
        }
    }
    Err(format!(
        "{}: no single block move reaches such a state",
        level.as_str().to_uppercase()
    ))
}

/// L4: a new block on top of a clear block (blocks something must still be stacked on first),
/// such that no L_k ⊆ S_C. Without stacking (B2, whose facts say nothing else a new block could
/// spoil) it is handed to an idle arm instead ([`new_block_in_hand`]).
fn new_block(
    world: &mut World,
    before: &Before,
    busy: &[usize],
    rng: &mut Pcg64Mcg,
) -> Result<Injection, String> {
    let snap = world.snapshot();
    let name = NEW_BLOCK_NAMES
        .into_iter()
        .find(|n| {
            !snap.bodies.iter().any(|b| b.name == *n) && !snap.arms.iter().any(|a| a.name == *n)
        })
        .ok_or("L4: no free block name")?;
    if !before.has_on {
        return new_block_in_hand(world, before, name, busy, rng);
    }
    let mut targets: Vec<String> = before
        .blocks
        .iter()
        .filter(|b| is_clear(&before.motions, &before.facts, b))
        .cloned()
        .collect();
    targets.shuffle(rng);
    // Blocks that something must still be stacked on come first: the new block is in
    // the way there.
    let goal = before.trace.states.last().cloned().unwrap_or_default();
    let needed = |t: &String| {
        goal.iter().any(|f| {
            is_about(&before.motions, f, Relation::OnBlock, Slot::Below, t)
                && !before.facts.contains(f)
        })
    };
    targets.sort_by_key(|t| !needed(t));
    // A spot on the table for the new block first, then it is dropped on the target.
    let Some([x, y]) = table_spot(world, rng, false) else {
        return Err("L4: no room for a new block".into());
    };
    let mut with_block = snap.clone();
    with_block
        .bodies
        .push(new_block_body(name, [x, y, 0.5 * BLOCK_SIZE], 0.0));
    let n_targets = targets.len();
    for (ti, t) in targets.into_iter().enumerate() {
        let last_resort = ti + 1 == n_targets;
        let Some(c) = centre(world, &t) else { continue };
        let Ok(mut w2) =
            World::from_snapshot(&with_block).map(|w| w.with_motions(world.motions_arc()))
        else {
            continue;
        };
        if w2
            .move_block(name, Vector3::new(c[0], c[1], c[2] + DROP_HEIGHT))
            .is_err()
        {
            continue;
        }
        let after = facts(&w2);
        if handleable(&w2, name).is_err() {
            continue;
        }
        if !before.seen_subset(&after) || (last_resort && !before.seen_equal(&after)) {
            let to = centre(&w2, name).unwrap_or([0.0; 3]);
            *world = w2;
            return Ok(Injection {
                level: Level::L4,
                description: format!("L4: a new block {name} appeared on {t}"),
                moved: vec![(name.to_string(), to)],
                during: None,
                push: None,
            });
        }
    }
    Err("L4: no block can take a new block on top".into())
}

/// A new 6 cm block called `name` centred at `at`, turned by `yaw` about world `z`.
fn new_block_body(name: &str, at: [f64; 3], yaw: f64) -> BodySnapshot {
    let q = nalgebra::UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw);
    BodySnapshot {
        name: name.to_string(),
        kind: BodyKind::Block,
        shape: ShapeSnapshot::Cuboid {
            half_extents: [0.5 * BLOCK_SIZE; 3],
        },
        pose: PoseSnapshot {
            position: at,
            quaternion: [q.i, q.j, q.k, q.w],
        },
        color: BLOCK_COLORS[4].into(),
        lost: false,
    }
}

/// L4 without stacking: a new block handed to an idle arm with an empty hand (a person puts it
/// between the fingers), so the hand is no longer empty and no L_k ⊆ S_C: every grasp of the
/// demonstration waits until the block is put down. Refused when every arm is busy or
/// holding something, or the block would touch another body.
fn new_block_in_hand(
    world: &mut World,
    before: &Before,
    name: &str,
    busy: &[usize],
    rng: &mut Pcg64Mcg,
) -> Result<Injection, String> {
    let snap = world.snapshot();
    let mut arms: Vec<usize> = (0..snap.arms.len())
        .filter(|a| !busy.contains(a) && world.held_by(*a).is_none())
        .collect();
    arms.shuffle(rng);
    for a in arms {
        let Some(tcp) = world.tcp_pose(a) else {
            continue;
        };
        // Square to the fingers, centred between them.
        let (_, _, yaw) = tcp.rotation.euler_angles();
        let mut with_block = snap.clone();
        with_block
            .bodies
            .push(new_block_body(name, tcp.translation.vector.into(), yaw));
        with_block.arms[a].holding = Some(name.to_string());
        with_block.arms[a].gripper_opening = BLOCK_SIZE;
        let Ok(w2) = World::from_snapshot(&with_block).map(|w| w.with_motions(world.motions_arc()))
        else {
            continue;
        };
        if w2.check_invariants().is_err() || before.seen_subset(&facts(&w2)) {
            continue;
        }
        let to = centre(&w2, name).unwrap_or([0.0; 3]);
        let arm = snap.arms[a].name.clone();
        *world = w2;
        return Ok(Injection {
            level: Level::L4,
            description: format!(
                "L4: a new block {name} was put into the hand of {arm}: no grasp of the plan can run before it is put down"
            ),
            moved: vec![(name.to_string(), to)],
            during: None,
            push: None,
        });
    }
    Err("L4: no idle arm has an empty hand to take a new block (the domain cannot put one in the plan's way otherwise)".into())
}
