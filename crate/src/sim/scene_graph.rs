//! The scene graph: the PDDL fluent facts `S_C` of the current world (paper Algorithm 1,
//! *SceneGraph*), derived from geometry.
//!
//! The facts are stated with the domain's own predicates, declared in its `motions.json`
//! ([`Motions`]: relation → predicate and argument order). Definitions (names are the bodies',
//! arms' and regions' lower-case names; a *free* body is a block or the hook that is neither held
//! nor lost; `tol` = [`WorldParams::support_tolerance`] (5 mm); "rests on s" means the body's
//! bottom is within `tol` of the top face of `s` and its centroid lies over that face — the same
//! test the invariants use):
//!
//! | relation | holds when |
//! |---|---|
//! | `on_block` (x, y) | free block x rests on block y |
//! | `on_table` (x) | free block or hook x rests on a table |
//! | `on_shelf` (x) | free block x rests on a shelf |
//! | `clear` (x) | block x is free and no free block rests on it |
//! | `held` (r, x) | arm r holds x |
//! | `hand_empty` (r) | arm r holds nothing |
//! | `in_reach` (r, x) | x (block or hook) is held by r, or is free and the horizontal distance from r's base axis to its grasp point (block centre, hook [`HOOK_GRASP_POINT`]) is within r's reach annulus |
//! | `in_region` (x, p) | free block x rests on a table or a block with its centre inside region p |
//!
//! plus, for each object kind declared with a type predicate, that predicate of each such object
//! (`(block a)` in an untyped domain). Only the relations the declaration names are reported, so
//! the set equals what the PDDL problem's `:init` states for that world. Facts are sorted
//! (relation order of [`Relation::ALL`], type predicates last, then arguments), so the output is
//! deterministic.
//!
//! [`WorldParams::support_tolerance`]: super::WorldParams::support_tolerance
//! [`HOOK_GRASP_POINT`]: super::geometry::HOOK_GRASP_POINT
//! [`Motions`]: super::motions::Motions

use super::geometry::HOOK_GRASP_POINT;
use super::motions::{ObjectKind, Relation, Slot};
use super::snapshot::BodyKind;
use super::world::World;
use crate::pddl::ObjectDecl;
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
        d.type_facts();
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

    /// The PDDL objects of `world` with their types: arms, blocks, hooks and regions, the kinds
    /// the domain's declaration names (`object` where it gives no type).
    pub fn objects(world: &World) -> Vec<ObjectDecl> {
        let m = world.motions();
        let mut out = Vec::new();
        for kind in ObjectKind::ALL {
            let Some(spec) = m.objects.get(&kind) else {
                continue;
            };
            let ty = spec.ty.clone().unwrap_or_else(|| "object".into());
            for name in names_of(world, kind) {
                out.push(ObjectDecl {
                    name,
                    ty: ty.clone(),
                });
            }
        }
        out
    }
}

/// The names of the scene's objects of one kind (blocks sorted by name).
fn names_of(world: &World, kind: ObjectKind) -> Vec<String> {
    match kind {
        ObjectKind::Arm => world.arms.iter().map(|a| a.name.clone()).collect(),
        ObjectKind::Block => {
            let mut blocks: Vec<String> =
                world.block_names().iter().map(|b| b.to_string()).collect();
            blocks.sort();
            blocks
        }
        ObjectKind::Hook => world.hook_names(),
        ObjectKind::Region => world.regions.iter().map(|r| r.name.clone()).collect(),
    }
}

/// The facts of one world as they are derived: who holds what, what rests on what.
struct Derivation<'a> {
    world: &'a World,
    /// held[a] = the body arm a holds.
    held: Vec<Option<usize>>,
    /// support[i] = the body free body i rests on.
    support: Vec<Option<usize>>,
    /// The facts with their sort rank (relation order, type predicates last).
    facts: Vec<(usize, Fact)>,
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

    /// Whether the domain states relation `r`.
    fn want(&self, r: Relation) -> bool {
        self.world.motions.reports(r)
    }

    /// Adds the fact stating `r` of these argument values.
    fn push(&mut self, r: Relation, values: &[(Slot, &str)]) {
        let Some(spec) = self.world.motions.fact(r) else {
            return;
        };
        let args: Option<Vec<&str>> = spec
            .args
            .iter()
            .map(|slot| values.iter().find(|(k, _)| k == slot).map(|v| v.1))
            .collect();
        if let Some(args) = args {
            let rank = Relation::ALL
                .iter()
                .position(|q| *q == r)
                .unwrap_or(usize::MAX);
            self.facts.push((rank, Fact::new(&spec.predicate, &args)));
        }
    }

    /// Whether body `i` is a block or the hook that is neither held nor lost.
    fn free(&self, i: usize) -> bool {
        let b = &self.world.bodies[i];
        b.is_movable() && !b.lost && !self.held.contains(&Some(i))
    }

    /// `on_block`, `on_table`, `on_shelf` and `in_region` of every free body.
    fn support_facts(&mut self) {
        let world = self.world;
        for (i, b) in world.bodies.iter().enumerate() {
            if !self.free(i) {
                continue;
            }
            let Some(s) = self.support[i] else { continue };
            let sk = world.bodies[s].kind;
            let body = (Slot::Body, b.name.as_str());
            match (b.kind, sk) {
                (BodyKind::Block, BodyKind::Block) => self.push(
                    Relation::OnBlock,
                    &[body, (Slot::Below, world.bodies[s].name.as_str())],
                ),
                (BodyKind::Block | BodyKind::Hook, BodyKind::Table) => {
                    self.push(Relation::OnTable, &[body])
                }
                (BodyKind::Block, BodyKind::Shelf) => self.push(Relation::OnShelf, &[body]),
                _ => {}
            }
            if b.kind == BodyKind::Block
                && self.want(Relation::InRegion)
                && matches!(sk, BodyKind::Table | BodyKind::Block)
            {
                let c = b.pose.translation.vector;
                for r in &world.regions {
                    if r.contains(c.x, c.y) {
                        self.push(Relation::InRegion, &[body, (Slot::Region, r.name.as_str())]);
                    }
                }
            }
        }
    }

    /// `clear` of every free block nothing rests on.
    fn clear_facts(&mut self) {
        if !self.want(Relation::Clear) {
            return;
        }
        for (i, b) in self.world.bodies.iter().enumerate() {
            if b.kind == BodyKind::Block && self.free(i) && !self.support.contains(&Some(i)) {
                self.push(Relation::Clear, &[(Slot::Body, b.name.as_str())]);
            }
        }
    }

    /// `held`, `hand_empty` and `in_reach` of arm `ai`.
    fn arm_facts(&mut self, ai: usize) {
        let world = self.world;
        let a = &world.arms[ai];
        let arm = (Slot::Arm, a.name.as_str());
        match self.held[ai] {
            Some(i) => self.push(
                Relation::Held,
                &[arm, (Slot::Body, world.bodies[i].name.as_str())],
            ),
            None => self.push(Relation::HandEmpty, &[arm]),
        }
        if !self.want(Relation::InReach) {
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
                self.push(Relation::InReach, &[arm, (Slot::Body, b.name.as_str())]);
            }
        }
    }

    /// The type predicates of the declared object kinds (`(block a)`).
    fn type_facts(&mut self) {
        let world = self.world;
        for kind in ObjectKind::ALL {
            let Some(p) = world
                .motions
                .objects
                .get(&kind)
                .and_then(|o| o.predicate.clone())
            else {
                continue;
            };
            for name in names_of(world, kind) {
                self.facts
                    .push((Relation::ALL.len(), Fact::new(&p, &[&name])));
            }
        }
    }

    /// The facts sorted (relation order, type predicates last, then arguments), without
    /// repeats.
    fn into_sorted(self) -> Vec<Fact> {
        let mut facts = self.facts;
        facts.sort_by(|x, y| {
            x.0.cmp(&y.0)
                .then_with(|| x.1.predicate.cmp(&y.1.predicate))
                .then_with(|| x.1.args.cmp(&y.1.args))
        });
        let mut out: Vec<Fact> = facts.into_iter().map(|(_, f)| f).collect();
        out.dedup();
        out
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
