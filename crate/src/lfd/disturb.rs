//! Disturbance injection for the loop (paper §IV-B), defined against the demonstration:
//!
//! ```text
//!   L1  move one free block on its support; S_C unchanged
//!   L2  move one clear block (to the table or onto another block) so that S_C = L_k for some k
//!   L3  move one clear block so that no L_k ⊆ S_C (a state the demonstration never visits)
//!   L4  add a new block on top of a clear block so that no L_k ⊆ S_C (it is in the way)
//! ```
//!
//! Candidates are tried in a seeded random order through the simulator's own user-move rule
//! ([`World::move_block`]: settles onto the support below, refuses interpenetration), so every
//! injected world satisfies the simulator's invariants (and the move rule refuses a world the
//! scene cannot describe: a block on the hook, on a held block, or on a block where the domain
//! has no `on`). A candidate whose resulting facts do not meet the level's definition, or that
//! leaves the moved or new block where no arm can grasp or pull it
//! ([`crate::sim::reach::handleable`], IK), is undone: an injection never makes
//! the task geometrically impossible; when no candidate qualifies it is refused with the reason.
//!
//! The same injector makes the Table I tasks (applied to the template scene), the disturbances
//! of Table II and of the soak, and those of the page's buttons
//! ([`Session::inject`](super::session::Session::inject)).

use std::collections::BTreeSet;
use std::sync::Arc;

use nalgebra::Vector3;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};

use crate::sim::benchmark::{BLOCK_COLORS, BLOCK_SIZE};
use crate::sim::motions::{Motions, Relation, Slot};
use crate::sim::reach::handleable;
use crate::sim::snapshot::{BodyKind, BodySnapshot, PoseSnapshot, ShapeSnapshot};
use crate::sim::{SceneGraph, World};

use super::demo::DemoTrace;

/// Disturbance levels of the paper (§IV-B); JSON and CLI: `l1`..`l4`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Level {
    /// Motion level: positions change, facts do not.
    L1,
    /// Slight task level: facts change to a state seen in the demonstration.
    L2,
    /// Severe task level: facts change to a state the demonstration never visits.
    L3,
    /// Extreme task level: a new block appears in the way.
    L4,
}

impl Level {
    /// All levels.
    pub const ALL: [Level; 4] = [Level::L1, Level::L2, Level::L3, Level::L4];

    /// `l1`..`l4`.
    pub fn as_str(self) -> &'static str {
        match self {
            Level::L1 => "l1",
            Level::L2 => "l2",
            Level::L3 => "l3",
            Level::L4 => "l4",
        }
    }

    /// Parses `l1`..`l4` (case-insensitive).
    pub fn parse(s: &str) -> Option<Level> {
        Level::ALL
            .into_iter()
            .find(|l| l.as_str().eq_ignore_ascii_case(s))
    }
}

/// What an injected disturbance did.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Injection {
    /// `l1`..`l4`.
    pub level: Level,
    /// What it did, in words.
    pub description: String,
    /// Bodies moved or added: (name, new centre).
    pub moved: Vec<(String, [f64; 3])>,
}

/// Margin kept inside a table region when a spot is drawn in it (m).
const REGION_MARGIN: f64 = 0.04;
/// Margin kept inside a table top's edges when a spot is drawn on it (m).
const TABLE_EDGE_MARGIN: f64 = 0.05;
/// Distance from a shelf's footprint within which no spot is drawn (m): a block behind the
/// shelf cannot be pulled past it.
const SHELF_KEEPOUT: f64 = 0.25;
/// A spot in reach lies this far outside an arm's minimum reach radius (m)…
const REACH_INNER_MARGIN: f64 = 0.03;
/// …and this far inside its maximum reach radius (m).
const REACH_OUTER_MARGIN: f64 = 0.05;
/// Range of an L1 displacement (m): at least 2 cm, so it is a visible motion-level change.
const L1_SHIFT: std::ops::Range<f64> = 0.02..0.05;
/// Height above its centre to which an L1 move lifts a block before it settles (m).
const L1_LIFT: f64 = 0.001;
/// Height above its target (a block's centre, or the table top) from which a moved or added
/// block is dropped to settle (m).
const DROP_HEIGHT: f64 = 0.1;
/// Height from which an added block is dropped onto a spot where the demonstration puts a
/// block down (m): above every support of the scenes.
const SPOT_DROP_Z: f64 = 0.3;
/// Names an added block may take, in order.
const NEW_BLOCK_NAMES: [&str; 7] = ["e", "f", "g", "h", "x", "y", "z"];

/// The world's fluent facts, as the demonstration's states list them (type predicates left out).
fn facts(world: &World) -> BTreeSet<String> {
    let m = world.motions();
    SceneGraph::from_world(world)
        .to_strings()
        .into_iter()
        .filter(|f| !m.is_type_fact(f))
        .collect()
}

fn centre(world: &World, b: &str) -> Option<[f64; 3]> {
    world.body_pose(b).map(|p| {
        let v = p.translation.vector;
        [v.x, v.y, v.z]
    })
}

/// Free blocks (not held, not lost), sorted.
fn free_blocks(world: &World) -> Vec<String> {
    let held: BTreeSet<String> = (0..world.arm_names().len())
        .filter_map(|a| world.held_by(a).map(str::to_string))
        .collect();
    let mut v: Vec<String> = world
        .block_names()
        .into_iter()
        .filter(|b| !held.contains(*b) && !world.is_lost(b))
        .map(str::to_string)
        .collect();
    v.sort();
    v
}

/// Whether nothing stands on `b` (by the domain's `clear` fact where it states one, else by
/// `on_block`).
fn is_clear(m: &Motions, f: &BTreeSet<String>, b: &str) -> bool {
    if let Some(spec) = m.fact(Relation::Clear) {
        return spec
            .render(&[(Slot::Body, b)])
            .is_some_and(|c| f.contains(&c));
    }
    !f.iter()
        .any(|x| is_about(m, x, Relation::OnBlock, Slot::Below, b))
}

/// Whether fact `f` states relation `rel` with `slot` = `value`.
fn is_about(m: &Motions, f: &str, rel: Relation, slot: Slot, value: &str) -> bool {
    matches!(m.relation_of(f), Some((r, spec, args)) if r == rel && spec.value(&args, slot) == Some(value))
}

/// A table spot for a block: random (x, y) over a table top, in reach of some arm unless
/// `anywhere`.
fn table_spot(world: &World, rng: &mut Pcg64Mcg, anywhere: bool) -> Option<[f64; 2]> {
    let snap = world.snapshot();
    // Scenes with table regions (B3): a spot inside a random region, so `(at x p)` holds.
    if !snap.regions.is_empty() {
        let r = &snap.regions[rng.random_range(0..snap.regions.len())];
        let m = REGION_MARGIN;
        if r.max[0] - r.min[0] > 2.0 * m && r.max[1] - r.min[1] > 2.0 * m {
            return Some([
                rng.random_range(r.min[0] + m..r.max[0] - m),
                rng.random_range(r.min[1] + m..r.max[1] - m),
            ]);
        }
    }
    let tables: Vec<_> = snap
        .bodies
        .iter()
        .filter(|b| b.kind == BodyKind::Table)
        .filter_map(|b| world.body_aabb(&b.name))
        .collect();
    let shelves: Vec<_> = snap
        .bodies
        .iter()
        .filter(|b| b.kind == BodyKind::Shelf)
        .filter_map(|b| world.body_aabb(&b.name))
        .collect();
    let clear_of_shelves = |x: f64, y: f64| {
        shelves.iter().all(|(lo, hi)| {
            x < lo.x - SHELF_KEEPOUT
                || x > hi.x + SHELF_KEEPOUT
                || y < lo.y - SHELF_KEEPOUT
                || y > hi.y + SHELF_KEEPOUT
        })
    };
    for _ in 0..50 {
        let (lo, hi) = tables.get(rng.random_range(0..tables.len().max(1)))?;
        let x = rng.random_range(lo.x + TABLE_EDGE_MARGIN..hi.x - TABLE_EDGE_MARGIN);
        let y = rng.random_range(lo.y + TABLE_EDGE_MARGIN..hi.y - TABLE_EDGE_MARGIN);
        let ok = clear_of_shelves(x, y)
            && (anywhere
                || snap.arms.iter().any(|a| {
                    let b = a.base.position;
                    let d = libm::hypot(x - b[0], y - b[1]);
                    d > a.reach.min_radius + REACH_INNER_MARGIN
                        && d < a.reach.max_radius - REACH_OUTER_MARGIN
                }));
        if ok {
            return Some([x, y]);
        }
    }
    None
}

/// What every level needs to know about the world before the injection.
struct Before<'a> {
    /// S_C.
    facts: BTreeSet<String>,
    /// Free blocks, sorted.
    blocks: Vec<String>,
    /// Whether the domain can say a block is on a block (B2 cannot).
    has_on: bool,
    /// The demonstration.
    trace: &'a DemoTrace,
    /// What the domain's predicates mean.
    motions: Arc<Motions>,
}

impl Before<'_> {
    /// Some L_k ⊆ `f`.
    fn seen_subset(&self, f: &BTreeSet<String>) -> bool {
        self.trace.states.iter().any(|l| l.is_subset(f))
    }

    /// Some L_k = `f`.
    fn seen_equal(&self, f: &BTreeSet<String>) -> bool {
        self.trace.states.iter().any(|l| l == f)
    }
}

/// Injects a disturbance of `level` into `world`; `trace` defines "seen in the
/// demonstration". Deterministic in `seed`.
///
/// `spots` are places the demonstration puts blocks down (its placements): where the scene has
/// no stacking (B2), the L4 block appears on one of them, in the way of the plan.
pub fn inject(
    world: &mut World,
    level: Level,
    trace: &DemoTrace,
    spots: &[(f64, f64)],
    seed: u64,
) -> Result<Injection, String> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let before = Before {
        facts: facts(world),
        blocks: free_blocks(world),
        // Domains without `on` (B2) cannot express a block on a block: only table moves there,
        // and a severe change is a block moved out of reach.
        has_on: world.motions().reports(Relation::OnBlock),
        motions: world.motions_arc(),
        trace,
    };
    match level {
        Level::L1 => motion_level(world, &before, &mut rng),
        Level::L2 | Level::L3 => task_level(world, level, &before, &mut rng),
        Level::L4 => new_block(world, &before, spots, &mut rng),
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
    for b in order {
        let Some(c) = centre(world, &b) else { continue };
        for _ in 0..12 {
            let a = rng.random_range(0.0..std::f64::consts::TAU);
            let r = rng.random_range(L1_SHIFT);
            let target = Vector3::new(
                c[0] + r * libm::cos(a),
                c[1] + r * libm::sin(a),
                c[2] + L1_LIFT,
            );
            let saved = world.clone();
            if world.move_block(&b, target).is_ok()
                && facts(world) == before.facts
                && handleable(world, &b).is_ok()
            {
                let to = centre(world, &b).unwrap_or(c);
                return Ok(Injection {
                    level: Level::L1,
                    description: format!(
                        "L1: moved {b} by {:.0} mm; the facts are unchanged",
                        r * 1e3
                    ),
                    moved: vec![(b.clone(), to)],
                });
            }
            *world = saved;
        }
    }
    Err("L1: no block can be moved without changing the facts".into())
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
    let cur = trace.states.iter().position(|l| *l == before.facts);
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
                        trace.states.iter().enumerate().any(|(k, l)| {
                            *l == after && k < n && (pass == 1 || cur.is_some_and(|c| k < c))
                        })
                    } else {
                        !before.seen_subset(&after) && out_of_reach
                    };
                // The moved block stays where an arm can grasp or pull it.
                if ok && handleable(world, b).is_ok() {
                    let to = centre(world, b).unwrap_or([0.0; 3]);
                    let place = onto
                        .as_ref()
                        .map(|o| format!("onto {o}"))
                        .unwrap_or_else(|| "to the table".into());
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
/// such that no L_k ⊆ S_C; without stacking, on a spot where the demonstration puts a block
/// down ([`new_block_in_the_way`]).
fn new_block(
    world: &mut World,
    before: &Before,
    spots: &[(f64, f64)],
    rng: &mut Pcg64Mcg,
) -> Result<Injection, String> {
    let snap = world.snapshot();
    let name = NEW_BLOCK_NAMES
        .into_iter()
        .find(|n| {
            !snap.bodies.iter().any(|b| b.name == *n) && !snap.arms.iter().any(|a| a.name == *n)
        })
        .ok_or("L4: no free block name")?;
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
    let half = 0.5 * BLOCK_SIZE;
    with_block.bodies.push(BodySnapshot {
        name: name.to_string(),
        kind: BodyKind::Block,
        shape: ShapeSnapshot::Cuboid {
            half_extents: [half; 3],
        },
        pose: PoseSnapshot {
            position: [x, y, half],
            quaternion: [0.0, 0.0, 0.0, 1.0],
        },
        color: BLOCK_COLORS[4].into(),
        lost: false,
    });
    if !before.has_on {
        return new_block_in_the_way(world, before, name, &with_block, [x, y, half], spots, rng);
    }
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
            });
        }
    }
    Err("L4: no block can take a new block on top".into())
}

/// L4 without stacking: the new block appears where the demonstration puts a block down (in
/// the way), else at its table spot `on_table` in `with_block`.
fn new_block_in_the_way(
    world: &mut World,
    before: &Before,
    name: &str,
    with_block: &crate::sim::snapshot::WorldSnapshot,
    on_table: [f64; 3],
    spots: &[(f64, f64)],
    rng: &mut Pcg64Mcg,
) -> Result<Injection, String> {
    let mut order: Vec<(f64, f64)> = spots.to_vec();
    order.shuffle(rng);
    if let Ok(w2) = World::from_snapshot(with_block).map(|w| w.with_motions(world.motions_arc())) {
        for (sx, sy) in order {
            let mut w3 = w2.clone();
            // Not on the shelf: a block left on the shelf can take the room the goal needs
            // there, and no action takes a block off the shelf.
            if w3
                .move_block(name, Vector3::new(sx, sy, SPOT_DROP_Z))
                .is_ok()
                && !before.seen_equal(&facts(&w3))
                && !facts(&w3)
                    .iter()
                    .any(|f| is_about(&before.motions, f, Relation::OnShelf, Slot::Body, name))
                && handleable(&w3, name).is_ok()
            {
                let to = centre(&w3, name).unwrap_or([sx, sy, 0.0]);
                *world = w3;
                return Ok(Injection {
                    level: Level::L4,
                    description: format!(
                        "L4: a new block {name} appeared where the demonstration puts a block down"
                    ),
                    moved: vec![(name.to_string(), to)],
                });
            }
        }
        if !before.seen_equal(&facts(&w2)) && handleable(&w2, name).is_ok() {
            *world = w2;
            return Ok(Injection {
                level: Level::L4,
                description: format!("L4: a new block {name} appeared on the table"),
                moved: vec![(name.to_string(), on_table)],
            });
        }
    }
    Err("L4: no room for a new block".into())
}
