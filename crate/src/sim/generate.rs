//! Scene generators: a benchmark's tower task scaled to N blocks (B1-N, B3-N), with its problem
//! and a demonstration recorded by the scripted expert along a planned action sequence.
//!
//! Blocks are named `a`, `b`, `c`, … and laid out on a grid of [`SPOT_SPACING`] around the
//! centre of the benchmark's start area (B1's table, B3's left-table region), keeping spots
//! inside the reach annulus of some arm and in front of it. The goal is the template's goal
//! shape for N blocks: the tower `x1` on `x2` on … on `xN`, plus the template's other goal facts
//! about the bottom block (B3: the bottom block in the right-table region). The tower grows on
//! the spot nearest the area's centre.

use super::benchmark::{block, Benchmark, BenchmarkSources};
use super::demo::{record_script, ExpertParams, Script, ScriptStep};
use super::motions::{MotionKind, Onto, Relation, Slot};
use super::scene_graph::Fact;
use super::snapshot::{BodyKind, ShapeSnapshot, WorldSnapshot};
use super::world::World;
use super::SceneError;
use crate::plan::{Algorithm, HeuristicKind, NoClock, SearchConfig};

/// Fewest blocks of a generated task per benchmark: B1 (3) and B3 (2).
pub const MIN_BLOCKS_B1: usize = 3;
/// Fewest blocks of a generated B3 task.
pub const MIN_BLOCKS_B3: usize = 2;
/// Most blocks of a generated task.
pub const MAX_BLOCKS: usize = 12;
/// Most blocks of a generated B3 task: the right arm, 45 cm from the right-table spot, does not
/// reach over a taller tower there.
pub const MAX_BLOCKS_B3: usize = 10;

/// Distance between neighbouring spots of the layout grid (m): a 6 cm block plus room for the
/// open fingers on both sides.
pub const SPOT_SPACING: f64 = 0.12;

/// Spots keep this far inside an area's edges (m): half a block plus a centimetre.
const EDGE_MARGIN: f64 = 0.04;

/// Spots keep this far inside an arm's reach annulus (m).
const REACH_MARGIN: f64 = 0.05;

/// Spots lie within this angle of the arm's forward `+x` axis (rad, 70°).
const FRONT_HALF_ANGLE: f64 = 1.221_730_476_396_030_7;

/// A spot is taken when a block's centre is closer than this to it (m).
const TAKEN_RADIUS: f64 = 0.75 * SPOT_SPACING;

/// Seed of the expert's variation in a generated demonstration.
const DEMO_SEED: u64 = 1;

/// Expansions allowed to the planner of a generated demonstration.
const PLAN_MAX_NODES: u64 = 20_000;

fn err(message: impl Into<String>) -> SceneError {
    SceneError {
        path: "generate".into(),
        message: message.into(),
    }
}

/// The names of an N-block task: `a`, `b`, … (N ≤ 26).
pub fn block_names(n: usize) -> Vec<String> {
    (0..n)
        .map(|i| char::from(b'a' + (i % 26) as u8).to_string())
        .collect()
}

/// The allowed block counts of a benchmark's N-block variant, or why it has none.
pub fn block_range(b: Benchmark) -> Result<std::ops::RangeInclusive<usize>, SceneError> {
    match b {
        Benchmark::B1 => Ok(MIN_BLOCKS_B1..=MAX_BLOCKS),
        Benchmark::B3 => Ok(MIN_BLOCKS_B3..=MAX_BLOCKS_B3),
        Benchmark::B2 => Err(err("B2 has no N-block variant")),
    }
}

/// The files of benchmark `b`'s tower task with `n` blocks: the template's domain and motions,
/// a generated scene, problem and demonstration. B1 takes 3–12 blocks, B3 2–10; B2 has none.
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
    let snap = tower_scene(b, &names)?;
    let world = World::from_snapshot(&snap)?.with_motions(b.motions());
    world
        .check_invariants()
        .map_err(|v| err(format!("generated scene breaks an invariant: {v:?}")))?;
    for x in &names {
        super::reach::handleable(&world, x).map_err(|e| err(format!("block {x}: {e}")))?;
    }
    let goal = tower_goal(b, &names)?;
    let problem = b.problem_for_goal(&world, &format!("{}-{n}-blocks", b.dir_name()), &goal);
    let script = tower_script(b, &world, &problem, &snap, &names, &goal)?;
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
        scene,
        problem,
        demo,
        ..template
    })
}

/// A rectangle of the plane where blocks may stand (a table top or a region).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Area {
    min: [f64; 2],
    max: [f64; 2],
}

impl Area {
    fn centre(&self) -> [f64; 2] {
        [
            0.5 * (self.min[0] + self.max[0]),
            0.5 * (self.min[1] + self.max[1]),
        ]
    }
}

/// The area where the blocks start: the template's first block's region, else its table.
fn start_area(s: &WorldSnapshot) -> Result<Area, SceneError> {
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

fn table_area(t: &super::snapshot::BodySnapshot) -> Option<Area> {
    let ShapeSnapshot::Cuboid { half_extents } = &t.shape else {
        return None;
    };
    let c = t.pose.position;
    Some(Area {
        min: [c[0] - half_extents[0], c[1] - half_extents[1]],
        max: [c[0] + half_extents[0], c[1] + half_extents[1]],
    })
}

/// Whether some arm works spot `p` comfortably: inside its reach annulus by [`REACH_MARGIN`] and
/// within [`FRONT_HALF_ANGLE`] of its forward axis.
fn workable(s: &WorldSnapshot, p: [f64; 2]) -> bool {
    s.arms.iter().any(|a| {
        let dx = p[0] - a.base.position[0];
        let dy = p[1] - a.base.position[1];
        let d = libm::hypot(dx, dy);
        d >= a.reach.min_radius + REACH_MARGIN
            && d <= a.reach.max_radius - REACH_MARGIN
            && libm::fabs(libm::atan2(dy, dx)) <= FRONT_HALF_ANGLE
    })
}

/// The grid spots of `area` that some arm works, nearest the area's centre first.
fn spots(s: &WorldSnapshot, area: Area) -> Vec<[f64; 2]> {
    let c = area.centre();
    let half = [
        0.5 * (area.max[0] - area.min[0]) - EDGE_MARGIN,
        0.5 * (area.max[1] - area.min[1]) - EDGE_MARGIN,
    ];
    let kx = libm::floor(half[0] / SPOT_SPACING) as i64;
    let ky = libm::floor(half[1] / SPOT_SPACING) as i64;
    let mut out: Vec<(i64, [f64; 2])> = Vec::new();
    for i in -kx..=kx {
        for j in -ky..=ky {
            let p = [
                c[0] + i as f64 * SPOT_SPACING,
                c[1] + j as f64 * SPOT_SPACING,
            ];
            if workable(s, p) {
                // Squared grid distance orders the spots exactly (integers, no rounding).
                out.push((i * i + j * j, p));
            }
        }
    }
    out.sort_by_key(|(d, _)| *d);
    out.into_iter().map(|(_, p)| p).collect()
}

/// The template scene with its blocks replaced by `names` on the start area's spots, the last
/// block (the tower's bottom) nearest the centre.
fn tower_scene(b: Benchmark, names: &[String]) -> Result<WorldSnapshot, SceneError> {
    let mut s = b.scene_snapshot();
    let area = start_area(&s)?;
    let free = spots(&s, area);
    if free.len() < names.len() {
        return Err(err(format!(
            "{}: room for {} blocks only",
            b.as_str(),
            free.len()
        )));
    }
    s.bodies.retain(|body| body.kind != BodyKind::Block);
    let n = names.len();
    for (i, x) in names.iter().enumerate() {
        let p = free[n - 1 - i];
        s.bodies.push(block(x, i, p[0], p[1], 0.0));
    }
    let w = World::from_snapshot(&s)?;
    Ok(w.snapshot())
}

/// The N-tower goal: `x1` on `x2` on … on `xN`, and the template goal's other facts with its
/// bottom block renamed to `xN`.
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
    let last = names.last().ok_or_else(|| err("no blocks"))?;
    let mut goal: Vec<Fact> = names
        .windows(2)
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
        goal.push(Fact {
            predicate: f.predicate.clone(),
            args,
        });
    }
    Ok(goal)
}

/// `ops` reordered so that an arm that grasps a body puts it down before any other arm acts
/// (two arms never meet over a hand-over spot), where the reordered plan still reaches the goal.
fn carry_through(task: &crate::plan::Task, world: &World, mut ops: Vec<usize>) -> Vec<usize> {
    let motion = |o: usize| {
        world
            .motions()
            .action(&task.operators[o].name)
            .map(|(m, args)| {
                let arm = m.arm.and_then(|i| args.get(i)).map(|a| a.to_string());
                (m.motion, arm)
            })
    };
    let valid = |ops: &[usize]| {
        crate::plan::replay(task, &task.init, ops).is_ok_and(|s| task.goal.holds(&s))
    };
    let mut i = 0;
    while i < ops.len() {
        if let Some((MotionKind::Grasp, arm)) = motion(ops[i]) {
            let release = (i + 1..ops.len())
                .find(|&j| matches!(motion(ops[j]), Some((MotionKind::Release, a)) if a == arm));
            if let Some(j) = release.filter(|&j| j > i + 1) {
                let mut moved = ops.clone();
                let r = moved.remove(j);
                moved.insert(i + 1, r);
                if valid(&moved) {
                    ops = moved;
                }
            }
        }
        i += 1;
    }
    ops
}

/// The expert's script for `problem`: the tower built bottom-up, each block's part planned by the
/// planner (A* with LM-cut, else greedy best-first search with h_FF) and carried through by one
/// arm at a time; each release onto a surface or a region put on the first free spot of its area.
fn tower_script(
    b: Benchmark,
    world: &World,
    problem: &str,
    snap: &WorldSnapshot,
    blocks: &[String],
    goal: &[Fact],
) -> Result<Script, SceneError> {
    let domain = crate::pddl::parse_domain(b.domain_pddl(), "domain.pddl")
        .map_err(|e| err(e.to_string()))?;
    let parsed = crate::pddl::parse_problem(problem, "problem.pddl", &domain)
        .map_err(|e| err(e.to_string()))?;
    let task = crate::plan::ground(&domain, &parsed).map_err(|e| err(e.to_string()))?;
    // The tower is demonstrated bottom-up, one block at a time: a plan from the state so far
    // to the goal's facts about the blocks placed so far (optimal where A* finds one within its
    // budget, else greedy), so one block travels at a time.
    let optimal = SearchConfig {
        max_nodes: Some(PLAN_MAX_NODES),
        ..SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut)
    };
    let greedy = SearchConfig {
        max_nodes: Some(PLAN_MAX_NODES),
        ..SearchConfig::new(Algorithm::Gbfs, HeuristicKind::HFf)
    };
    let mut ops = Vec::new();
    let mut state = task.init.clone();
    for k in 1..=blocks.len() {
        let placed = &blocks[blocks.len() - k..];
        let pos = goal
            .iter()
            .filter(|f| {
                f.args
                    .iter()
                    .all(|a| !blocks.contains(a) || placed.contains(a))
            })
            .map(|f| {
                task.fact_id(&f.to_string())
                    .ok_or_else(|| err(format!("goal fact {f} is not a fact of the task")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut sub = task.clone();
        sub.init = state.clone();
        sub.goal = crate::plan::Goal {
            alternatives: vec![crate::plan::Condition { pos, neg: vec![] }],
            terminal_cost: 0,
        };
        let plan = [&optimal, &greedy]
            .iter()
            .find_map(|c| {
                crate::plan::search(&sub, c, &NoClock)
                    .outcome
                    .plan()
                    .cloned()
            })
            .ok_or_else(|| err(format!("the planner found no plan for {} blocks", k)))?;
        let part = carry_through(&sub, world, plan.operators.clone());
        state = crate::plan::replay(&sub, &state, &part)
            .map_err(|i| err(format!("step {i} of a planned part does not apply")))?;
        ops.extend(part);
    }
    let mut at: Vec<(String, [f64; 2])> = snap
        .bodies
        .iter()
        .filter(|body| body.kind == BodyKind::Block)
        .map(|body| {
            (
                body.name.clone(),
                [body.pose.position[0], body.pose.position[1]],
            )
        })
        .collect();
    let multi_arm = snap.arms.len() > 1;
    let names: Vec<String> = ops
        .iter()
        .map(|&o| task.operators[o].name.clone())
        .collect();
    let mut steps = Vec::with_capacity(names.len());
    for action in &names {
        let (m, args) = world
            .motions()
            .action(action)
            .ok_or_else(|| err(format!("{action}: no declared motion")))?;
        let x = m.object.and_then(|i| args.get(i)).map(|s| s.to_string());
        let mut step = ScriptStep {
            action: action.to_string(),
            to: None,
            yaw: 0.0,
            home: false,
        };
        match m.motion {
            MotionKind::Grasp => at.retain(|(b, _)| Some(b) != x.as_ref()),
            MotionKind::Release => {
                let area = match m.onto {
                    Some(Onto::Param(i)) => {
                        let y = args.get(i).copied().unwrap_or_default();
                        match world.body_kind(y) {
                            Some(BodyKind::Block) => None,
                            _ => Some(
                                snap.regions
                                    .iter()
                                    .find(|r| r.name == y)
                                    .map(|r| Area {
                                        min: r.min,
                                        max: r.max,
                                    })
                                    .ok_or_else(|| err(format!("{action}: no region {y}")))?,
                            ),
                        }
                    }
                    Some(Onto::Table) => Some(start_area(snap)?),
                    _ => return Err(err(format!("{action}: unsupported release"))),
                };
                if let Some(area) = area {
                    let p = spots(snap, area)
                        .into_iter()
                        .find(|p| {
                            at.iter()
                                .all(|(_, q)| libm::hypot(p[0] - q[0], p[1] - q[1]) >= TAKEN_RADIUS)
                        })
                        .ok_or_else(|| err(format!("{action}: no free spot")))?;
                    step.to = Some([p[0], p[1], 0.5 * super::benchmark::BLOCK_SIZE]);
                    if let Some(x) = &x {
                        at.push((x.clone(), p));
                    }
                }
                // Two arms keep apart: each goes home after putting a block down.
                step.home = multi_arm;
            }
            _ => return Err(err(format!("{action}: unsupported motion"))),
        }
        steps.push(step);
    }
    Ok(Script { steps })
}
