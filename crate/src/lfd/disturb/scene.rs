//! What every disturbance level reads of the world before it changes it ([`Before`]), and
//! where a block may go: the facts, free and clear blocks, a block's resting place, a spot on
//! a table in reach, and the margins that keep a spot graspable.

use std::collections::BTreeSet;
use std::sync::Arc;

use rand::Rng;
use rand_pcg::Pcg64Mcg;

use crate::sim::BodyKind;
use crate::sim::BLOCK_SIZE;
use crate::sim::{Motions, Relation, Slot};
use crate::sim::{SceneGraph, World};

use crate::lfd::DemoTrace;

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
pub(super) const L1_SHIFT: std::ops::Range<f64> = 0.02..0.05;
/// Directions drawn for a push or a move before the candidate is given up.
pub(super) const MOTION_TRIES: usize = 12;
/// Height above its centre to which an L1 move lifts a block before it settles (m).
pub(super) const L1_LIFT: f64 = 0.001;
/// Height above its target (a block's centre, or the table top) from which a moved or added
/// block is dropped to settle (m).
pub(super) const DROP_HEIGHT: f64 = 0.1;
/// Names an added block may take, in order.
pub(super) const NEW_BLOCK_NAMES: [&str; 7] = ["e", "f", "g", "h", "x", "y", "z"];

/// The world's fluent facts, as the demonstration's states list them (type predicates left out).
pub(super) fn facts(world: &World) -> BTreeSet<String> {
    let m = world.motions();
    SceneGraph::from_world(world)
        .to_strings()
        .into_iter()
        .filter(|f| !m.is_type_fact(f))
        .collect()
}

pub(super) fn centre(world: &World, b: &str) -> Option<[f64; 3]> {
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
pub(super) fn is_clear(m: &Motions, f: &BTreeSet<String>, b: &str) -> bool {
    if let Some(spec) = m.fact(Relation::Clear) {
        return spec
            .render(&[(Slot::Body, b)])
            .is_some_and(|c| f.contains(&c));
    }
    !f.iter()
        .any(|x| is_about(m, x, Relation::OnBlock, Slot::Below, b))
}

/// Whether fact `f` states relation `rel` with `slot` = `value`.
pub(super) fn is_about(m: &Motions, f: &str, rel: Relation, slot: Slot, value: &str) -> bool {
    matches!(m.relation_of(f), Some((r, spec, args)) if r == rel && spec.value(&args, slot) == Some(value))
}

/// Where block `b` rests, as the scene graph's facts `after` state it (`onto c`, `to the table`,
/// `onto the shelf`, with the region it lies in), else from its height in `world`.
pub(super) fn resting_place(world: &World, after: &BTreeSet<String>, b: &str) -> String {
    let m = world.motions();
    let about = |rel: Relation| {
        after.iter().find_map(|f| match m.relation_of(f) {
            Some((r, spec, args)) if r == rel && spec.value(&args, Slot::Body) == Some(b) => {
                Some((
                    spec.clone(),
                    args.iter().map(|a| a.to_string()).collect::<Vec<_>>(),
                ))
            }
            _ => None,
        })
    };
    let region = about(Relation::InRegion)
        .and_then(|(spec, args)| {
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            spec.value(&args, Slot::Region).map(|r| format!(" in {r}"))
        })
        .unwrap_or_default();
    if let Some((spec, args)) = about(Relation::OnBlock) {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        if let Some(below) = spec.value(&args, Slot::Below) {
            return format!("onto {below}");
        }
    }
    if about(Relation::OnShelf).is_some() {
        return "onto the shelf".into();
    }
    if about(Relation::OnTable).is_some() {
        return format!("to the table{region}");
    }
    // The domain states none of these: read the height (a block on the table top stands half
    // its side above it).
    match centre(world, b) {
        Some(c) if c[2] > BLOCK_SIZE => format!("onto another body{region}"),
        _ => format!("to the table{region}"),
    }
}

/// A table spot for a block: random (x, y) over a table top, in reach of some arm unless
/// `anywhere`.
pub(super) fn table_spot(world: &World, rng: &mut Pcg64Mcg, anywhere: bool) -> Option<[f64; 2]> {
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
    let tables = world.aabbs_of(BodyKind::Table);
    let shelves = world.aabbs_of(BodyKind::Shelf);
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
pub(super) struct Before<'a> {
    /// S_C.
    pub(super) facts: BTreeSet<String>,
    /// Free blocks, sorted.
    pub(super) blocks: Vec<String>,
    /// Whether the domain can say a block is on a block (B2 cannot).
    pub(super) has_on: bool,
    /// The demonstration.
    pub(super) trace: &'a DemoTrace,
    /// What the domain's predicates mean.
    pub(super) motions: Arc<Motions>,
}

impl Before<'_> {
    /// `f` as the demonstration's states list facts: the task's static facts left out (a
    /// scene reports `(inreach panda hook)`, which no action of B2 changes).
    fn fluents(&self, f: &BTreeSet<String>) -> BTreeSet<String> {
        f.difference(&self.trace.static_facts).cloned().collect()
    }

    /// Some L_k ⊆ `f`.
    pub(super) fn seen_subset(&self, f: &BTreeSet<String>) -> bool {
        self.trace.states.iter().any(|l| l.is_subset(f))
    }

    /// The k of every L_k equal to `f`'s fluents.
    pub(super) fn seen_at(&self, f: &BTreeSet<String>) -> Vec<usize> {
        let f = self.fluents(f);
        (0..self.trace.states.len())
            .filter(|&k| self.trace.states[k] == f)
            .collect()
    }

    /// Some L_k equals `f`'s fluents.
    pub(super) fn seen_equal(&self, f: &BTreeSet<String>) -> bool {
        !self.seen_at(f).is_empty()
    }
}

impl<'a> Before<'a> {
    pub(super) fn of(world: &World, trace: &'a DemoTrace) -> Before<'a> {
        Before {
            facts: facts(world),
            blocks: free_blocks(world),
            // Domains without `on` (B2) cannot express a block on a block: only table moves
            // there, and a severe change is a block moved out of reach.
            has_on: world.motions().reports(Relation::OnBlock),
            motions: world.motions_arc(),
            trace,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::Benchmark;
    use nalgebra::Vector3;

    /// A block dropped over another comes to rest on it: its resting place says so, whatever
    /// spot it was dropped at; one dropped on a free spot is on the table.
    #[test]
    fn the_resting_place_is_read_from_the_scene_graph() {
        let mut w = Benchmark::B1.scene();
        let b = centre(&w, "b").unwrap();
        // Off b's centre by a third of a block: still over b.
        w.move_block("c", Vector3::new(b[0] + 0.02, b[1], b[2] + 0.1))
            .unwrap();
        assert_eq!(resting_place(&w, &facts(&w), "c"), "onto b");
        let a = centre(&w, "a").unwrap();
        w.move_block("a", Vector3::new(a[0], a[1] + 0.1, 0.1))
            .unwrap();
        assert_eq!(resting_place(&w, &facts(&w), "a"), "to the table");
    }
}
