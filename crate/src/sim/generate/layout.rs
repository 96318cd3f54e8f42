//! Where a generated task's blocks start: a grid of spots [`SPOT_SPACING`] apart around the
//! centre of the benchmark's start area, each inside the reach annulus of some arm and in front
//! of it. Each tower's bottom block starts on its tower's spot, where the tower is built.
//!
//! One tower (up to [`MAX_TOWER_HEIGHT`](super::MAX_TOWER_HEIGHT) blocks) stands on the spot
//! nearest the area's centre and its blocks lie on the next spots out, bottom-up, the tower
//! spot's neighbours left free where there is room. Several towers
//! stand on spots at least [`TOWER_SPACING`] apart where the arm reaches their tops, and each of
//! their blocks starts on a spot from which the arm takes it, and carries it to its tower, clear
//! of the towers as they stand when the demonstration takes it ([`open_at`]): not next to a
//! tower, not in a tower's shadow ([`in_shadow`]), no other tower in the way.

use super::names::err;
use crate::sim::world::World;
use crate::sim::SceneError;
use crate::sim::{block, Benchmark, BLOCK_SIZE};
use crate::sim::{ArmSnapshot, BodyKind, BodySnapshot, ShapeSnapshot, WorldSnapshot};

/// Distance between neighbouring spots of the layout grid (m): a 6 cm block plus room for the
/// open fingers on both sides.
pub const SPOT_SPACING: f64 = 0.12;

/// Least distance between the bottoms of two towers (m), four grid steps: the hand (11.5 cm
/// from its axis along the fingers) and the wrist's link (the Panda's flange offset, 8.8 cm,
/// plus its 5 cm radius) working one tower at any height clear the other at full height, with
/// room between them for blocks that neither tower shades.
pub const TOWER_SPACING: f64 = 4.0 * SPOT_SPACING;

/// [`TOWER_SPACING`] in grid steps, squared (an exact integer test on grid indices).
const TOWER_SPACING_STEPS_SQ: i64 = 16;

/// Half-width of a tower's shadow (m): a spot farther from an arm's base than a tower and within
/// this distance of the vertical plane through the base and the spot has the arm pass its
/// forearm (a 6 cm capsule, with the wrist's 8.8 cm offset) over the tower to reach it. With 9
/// blocks on (0.35, −0.24), the expert's forearm cut up to 10 cm into the tower taking blocks
/// from grid spots 2 to 14 cm from that plane, and cleared it by 3.6 cm or more from 14.6 cm.
const SHADOW_RADIUS: f64 = 0.15;

/// Spots keep this far inside an area's edges (m): half a block plus a centimetre.
const EDGE_MARGIN: f64 = 0.04;

/// Spots keep this far inside an arm's reach annulus (m).
const REACH_MARGIN: f64 = 0.05;

/// Spots lie within this angle of the arm's forward `+x` axis (rad, 70°).
const FRONT_HALF_ANGLE: f64 = 1.221_730_476_396_030_7;

/// A spot is taken when a block's centre is closer than this to it (m).
pub(super) const TAKEN_RADIUS: f64 = 0.75 * SPOT_SPACING;

/// A rectangle of the plane where blocks may stand (a table top or a region).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Area {
    pub(super) min: [f64; 2],
    pub(super) max: [f64; 2],
}

impl Area {
    fn centre(&self) -> [f64; 2] {
        [
            0.5 * (self.min[0] + self.max[0]),
            0.5 * (self.min[1] + self.max[1]),
        ]
    }
}

/// A spot of an area's grid: its grid indices from the area's centre and its position (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Spot {
    ij: [i64; 2],
    pub(super) p: [f64; 2],
}

impl Spot {
    /// Squared distance to `o` in grid steps: exact, so ties order the same on every target.
    fn steps_sq(&self, o: &Spot) -> i64 {
        let di = self.ij[0] - o.ij[0];
        let dj = self.ij[1] - o.ij[1];
        di * di + dj * dj
    }
}

/// The area where the blocks start: the template's first block's region, else its table.
pub(super) fn start_area(s: &WorldSnapshot) -> Result<Area, SceneError> {
    let first = s
        .bodies
        .iter()
        .find(|b| b.kind == BodyKind::Block)
        .ok_or_else(|| err("the template has no block"))?;
    let p = first.pose.position;
    if let Some(r) = s
        .regions
        .iter()
        .find(|r| p[0] >= r.min[0] && p[0] <= r.max[0] && p[1] >= r.min[1] && p[1] <= r.max[1])
    {
        return Ok(Area {
            min: r.min,
            max: r.max,
        });
    }
    s.bodies
        .iter()
        .find(|b| b.kind == BodyKind::Table)
        .and_then(table_area)
        .ok_or_else(|| err("the template has no table"))
}

fn table_area(t: &BodySnapshot) -> Option<Area> {
    let ShapeSnapshot::Cuboid { half_extents } = &t.shape else {
        return None;
    };
    let c = t.pose.position;
    Some(Area {
        min: [c[0] - half_extents[0], c[1] - half_extents[1]],
        max: [c[0] + half_extents[0], c[1] + half_extents[1]],
    })
}

/// Whether arm `a` works spot `p` comfortably: inside its reach annulus by [`REACH_MARGIN`] and
/// within [`FRONT_HALF_ANGLE`] of its forward axis.
fn works(a: &ArmSnapshot, p: [f64; 2]) -> bool {
    let dx = p[0] - a.base.position[0];
    let dy = p[1] - a.base.position[1];
    let d = libm::hypot(dx, dy);
    d >= a.reach.min_radius + REACH_MARGIN
        && d <= a.reach.max_radius - REACH_MARGIN
        && libm::fabs(libm::atan2(dy, dx)) <= FRONT_HALF_ANGLE
}

/// Whether some arm works spot `p` comfortably ([`works`]).
fn workable(s: &WorldSnapshot, p: [f64; 2]) -> bool {
    s.arms.iter().any(|a| works(a, p))
}

/// Whether a tower on spot `t` stands in the way of a straight reach from `a` to `b` in the
/// plane: `t` lies between them (along the line from `a` to `b`) within [`SHADOW_RADIUS`] of
/// that line.
fn in_the_way(a: [f64; 2], b: [f64; 2], t: [f64; 2]) -> bool {
    let v = [b[0] - a[0], b[1] - a[1]];
    let w = [t[0] - a[0], t[1] - a[1]];
    let r = libm::hypot(v[0], v[1]);
    if r <= 0.0 {
        return false;
    }
    let along = (w[0] * v[0] + w[1] * v[1]) / r;
    let across = libm::fabs(w[0] * v[1] - w[1] * v[0]) / r;
    along > 0.0 && along < r && across < SHADOW_RADIUS
}

/// Whether spot `p` lies in the shadow of a tower on spot `t`: the tower stands in the way
/// ([`in_the_way`]) from the base of an arm that works `p` to `p`, so the arm's forearm passes
/// over it.
fn in_shadow(s: &WorldSnapshot, t: [f64; 2], p: [f64; 2]) -> bool {
    s.arms
        .iter()
        .filter(|a| works(a, p))
        .any(|a| in_the_way([a.base.position[0], a.base.position[1]], p, t))
}

/// Whether some arm can grasp the top of a tower of `h` blocks on spot `p` and come down onto
/// it ([`crate::sim::handleable`], IK), in the template scene without its blocks.
fn top_reached(s: &WorldSnapshot, p: [f64; 2], h: usize) -> bool {
    let mut probe = s.clone();
    probe.bodies.retain(|b| b.kind != BodyKind::Block);
    let names = super::names::block_names(h);
    for (i, x) in names.iter().enumerate() {
        let mut body = block(x, i, p[0], p[1], 0.0);
        body.pose.position[2] += (h - 1 - i) as f64 * BLOCK_SIZE;
        probe.bodies.push(body);
    }
    World::from_snapshot(&probe).is_ok_and(|w| crate::sim::handleable(&w, &names[0]).is_ok())
}

/// The grid spots of `area` that some arm works, nearest the area's centre first.
pub(super) fn spots(s: &WorldSnapshot, area: Area) -> Vec<Spot> {
    let c = area.centre();
    let half = [
        0.5 * (area.max[0] - area.min[0]) - EDGE_MARGIN,
        0.5 * (area.max[1] - area.min[1]) - EDGE_MARGIN,
    ];
    let kx = libm::floor(half[0] / SPOT_SPACING) as i64;
    let ky = libm::floor(half[1] / SPOT_SPACING) as i64;
    let mut out: Vec<Spot> = Vec::new();
    for i in -kx..=kx {
        for j in -ky..=ky {
            let p = [
                c[0] + i as f64 * SPOT_SPACING,
                c[1] + j as f64 * SPOT_SPACING,
            ];
            if workable(s, p) {
                out.push(Spot { ij: [i, j], p });
            }
        }
    }
    // Squared grid distance orders the spots exactly (integers, no rounding); the sort is
    // stable, so equal distances keep the grid's order.
    out.sort_by_key(|s| s.ij[0] * s.ij[0] + s.ij[1] * s.ij[1]);
    out
}

/// The template scene with its blocks replaced by the towers' blocks (`towers[t]`, top first),
/// laid out for one tower ([`one_tower`]) or several ([`several_towers`]); `build` is the order
/// in which the demonstration puts them in place (bottoms first).
pub(super) fn tower_scene(
    b: Benchmark,
    towers: &[&[String]],
    build: &[String],
) -> Result<WorldSnapshot, SceneError> {
    let mut s = b.scene_snapshot();
    let area = start_area(&s)?;
    let free = spots(&s, area);
    let n: usize = towers.iter().map(|t| t.len()).sum();
    if free.len() < n {
        return Err(err(format!(
            "{}: room for {} blocks only",
            b.as_str(),
            free.len()
        )));
    }
    let at = match towers {
        [tower] => one_tower(&free, tower),
        _ => several_towers(&s, free, towers, build).ok_or_else(|| {
            err(format!(
                "{}: no room for {} towers",
                b.as_str(),
                towers.len()
            ))
        })?,
    };
    s.bodies.retain(|body| body.kind != BodyKind::Block);
    for (i, x) in towers.iter().flat_map(|t| t.iter()).enumerate() {
        let p = at
            .iter()
            .find(|(y, _)| y == x)
            .map(|(_, p)| *p)
            .ok_or_else(|| err(format!("block {x} is not in the build order")))?;
        s.bodies.push(block(x, i, p[0], p[1], 0.0));
    }
    let w = World::from_snapshot(&s)?;
    Ok(w.snapshot())
}

/// One tower's layout (`free` holds a spot for each block): the bottom on the spot nearest the
/// area's centre, the blocks above it on the next spots out, bottom-up, leaving the spots next
/// to the tower's free where the area has room for it.
///
/// A hand working a spot reaches 11.5 cm along its fingers: with blocks on the tower spot's four
/// neighbours every grasp of the bottom block hits one, so a bottom block moved away (an L3
/// disturbance) could not be put back, and the hand grazes the tower working its neighbours.
fn one_tower(free: &[Spot], tower: &[String]) -> Vec<(String, [f64; 2])> {
    let Some(bottom) = free.first() else {
        return vec![];
    };
    let mut spare = free.len().saturating_sub(tower.len());
    let spots = free.iter().filter(|s| {
        let skip = spare > 0 && s.steps_sq(bottom) == 1;
        spare -= usize::from(skip);
        !skip
    });
    tower
        .iter()
        .rev()
        .zip(spots)
        .map(|(x, spot)| (x.clone(), spot.p))
        .collect()
}

/// Several towers' layout, `None` if it does not fit: on the first choice of tower spots
/// ([`tower_spot_choices`]) where every block finds a spot ([`place_blocks`]), among spots where
/// the arm reaches the top of a tower a block taller than the tallest, else of the tallest.
fn several_towers(
    s: &WorldSnapshot,
    free: Vec<Spot>,
    towers: &[&[String]],
    build: &[String],
) -> Option<Vec<(String, [f64; 2])>> {
    let tallest = towers.iter().map(|t| t.len()).max()?;
    // Spots where the arm would reach a block higher first: at the limit of its reach the
    // expert's approach above the top is cut short and its carry comes in from the side.
    [tallest + 1, tallest].into_iter().find_map(|h| {
        tower_spot_choices(s, &free, towers.len(), h)
            .into_iter()
            .find_map(|chosen| place_blocks(s, &free, &chosen, towers, build))
    })
}

/// The blocks of `towers` laid out with tower `t`'s bottom on `free[chosen[t]]`, `None` if some
/// block finds no spot. The other blocks take the free spots in the order `build`, each a spot
/// the arm reaches, and carries the block from to its tower, clear of the towers as they then
/// stand ([`open_at`]). Each takes the open spot that closes first (its last step open: the
/// spots usable early are used early), then the nearest its tower's spot, then the first in
/// order from the area's centre.
fn place_blocks(
    s: &WorldSnapshot,
    free: &[Spot],
    chosen: &[usize],
    towers: &[&[String]],
    build: &[String],
) -> Option<Vec<(String, [f64; 2])>> {
    let tower_of: Vec<usize> = build
        .iter()
        .map(|x| towers.iter().position(|t| t.contains(x)))
        .collect::<Option<_>>()?;
    let bottoms: Vec<Spot> = chosen.iter().map(|&i| free[i]).collect();
    // Blocks of each tower in place before each step.
    let heights: Vec<Vec<usize>> = (0..build.len())
        .map(|k| {
            (0..towers.len())
                .map(|t| tower_of[..k].iter().filter(|&&u| u == t).count())
                .collect()
        })
        .collect();
    let open_at = |spot: &Spot, k: usize| open_at(s, spot, &bottoms, &heights[k], tower_of[k]);
    let mut spots: Vec<(Spot, usize)> = (0..free.len())
        .filter(|i| !chosen.contains(i))
        .filter_map(|i| {
            let last = (0..build.len()).rev().find(|&k| open_at(&free[i], k))?;
            Some((free[i], last))
        })
        .collect();
    let mut at = Vec::with_capacity(build.len());
    for (k, x) in build.iter().enumerate() {
        let home = bottoms[tower_of[k]];
        if towers[tower_of[k]].last() == Some(x) {
            at.push((x.clone(), home.p));
            continue;
        }
        // `min_by_key` keeps the first of equals: `spots` is in order from the centre.
        let i = (0..spots.len())
            .filter(|&i| open_at(&spots[i].0, k))
            .min_by_key(|&i| (spots[i].1, spots[i].0.steps_sq(&home)))?;
        at.push((x.clone(), spots.remove(i).0.p));
    }
    Some(at)
}

/// Whether the arm may take a block for tower `to` from `spot` while the towers on `bottoms`
/// are `heights` blocks high: no tower of two blocks or more stands next to the spot (a grid
/// step away: the hand, 11.5 cm from its axis along the fingers, would graze it), casts its
/// shadow on it ([`in_shadow`]: the forearm would pass over it) or, another tower's, stands in
/// the way ([`in_the_way`]) of the block carried from the spot to its tower.
fn open_at(s: &WorldSnapshot, spot: &Spot, bottoms: &[Spot], heights: &[usize], to: usize) -> bool {
    bottoms.iter().zip(heights).enumerate().all(|(t, (b, &h))| {
        h < 2
            || !(b.steps_sq(spot) == 1
                || in_shadow(s, b.p, spot.p)
                || (t != to && in_the_way(spot.p, bottoms[to].p, b.p)))
    })
}

/// The choices of `towers` spots (indices into `free`, nearest the centre first) pairwise at
/// least [`TOWER_SPACING`] apart where the arm reaches the top of a tower of `tallest` blocks
/// ([`top_reached`]), best first: the least sum of indices (the towers nearest the centre),
/// then in index order.
fn tower_spot_choices(
    s: &WorldSnapshot,
    free: &[Spot],
    towers: usize,
    tallest: usize,
) -> Vec<Vec<usize>> {
    let reached: Vec<usize> = (0..free.len())
        .filter(|&i| top_reached(s, free[i].p, tallest))
        .collect();
    fn each(
        reached: &[usize],
        free: &[Spot],
        towers: usize,
        chosen: &mut Vec<usize>,
        out: &mut Vec<Vec<usize>>,
    ) {
        if chosen.len() == towers {
            out.push(chosen.clone());
            return;
        }
        for (k, &i) in reached.iter().enumerate() {
            if chosen
                .iter()
                .all(|&c| free[c].steps_sq(&free[i]) >= TOWER_SPACING_STEPS_SQ)
            {
                chosen.push(i);
                each(&reached[k + 1..], free, towers, chosen, out);
                chosen.pop();
            }
        }
    }
    let mut out = Vec::new();
    each(&reached, free, towers, &mut Vec::new(), &mut out);
    // Stable: equal sums keep the enumeration's index order.
    out.sort_by_key(|c| c.iter().sum::<usize>());
    out
}
