//! The expert's script of a generated task: the towers built block by block, each block's part
//! of the plan found by the planner and carried through by one arm at a time.

use super::layout::{spots, start_area, Area, TAKEN_RADIUS};
use super::names::err;
use crate::plan::{Algorithm, HeuristicKind, NoClock, SearchConfig};
use crate::sim::demo::{Script, ScriptStep};
use crate::sim::world::World;
use crate::sim::Benchmark;
use crate::sim::Fact;
use crate::sim::SceneError;
use crate::sim::{BodyKind, WorldSnapshot};
use crate::sim::{MotionKind, Onto};

/// Expansions allowed to the planner of a generated demonstration.
const PLAN_MAX_NODES: u64 = 20_000;

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

/// The expert's script for `problem`: the blocks put in place in the order `build` (each tower
/// bottom-up), each block's part planned by the planner (A* with LM-cut, else greedy best-first
/// search with h_FF) and carried through by one arm at a time; each release onto a surface or a
/// region put on the first free spot of its area.
pub(super) fn tower_script(
    b: Benchmark,
    world: &World,
    problem: &str,
    snap: &WorldSnapshot,
    build: &[String],
    goal: &[Fact],
) -> Result<Script, SceneError> {
    let domain = crate::pddl::parse_domain(b.domain_pddl(), "domain.pddl")
        .map_err(|e| err(e.to_string()))?;
    let parsed = crate::pddl::parse_problem(problem, "problem.pddl", &domain)
        .map_err(|e| err(e.to_string()))?;
    let task = crate::plan::ground(&domain, &parsed).map_err(|e| err(e.to_string()))?;
    // The towers are demonstrated bottom-up, one block at a time: a plan from the state so far
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
    for k in 1..=build.len() {
        let placed = &build[..k];
        let pos = goal
            .iter()
            .filter(|f| {
                f.args
                    .iter()
                    .all(|a| !build.contains(a) || placed.contains(a))
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
                        .map(|s| s.p)
                        .find(|p| {
                            at.iter()
                                .all(|(_, q)| libm::hypot(p[0] - q[0], p[1] - q[1]) >= TAKEN_RADIUS)
                        })
                        .ok_or_else(|| err(format!("{action}: no free spot")))?;
                    step.to = Some([p[0], p[1], 0.5 * crate::sim::BLOCK_SIZE]);
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
