//! The paper's three benchmarks (§IV-A): their template worlds, PDDL texts and goal facts.
//!
//! Layouts (world frame, metres, table tops at `z = 0`, arms facing `+x`):
//! * **B1** `b1-tower`: one arm `panda` at the origin; blocks `a b c d` on one table; goal
//!   `(on a b) (on b c) (on c d)`.
//! * **B2** `b2-workspace-reach`: one arm `panda` at the origin (blocks count as in reach between
//!   0.25 and 0.70 m from its base axis); block `a` in reach, block `b` at 0.95 m beyond reach, the
//!   L-shaped `hook` in reach, a shelf at `(0.35, −0.50)` with its top at 0.10 m; goal
//!   `(onshelf a) (onshelf b)`.
//! * **B3** `b3-dual-arm`: arms `left` at `(0, 0.45)` and `right` at `(0, −0.45)` on two tables
//!   that meet at `y = 0`; regions `left-table` (`y ≥ 0.35`, only the left arm reaches it),
//!   `handover` (around `(0.38, 0)`, both reach it) and `right-table` (`y ≤ −0.35`, only the right
//!   arm); blocks `a b` start on the left table; goal `(on a b) (at b right-table)`.

use super::motions::{Motions, MotionsError};
use super::panda::{self, DOF};
use super::scene_graph::{Fact, SceneGraph};
use super::snapshot::*;
use super::world::World;
use super::SceneError;
use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::sync::{Arc, OnceLock};

/// Side of a block (m).
pub const BLOCK_SIZE: f64 = 0.06;

/// One of the paper's benchmarks (JSON and CLI: `b1`, `b2`, `b3`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify))]
pub enum Benchmark {
    /// Tower construction: one arm, four blocks.
    B1,
    /// Workspace reach: one arm, blocks partly beyond reach, a hook, a shelf.
    B2,
    /// Dual-arm block transportation: two arms, hand-over region.
    B3,
}

/// The colours of blocks `a`, `b`, `c`, `d`, then extra blocks.
pub const BLOCK_COLORS: [&str; 6] = [
    "#d62728", "#2ca02c", "#1f77b4", "#ffbf00", "#9467bd", "#8c564b",
];

impl Benchmark {
    /// All three, in order.
    pub const ALL: [Benchmark; 3] = [Benchmark::B1, Benchmark::B2, Benchmark::B3];

    /// Parses `b1`, `b2`, `b3` or the directory names (`b1-tower`, …).
    pub fn parse(s: &str) -> Option<Benchmark> {
        match s.to_ascii_lowercase().as_str() {
            "b1" | "b1-tower" => Some(Benchmark::B1),
            "b2" | "b2-workspace-reach" => Some(Benchmark::B2),
            "b3" | "b3-dual-arm" => Some(Benchmark::B3),
            _ => None,
        }
    }

    /// Short name (`b1`, `b2`, `b3`), as on the CLI and in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            Benchmark::B1 => "b1",
            Benchmark::B2 => "b2",
            Benchmark::B3 => "b3",
        }
    }

    /// Directory name under `domains/` (also the PDDL domain name and the scene name).
    pub fn dir_name(self) -> &'static str {
        match self {
            Benchmark::B1 => "b1-tower",
            Benchmark::B2 => "b2-workspace-reach",
            Benchmark::B3 => "b3-dual-arm",
        }
    }

    /// The PDDL domain text (`domains/<dir>/domain.pddl`).
    pub fn domain_pddl(self) -> &'static str {
        match self {
            Benchmark::B1 => include_str!("../../../domains/b1-tower/domain.pddl"),
            Benchmark::B2 => include_str!("../../../domains/b2-workspace-reach/domain.pddl"),
            Benchmark::B3 => include_str!("../../../domains/b3-dual-arm/domain.pddl"),
        }
    }

    /// The PDDL template problem text (`domains/<dir>/problem.pddl`).
    pub fn problem_pddl(self) -> &'static str {
        match self {
            Benchmark::B1 => include_str!("../../../domains/b1-tower/problem.pddl"),
            Benchmark::B2 => include_str!("../../../domains/b2-workspace-reach/problem.pddl"),
            Benchmark::B3 => include_str!("../../../domains/b3-dual-arm/problem.pddl"),
        }
    }

    /// The demonstration (`domains/<dir>/demo.json`).
    ///
    /// The page's first-load wasm module (cfg `first_load`) embeds B1's only (B2's and B3's are
    /// three quarters of its data) and returns `""` for the others, which
    /// [`Benchmark::available`] refuses before anything reads them.
    pub fn demo_json(self) -> &'static str {
        match self {
            Benchmark::B1 => include_str!("../../../domains/b1-tower/demo.json"),
            #[cfg(not(first_load))]
            Benchmark::B2 => include_str!("../../../domains/b2-workspace-reach/demo.json"),
            #[cfg(not(first_load))]
            Benchmark::B3 => include_str!("../../../domains/b3-dual-arm/demo.json"),
            #[cfg(first_load)]
            Benchmark::B2 | Benchmark::B3 => "",
        }
    }

    /// Whether this build carries the benchmark's demonstration: always, except B2 and B3 in
    /// the page's first-load wasm module (cfg `first_load`), where the error says so.
    pub fn available(self) -> Result<(), SceneError> {
        if cfg!(first_load) && self != Benchmark::B1 {
            return Err(SceneError {
                path: String::new(),
                message: format!(
                    "{} runs on the page's full module, not its first-load module",
                    self.as_str()
                ),
            });
        }
        Ok(())
    }

    /// What the domain's actions do physically and how its predicates read the scene
    /// (`domains/<dir>/motions.json`).
    pub fn motions_json(self) -> &'static str {
        match self {
            Benchmark::B1 => include_str!("../../../domains/b1-tower/motions.json"),
            Benchmark::B2 => include_str!("../../../domains/b2-workspace-reach/motions.json"),
            Benchmark::B3 => include_str!("../../../domains/b3-dual-arm/motions.json"),
        }
    }

    /// The expert's script of the template demonstration (`domains/<dir>/expert.json`, see
    /// [`crate::sim::demo::Script`]).
    pub fn expert_json(self) -> &'static str {
        match self {
            Benchmark::B1 => include_str!("../../../domains/b1-tower/expert.json"),
            Benchmark::B2 => include_str!("../../../domains/b2-workspace-reach/expert.json"),
            Benchmark::B3 => include_str!("../../../domains/b3-dual-arm/expert.json"),
        }
    }

    /// The parsed [`Benchmark::motions_json`] (read once).
    pub fn motions(self) -> Arc<Motions> {
        static CACHE: [OnceLock<Arc<Motions>>; 3] =
            [OnceLock::new(), OnceLock::new(), OnceLock::new()];
        let i = self as usize;
        Arc::clone(CACHE[i].get_or_init(|| {
            let parsed = crate::pddl::parse_domain(self.domain_pddl(), "domain.pddl")
                .map_err(|e| e.to_string())
                .and_then(|d| {
                    Motions::parse(self.motions_json(), "motions.json", &d)
                        .map_err(|e| e.to_string())
                });
            match parsed {
                Ok(m) => Arc::new(m),
                // Fixed data checked by the tests; a failure is a bug here.
                Err(e) => panic!("benchmark {} motions: {e}", self.dir_name()),
            }
        }))
    }

    /// The benchmark's files (embedded in the library), the scene as the JSON of
    /// [`Benchmark::scene_snapshot`].
    pub fn sources(self) -> Result<BenchmarkSources, SceneError> {
        self.available()?;
        let scene = serde_json::to_string(&self.scene_snapshot()).map_err(|e| SceneError {
            path: "snapshot".into(),
            message: e.to_string(),
        })?;
        Ok(BenchmarkSources {
            folder: None,
            dir: self.dir_name().to_string(),
            domain: self.domain_pddl().to_string(),
            problem: self.problem_pddl().to_string(),
            scene,
            demo: self.demo_json().to_string(),
            motions: self.motions_json().to_string(),
        })
    }

    /// The goal facts (the same for every task of the benchmark): the template problem's goal.
    pub fn goal(self) -> Vec<Fact> {
        self.template_facts().0.clone()
    }

    /// Static facts of the template problem that the scene graph does not report (B3's arm
    /// reach of each region).
    pub fn static_facts(self) -> Vec<Fact> {
        self.template_facts().1.clone()
    }

    /// The template problem's goal and static facts, read once (every generated problem of the
    /// benchmark needs them).
    fn template_facts(self) -> &'static (Vec<Fact>, Vec<Fact>) {
        static CACHE: [OnceLock<(Vec<Fact>, Vec<Fact>)>; 3] =
            [OnceLock::new(), OnceLock::new(), OnceLock::new()];
        CACHE[self as usize].get_or_init(|| {
            let parsed =
                crate::pddl::parse_domain(self.domain_pddl(), "domain.pddl").and_then(|d| {
                    crate::pddl::parse_problem(self.problem_pddl(), "problem.pddl", &d)
                        .map(|p| (d, p))
                });
            let Ok((domain, problem)) = parsed else {
                return (Vec::new(), Vec::new());
            };
            let scene = self.motions().scene_predicates();
            let statics = problem
                .init
                .iter()
                .filter(|a| !scene.contains(&domain.predicates[a.predicate].name.text))
                .map(|a| atom_fact(&domain, a))
                .collect();
            (goal_facts(&domain, &problem), statics)
        })
    }

    /// The blocks of the template task.
    pub fn blocks(self) -> &'static [&'static str] {
        match self {
            Benchmark::B1 => &["a", "b", "c", "d"],
            Benchmark::B2 | Benchmark::B3 => &["a", "b"],
        }
    }

    /// The template task's initial world (what `domains/<dir>/scene.json` holds).
    pub fn scene(self) -> World {
        let snap = self.scene_snapshot();
        match World::from_snapshot(&snap) {
            Ok(w) => w.with_motions(self.motions()),
            // The builders below are fixed data checked by the tests; a failure is a bug here.
            Err(e) => panic!("benchmark scene {} is invalid: {e}", self.dir_name()),
        }
    }

    /// A PDDL problem for the task "reach this benchmark's goal from `world`": objects and init
    /// from the scene graph (plus [`Benchmark::static_facts`]), the benchmark's goal. This is how a
    /// disturbed world (for example with an added block) becomes a planning problem.
    pub fn problem_for(self, world: &World, problem_name: &str) -> String {
        self.problem_for_goal(world, problem_name, &self.goal())
    }

    /// [`Benchmark::problem_for`] with another goal (a generated N-block tower's).
    pub fn problem_for_goal(self, world: &World, problem_name: &str, goal: &[Fact]) -> String {
        // Read through this benchmark's declaration (a copy only when the world has another).
        let motions = self.motions();
        let own;
        let world = if Arc::ptr_eq(&world.motions_arc(), &motions) {
            world
        } else {
            own = world.clone().with_motions(motions);
            &own
        };
        let objects = SceneGraph::objects(world);
        let mut by_type: Vec<(String, Vec<String>)> = Vec::new();
        for o in objects {
            match by_type.iter_mut().find(|(t, _)| *t == o.ty) {
                Some((_, v)) => v.push(o.name),
                None => by_type.push((o.ty, vec![o.name])),
            }
        }
        let mut text = format!(
            "(define (problem {problem_name})\n  (:domain {})\n  (:objects\n",
            self.dir_name()
        );
        for (t, names) in by_type {
            text += &format!("    {} - {t}\n", names.join(" "));
        }
        text += "  )\n  (:init\n";
        for f in SceneGraph::from_world(world)
            .facts
            .iter()
            .chain(self.static_facts().iter())
        {
            text += &format!("    {f}\n");
        }
        text += "  )\n  (:goal (and";
        for g in goal {
            text += &format!(" {g}");
        }
        text += ")))\n";
        text
    }

    /// The template world as a snapshot (derived drawing fields filled in).
    pub fn scene_snapshot(self) -> WorldSnapshot {
        let mut s = match self {
            Benchmark::B1 => WorldSnapshot {
                version: SNAPSHOT_VERSION,
                name: self.dir_name().into(),
                time: 0.0,
                dt: 0.01,
                floor_z: -0.75,
                regions: vec![],
                bodies: vec![
                    table("table", [0.35, 0.0], [0.60, 0.60]),
                    block("a", 0, 0.40, -0.25, 0.0),
                    block("b", 1, 0.55, -0.08, 0.0),
                    block("c", 2, 0.42, 0.10, 0.0),
                    block("d", 3, 0.55, 0.26, 0.0),
                ],
                arms: vec![arm("panda", [0.0, 0.0], 0.25, 0.70)],
            },
            Benchmark::B2 => WorldSnapshot {
                version: SNAPSHOT_VERSION,
                name: self.dir_name().into(),
                time: 0.0,
                dt: 0.01,
                floor_z: -0.75,
                regions: vec![],
                bodies: vec![
                    table("table", [0.45, 0.0], [0.75, 0.70]),
                    BodySnapshot {
                        name: "shelf".into(),
                        kind: BodyKind::Shelf,
                        shape: ShapeSnapshot::Cuboid {
                            half_extents: [0.12, 0.08, 0.05],
                        },
                        pose: pose([0.35, -0.50, 0.05], 0.0),
                        color: "#8c6d46".into(),
                        lost: false,
                    },
                    hook("hook", [0.50, -0.20], 0.0),
                    block("a", 0, 0.45, 0.25, 0.0),
                    block("b", 1, 0.95, 0.05, 0.0),
                ],
                arms: vec![arm("panda", [0.0, 0.0], 0.25, 0.70)],
            },
            Benchmark::B3 => WorldSnapshot {
                version: SNAPSHOT_VERSION,
                name: self.dir_name().into(),
                time: 0.0,
                dt: 0.01,
                floor_z: -0.75,
                regions: vec![
                    region("left-table", [0.20, 0.35], [0.75, 0.95], "#f4a6a6"),
                    region("handover", [0.28, -0.10], [0.48, 0.10], "#f4e3a6"),
                    region("right-table", [0.20, -0.95], [0.75, -0.35], "#a6c8f4"),
                ],
                bodies: vec![
                    table("left-bench", [0.35, 0.50], [0.50, 0.50]),
                    table("right-bench", [0.35, -0.50], [0.50, 0.50]),
                    block("a", 0, 0.40, 0.58, 0.0),
                    block("b", 1, 0.42, 0.74, 0.0),
                ],
                arms: vec![
                    arm("left", [0.0, 0.45], 0.25, 0.70),
                    arm("right", [0.0, -0.45], 0.25, 0.70),
                ],
            },
        };
        // Fill in the derived fields by a round trip through the world.
        if let Ok(w) = World::from_snapshot(&s) {
            s = w.snapshot();
        }
        s
    }
}

/// What an episode log keeps of the task folder it ran on: where it was and each file's hash,
/// and the files themselves when the log must replay without the folder (the page's Save).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct FolderRecord {
    /// The folder as messages name it.
    pub dir: String,
    /// The content hash (`sim::content_hash`) of each file but `README.md`, by file name.
    pub hashes: BTreeMap<String, String>,
    /// The files' text, by name (absent: replay needs the folder).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub files: Option<BTreeMap<String, String>>,
}

/// The text of a benchmark's files (a taught task's too: its own problem, scene and demo).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BenchmarkSources {
    /// The task folder the files come from (`None`: a shipped benchmark or a generated task).
    pub folder: Option<FolderRecord>,
    /// Directory name under `domains/`, or a directory's path (for error messages, see
    /// [`BenchmarkSources::file`]).
    pub dir: String,
    /// `domain.pddl`.
    pub domain: String,
    /// `problem.pddl` (the template task).
    pub problem: String,
    /// `scene.json` (the template task's initial world).
    pub scene: String,
    /// `demo.json` (the demonstration).
    pub demo: String,
    /// `motions.json` (what the actions do physically, how the predicates read the scene).
    pub motions: String,
}

/// The positive atoms of a problem's goal, as facts (a conjunction of atoms, the tasks the
/// robot runs).
pub fn goal_facts(domain: &crate::pddl::Domain, problem: &crate::pddl::Problem) -> Vec<Fact> {
    let mut out = Vec::new();
    goal_atoms(domain, &problem.goal, &mut out);
    out
}

/// The positive atoms of a goal formula, as facts.
fn goal_atoms(domain: &crate::pddl::Domain, f: &crate::pddl::Formula, out: &mut Vec<Fact>) {
    match f {
        crate::pddl::Formula::Atom(a) => out.push(atom_fact(domain, a)),
        crate::pddl::Formula::And(v, _) => v.iter().for_each(|g| goal_atoms(domain, g, out)),
        _ => {}
    }
}

fn atom_fact(domain: &crate::pddl::Domain, a: &crate::pddl::Atom) -> Fact {
    Fact {
        predicate: domain.predicates[a.predicate].name.text.clone(),
        args: a.args.iter().map(|t| t.text().to_string()).collect(),
    }
}

impl BenchmarkSources {
    /// The path of one of the files, for messages: `domains/<dir>/<name>` for a shipped domain,
    /// `<dir>/<name>` when `dir` is a path.
    pub fn file(&self, name: &str) -> String {
        if self.dir.contains('/') {
            format!("{}/{name}", self.dir.trim_end_matches('/'))
        } else {
            format!("domains/{}/{name}", self.dir)
        }
    }

    /// The parsed `motions.json`, checked against the domain. `Err(Err(text))`: the domain itself
    /// does not parse.
    pub fn parse_motions(&self) -> Result<Motions, Result<MotionsError, String>> {
        let domain_file = self.file("domain.pddl");
        let domain = crate::pddl::parse_domain(&self.domain, &domain_file)
            .map_err(|e| Err(e.to_string()))?;
        Motions::parse(&self.motions, &self.file("motions.json"), &domain).map_err(Ok)
    }
}

/// A pose snapshot at `p` with yaw `yaw`.
pub(crate) fn pose(p: [f64; 3], yaw: f64) -> PoseSnapshot {
    let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw).coords;
    PoseSnapshot {
        position: p,
        quaternion: [q.x, q.y, q.z, q.w],
    }
}

fn table(name: &str, centre: [f64; 2], half: [f64; 2]) -> BodySnapshot {
    BodySnapshot {
        name: name.into(),
        kind: BodyKind::Table,
        shape: ShapeSnapshot::Cuboid {
            half_extents: [half[0], half[1], 0.02],
        },
        pose: pose([centre[0], centre[1], -0.02], 0.0),
        color: "#c8b38a".into(),
        lost: false,
    }
}

/// A 6 cm block resting on a table top at `z = 0`; `colour` indexes [`BLOCK_COLORS`].
pub(crate) fn block(name: &str, colour: usize, x: f64, y: f64, yaw: f64) -> BodySnapshot {
    let h = 0.5 * BLOCK_SIZE;
    BodySnapshot {
        name: name.into(),
        kind: BodyKind::Block,
        shape: ShapeSnapshot::Cuboid {
            half_extents: [h; 3],
        },
        pose: pose([x, y, h], yaw),
        color: BLOCK_COLORS[colour % BLOCK_COLORS.len()].into(),
        lost: false,
    }
}

/// The L-shaped hook lying on the table: a 40 cm handle along the hook's `x` axis and a 16 cm
/// blade at its far end pointing to `+y`, both 2 cm square in section; origin at the handle centre.
fn hook(name: &str, xy: [f64; 2], yaw: f64) -> BodySnapshot {
    BodySnapshot {
        name: name.into(),
        kind: BodyKind::Hook,
        shape: ShapeSnapshot::Compound {
            parts: vec![
                PartSnapshot {
                    pose: pose([0.0, 0.0, 0.0], 0.0),
                    half_extents: [0.20, 0.01, 0.01],
                },
                PartSnapshot {
                    pose: pose([0.19, 0.08, 0.0], 0.0),
                    half_extents: [0.01, 0.07, 0.01],
                },
            ],
        },
        pose: pose([xy[0], xy[1], 0.01], yaw),
        color: "#555555".into(),
        lost: false,
    }
}

fn region(name: &str, min: [f64; 2], max: [f64; 2], color: &str) -> RegionSnapshot {
    RegionSnapshot {
        name: name.into(),
        min,
        max,
        color: color.into(),
    }
}

fn arm(name: &str, xy: [f64; 2], rmin: f64, rmax: f64) -> ArmSnapshot {
    let base = pose([xy[0], xy[1], 0.0], 0.0);
    let iso = Isometry3::translation(xy[0], xy[1], 0.0);
    ArmSnapshot {
        name: name.into(),
        base,
        robot: None,
        joints: panda::READY.to_vec(),
        gripper_opening: panda::GRIPPER_MAX_OPENING,
        holding: None,
        reach: ReachSnapshot {
            min_radius: rmin,
            max_radius: rmax,
        },
        tcp: {
            let t = panda::forward_kinematics(&iso, &ready());
            let q = t.rotation.coords;
            PoseSnapshot {
                position: t.translation.vector.into(),
                quaternion: [q.x, q.y, q.z, q.w],
            }
        },
        links: vec![],
        fingers: vec![],
        model: None,
    }
}

fn ready() -> [f64; DOF] {
    panda::READY
}
