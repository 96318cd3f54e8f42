//! Scene generators: a benchmark's tower task scaled to N blocks (B1-N, B3-N), with its problem
//! and a demonstration recorded by the scripted expert along a planned action sequence.
//!
//! Blocks are named `a`, `b`, `c`, … and laid out on a grid of [`SPOT_SPACING`] around the
//! centre of the benchmark's start area (B1's table, B3's left-table region), keeping spots
//! inside the reach annulus of some arm and in front of it. The goal is the template's goal
//! shape for N blocks: towers of at most [`MAX_TOWER_HEIGHT`] blocks ([`tower_heights`]: one
//! tower `a` on `b` on … on the Nth block up to 12 blocks, two from 13), plus the template's
//! other goal facts about each tower's bottom block (B3: the bottom block in the right-table
//! region). One tower grows on the spot nearest the area's centre; several on spots at least
//! [`TOWER_SPACING`] apart where the arm reaches their tops. The demonstration builds the towers
//! bottom-up, one after the other, and each block starts where the arm takes it and carries it
//! to its tower clear of the towers as they then stand.

mod layout;
mod names;
mod script;

pub use layout::{SPOT_SPACING, TOWER_SPACING};
pub use names::block_names;
use names::err;

use super::benchmark::{Benchmark, BenchmarkSources};
use super::demo::{record_script, ExpertParams};
use super::motions::{Relation, Slot};
use super::scene_graph::Fact;
use super::world::World;
use super::SceneError;

/// Fewest blocks of a generated B1 task.
pub const MIN_BLOCKS_B1: usize = 3;
/// Fewest blocks of a generated B3 task.
pub const MIN_BLOCKS_B3: usize = 2;
/// Most blocks of a generated B1 task: two towers of 10, whose tops the arm reaches on their
/// spots (a tower of 11 there still is).
pub const MAX_BLOCKS: usize = 20;
/// Most blocks of a generated B3 task, one tower: the right arm does not reach over a taller
/// tower on the right-table spot. Two towers do not fit: the left-table region, where the
/// blocks start, has room for 13 blocks only, and the right-table region's only spots
/// [`TOWER_SPACING`] apart are its two ends, the far one 56 cm from the right arm, which reaches
/// over 9 blocks there; widening the regions would change the benchmark's own workcell.
pub const MAX_BLOCKS_B3: usize = 10;
/// Most blocks of one tower of a generated task: the tallest single tower the loop builds
/// (B1 with 12 blocks); a task with more blocks has the fewest towers of at most this many.
pub const MAX_TOWER_HEIGHT: usize = 12;

/// Seed of the expert's variation in a generated demonstration.
const DEMO_SEED: u64 = 1;

/// The allowed block counts of a benchmark's N-block variant, or why it has none.
pub fn block_range(b: Benchmark) -> Result<std::ops::RangeInclusive<usize>, SceneError> {
    match b {
        Benchmark::B1 => Ok(MIN_BLOCKS_B1..=MAX_BLOCKS),
        Benchmark::B3 => Ok(MIN_BLOCKS_B3..=MAX_BLOCKS_B3),
        Benchmark::B2 => Err(err("B2 has no N-block variant")),
    }
}

/// The allowed block counts of every benchmark with an N-block variant, in words, from
/// [`block_range`]: `B1: 3 to 20, B3: 2 to 10` (help texts).
pub fn block_ranges_text() -> String {
    Benchmark::ALL
        .into_iter()
        .filter_map(|b| {
            block_range(b).ok().map(|r| {
                format!(
                    "{}: {} to {}",
                    b.as_str().to_uppercase(),
                    r.start(),
                    r.end()
                )
            })
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The heights of the goal's towers for `n` blocks, the first tower's (`a` on …) first: the
/// fewest towers of at most [`MAX_TOWER_HEIGHT`] blocks, the first ones a block taller where
/// `n` does not split evenly (13 blocks: 7 and 6; 20: 10 and 10; up to 12: one tower).
pub fn tower_heights(n: usize) -> Vec<usize> {
    let t = n.div_ceil(MAX_TOWER_HEIGHT).max(1);
    (0..t).map(|i| n / t + usize::from(i < n % t)).collect()
}

/// `names` cut into the goal's towers ([`tower_heights`]), each top first.
fn towers(names: &[String]) -> Vec<&[String]> {
    let mut rest = names;
    let mut out = Vec::new();
    for h in tower_heights(names.len()) {
        let (tower, tail) = rest.split_at(h.min(rest.len()));
        out.push(tower);
        rest = tail;
    }
    out
}

/// The order in which the demonstration puts the blocks of `towers` in place: the bottoms,
/// then each tower bottom-up, one after the other (so a block for the second tower may start
/// behind it, in the way of the arm reaching it, while the first is built).
fn build_order(towers: &[&[String]]) -> Vec<String> {
    let bottoms = towers.iter().filter_map(|t| t.last().cloned());
    let rest = towers.iter().flat_map(|t| t.iter().rev().skip(1).cloned());
    bottoms.chain(rest).collect()
}

/// The files of benchmark `b`'s tower task with `n` blocks: the template's domain and motions,
/// a generated scene, problem and demonstration. `n` must lie in [`block_range`].
pub fn tower_task(b: Benchmark, n: usize) -> Result<BenchmarkSources, SceneError> {
    let range = block_range(b)?;
    if !range.contains(&n) {
        return Err(err(format!(
            "{}: {n} blocks (allowed: {} to {})",
            b.as_str(),
            range.start(),
            range.end()
        )));
    }
    let names = block_names(n);
    let towers = towers(&names);
    let build = build_order(&towers);
    let snap = layout::tower_scene(b, &towers, &build)?;
    let world = World::from_snapshot(&snap)?.with_motions(b.motions());
    world
        .check_invariants()
        .map_err(|v| err(format!("generated scene breaks an invariant: {v:?}")))?;
    for x in &names {
        super::reach::handleable(&world, x).map_err(|e| err(format!("block {x}: {e}")))?;
    }
    let goal = tower_goal(b, &names)?;
    let problem = b.problem_for_goal(&world, &format!("{}-{n}-blocks", b.dir_name()), &goal);
    let script = script::tower_script(b, &world, &problem, &snap, &build, &goal)?;
    let demo = record_script(
        world,
        &script,
        &goal,
        b.dir_name(),
        DEMO_SEED,
        &ExpertParams::default(),
    )
    .map_err(|e| err(format!("demonstration: {e}")))?;
    let demo = serde_json::to_string_pretty(&demo).map_err(|e| err(e.to_string()))?;
    let scene = serde_json::to_string(&snap).map_err(|e| err(e.to_string()))?;
    let template = b.sources()?;
    Ok(BenchmarkSources {
        folder: None,
        scene,
        problem,
        demo,
        ..template
    })
}

/// The goal of the N-block task on `names`: each tower of [`tower_heights`] stacked top to
/// bottom (`x1` on `x2` on …), and the template goal's other facts with its bottom block
/// renamed to each tower's bottom.
pub fn tower_goal(b: Benchmark, names: &[String]) -> Result<Vec<Fact>, SceneError> {
    let motions = b.motions();
    let on = motions
        .fact(Relation::OnBlock)
        .ok_or_else(|| err("the domain declares no on-block relation"))?;
    let template = b.goal();
    let is_on = |f: &Fact| f.predicate == on.predicate;
    let below = on.args.iter().position(|s| *s == Slot::Below);
    let body = on.args.iter().position(|s| *s == Slot::Body);
    let (Some(below), Some(body)) = (below, body) else {
        return Err(err("the on-block relation lacks a slot"));
    };
    // The template's bottom: below something, on nothing.
    let bottom = template
        .iter()
        .filter(|f| is_on(f))
        .filter_map(|f| f.args.get(below))
        .find(|y| {
            !template
                .iter()
                .any(|f| is_on(f) && f.args.get(body) == Some(y))
        })
        .cloned();
    if names.is_empty() {
        return Err(err("no blocks"));
    }
    let towers = towers(names);
    let mut goal: Vec<Fact> = towers
        .iter()
        .flat_map(|t| t.windows(2))
        .map(|w| {
            let mut args = vec![String::new(); on.args.len()];
            args[body] = w[0].clone();
            args[below] = w[1].clone();
            Fact {
                predicate: on.predicate.clone(),
                args,
            }
        })
        .collect();
    for last in towers.iter().filter_map(|t| t.last()) {
        for f in template.iter().filter(|f| !is_on(f)) {
            let args = f
                .args
                .iter()
                .map(|a| {
                    if Some(a) == bottom.as_ref() {
                        last.clone()
                    } else {
                        a.clone()
                    }
                })
                .collect();
            let fact = Fact {
                predicate: f.predicate.clone(),
                args,
            };
            // A fact about no bottom holds once, whatever the towers.
            if !goal.contains(&fact) {
                goal.push(fact);
            }
        }
    }
    Ok(goal)
}
