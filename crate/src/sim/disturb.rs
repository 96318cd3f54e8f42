//! Disturbances L1–L4 (paper §IV-B), seeded, applied to a world at any moment (blocks held by a
//! gripper are left alone).
//!
//! With `F` the scene-graph facts before and `F'` after, and `L = {L0..LN}` the demonstration's
//! states ([`demo_states`](super::demo::demo_states)):
//!
//! * **L1 motion-level**: one or more towers of free blocks are moved (≥ 2 cm) to new places and
//!   yaws, `F' = F`;
//! * **L2 slight task-level**: the free blocks are rearranged so that `F' ∈ L`, `F' ≠ F` (never the
//!   final state, which would solve the task);
//! * **L3 severe task-level**: the free blocks are rearranged to a random state with `F' ∉ L`, still
//!   solvable (every arrangement the injector builds is: blocks stay where an arm can reach them,
//!   blocks beyond reach in B2 stay where the hook can pull them);
//! * **L4 extreme task-level**: a new block appears where it blocks the plan: on top of a clear
//!   block still to be moved (B1, B3), or on the table in the way of a block still to be shelved
//!   (B2, whose domain has no stacking). `F'` has one more block.
//!
//! Placement: each moved block goes to a sampled spot (seeded) on its support — a table area the
//! right arm reaches, the shelf, a region, or the top of another block (±4 mm, yaw ±0.1 rad) —
//! through [`World::move_block_to`], so every rule of a user move applies (no interpenetration,
//! settles onto its support). A sample is kept only if the block's facts come out as intended and
//! the arms that must handle it can (IK of the top grasp; in B2 out-of-reach blocks: IK of the
//! hook's contact and pulled poses).

use super::benchmark::{Benchmark, BLOCK_COLORS, BLOCK_SIZE};
use super::demo::{pull_hook_poses_turned, PULL_LIFT, PULL_TARGET_RADIUS, PULL_TURNS};
use super::geometry;
use super::scene_graph::SceneGraph;
use super::snapshot::BodyKind;
use super::world::{yaw_of, World};
use nalgebra::{Isometry3, Translation3, Vector3};
use parry3d_f64::query;
use parry3d_f64::shape::Cuboid;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;

/// A disturbance level.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Level {
    /// Motion-level: positions change, facts do not.
    L1,
    /// Slight task-level: facts change to a state of the demonstration.
    L2,
    /// Severe task-level: facts change to a state the demonstration never visits.
    L3,
    /// Extreme task-level: a new block appears in the way.
    L4,
}

impl Level {
    /// All four, in order.
    pub const ALL: [Level; 4] = [Level::L1, Level::L2, Level::L3, Level::L4];

    /// Parses `l1`..`l4` (any case).
    pub fn parse(s: &str) -> Option<Level> {
        match s.to_ascii_lowercase().as_str() {
            "l1" => Some(Level::L1),
            "l2" => Some(Level::L2),
            "l3" => Some(Level::L3),
            "l4" => Some(Level::L4),
            _ => None,
        }
    }

    /// `l1`..`l4`.
    pub fn id(self) -> &'static str {
        match self {
            Level::L1 => "l1",
            Level::L2 => "l2",
            Level::L3 => "l3",
            Level::L4 => "l4",
        }
    }
}

/// One body moved by an injector.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BlockMove {
    /// The body.
    pub body: String,
    /// Centre before (m).
    pub from: [f64; 3],
    /// Centre after (m).
    pub to: [f64; 3],
}

/// What an injector did, in words and as data (for logs and the page).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Disturbance {
    /// The level.
    pub level: Level,
    /// The seed used.
    pub seed: u64,
    /// One sentence for a log.
    pub description: String,
    /// Bodies whose centre moved (more than 1 mm), with old and new centres.
    pub moves: Vec<BlockMove>,
    /// Blocks added (L4).
    pub added: Vec<String>,
    /// Scene-graph facts before.
    pub facts_before: Vec<String>,
    /// Scene-graph facts after.
    pub facts_after: Vec<String>,
}

/// An injector could not do what it promises here.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DisturbError {
    /// The level makes no sense in this world (e.g. L2 when no other demo state is realisable).
    #[error("{0}")]
    NotApplicable(String),
    /// No arrangement was found within the attempts.
    #[error("no arrangement found: {0}")]
    Failed(String),
}

/// Where a block should rest.
#[derive(Clone, Debug, PartialEq)]
enum Support {
    /// On a table, optionally in a region (B3) and in or out of reach (B2).
    Table {
        region: Option<String>,
        inreach: Option<bool>,
    },
    /// On the shelf (B2).
    Shelf,
    /// On another block.
    On(String),
}

fn facts(w: &World) -> BTreeSet<String> {
    SceneGraph::from_world(w).to_strings().into_iter().collect()
}

fn args(f: &str) -> Vec<&str> {
    f.trim_matches(|c| c == '(' || c == ')')
        .split_whitespace()
        .collect()
}

/// Blocks that are neither held nor lost.
fn free_blocks(w: &World) -> Vec<String> {
    let held: Vec<String> = (0..w.arm_names().len())
        .filter_map(|a| w.held_by(a).map(String::from))
        .collect();
    w.block_names()
        .into_iter()
        .filter(|b| !held.iter().any(|h| h == b) && !w.is_lost(b))
        .map(String::from)
        .collect()
}

/// The support spec of block `x` in a fact set.
fn spec_of(x: &str, f: &BTreeSet<String>) -> Option<Support> {
    let mut region = None;
    let mut inreach = false;
    let mut on_table = false;
    let mut on_shelf = false;
    let mut on = None;
    for fact in f {
        let a = args(fact);
        match a.as_slice() {
            ["on", y, z] if *y == x => on = Some(z.to_string()),
            ["ontable", y] if *y == x => on_table = true,
            ["onshelf", y] if *y == x => on_shelf = true,
            ["at", y, p] if *y == x => region = Some(p.to_string()),
            ["inreach", _, y] if *y == x => inreach = true,
            _ => {}
        }
    }
    if let Some(y) = on {
        return Some(Support::On(y));
    }
    if on_shelf {
        return Some(Support::Shelf);
    }
    if on_table {
        return Some(Support::Table {
            region,
            inreach: Some(inreach),
        });
    }
    None
}

fn centre(w: &World, x: &str) -> Vector3<f64> {
    w.body_pose(x)
        .map(|p| p.translation.vector)
        .unwrap_or_else(Vector3::zeros)
}

/// Arms that must be able to grasp block `x` where it is, per benchmark.
fn arms_for(w: &World, b: Benchmark, f: &BTreeSet<String>, x: &str) -> Vec<usize> {
    match b {
        Benchmark::B1 => vec![0],
        Benchmark::B2 => {
            if f.iter()
                .any(|s| args(s).as_slice() == ["inreach", "panda", x])
            {
                vec![0]
            } else {
                vec![]
            }
        }
        Benchmark::B3 => {
            let region = f.iter().find_map(|s| match args(s).as_slice() {
                ["at", y, p] if *y == x => Some(p.to_string()),
                _ => None,
            });
            let names: Vec<&str> = match region.as_deref() {
                Some("left-table") => vec!["left"],
                Some("handover") => vec!["left", "right"],
                Some("right-table") => vec!["right"],
                _ => vec![],
            };
            names.iter().filter_map(|n| w.arm_index(n)).collect()
        }
    }
}

/// Whether the arms that must handle block `x` can, where it is now.
fn workable(w: &World, b: Benchmark, x: &str) -> bool {
    let f = facts(w);
    for arm in arms_for(w, b, &f, x) {
        let Some(g) = geometry::grasp_pose(w, arm, x) else {
            return false;
        };
        if w.reachable(arm, &g).is_err() {
            return false;
        }
        let mut above = g;
        above.translation.vector.z += 0.12;
        if w.reachable(arm, &above).is_err() {
            return false;
        }
    }
    if b == Benchmark::B2
        && f.contains(&format!("(ontable {x})"))
        && !f.contains(&format!("(inreach panda {x})"))
    {
        // Out of reach: the hook must be able to pull it in.
        return hook_can_pull(w, 0, "hook", x);
    }
    true
}

/// Whether some arm can work block `x` where it is, whatever the benchmark: grasp it from above
/// (inside the arm's reach annulus, IK of the top grasp and of the approach 12 cm above it), or,
/// where the scene has a hook and the block lies beyond the annulus, pull it in
/// ([`hook_can_pull`]). `Err` says why not. Disturbances keep every block they move workable,
/// and the soak uses this to tell a user drag that put a block beyond every arm from a planner
/// failure.
pub fn handleable(w: &World, x: &str) -> Result<(), String> {
    let arms = w.arm_names().len();
    let snap = w.snapshot();
    let Some(c) = w.body_pose(x).map(|p| p.translation.vector) else {
        return Err(format!("there is no body {x}"));
    };
    // Distance of the block from arm `arm`'s base in the plane, and its reach annulus (the
    // scene graph's `inreach`).
    let radius = |arm: usize| {
        snap.arms.get(arm).map(|a| {
            let b = a.base.position;
            (
                libm::hypot(c.x - b[0], c.y - b[1]),
                a.reach.min_radius,
                a.reach.max_radius,
            )
        })
    };
    for arm in 0..arms {
        let Some(g) = geometry::grasp_pose(w, arm, x) else {
            return Err(format!("{x} is not a block or hook"));
        };
        if radius(arm).is_none_or(|(d, lo, hi)| d < lo || d > hi) {
            continue;
        }
        let mut above = g;
        above.translation.vector.z += 0.12;
        if w.reachable(arm, &g).is_ok() && w.reachable(arm, &above).is_ok() {
            return Ok(());
        }
    }
    let hooks: Vec<String> = snap
        .bodies
        .iter()
        .filter(|b| b.kind == super::snapshot::BodyKind::Hook && !b.lost)
        .map(|b| b.name.clone())
        .collect();
    for hook in &hooks {
        for arm in 0..arms {
            // The hook pulls a block from beyond the annulus towards the base.
            if radius(arm).is_none_or(|(d, _, hi)| d <= hi) {
                continue;
            }
            if hook_can_pull(w, arm, hook, x) {
                return Ok(());
            }
        }
    }
    Err(if hooks.is_empty() {
        format!("no arm can grasp {x} where it is (IK)")
    } else {
        format!("no arm can grasp {x} where it is, nor pull it in with a clear stroke of the hook")
    })
}

/// Whether arm `arm`, holding `hook` as it holds it now or would grasp it where it rests, can
/// pull block `x` towards its base with one of the hook's strokes ([`PULL_TURNS`],
/// [`pull_hook_poses_turned`]): the arm reaches the stroke's contact and pulled poses and the
/// poses [`PULL_LIFT`] above them (IK) with its hand clear of everything but the tables there,
/// the hook sweeps from contact to pulled through nothing but the tables and `x`, and `x`
/// slides along the stroke into nothing but the tables and the hook (every shape shrunk by 2 mm,
/// so resting contacts do not count, but a shelf only as far as the simulator lets a carried or
/// pushed body press into it). The arm's path is not checked: a stroke that fails here
/// cannot be executed, whatever the planner.
pub fn hook_can_pull(w: &World, arm: usize, hook: &str, x: &str) -> bool {
    let (Some(base), Some(bp), Some(hp), Some(gp)) = (
        w.arm_base(arm),
        w.body_pose(x),
        w.body_pose(hook),
        geometry::grasp_pose(w, arm, hook),
    ) else {
        return false;
    };
    // The hook's pose in the hand: as the hand holds it now, or as a grasp of it where it
    // rests would hold it (not the resting grasp of a hook the hand tilts while it carries it).
    let grasp = match w.grasp_transform(arm) {
        Some(g) if w.held_by(arm) == Some(hook) => g,
        _ => gp.inverse() * hp,
    };
    const SLACK: f64 = 0.002;
    let shrink = |c: &Cuboid| geometry::shrunk(c, SLACK);
    let hits = |parts: &[(Isometry3<f64>, Cuboid)], others: &[(Isometry3<f64>, Cuboid)]| {
        parts.iter().any(|(iso, c)| {
            others
                .iter()
                .any(|(oi, oc)| query::intersection_test(iso, c, oi, oc).unwrap_or(true))
        })
    };
    // Everything but the tables, the hook and x, shrunk by SLACK, a shelf by `shelf_slack`.
    let around = |shelf_slack: f64| -> Vec<(Isometry3<f64>, Cuboid)> {
        w.bodies
            .iter()
            .filter(|b| !b.lost && b.kind != BodyKind::Table && b.name != hook && b.name != x)
            .flat_map(|b| {
                let slack = if b.kind == BodyKind::Shelf {
                    shelf_slack
                } else {
                    SLACK
                };
                b.world_parts()
                    .map(move |(iso, c)| (iso, geometry::shrunk(c, slack)))
            })
            .collect()
    };
    let others = around(SLACK);
    // For the hook and x (shrunk by SLACK): a shelf only as far as the simulator lets a carried
    // or pushed body press into it.
    let pressed = around(w.params().carried_stop_depth() - SLACK);
    let hook_parts = w.body_shapes(hook);
    let block_parts = w.body_shapes(x);
    PULL_TURNS.iter().any(|&turn| {
        let Some((contact, pulled)) = pull_hook_poses_turned(&base, &bp, PULL_TARGET_RADIUS, turn)
        else {
            return false;
        };
        let lifted = |h: &Isometry3<f64>| geometry::raised(h, PULL_LIFT);
        if [contact, pulled, lifted(&contact), lifted(&pulled)]
            .iter()
            .map(|h| h * grasp.inverse())
            .any(|tcp| w.reachable(arm, &tcp).is_err() || geometry::hand_hits(&tcp, &others))
        {
            return false;
        }
        let at_contact: Vec<_> = hook_parts
            .iter()
            .map(|(iso, c)| (contact * hp.inverse() * iso, shrink(c)))
            .collect();
        if hits(&at_contact, &pressed) {
            return false;
        }
        // The hook sweeps from contact to pulled; its blade meets the block after its 1 cm
        // gap, then drags it the rest of the way.
        let d = pulled.translation.vector - contact.translation.vector;
        let slide = d * (1.0 - 0.01 / d.norm().max(0.01));
        let steps = (d.norm() / 0.01).ceil().max(1.0) as usize;
        (0..=steps).all(|k| {
            let s = k as f64 / steps as f64;
            let hook_shift = Translation3::from(d * s);
            let swept: Vec<_> = at_contact
                .iter()
                .map(|(iso, c)| (hook_shift * iso, *c))
                .collect();
            let shift = Translation3::from(slide * s);
            let moved: Vec<_> = block_parts
                .iter()
                .map(|(iso, c)| (shift * iso, shrink(c)))
                .collect();
            !hits(&swept, &pressed) && !hits(&moved, &pressed)
        })
    })
}

/// A sampling rectangle `(xmin, xmax, ymin, ymax)` for a table/shelf support.
fn area(w: &World, b: Benchmark, s: &Support) -> Option<(f64, f64, f64, f64)> {
    let m = 0.5 * BLOCK_SIZE + 0.01;
    match (b, s) {
        (_, Support::Shelf) => {
            let (lo, hi) = w.body_aabb("shelf")?;
            Some((lo.x + m, hi.x - m, lo.y + m, hi.y - m))
        }
        (Benchmark::B1, _) => Some((0.28, 0.68, -0.45, 0.45)),
        (Benchmark::B2, Support::Table { inreach, .. }) => {
            if *inreach == Some(false) {
                Some((0.80, 1.02, -0.25, 0.35))
            } else {
                Some((0.28, 0.62, -0.30, 0.45))
            }
        }
        (Benchmark::B3, Support::Table { region, .. }) => {
            let r = region.as_deref()?;
            let snap = w.snapshot();
            let reg = snap.regions.iter().find(|g| g.name == r)?;
            Some((
                reg.min[0] + m,
                reg.max[0] - m,
                reg.min[1] + m,
                reg.max[1] - m,
            ))
        }
        _ => None,
    }
}

/// Whether the facts of `x` in `now` are those asked by `want` (support, region, reach).
fn placed_as(now: &BTreeSet<String>, x: &str, want: &Support) -> bool {
    match (spec_of(x, now), want) {
        (Some(Support::On(y)), Support::On(z)) => &y == z,
        (Some(Support::Shelf), Support::Shelf) => true,
        (
            Some(Support::Table { region, inreach }),
            Support::Table {
                region: wr,
                inreach: wi,
            },
        ) => (wr.is_none() || &region == wr) && (wi.is_none() || &inreach == wi),
        _ => false,
    }
}

/// Moves the blocks of `specs` (in order, each support placed before what stands on it) to
/// sampled places satisfying their spec. Works on `w` in place; the caller keeps a copy.
fn arrange(
    w: &mut World,
    b: Benchmark,
    specs: &[(String, Support)],
    rng: &mut Pcg64Mcg,
) -> Result<(), String> {
    // Order: bases first, then blocks whose support is placed or not being moved.
    let mut order: Vec<&(String, Support)> = Vec::new();
    let moving: Vec<&str> = specs.iter().map(|(x, _)| x.as_str()).collect();
    while order.len() < specs.len() {
        let before = order.len();
        for s in specs {
            if order.iter().any(|o| o.0 == s.0) {
                continue;
            }
            let ready = match &s.1 {
                Support::On(y) => !moving.contains(&y.as_str()) || order.iter().any(|o| &o.0 == y),
                _ => true,
            };
            if ready {
                order.push(s);
            }
        }
        if order.len() == before {
            return Err("the requested towers form a cycle".into());
        }
    }
    // First lift every moving block out of the way onto free table spots far apart is not needed:
    // a base that moves lets what stood on it settle, and those are moved later anyway.
    for (x, spec) in order {
        let mut ok = false;
        for _ in 0..300 {
            let trial_world = w.clone();
            let (p, yaw) = match spec {
                Support::On(y) => {
                    let yp = w.body_pose(y).ok_or(format!("no block {y}"))?;
                    let (_, hi) = w.body_aabb(y).ok_or(format!("no block {y}"))?;
                    let c = yp.translation.vector;
                    (
                        Vector3::new(
                            c.x + rng.random_range(-0.004..0.004),
                            c.y + rng.random_range(-0.004..0.004),
                            hi.z + 0.5 * BLOCK_SIZE + 0.001,
                        ),
                        yaw_of(&yp.rotation) + rng.random_range(-0.1..0.1),
                    )
                }
                _ => {
                    let (x0, x1, y0, y1) =
                        area(w, b, spec).ok_or(format!("no area for {x} ({spec:?})"))?;
                    let px = rng.random_range(x0..x1);
                    let py = rng.random_range(y0..y1);
                    let top = match spec {
                        Support::Shelf => w.body_aabb("shelf").map(|(_, h)| h.z).unwrap_or(0.0),
                        _ => 0.0,
                    };
                    (
                        Vector3::new(px, py, top + 0.5 * BLOCK_SIZE + 0.001),
                        rng.random_range(-0.3..0.3),
                    )
                }
            };
            if w.move_block_to(x, p, yaw).is_err() {
                continue;
            }
            if placed_as(&facts(w), x, spec) && workable(w, b, x) {
                ok = true;
                break;
            }
            *w = trial_world;
        }
        if !ok {
            return Err(format!("no place found for {x} ({spec:?})"));
        }
    }
    Ok(())
}

fn moves_between(before: &World, after: &World) -> Vec<BlockMove> {
    let mut out = Vec::new();
    for x in after.block_names() {
        let to = centre(after, x);
        match before.body_pose(x) {
            Some(p) if (p.translation.vector - to).norm() > 1e-3 => out.push(BlockMove {
                body: x.to_string(),
                from: p.translation.vector.into(),
                to: to.into(),
            }),
            _ => {}
        }
    }
    out
}

/// Groups the free blocks into towers (bottom first) using the scene graph.
fn towers(w: &World) -> Vec<Vec<String>> {
    let f = facts(w);
    let free = free_blocks(w);
    let below = |x: &str| {
        f.iter().find_map(|s| match args(s).as_slice() {
            ["on", a, y] if *a == x => Some(y.to_string()),
            _ => None,
        })
    };
    let mut out = Vec::new();
    for x in &free {
        if below(x).is_none() {
            let mut t = vec![x.clone()];
            loop {
                let top = t.last().cloned().unwrap_or_default();
                match free
                    .iter()
                    .find(|y| below(y).as_deref() == Some(top.as_str()))
                {
                    Some(y) => t.push(y.clone()),
                    None => break,
                }
            }
            out.push(t);
        }
    }
    out
}

/// Applies a disturbance of `level` to `world` (see the module docs). On error the world is
/// unchanged. `demo_states` are the demonstration's scene-graph states (for L2 / L3).
pub fn inject(
    world: &mut World,
    b: Benchmark,
    level: Level,
    demo_states: &[BTreeSet<String>],
    seed: u64,
) -> Result<Disturbance, DisturbError> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed ^ 0x5eed_d157);
    let before = world.clone();
    let f0 = facts(world);
    let mut w = world.clone();
    let mut added = Vec::new();
    let description = match level {
        Level::L1 => {
            let mut ts = towers(&w);
            if ts.is_empty() {
                return Err(DisturbError::NotApplicable("no free block to move".into()));
            }
            ts.shuffle(&mut rng);
            let n = rng.random_range(1..=ts.len());
            let mut last = String::new();
            for attempt in 0..20 {
                let mut trial = w.clone();
                let chosen: Vec<String> = ts[..n].iter().flatten().cloned().collect();
                let specs: Vec<(String, Support)> = chosen
                    .iter()
                    .filter_map(|x| spec_of(x, &f0).map(|s| (x.clone(), s)))
                    .collect();
                match arrange(&mut trial, b, &specs, &mut rng) {
                    Ok(())
                        if facts(&trial) == f0
                            && moves_between(&before, &trial).iter().any(|m| {
                                (Vector3::from(m.to) - Vector3::from(m.from)).norm() > 0.02
                            }) =>
                    {
                        w = trial;
                        last.clear();
                        break;
                    }
                    Ok(()) => last = format!("attempt {attempt}: facts changed"),
                    Err(e) => last = e,
                }
            }
            if !last.is_empty() {
                return Err(DisturbError::Failed(last));
            }
            format!(
                "L1: moved {} to new positions; the facts are unchanged",
                ts[..n]
                    .iter()
                    .flatten()
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
        Level::L2 | Level::L3 => {
            let hands = |f: &BTreeSet<String>| -> Vec<String> {
                f.iter()
                    .filter(|s| s.starts_with("(holding") || s.starts_with("(handempty"))
                    .cloned()
                    .collect()
            };
            let free = free_blocks(&w);
            let same_objects = |s: &BTreeSet<String>| {
                w.block_names()
                    .iter()
                    .all(|x| s.iter().any(|f| args(f).contains(x)))
                    && s.iter().all(|f| {
                        args(f)[1..].iter().all(|a| {
                            w.body_index(a).is_some()
                                || w.arm_index(a).is_some()
                                || w.region_names().contains(a)
                        })
                    })
            };
            let goal: Vec<String> = b.goal().iter().map(|g| g.to_string()).collect();
            let mut result = None;
            let mut last = String::from("no candidate state");
            if level == Level::L2 {
                let n = demo_states.len();
                let mut cands: Vec<&BTreeSet<String>> = demo_states
                    .iter()
                    .take(n.saturating_sub(1))
                    .filter(|s| **s != f0 && hands(s) == hands(&f0) && same_objects(s))
                    .collect();
                if cands.is_empty() {
                    return Err(DisturbError::NotApplicable(
                        "no other demonstration state matches what the arms hold and the blocks present".into(),
                    ));
                }
                cands.shuffle(&mut rng);
                'outer: for target in cands {
                    for _ in 0..5 {
                        let mut trial = w.clone();
                        let specs: Vec<(String, Support)> = free
                            .iter()
                            .filter_map(|x| spec_of(x, target).map(|s| (x.clone(), s)))
                            .collect();
                        match arrange(&mut trial, b, &specs, &mut rng) {
                            Ok(()) if facts(&trial) == *target => {
                                result = Some(trial);
                                break 'outer;
                            }
                            Ok(()) => last = "facts differ from the demo state".into(),
                            Err(e) => last = e,
                        }
                    }
                }
            } else {
                for _ in 0..60 {
                    let specs = random_specs(&w, b, &free, &mut rng);
                    let mut trial = w.clone();
                    match arrange(&mut trial, b, &specs, &mut rng) {
                        Ok(()) => {
                            let f = facts(&trial);
                            let solved = goal.iter().all(|g| f.contains(g));
                            if f != f0 && !demo_states.contains(&f) && !solved {
                                result = Some(trial);
                                break;
                            }
                            last = "state seen in the demo or already solved".into();
                        }
                        Err(e) => last = e,
                    }
                }
            }
            w = result.ok_or(DisturbError::Failed(last))?;
            let f1 = facts(&w);
            let gained: Vec<String> = f1.difference(&f0).cloned().collect();
            let lost: Vec<String> = f0.difference(&f1).cloned().collect();
            format!(
                "{}: rearranged the blocks to a state {} the demonstration; now {}; no longer {}",
                level.id().to_uppercase(),
                if level == Level::L2 {
                    "of"
                } else {
                    "never seen in"
                },
                gained.join(" "),
                lost.join(" ")
            )
        }
        Level::L4 => {
            let name = ["e", "f", "g", "h", "i", "j"]
                .iter()
                .find(|n| {
                    w.body_index(n).is_none()
                        && w.arm_index(n).is_none()
                        && !w.region_names().contains(n)
                })
                .ok_or(DisturbError::NotApplicable(
                    "no free block name left".into(),
                ))?
                .to_string();
            let color = BLOCK_COLORS[(w.block_names().len()) % BLOCK_COLORS.len()];
            let goal: Vec<String> = b.goal().iter().map(|g| g.to_string()).collect();
            // Blocks still to be handled: mentioned by an unsatisfied goal fact.
            let todo: Vec<String> = free_blocks(&w)
                .into_iter()
                .filter(|x| {
                    goal.iter()
                        .any(|g| !f0.contains(g) && args(g)[1..].contains(&x.as_str()))
                })
                .collect();
            if todo.is_empty() {
                return Err(DisturbError::NotApplicable(
                    "every block is already done".into(),
                ));
            }
            let mut done = None;
            for _ in 0..100 {
                let x = todo[rng.random_range(0..todo.len())].clone();
                let mut trial = w.clone();
                let p = centre(&trial, &x);
                let yaw = rng.random_range(-0.3..0.3);
                let ok = if b == Benchmark::B2 {
                    // In the way: on the table between the block and the arm (or beside it).
                    let base = trial
                        .arm_base(0)
                        .map(|b| b.translation.vector)
                        .unwrap_or_default();
                    let u = Vector3::new(p.x - base.x, p.y - base.y, 0.0).normalize();
                    let side = Vector3::new(-u.y, u.x, 0.0) * rng.random_range(-0.03..0.03);
                    let q = p - u * rng.random_range(0.075..0.11) + side;
                    trial
                        .add_block(
                            &name,
                            color,
                            Vector3::new(q.x, q.y, 0.5 * BLOCK_SIZE + 0.001),
                            yaw,
                        )
                        .is_ok()
                        && facts(&trial).contains(&format!("(ontable {name})"))
                } else {
                    let top = facts(&trial).contains(&format!("(clear {x})"));
                    top && trial
                        .add_block(
                            &name,
                            color,
                            Vector3::new(p.x, p.y, p.z + BLOCK_SIZE + 0.001),
                            yaw,
                        )
                        .is_ok()
                        && facts(&trial).contains(&format!("(on {name} {x})"))
                };
                if ok && workable(&trial, b, &name) {
                    done = Some((trial, x));
                    break;
                }
            }
            let (trial, x) = done.ok_or(DisturbError::Failed("no place for a new block".into()))?;
            w = trial;
            added.push(name.clone());
            if b == Benchmark::B2 {
                format!("L4: a new block {name} appeared on the table in the way of {x}")
            } else {
                format!("L4: a new block {name} appeared on top of {x}")
            }
        }
    };
    if let Err(v) = w.check_invariants() {
        return Err(DisturbError::Failed(format!("invariants broken: {v:?}")));
    }
    let d = Disturbance {
        level,
        seed,
        description,
        moves: moves_between(&before, &w)
            .into_iter()
            .filter(|m| !added.contains(&m.body))
            .collect(),
        added,
        facts_before: f0.iter().cloned().collect(),
        facts_after: facts(&w).iter().cloned().collect(),
    };
    *world = w;
    Ok(d)
}

/// A random arrangement of the free blocks for L3, per benchmark.
fn random_specs(
    w: &World,
    b: Benchmark,
    free: &[String],
    rng: &mut Pcg64Mcg,
) -> Vec<(String, Support)> {
    let mut blocks: Vec<String> = free.to_vec();
    blocks.shuffle(rng);
    let mut out = Vec::new();
    match b {
        Benchmark::B2 => {
            let mut on_shelf = 0;
            for x in blocks {
                let r: f64 = rng.random();
                if r < 0.3 && on_shelf < 2 {
                    on_shelf += 1;
                    out.push((x, Support::Shelf));
                } else {
                    out.push((
                        x,
                        Support::Table {
                            region: None,
                            inreach: Some(r < 0.65),
                        },
                    ));
                }
            }
        }
        Benchmark::B1 | Benchmark::B3 => {
            let regions: Vec<String> = w.region_names().iter().map(|s| s.to_string()).collect();
            let mut i = 0;
            while i < blocks.len() {
                let h = rng.random_range(1..=(blocks.len() - i).min(3));
                let region = if regions.is_empty() {
                    None
                } else {
                    Some(regions[rng.random_range(0..regions.len())].clone())
                };
                out.push((
                    blocks[i].clone(),
                    Support::Table {
                        region,
                        inreach: None,
                    },
                ));
                for k in 1..h {
                    out.push((
                        blocks[i + k].clone(),
                        Support::On(blocks[i + k - 1].clone()),
                    ));
                }
                i += h;
            }
        }
    }
    out
}
