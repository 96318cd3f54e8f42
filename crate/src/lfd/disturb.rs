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
//! ([`crate::sim::disturb::handleable`], IK), is undone: an injection never makes
//! the task geometrically impossible; when no candidate qualifies it is refused with the reason.

use std::collections::BTreeSet;

use nalgebra::Vector3;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use crate::sim::disturb::handleable;
use crate::sim::snapshot::{BodyKind, BodySnapshot, PoseSnapshot, ShapeSnapshot};
use crate::sim::{SceneGraph, World};

use super::demo::DemoTrace;
use super::session::Injection;

fn facts(world: &World) -> BTreeSet<String> {
    SceneGraph::from_world(world)
        .to_strings()
        .into_iter()
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

/// Whether nothing stands on `b` (by `(clear b)` where the domain has it, else by `on`).
fn is_clear(f: &BTreeSet<String>, b: &str) -> bool {
    if f.iter().any(|x| x.starts_with("(clear ")) {
        return f.contains(&format!("(clear {b})"));
    }
    !f.iter()
        .any(|x| x.starts_with("(on ") && x.ends_with(&format!(" {b})")))
}

/// A table spot for a block: random (x, y) over a table top, in reach of some arm unless
/// `anywhere`.
fn table_spot(world: &World, rng: &mut Pcg64Mcg, anywhere: bool) -> Option<[f64; 2]> {
    let snap = world.snapshot();
    // Scenes with table regions (B3): a spot inside a random region, so `(at x p)` holds.
    if !snap.regions.is_empty() {
        let r = &snap.regions[rng.random_range(0..snap.regions.len())];
        let m = 0.04;
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
    // Keep moved blocks away from shelves (a block behind the shelf cannot be pulled past it).
    let shelves: Vec<_> = snap
        .bodies
        .iter()
        .filter(|b| b.kind == BodyKind::Shelf)
        .filter_map(|b| world.body_aabb(&b.name))
        .collect();
    let clear_of_shelves = |x: f64, y: f64| {
        shelves.iter().all(|(lo, hi)| {
            x < lo.x - 0.25 || x > hi.x + 0.25 || y < lo.y - 0.25 || y > hi.y + 0.25
        })
    };
    for _ in 0..50 {
        let (lo, hi) = tables.get(rng.random_range(0..tables.len().max(1)))?;
        let x = rng.random_range(lo.x + 0.05..hi.x - 0.05);
        let y = rng.random_range(lo.y + 0.05..hi.y - 0.05);
        let ok = clear_of_shelves(x, y)
            && (anywhere
                || snap.arms.iter().any(|a| {
                    let b = a.base.position;
                    let d = libm::hypot(x - b[0], y - b[1]);
                    d > a.reach.min_radius + 0.03 && d < a.reach.max_radius - 0.05
                }));
        if ok {
            return Some([x, y]);
        }
    }
    None
}

/// Injects a disturbance of `level` (`l1`..`l4`) into `world`; `trace` defines "seen in the
/// demonstration". Deterministic in `seed`.
///
/// `spots` are places the demonstration puts blocks down (its placements): where the scene has
/// no stacking (B2), the L4 block appears on one of them, in the way of the plan.
pub fn inject(
    world: &mut World,
    level: &str,
    trace: &DemoTrace,
    spots: &[(f64, f64)],
    seed: u64,
) -> Result<Injection, String> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let before = facts(world);
    let seen_subset = |f: &BTreeSet<String>| trace.states.iter().any(|l| l.is_subset(f));
    let seen_equal = |f: &BTreeSet<String>| trace.states.iter().any(|l| l == f);
    let level = level.to_ascii_lowercase();
    let blocks = free_blocks(world);
    // Domains without `on` (B2) cannot express a block on a block: only table moves there, and
    // a severe change is a block moved out of reach.
    let has_on = world.snapshot().predicates.iter().any(|p| p == "on");
    match level.as_str() {
        "l1" => {
            let mut order = blocks.clone();
            order.shuffle(&mut rng);
            for b in order {
                let Some(c) = centre(world, &b) else { continue };
                for _ in 0..12 {
                    let a = rng.random_range(0.0..std::f64::consts::TAU);
                    let r = rng.random_range(0.02..0.05);
                    let target = Vector3::new(
                        c[0] + r * libm::cos(a),
                        c[1] + r * libm::sin(a),
                        c[2] + 0.001,
                    );
                    let saved = world.clone();
                    if world.move_block(&b, target).is_ok()
                        && facts(world) == before
                        && handleable(world, &b).is_ok()
                    {
                        let to = centre(world, &b).unwrap_or(c);
                        return Ok(Injection {
                            level: "l1".into(),
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
        "l2" | "l3" => {
            let want_seen = level == "l2";
            let n = trace.states.len().saturating_sub(1);
            let cur = trace.states.iter().position(|l| *l == before);
            let mut moves: Vec<(String, Option<String>)> = vec![];
            for b in &blocks {
                if !is_clear(&before, b) {
                    continue;
                }
                // Several table spots per block (a spot is drawn per try).
                for _ in 0..6 {
                    moves.push((b.clone(), None));
                }
                for o in &blocks {
                    if has_on && o != b && is_clear(&before, o) {
                        moves.push((b.clone(), Some(o.clone())));
                    }
                }
            }
            moves.shuffle(&mut rng);
            // L2 prefers going back along the demonstration (work is undone), then any other
            // demonstration state short of the goal.
            let passes: &[u8] = if want_seen { &[0, 1] } else { &[1] };
            for &pass in passes {
                for (b, onto) in &moves {
                    let target = match onto {
                        Some(o) => {
                            let Some(c) = centre(world, o) else { continue };
                            Vector3::new(c[0], c[1], c[2] + 0.1)
                        }
                        None => {
                            let Some([x, y]) = table_spot(world, &mut rng, !has_on) else {
                                continue;
                            };
                            Vector3::new(x, y, 0.1)
                        }
                    };
                    let saved = world.clone();
                    if world.move_block(b, target).is_ok() {
                        let after = facts(world);
                        // Without stacking (B2) a severe change takes the block out of reach.
                        let out_of_reach = has_on
                            || !after.iter().any(|f| {
                                f.starts_with("(inreach ") && f.ends_with(&format!(" {b})"))
                            });
                        let ok = after != before
                            && if want_seen {
                                trace.states.iter().enumerate().any(|(k, l)| {
                                    *l == after
                                        && k < n
                                        && (pass == 1 || cur.is_some_and(|c| k < c))
                                })
                            } else {
                                !seen_subset(&after) && out_of_reach
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
                                level: level.clone(),
                                description: format!(
                                    "{}: moved {b} {place}: {what}",
                                    level.to_uppercase()
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
                level.to_uppercase()
            ))
        }
        "l4" => {
            let snap = world.snapshot();
            let name = ["e", "f", "g", "h", "x", "y", "z"]
                .into_iter()
                .find(|n| {
                    !snap.bodies.iter().any(|b| b.name == *n)
                        && !snap.arms.iter().any(|a| a.name == *n)
                })
                .ok_or("L4: no free block name")?;
            let mut targets: Vec<String> = blocks
                .iter()
                .filter(|b| is_clear(&before, b))
                .cloned()
                .collect();
            targets.shuffle(&mut rng);
            // Blocks that something must still be stacked on come first: the new block is in
            // the way there.
            let goal = trace.states.last().cloned().unwrap_or_default();
            let needed = |t: &String| {
                goal.iter().any(|f| {
                    f.starts_with("(on ") && f.ends_with(&format!(" {t})")) && !before.contains(f)
                })
            };
            targets.sort_by_key(|t| !needed(t));
            let n_targets = targets.len();
            let targets: Vec<(usize, String)> = targets.into_iter().enumerate().collect();
            // A spot on the table for the new block first, then it is dropped on the target.
            let Some([x, y]) = table_spot(world, &mut rng, false) else {
                return Err("L4: no room for a new block".into());
            };
            let mut s2 = snap.clone();
            s2.bodies.push(BodySnapshot {
                name: name.to_string(),
                kind: BodyKind::Block,
                shape: ShapeSnapshot::Cuboid {
                    half_extents: [0.03; 3],
                },
                pose: PoseSnapshot {
                    position: [x, y, 0.03],
                    quaternion: [0.0, 0.0, 0.0, 1.0],
                },
                color: "#9467bd".into(),
                lost: false,
            });
            if !has_on {
                // No stacking in this domain: the new block appears where the demonstration puts
                // a block down (in the way), else on the table.
                let mut order: Vec<(f64, f64)> = spots.to_vec();
                order.shuffle(&mut rng);
                if let Ok(w2) = World::from_snapshot(&s2) {
                    for (sx, sy) in order {
                        let mut w3 = w2.clone();
                        // Not on the shelf: a block left on the shelf can take the room the
                        // goal needs there, and no action takes a block off the shelf.
                        if w3.move_block(name, Vector3::new(sx, sy, 0.3)).is_ok()
                            && !seen_equal(&facts(&w3))
                            && !facts(&w3).contains(&format!("(onshelf {name})"))
                            && handleable(&w3, name).is_ok()
                        {
                            let to = centre(&w3, name).unwrap_or([sx, sy, 0.0]);
                            *world = w3;
                            return Ok(Injection {
                                level: "l4".into(),
                                description: format!(
                                    "L4: a new block {name} appeared where the demonstration puts a block down"
                                ),
                                moved: vec![(name.to_string(), to)],
                            });
                        }
                    }
                    if !seen_equal(&facts(&w2)) && handleable(&w2, name).is_ok() {
                        *world = w2;
                        return Ok(Injection {
                            level: "l4".into(),
                            description: format!("L4: a new block {name} appeared on the table"),
                            moved: vec![(name.to_string(), [x, y, 0.03])],
                        });
                    }
                }
                return Err("L4: no room for a new block".into());
            }
            for (ti, t) in targets {
                let last_resort = ti + 1 == n_targets;
                let Some(c) = centre(world, &t) else { continue };
                let Ok(mut w2) = World::from_snapshot(&s2) else {
                    continue;
                };
                if w2
                    .move_block(name, Vector3::new(c[0], c[1], c[2] + 0.1))
                    .is_err()
                {
                    continue;
                }
                let after = facts(&w2);
                if handleable(&w2, name).is_err() {
                    continue;
                }
                if !seen_subset(&after) || (last_resort && !seen_equal(&after)) {
                    let to = centre(&w2, name).unwrap_or([0.0; 3]);
                    *world = w2;
                    return Ok(Injection {
                        level: "l4".into(),
                        description: format!("L4: a new block {name} appeared on {t}"),
                        moved: vec![(name.to_string(), to)],
                    });
                }
            }
            Err("L4: no block can take a new block on top".into())
        }
        other => Err(format!("unknown disturbance level {other:?} (l1..l4)")),
    }
}
