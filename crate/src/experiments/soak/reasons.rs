//! Why a soak episode may legitimately fail: the checks behind each stated reason (a user drag
//! that left a block out of every arm's reach, a full shelf, a disturbed task proved
//! unsolvable), and the parsed benchmark models the plan check and the unsolvability proof use.

use std::collections::{BTreeMap, BTreeSet};

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::query;
use parry3d_f64::shape::Cuboid;

use crate::lfd::DomainModel;
use crate::lfd::FailReason;
use crate::pddl::{parse_domain, parse_problem, Domain, Problem};
use crate::plan::fact_args;
use crate::plan::{
    ground, search, validate_names, Algorithm, HeuristicKind, NoClock, Outcome, SearchConfig,
    SearchOutcome,
};
use crate::sim::handleable;
use crate::sim::Benchmark;
use crate::sim::BodyKind;
use crate::sim::World;
use crate::sim::{block_names, tower_goal};
use crate::sim::{BenchmarkSources, SceneGraph};
use crate::sim::{Relation, Slot};

/// The block the failure `reason` acts on that a user drag left unworkable, with the proof: the
/// failed action (or the action the planner could not bind) names a block in `dragged`, and IK
/// ([`handleable`]: no arm can grasp it, nor pull it in with a clear stroke of the hook) says
/// why that block cannot be worked, either now or, in `away`, right after its last drag. A block
/// in a hand is judged where it is: an arm may close on a block dragged inside its minimum reach
/// and then be unable to lift it.
pub(super) fn drag_proof(
    world: &World,
    reason: &FailReason,
    dragged: &BTreeSet<String>,
    away: &BTreeMap<String, String>,
) -> Option<String> {
    acted_on(reason)
        .into_iter()
        .filter(|b| dragged.contains(b))
        .find_map(|b| {
            let now = (!world.is_lost(&b) && world.body_kind(&b) == Some(BodyKind::Block))
                .then(|| handleable(world, &b).err())
                .flatten();
            now.or_else(|| away.get(&b).cloned())
                .map(|why| format!("{b} (dragged): {why}"))
        })
}

/// The objects the failed action, or the action the planner could not bind, acts on.
pub(super) fn acted_on(reason: &FailReason) -> Vec<String> {
    let action = match reason {
        FailReason::ActionFailed { action, .. } => action.as_str(),
        FailReason::NoPlan { message } => message
            .split_once("cannot bind ")
            .map_or("", |(_, rest)| rest.split(')').next().unwrap_or("")),
        _ => "",
    };
    let (_, args) = fact_args(action.trim_start_matches('(').trim_end_matches(')'));
    args.iter().map(|a| a.to_string()).collect()
}

/// Overlap allowed between a block on a shelf and its neighbours (m): the contact slack.
const SHELF_SLACK: f64 = 0.002;
/// Spacing of the grid of candidate spots on a shelf's top (m).
const SHELF_GRID_STEP: f64 = 0.002;
/// Largest offset of a body's only part from the body's origin still taken as centred (m).
const CENTRED_PART: f64 = 1e-12;

/// A block the task's goal puts on a shelf, not on one now, for which no shelf has room left:
/// no spot on the shelf's top (the block's footprint within it; a 2 mm grid, turned in 15°
/// steps) where the block would overlap no other free body by more than the 2 mm contact slack.
/// The blocks disturbances left on the shelf fill it, and B2's domain (as the paper's) has no
/// action that takes a block off a shelf. Generous otherwise: arm reach and clearance are
/// ignored.
pub(super) fn shelf_full_for(
    world: &World,
    goal_facts: &[String],
    facts: &[String],
) -> Option<String> {
    let shelves: Vec<usize> = (0..world.bodies.len())
        .filter(|&i| world.bodies[i].kind == BodyKind::Shelf)
        .collect();
    if shelves.is_empty() {
        return None;
    }
    let m = world.motions();
    let on_shelf = |f: &str| match m.relation_of(f) {
        Some((Relation::OnShelf, spec, args)) => spec.value(&args, Slot::Body).map(str::to_string),
        _ => None,
    };
    let wanted = goal_facts.iter().filter_map(|f| on_shelf(f));
    for x in wanted {
        if facts
            .iter()
            .any(|f| on_shelf(f).as_deref() == Some(x.as_str()))
            || world.is_lost(&x)
        {
            continue;
        }
        let Some(bi) = world.body_index(&x) else {
            continue;
        };
        let body = &world.bodies[bi];
        let [(part, cuboid)] = body.parts.as_slice() else {
            continue;
        };
        if part.translation.vector.norm() > CENTRED_PART {
            continue;
        }
        let h = cuboid.half_extents;
        let me = Cuboid::new(h - Vector3::repeat(SHELF_SLACK).inf(&(h * 0.5)));
        let others: Vec<(Isometry3<f64>, Cuboid)> = world
            .bodies
            .iter()
            .enumerate()
            .filter(|(j, o)| *j != bi && o.is_movable() && !o.lost)
            .flat_map(|(_, o)| {
                o.world_parts()
                    .map(|(iso, c)| (iso, *c))
                    .collect::<Vec<_>>()
            })
            .collect();
        let room = shelves
            .iter()
            .any(|&si| shelf_has_room(world, si, &me, h.z, &others));
        if !room {
            return Some(x);
        }
    }
    None
}

/// Whether the block `me` (shrunk by the slack; `half_height` its unshrunk half height) fits on
/// the top of shelf `si` somewhere on the grid, in one of the turns, touching none of `others`.
fn shelf_has_room(
    world: &World,
    si: usize,
    me: &Cuboid,
    half_height: f64,
    others: &[(Isometry3<f64>, Cuboid)],
) -> bool {
    let (lo, hi) = world.bodies[si].aabb();
    let (nx, ny) = (
        ((hi.x - lo.x) / SHELF_GRID_STEP).floor() as usize,
        ((hi.y - lo.y) / SHELF_GRID_STEP).floor() as usize,
    );
    (0..6).any(|k| {
        let turn = UnitQuaternion::from_axis_angle(
            &Vector3::z_axis(),
            k as f64 * std::f64::consts::PI / 12.0,
        );
        // The turned footprint's half widths (of the shrunk box): it lies on the top.
        let m = turn.to_rotation_matrix().matrix().abs() * me.half_extents;
        (0..=nx).any(|i| {
            (0..=ny).any(|j| {
                let (cx, cy) = (
                    lo.x + i as f64 * SHELF_GRID_STEP,
                    lo.y + j as f64 * SHELF_GRID_STEP,
                );
                if cx - m.x < lo.x || cx + m.x > hi.x || cy - m.y < lo.y || cy + m.y > hi.y {
                    return false;
                }
                let at = Isometry3::from_parts(Translation3::new(cx, cy, hi.z + half_height), turn);
                others
                    .iter()
                    .all(|(iso, c)| !query::intersection_test(&at, me, iso, c).unwrap_or(true))
            })
        })
    })
}

/// The legitimate reason of [`shelf_full_for`].
pub(super) const SHELF_FULL: &str = "the shelf has no room left for a block the goal puts on it (disturbances filled it; the domain cannot take a block off the shelf)";

/// The legitimate reason of [`drag_proof`].
pub(super) const DRAGGED_AWAY: &str =
    "the failing action acts on a block a user drag put where no arm can grasp it (IK) or pull it in with a clear stroke of the hook";

/// The legitimate reason of [`Check::Unsolvable`].
pub(super) const UNSOLVABLE: &str = "no plan: the disturbed task is unsolvable";

/// What the exhaustive search of the observed task found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Check {
    /// Breadth-first search exhausted the reachable states (this many) without a goal state.
    Unsolvable { states: u64 },
    /// It found a plan of this many actions.
    Solvable { length: usize },
    /// It ran out of its node budget after this many expansions: nothing is proved.
    Undecided { expanded: u64 },
}

/// Parsed benchmark domains, or a task folder's model (for the validator and the unsolvability
/// check).
pub(super) struct Models {
    domains: Vec<(Benchmark, Domain)>,
    /// The soak's N-block tower tasks, if it runs them.
    blocks: Option<usize>,
    /// The task folder's domain and problem, if the soak runs its task.
    folder: Option<DomainModel>,
}

impl Models {
    /// The problem of `world` with the task's goal (the template's, or the N-block tower's).
    fn problem_text(&self, b: Benchmark, world: &World) -> Option<String> {
        match self.blocks {
            None => Some(b.problem_for(world, "observed")),
            Some(n) => {
                let goal = tower_goal(b, &block_names(n)).ok()?;
                Some(b.problem_for_goal(world, "observed", &goal))
            }
        }
    }

    pub(super) fn new(blocks: Option<usize>) -> Result<Models, String> {
        let domains = Benchmark::ALL
            .into_iter()
            .map(|b| {
                parse_domain(b.domain_pddl(), "domain.pddl")
                    .map(|d| (b, d))
                    .map_err(|e| e.to_string())
            })
            .collect::<Result<_, _>>()?;
        Ok(Models {
            domains,
            blocks,
            folder: None,
        })
    }

    /// The models of a task folder's task (`sources`: its files).
    pub(super) fn in_folder(sources: &BenchmarkSources) -> Result<Models, String> {
        let motions = sources.parse_motions().map_err(|e| match e {
            Ok(m) => m.to_string(),
            Err(pddl) => pddl,
        })?;
        let model = DomainModel::new(
            &sources.domain,
            &sources.file("domain.pddl"),
            &sources.problem,
            &sources.file("problem.pddl"),
            &motions.scene_predicates(),
        )
        .map_err(|e| e.to_string())?;
        Ok(Models {
            domains: Vec::new(),
            blocks: None,
            folder: Some(model),
        })
    }

    fn domain(&self, b: Benchmark) -> &Domain {
        &self
            .domains
            .iter()
            .find(|(x, _)| *x == b)
            .expect("every benchmark's domain is parsed in Models::new")
            .1
    }

    /// The domain and the parsed problem "reach the task's goal from the world's observed
    /// state": benchmark `b`'s (`None`: the task folder's).
    fn observed(&self, b: Option<Benchmark>, world: &World) -> Result<(&Domain, Problem), String> {
        let b = match (b, &self.folder) {
            (Some(b), _) => b,
            (None, Some(m)) => {
                let facts = SceneGraph::from_world(world).to_strings();
                let p = m
                    .problem(&SceneGraph::objects(world), &facts)
                    .map_err(|e| e.to_string())?;
                return Ok((m.domain(), p));
            }
            (None, None) => return Err("a soak over the benchmarks has no task folder".into()),
        };
        let text = self.problem_text(b, world).ok_or_else(|| {
            format!(
                "no {}-block task of {}",
                self.blocks.unwrap_or(0),
                b.as_str()
            )
        })?;
        let d = self.domain(b);
        let p = parse_problem(&text, "observed.pddl", d).map_err(|e| e.to_string())?;
        Ok((d, p))
    }

    /// Validates `plan` from the world's observed state to the benchmark's goal.
    pub(super) fn validate(
        &self,
        b: Option<Benchmark>,
        world: &World,
        plan: &[String],
    ) -> Result<(), String> {
        let (d, p) = self.observed(b, world)?;
        let r = validate_names(d, &p, plan);
        match r.outcome {
            Outcome::Valid => Ok(()),
            Outcome::Malformed(e) => Err(format!("malformed: {e}")),
            Outcome::PreconditionFalse {
                step,
                action,
                false_literals,
                ..
            } => Err(format!(
                "step {step} {action}: false precondition {}",
                false_literals.join(" ")
            )),
            Outcome::GoalNotReached { false_literals } => {
                Err(format!("goal not reached: {}", false_literals.join(" ")))
            }
        }
    }

    /// Searches the observed task (the world's facts, the benchmark's goal) exhaustively:
    /// breadth-first with duplicate detection and no heuristic, so an exhausted state space is a
    /// proof that no plan exists, up to `nodes` expansions. `Err`: the observed task could not be
    /// written, parsed or grounded.
    pub(super) fn check_solvable(
        &self,
        b: Option<Benchmark>,
        world: &World,
        nodes: u64,
    ) -> Result<Check, String> {
        let (d, p) = self.observed(b, world)?;
        let task = ground(d, &p).map_err(|e| e.to_string())?;
        let cfg = SearchConfig {
            max_nodes: Some(nodes),
            ..SearchConfig::new(Algorithm::Bfs, HeuristicKind::Blind)
        };
        let r = search(&task, &cfg, &NoClock);
        Ok(match r.outcome {
            SearchOutcome::Unsolvable => Check::Unsolvable {
                states: r.stats.states,
            },
            SearchOutcome::Plan(plan) => Check::Solvable {
                length: plan.operators.len(),
            },
            SearchOutcome::BudgetExhausted { .. } => Check::Undecided {
                expanded: r.stats.expanded,
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn a_shelf_is_full_only_when_no_footprint_on_its_top_is_free() {
        // Found by the soak. An L4 block e, put where the demonstration puts a block down, and
        // an L1 that slid it leave gaps of 5.2 and 4.8 cm on the shelf for the 6 cm block b the
        // arm holds. Without an action that takes a block off the shelf, no plan exists: a
        // legitimate failure.
        let path = format!(
            "{}/tests/data/worlds/b2-b-held-over-full-shelf.json",
            env!("CARGO_MANIFEST_DIR")
        );
        let mut world = World::from_json(&std::fs::read_to_string(path).unwrap())
            .unwrap()
            .with_motions(Benchmark::B2.motions());
        let goal = [
            "(onshelf a)".to_string(),
            "(onshelf b)".to_string(),
            "(onshelf e)".to_string(),
        ];
        let facts = |w: &World| crate::sim::SceneGraph::from_world(w).to_strings();
        assert_eq!(world.held_by(0), Some("b"));
        assert_eq!(
            shelf_full_for(&world, &goal, &facts(&world)),
            Some("b".into())
        );
        // e slid 1 cm towards the shelf's end: a 6.2 cm gap, room for b (2 mm to spare).
        let e = world.body_pose("e").unwrap().translation.vector;
        world
            .move_block_to("e", Vector3::new(e.x + 0.01, e.y, e.z), FRAC_PI_2)
            .unwrap();
        assert_eq!(shelf_full_for(&world, &goal, &facts(&world)), None);
        // Blocks the goal does not put on the shelf do not count.
        assert_eq!(shelf_full_for(&world, &[], &facts(&world)), None);
    }

    #[test]
    fn a_failure_is_the_drags_only_when_its_action_names_a_dragged_unworkable_block() {
        let world = Benchmark::B1.scene();
        let dragged: BTreeSet<String> = ["c".to_string(), "a".to_string()].into();
        let away: BTreeMap<String, String> = [("c".to_string(), "beyond reach".to_string())].into();
        let failed = |action: &str| FailReason::ActionFailed {
            action: action.into(),
            why: "the arm cannot reach its via-point (4.4 mm away)".into(),
        };
        let proof = drag_proof(&world, &failed("(stack panda c d)"), &dragged, &away);
        assert_eq!(proof.as_deref(), Some("c (dragged): beyond reach"));
        assert_eq!(
            drag_proof(&world, &failed("(stack panda b d)"), &dragged, &away),
            None
        );
        // a was dragged but can be worked where it is: no proof.
        assert_eq!(
            drag_proof(&world, &failed("(pick panda a)"), &dragged, &away),
            None
        );
        let unbound = |message: &str| FailReason::NoPlan {
            message: message.into(),
        };
        assert!(drag_proof(
            &world,
            &unbound("2 skeletons tried; last failure: cannot bind (pick panda c) (link 6 hits b)"),
            &dragged,
            &away
        )
        .is_some());
        assert_eq!(
            drag_proof(
                &world,
                &unbound(
                    "2 skeletons tried; last failure: cannot bind (pick panda a) (c overhangs a)"
                ),
                &dragged,
                &away
            ),
            None
        );
        assert_eq!(
            drag_proof(
                &world,
                &unbound("no action skeleton: the goal is unreachable"),
                &dragged,
                &away
            ),
            None
        );
    }

    #[test]
    fn a_held_block_dragged_inside_the_arms_minimum_reach_is_a_legitimate_failure() {
        // A user dragged a 15 cm from the base (the arm's reach starts at 25 cm); the arm closed
        // on it and cannot lift it.
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/data/worlds/b1-a-held-inside-minimum-reach.json"
        ))
        .unwrap();
        let world = World::from_json(&text).unwrap();
        assert_eq!(world.held_by(0), Some("a"));
        let failed = FailReason::ActionFailed {
            action: "(stack panda a b)".into(),
            why: "the arm cannot reach its via-point".into(),
        };
        let none = BTreeMap::new();
        let dragged: BTreeSet<String> = ["a".to_string()].into();
        assert!(drag_proof(&world, &failed, &dragged, &none).is_some());
        // A block the user did not move explains nothing.
        assert_eq!(
            drag_proof(&world, &failed, &["b".to_string()].into(), &none),
            None
        );
    }

    #[test]
    fn the_unsolvability_check_proves_by_exhausting_the_states() {
        let models = Models::new(None).unwrap();
        let world = Benchmark::B1.scene();
        let c = models
            .check_solvable(Some(Benchmark::B1), &world, 1_000_000)
            .unwrap();
        assert!(
            matches!(c, Check::Solvable { length } if length > 0),
            "{c:?}"
        );
        // A budget too small to finish proves nothing.
        let c = models
            .check_solvable(Some(Benchmark::B1), &world, 2)
            .unwrap();
        assert!(
            matches!(c, Check::Undecided { expanded } if expanded <= 3),
            "{c:?}"
        );
    }

    #[test]
    fn a_task_folders_plans_are_checked_on_its_own_domain_and_goal() {
        let dir =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../domains/b1-paper-naming");
        let sources = crate::sim::TaskFolder::read(&dir)
            .unwrap()
            .sources()
            .unwrap();
        let models = Models::in_folder(&sources).unwrap();
        let motions = std::sync::Arc::new(sources.parse_motions().unwrap());
        let world = World::from_json(&sources.scene)
            .unwrap()
            .with_motions(motions);
        let demo = crate::sim::demo::parse(&sources.demo).unwrap();
        let plan: Vec<String> = demo.plan().iter().map(|a| a.to_string()).collect();
        assert!(plan[0].starts_with("(pick-up "), "{plan:?}");
        models.validate(None, &world, &plan).unwrap();
        let short = models
            .validate(None, &world, &plan[..plan.len() - 1])
            .unwrap_err();
        assert!(short.starts_with("goal not reached"), "{short}");
        let c = models.check_solvable(None, &world, 1_000_000).unwrap();
        assert!(
            matches!(c, Check::Solvable { length } if length <= plan.len()),
            "{c:?}"
        );
        // A soak over the benchmarks has no folder to check against.
        assert!(Models::new(None)
            .unwrap()
            .validate(None, &world, &plan)
            .is_err());
    }
}
