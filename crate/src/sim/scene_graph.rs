//! The scene graph: the PDDL fluent facts `S_C` of the current world (paper Algorithm 1,
//! *SceneGraph*), derived from geometry.
//!
//! Definitions (names are the bodies', arms' and regions' lower-case names; a *free* body is a
//! block or the hook that is neither held nor lost; `tol` = [`WorldParams::support_tolerance`]
//! (5 mm); "rests on s" means the body's bottom is within `tol` of the top face of `s` and its
//! centroid lies over that face — the same test the invariants use):
//!
//! | fact | holds when |
//! |---|---|
//! | `(on x y)` | free block x rests on block y |
//! | `(ontable x)` | free block or hook x rests on a table |
//! | `(onshelf x)` | free block x rests on a shelf |
//! | `(clear x)` | block x is free and no free block rests on it |
//! | `(holding r x)` | arm r holds x |
//! | `(handempty r)` | arm r holds nothing |
//! | `(inreach r x)` | x (block or hook) is held by r, or is free and the horizontal distance from r's base axis to its grasp point (block centre, hook [`HOOK_GRASP_POINT`]) is within r's reach annulus |
//! | `(at x p)` | free block x rests on a table or a block with its centre inside region p |
//!
//! Only the predicates listed in the scene's `predicates` are reported (the benchmark domain's
//! fluents), so the set equals what the PDDL problem's `:init` states for that world. Facts are
//! sorted (predicate order of [`KNOWN_PREDICATES`], then
//! arguments), so the output is deterministic.
//!
//! [`WorldParams::support_tolerance`]: super::WorldParams::support_tolerance
//! [`HOOK_GRASP_POINT`]: super::geometry::HOOK_GRASP_POINT

use super::geometry::HOOK_GRASP_POINT;
use super::snapshot::BodyKind;
use super::world::{World, KNOWN_PREDICATES};
use nalgebra::{Point3, Vector3};
use serde::{Deserialize, Serialize};
use std::fmt;

/// One ground fact, e.g. `(on a b)`.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Fact {
    /// Predicate name (lower case).
    pub predicate: String,
    /// Object names (lower case).
    pub args: Vec<String>,
}

impl Fact {
    /// A fact from a predicate and arguments.
    pub fn new(predicate: &str, args: &[&str]) -> Fact {
        Fact {
            predicate: predicate.to_string(),
            args: args.iter().map(|s| s.to_string()).collect(),
        }
    }
}

impl fmt::Display for Fact {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "({}", self.predicate)?;
        for a in &self.args {
            write!(f, " {a}")?;
        }
        write!(f, ")")
    }
}

/// A PDDL object present in the scene and its type.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SceneObject {
    /// Object name.
    pub name: String,
    /// PDDL type: `arm`, `block`, `hook` or `region`.
    pub kind: String,
}

/// The facts of a world.
#[derive(Clone, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct SceneGraph {
    /// The facts, sorted.
    pub facts: Vec<Fact>,
}

impl SceneGraph {
    /// Derives the facts of `world` (see the module documentation for the definitions).
    pub fn from_world(world: &World) -> SceneGraph {
        let mut d = Derivation::new(world);
        d.support_facts();
        d.clear_facts();
        for ai in 0..world.arms.len() {
            d.arm_facts(ai);
        }
        SceneGraph {
            facts: d.into_sorted(),
        }
    }

    /// The facts as strings like `(on a b)`.
    pub fn to_strings(&self) -> Vec<String> {
        self.facts.iter().map(|f| f.to_string()).collect()
    }

    /// Whether the fact written as `(pred arg …)` holds (whitespace and case insensitive).
    pub fn contains(&self, fact: &str) -> bool {
        let norm = normalise(fact);
        self.facts.iter().any(|f| f.to_string() == norm)
    }

    /// The PDDL objects of `world`: arms, blocks, the hook (if the domain uses it), regions.
    pub fn objects(world: &World) -> Vec<SceneObject> {
        let mut out: Vec<SceneObject> = world
            .arms
            .iter()
            .map(|a| SceneObject {
                name: a.name.clone(),
                kind: "arm".into(),
            })
            .collect();
        let mut blocks: Vec<&str> = world.block_names();
        blocks.sort();
        out.extend(blocks.iter().map(|b| SceneObject {
            name: b.to_string(),
            kind: "block".into(),
        }));
        out.extend(
            world
                .bodies
                .iter()
                .filter(|b| b.kind == BodyKind::Hook)
                .map(|b| SceneObject {
                    name: b.name.clone(),
                    kind: "hook".into(),
                }),
        );
        out.extend(world.regions.iter().map(|r| SceneObject {
            name: r.name.clone(),
            kind: "region".into(),
        }));
        out
    }
}

/// The facts of one world as they are derived: who holds what, what rests on what.
struct Derivation<'a> {
    world: &'a World,
    /// held[a] = the body arm a holds.
    held: Vec<Option<usize>>,
    /// support[i] = the body free body i rests on.
    support: Vec<Option<usize>>,
    facts: Vec<Fact>,
}

impl<'a> Derivation<'a> {
    fn new(world: &'a World) -> Self {
        let held: Vec<Option<usize>> = world
            .arms
            .iter()
            .map(|a| a.holding.map(|(i, _)| i))
            .collect();
        let mut d = Derivation {
            world,
            held,
            support: Vec::new(),
            facts: Vec::new(),
        };
        d.support = (0..world.bodies.len())
            .map(|i| if d.free(i) { world.support_of(i) } else { None })
            .collect();
        d
    }

    /// Whether the scene reports predicate `p`.
    fn want(&self, p: &str) -> bool {
        self.world.predicates.iter().any(|q| q == p)
    }

    /// Whether body `i` is a block or the hook that is neither held nor lost.
    fn free(&self, i: usize) -> bool {
        let b = &self.world.bodies[i];
        b.is_movable() && !b.lost && !self.held.contains(&Some(i))
    }

    /// `on`, `ontable`, `onshelf` and `at` of every free body.
    fn support_facts(&mut self) {
        let world = self.world;
        for (i, b) in world.bodies.iter().enumerate() {
            if !self.free(i) {
                continue;
            }
            let Some(s) = self.support[i] else { continue };
            let sk = world.bodies[s].kind;
            match (b.kind, sk) {
                (BodyKind::Block, BodyKind::Block) if self.want("on") => self
                    .facts
                    .push(Fact::new("on", &[&b.name, &world.bodies[s].name])),
                (BodyKind::Block | BodyKind::Hook, BodyKind::Table) if self.want("ontable") => {
                    self.facts.push(Fact::new("ontable", &[&b.name]))
                }
                (BodyKind::Block, BodyKind::Shelf) if self.want("onshelf") => {
                    self.facts.push(Fact::new("onshelf", &[&b.name]))
                }
                _ => {}
            }
            if b.kind == BodyKind::Block
                && self.want("at")
                && matches!(sk, BodyKind::Table | BodyKind::Block)
            {
                let c = b.pose.translation.vector;
                for r in &world.regions {
                    if r.contains(c.x, c.y) {
                        self.facts.push(Fact::new("at", &[&b.name, &r.name]));
                    }
                }
            }
        }
    }

    /// `clear` of every free block nothing rests on.
    fn clear_facts(&mut self) {
        if !self.want("clear") {
            return;
        }
        for (i, b) in self.world.bodies.iter().enumerate() {
            if b.kind == BodyKind::Block && self.free(i) && !self.support.contains(&Some(i)) {
                self.facts.push(Fact::new("clear", &[&b.name]));
            }
        }
    }

    /// `holding`, `handempty` and `inreach` of arm `ai`.
    fn arm_facts(&mut self, ai: usize) {
        let world = self.world;
        let a = &world.arms[ai];
        match self.held[ai] {
            Some(i) if self.want("holding") => self
                .facts
                .push(Fact::new("holding", &[&a.name, &world.bodies[i].name])),
            None if self.want("handempty") => self.facts.push(Fact::new("handempty", &[&a.name])),
            _ => {}
        }
        if !self.want("inreach") {
            return;
        }
        let base = a.base.translation.vector;
        for (i, b) in world.bodies.iter().enumerate() {
            let inreach = if self.held[ai] == Some(i) {
                true
            } else if self.free(i) {
                let p = match b.kind {
                    BodyKind::Hook => {
                        (b.pose * Point3::from(Vector3::from(HOOK_GRASP_POINT))).coords
                    }
                    _ => b.pose.translation.vector,
                };
                let r = libm::hypot(p.x - base.x, p.y - base.y);
                r >= a.reach.min_radius && r <= a.reach.max_radius
            } else {
                false
            };
            if inreach {
                self.facts.push(Fact::new("inreach", &[&a.name, &b.name]));
            }
        }
    }

    /// The facts sorted (predicate order of [`KNOWN_PREDICATES`], then arguments), without
    /// repeats.
    fn into_sorted(self) -> Vec<Fact> {
        let mut facts = self.facts;
        let rank = |p: &str| {
            KNOWN_PREDICATES
                .iter()
                .position(|q| *q == p)
                .unwrap_or(usize::MAX)
        };
        facts.sort_by(|x, y| {
            rank(&x.predicate)
                .cmp(&rank(&y.predicate))
                .then_with(|| x.args.cmp(&y.args))
        });
        facts.dedup();
        facts
    }
}

/// `( On  A b )` → `(on a b)`.
pub(crate) fn normalise(fact: &str) -> String {
    let inner = fact.trim().trim_start_matches('(').trim_end_matches(')');
    format!(
        "({})",
        inner
            .split_whitespace()
            .map(|s| s.to_ascii_lowercase())
            .collect::<Vec<_>>()
            .join(" ")
    )
}
