//! What a domain's actions do physically and how its predicates read the scene
//! (`domains/*/motions.json`), so the simulator, executor, streams, recorder and skills work on
//! a domain with any names.
//!
//! # Format
//!
//! ```json
//! {
//!   "objects": { "arm": { "type": "arm" }, "block": { "type": "block" } },
//!   "facts": {
//!     "on_block": { "predicate": "on", "args": ["body", "below"] },
//!     "on_table": "ontable",
//!     "clear": "clear",
//!     "held": { "predicate": "holding", "args": ["arm", "body"] },
//!     "hand_empty": "handempty"
//!   },
//!   "actions": {
//!     "pick":  { "motion": "grasp", "object": "?x", "arm": "?r" },
//!     "stack": { "motion": "release", "object": "?x", "arm": "?r", "onto": "?y" },
//!     "place": { "motion": "release", "object": "?x", "arm": "?r", "onto": "table" }
//!   }
//! }
//! ```
//!
//! * `objects`: for each kind of scene object (`arm`, `block`, `hook`, `region`) the PDDL
//!   `type` it is declared with and/or a unary type `predicate` the scene graph writes for it
//!   (untyped domains: `(block a)`). Kinds left out are not PDDL objects of the domain.
//! * `facts`: for each relation the scene graph can see, the domain predicate that states it and
//!   its argument order (a bare string keeps the default order). Relations and their arguments:
//!   `on_block` (body, below), `on_table` (body), `on_shelf` (body), `clear` (body), `held`
//!   (arm, body), `hand_empty` (arm), `in_reach` (arm, body), `in_region` (body, region). `arm`
//!   may be left out in one-arm scenes. Relations left out are not reported.
//! * `actions`: every action schema of the domain, with its `motion`: `grasp` the `object`;
//!   `release` the `object` `onto` a parameter (a block or a region) or onto `table` / `shelf`;
//!   `pull` the `object` into reach with the held `tool`; or `none` (no physical effect). `arm`
//!   names the parameter of the arm that moves (left out in one-arm domains).
//!
//! A file naming a missing action, predicate, type or parameter is refused with its line; a
//! domain action without a declared motion is refused before any episode starts.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::pddl::Domain;

/// A relation of the scene the scene graph can report (the keys of `facts`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Relation {
    /// A free block rests on a block.
    OnBlock,
    /// A free block or tool rests on a table.
    OnTable,
    /// A free block rests on a shelf.
    OnShelf,
    /// A free block with nothing on it.
    Clear,
    /// An arm holds a body.
    Held,
    /// An arm holds nothing.
    HandEmpty,
    /// A body is inside an arm's reach annulus (or held by it).
    InReach,
    /// A free block's centre lies inside a table region.
    InRegion,
}

impl Relation {
    /// Every relation, in the order the scene graph sorts its facts.
    pub const ALL: [Relation; 8] = [
        Relation::OnBlock,
        Relation::OnTable,
        Relation::OnShelf,
        Relation::Clear,
        Relation::Held,
        Relation::HandEmpty,
        Relation::InReach,
        Relation::InRegion,
    ];

    /// The relation's arguments in their default order.
    pub fn slots(self) -> &'static [Slot] {
        use Slot::*;
        match self {
            Relation::OnBlock => &[Body, Below],
            Relation::OnTable | Relation::OnShelf | Relation::Clear => &[Body],
            Relation::Held | Relation::InReach => &[Arm, Body],
            Relation::HandEmpty => &[Arm],
            Relation::InRegion => &[Body, Region],
        }
    }

    /// The JSON key.
    pub fn key(self) -> &'static str {
        match self {
            Relation::OnBlock => "on_block",
            Relation::OnTable => "on_table",
            Relation::OnShelf => "on_shelf",
            Relation::Clear => "clear",
            Relation::Held => "held",
            Relation::HandEmpty => "hand_empty",
            Relation::InReach => "in_reach",
            Relation::InRegion => "in_region",
        }
    }
}

/// An argument of a [`Relation`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Slot {
    /// The body the relation is about.
    Body,
    /// The block under it (`on_block`).
    Below,
    /// The arm.
    Arm,
    /// The region (`in_region`).
    Region,
}

/// The predicate stating a relation and its argument order.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FactSpec {
    /// Domain predicate (lower case).
    pub predicate: String,
    /// Its arguments in PDDL order.
    pub args: Vec<Slot>,
}

impl FactSpec {
    /// The fact with these argument values, e.g. `(on a b)`; `None` if a needed slot is missing.
    pub fn render(&self, values: &[(Slot, &str)]) -> Option<String> {
        let mut s = format!("({}", self.predicate);
        for slot in &self.args {
            let v = values.iter().find(|(k, _)| k == slot)?.1;
            s.push(' ');
            s.push_str(v);
        }
        s.push(')');
        Some(s)
    }

    /// The value of `slot` in `args` (the arguments of a fact of this predicate).
    pub fn value<'a>(&self, args: &[&'a str], slot: Slot) -> Option<&'a str> {
        let i = self.args.iter().position(|s| *s == slot)?;
        args.get(i).copied()
    }
}

/// A kind of scene object.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ObjectKind {
    /// A robot arm.
    Arm,
    /// A movable block.
    Block,
    /// A tool that pulls blocks (the L-shaped hook).
    Hook,
    /// A named table region.
    Region,
}

impl ObjectKind {
    /// Every kind, in the order the scene lists its objects.
    pub const ALL: [ObjectKind; 4] = [
        ObjectKind::Arm,
        ObjectKind::Block,
        ObjectKind::Hook,
        ObjectKind::Region,
    ];
}

/// How objects of one kind appear in the domain.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ObjectSpec {
    /// PDDL type (`None`: `object`).
    #[serde(default, rename = "type", skip_serializing_if = "Option::is_none")]
    pub ty: Option<String>,
    /// Unary type predicate the scene graph writes for each such object.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub predicate: Option<String>,
}

/// What an action does with its body.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MotionKind {
    /// Grasp the object.
    Grasp,
    /// Put the held object down.
    Release,
    /// Pull the object into reach with a held tool.
    Pull,
    /// No physical effect.
    None,
}

/// Where a release puts its object.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Onto {
    /// The object bound to this parameter (a block, or a region of a table).
    Param(usize),
    /// Any table.
    Table,
    /// Any shelf.
    Shelf,
}

/// The motion of one action schema, parameters by index.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ActionMotion {
    /// What it does.
    pub motion: MotionKind,
    /// The body moved.
    pub object: Option<usize>,
    /// The arm that moves (`None`: the scene's only arm).
    pub arm: Option<usize>,
    /// Where a release puts the body.
    pub onto: Option<Onto>,
    /// The tool a pull holds.
    pub tool: Option<usize>,
}

/// A domain's declaration of what its actions do physically and how its predicates read the
/// scene (see the module documentation).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Motions {
    /// Object kinds → how they appear in the domain.
    pub objects: BTreeMap<ObjectKind, ObjectSpec>,
    /// Relations → the predicate stating them.
    pub facts: BTreeMap<Relation, FactSpec>,
    /// Action schema → its motion.
    pub actions: BTreeMap<String, ActionMotion>,
}

/// A motions file that cannot be used: where and why.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}:{column}: {path}: {message}")]
pub struct MotionsError {
    /// The file.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
    /// JSON path of the offending entry (`actions.pick.object`).
    pub path: String,
    /// What is wrong.
    pub message: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    #[serde(default)]
    objects: BTreeMap<String, ObjectSpec>,
    #[serde(default)]
    facts: BTreeMap<String, RawFact>,
    #[serde(default)]
    actions: BTreeMap<String, RawAction>,
}

/// A `facts` entry: a predicate name, or `{"predicate": …, "args": […]}`.
enum RawFact {
    Name(String),
    Spec(FactSpec),
}

/// What a `facts` entry must look like, for its errors.
const FACT_FORM: &str =
    r#"a predicate name ("on") or an object {"predicate": "on", "args": ["body", "below"]}"#;

impl<'de> Deserialize<'de> for RawFact {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let v = serde_json::Value::deserialize(d)?;
        let what = |v: &serde_json::Value| match v {
            serde_json::Value::Null => "null".to_string(),
            serde_json::Value::Bool(b) => format!("the boolean {b}"),
            serde_json::Value::Number(n) => format!("the number {n}"),
            serde_json::Value::String(s) => format!("the string {s:?}"),
            serde_json::Value::Array(_) => "an array".to_string(),
            serde_json::Value::Object(_) => "an object".to_string(),
        };
        match v {
            // A fact written as PDDL (`"(on ?b ?c)"`) is not a predicate name.
            serde_json::Value::String(s) if s.contains(['(', ' ', '?']) => Err(D::Error::custom(
                format!("expected {FACT_FORM}, got the string {s:?}"),
            )),
            serde_json::Value::String(s) => Ok(RawFact::Name(s)),
            serde_json::Value::Object(ref o) => {
                if let Some(k) = o.keys().find(|k| *k != "predicate" && *k != "args") {
                    return Err(D::Error::custom(format!(
                        "unknown field `{k}`: expected {FACT_FORM}"
                    )));
                }
                let predicate = match o.get("predicate") {
                    Some(serde_json::Value::String(p)) => p.clone(),
                    Some(x) => {
                        return Err(D::Error::custom(format!(
                            "`predicate` must be a predicate name, got {}: expected {FACT_FORM}",
                            what(x)
                        )))
                    }
                    None => {
                        return Err(D::Error::custom(format!(
                            "missing `predicate`: expected {FACT_FORM}"
                        )))
                    }
                };
                let args = match o.get("args") {
                    Some(a @ serde_json::Value::Array(_)) => {
                        serde_json::from_value::<Vec<Slot>>(a.clone()).map_err(|e| {
                            D::Error::custom(format!(
                                "`args` must list argument names (`body`, `below`, `arm`, `region`): {e}"
                            ))
                        })?
                    }
                    Some(x) => {
                        return Err(D::Error::custom(format!(
                            "`args` must be an array of argument names like [\"body\", \"below\"], got {}",
                            what(x)
                        )))
                    }
                    None => {
                        return Err(D::Error::custom(format!(
                            "missing `args`: expected {FACT_FORM}"
                        )))
                    }
                };
                Ok(RawFact::Spec(FactSpec { predicate, args }))
            }
            other => Err(D::Error::custom(format!(
                "expected {FACT_FORM}, got {}",
                what(&other)
            ))),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAction {
    motion: MotionKind,
    #[serde(default)]
    object: Option<String>,
    #[serde(default)]
    arm: Option<String>,
    #[serde(default)]
    onto: Option<String>,
    #[serde(default)]
    tool: Option<String>,
}

impl Motions {
    /// Reads a motions file and checks it against `domain` (see the module documentation).
    pub fn parse(text: &str, file: &str, domain: &Domain) -> Result<Motions, MotionsError> {
        let raw = read_raw(text).map_err(|(path, e)| {
            let full = e.to_string();
            let suffix = format!(" at line {} column {}", e.line(), e.column());
            MotionsError {
                file: file.into(),
                line: e.line().max(1),
                column: e.column().max(1),
                path: if path.is_empty() { "$".into() } else { path },
                message: full.strip_suffix(&suffix).unwrap_or(&full).to_string(),
            }
        })?;
        let at = |path: &[&str], message: String| {
            let (line, column) = locate(text, path);
            MotionsError {
                file: file.into(),
                line,
                column,
                path: path.join("."),
                message,
            }
        };
        let mut m = Motions::default();
        // Keys are read as strings, so an error inside an entry is named by its key.
        for (key, spec) in &raw.objects {
            let key = key.as_str();
            let Some(kind) = ObjectKind::ALL.into_iter().find(|k| kind_key(*k) == key) else {
                return Err(at(
                    &["objects", key],
                    format!("unknown object kind `{key}`: expected one of `arm`, `block`, `hook`, `region`"),
                ));
            };
            let spec = spec.clone();
            if let Some(t) = &spec.ty {
                if domain.type_index(t).is_none() {
                    return Err(at(
                        &["objects", key, "type"],
                        format!("the domain declares no type `{t}`"),
                    ));
                }
            }
            if let Some(p) = &spec.predicate {
                check_predicate(domain, p, 1)
                    .map_err(|msg| at(&["objects", key, "predicate"], msg))?;
            }
            m.objects.insert(kind, spec);
        }
        for (key, raw) in raw.facts {
            let Some(rel) = Relation::ALL.into_iter().find(|r| r.key() == key) else {
                let keys: Vec<&str> = Relation::ALL.iter().map(|r| r.key()).collect();
                return Err(at(
                    &["facts", &key],
                    format!(
                        "unknown relation `{key}`: expected one of {}",
                        keys.join(", ")
                    ),
                ));
            };
            let spec = match raw {
                RawFact::Name(p) => FactSpec {
                    predicate: p,
                    args: rel.slots().to_vec(),
                },
                RawFact::Spec(s) => s,
            };
            let path = ["facts", rel.key(), "args"];
            let mut want: Vec<Slot> = rel.slots().to_vec();
            let mut got = spec.args.clone();
            want.sort();
            got.sort();
            let without_arm: Vec<Slot> = want.iter().copied().filter(|s| *s != Slot::Arm).collect();
            if got != want && got != without_arm {
                return Err(at(
                    &path,
                    format!(
                        "expected the arguments {:?} in some order (`arm` may be left out), got {:?}",
                        rel.slots(),
                        spec.args
                    ),
                ));
            }
            check_predicate(domain, &spec.predicate, spec.args.len())
                .map_err(|msg| at(&["facts", rel.key()], msg))?;
            m.facts.insert(rel, spec);
        }
        for (name, a) in &raw.actions {
            let Some(schema) = domain.actions.iter().find(|s| s.name.text == *name) else {
                return Err(at(
                    &["actions", name],
                    format!("the domain has no action `{name}`"),
                ));
            };
            let param = |field: &str, v: &Option<String>| -> Result<Option<usize>, MotionsError> {
                let Some(v) = v else { return Ok(None) };
                let v = v.to_ascii_lowercase();
                schema
                    .params
                    .iter()
                    .position(|p| p.name.text == v)
                    .map(Some)
                    .ok_or_else(|| {
                        at(
                            &["actions", name, field],
                            format!("`{name}` has no parameter `{v}`"),
                        )
                    })
            };
            let need = |field: &str, v: Option<usize>| {
                v.map(Some).ok_or_else(|| {
                    at(
                        &["actions", name],
                        format!("a {:?} motion needs `{field}`", a.motion).to_lowercase(),
                    )
                })
            };
            let object = param("object", &a.object)?;
            let arm = param("arm", &a.arm)?;
            let tool = param("tool", &a.tool)?;
            let onto = match a.onto.as_deref() {
                None => None,
                Some("table") => Some(Onto::Table),
                Some("shelf") => Some(Onto::Shelf),
                Some(p) => param("onto", &Some(p.to_string()))?.map(Onto::Param),
            };
            let motion = match a.motion {
                MotionKind::None => ActionMotion {
                    motion: MotionKind::None,
                    object: None,
                    arm,
                    onto: None,
                    tool: None,
                },
                kind => ActionMotion {
                    motion: kind,
                    object: need("object", object)?,
                    arm,
                    onto: if kind == MotionKind::Release {
                        Some(onto.ok_or_else(|| {
                            at(&["actions", name], "a release needs `onto`".into())
                        })?)
                    } else {
                        None
                    },
                    tool: if kind == MotionKind::Pull {
                        need("tool", tool)?
                    } else {
                        None
                    },
                },
            };
            m.actions.insert(name.clone(), motion);
        }
        let missing: Vec<&str> = domain
            .actions
            .iter()
            .map(|a| a.name.text.as_str())
            .filter(|a| !m.actions.contains_key(*a))
            .collect();
        if !missing.is_empty() {
            return Err(at(
                &["actions"],
                format!(
                    "no motion declared for the domain's action{} {} (use {{\"motion\": \"none\"}} for an action without a physical effect)",
                    if missing.len() == 1 { "" } else { "s" },
                    missing.iter().map(|a| format!("`{a}`")).collect::<Vec<_>>().join(", ")
                ),
            ));
        }
        Ok(m)
    }

    /// Checks that a scene with `arms` arms can be read: a fact or action that leaves out its arm
    /// needs a one-arm scene.
    pub fn check_arms(&self, arms: usize) -> Result<(), String> {
        if arms == 1 {
            return Ok(());
        }
        for (rel, spec) in &self.facts {
            if rel.slots().contains(&Slot::Arm) && !spec.args.contains(&Slot::Arm) {
                return Err(format!(
                    "motions.json: facts.{} leaves out the arm, but the scene has {arms} arms",
                    rel.key()
                ));
            }
        }
        for (name, a) in &self.actions {
            if a.motion != MotionKind::None && a.arm.is_none() {
                return Err(format!(
                    "motions.json: actions.{name} names no `arm`, but the scene has {arms} arms"
                ));
            }
        }
        Ok(())
    }

    /// The predicate stating `rel`, if the domain has one.
    pub fn fact(&self, rel: Relation) -> Option<&FactSpec> {
        self.facts.get(&rel)
    }

    /// Whether the scene graph reports `rel`.
    pub fn reports(&self, rel: Relation) -> bool {
        self.facts.contains_key(&rel)
    }

    /// The relation a fact like `(on a b)` states, with its arguments (`None`: not a scene fact).
    pub fn relation_of<'a>(&self, fact: &'a str) -> Option<(Relation, &FactSpec, Vec<&'a str>)> {
        let (p, args) = crate::plan::fact_args(fact);
        self.facts
            .iter()
            .find(|(_, s)| s.predicate == p && s.args.len() == args.len())
            .map(|(r, s)| (*r, s, args))
    }

    /// Whether `fact` is a type predicate's (`(block a)`): static, never part of a
    /// demonstration's states `L_k`.
    pub fn is_type_fact(&self, fact: &str) -> bool {
        let (p, args) = crate::plan::fact_args(fact);
        args.len() == 1
            && self
                .objects
                .values()
                .any(|o| o.predicate.as_deref() == Some(p))
    }

    /// The predicates the scene graph writes (relations and type predicates).
    pub fn scene_predicates(&self) -> Vec<String> {
        let mut out: Vec<String> = self.facts.values().map(|s| s.predicate.clone()).collect();
        out.extend(self.objects.values().filter_map(|o| o.predicate.clone()));
        out.sort();
        out.dedup();
        out
    }

    /// The motion of a grounded action `(name arg …)` with its arguments, if declared.
    pub fn action<'a>(&self, action: &'a str) -> Option<(&ActionMotion, Vec<&'a str>)> {
        let (name, args) = crate::plan::fact_args(action);
        self.actions.get(name).map(|m| (m, args))
    }
}

/// The file's entries, an error with the JSON path of the value at fault (`facts.clear`; empty
/// for the document). The page's first-load module reads the embedded files without paths,
/// as `sim::parse_json` does there.
fn read_raw(text: &str) -> Result<RawFile, (String, serde_json::Error)> {
    let mut de = serde_json::Deserializer::from_str(text);
    #[cfg(not(first_load))]
    let raw = serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().to_string();
        (
            if path == "." { String::new() } else { path },
            e.into_inner(),
        )
    })?;
    #[cfg(first_load)]
    let raw = RawFile::deserialize(&mut de).map_err(|e| (String::new(), e))?;
    de.end().map_err(|e| (String::new(), e))?;
    Ok(raw)
}

/// The JSON key of an object kind (`arm`, `block`, `hook`, `region`).
fn kind_key(kind: ObjectKind) -> &'static str {
    match kind {
        ObjectKind::Arm => "arm",
        ObjectKind::Block => "block",
        ObjectKind::Hook => "hook",
        ObjectKind::Region => "region",
    }
}

fn check_predicate(domain: &Domain, p: &str, arity: usize) -> Result<(), String> {
    match domain.predicates.iter().find(|s| s.name.text == p) {
        None => Err(format!("the domain declares no predicate `{p}`")),
        Some(s) if s.params.len() != arity => Err(format!(
            "`{p}` takes {} argument{}, the declaration gives {arity}",
            s.params.len(),
            if s.params.len() == 1 { "" } else { "s" }
        )),
        Some(_) => Ok(()),
    }
}

/// Line and column of the last key of `path` found in order in `text` (1, 1 if none).
fn locate(text: &str, path: &[&str]) -> (usize, usize) {
    let mut at = 0usize;
    let mut found = None;
    for key in path {
        let needle = format!("\"{key}\"");
        if let Some(off) = text[at..].find(&needle) {
            at += off;
            found = Some(at);
            at += needle.len();
        }
    }
    let Some(pos) = found else { return (1, 1) };
    let before = &text[..pos];
    let line = before.matches('\n').count() + 1;
    let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    (line, column)
}

#[cfg(test)]
mod tests {
    use super::*;

    const DOMAIN: &str = "(define (domain d) (:requirements :strips)
      (:predicates (up ?b) (grip ?a ?b) (free ?a))
      (:action lift :parameters (?a ?b) :precondition (free ?a) :effect (grip ?a ?b))
      (:action drop :parameters (?a ?b) :precondition (grip ?a ?b) :effect (up ?b)))";

    fn parse(text: &str) -> Result<Motions, MotionsError> {
        let d = crate::pddl::parse_domain(DOMAIN, "d.pddl").unwrap();
        Motions::parse(text, "m.json", &d)
    }

    const GOOD: &str = r#"{
  "facts": { "held": "grip", "on_table": "up", "hand_empty": "free" },
  "actions": {
    "lift": { "motion": "grasp", "object": "?b", "arm": "?a" },
    "drop": { "motion": "release", "object": "?b", "arm": "?a", "onto": "table" }
  }
}"#;

    #[test]
    fn a_declaration_resolves_parameters_and_renders_facts() {
        let m = parse(GOOD).unwrap();
        let (lift, args) = m.action("(lift r1 x)").unwrap();
        assert_eq!(lift.motion, MotionKind::Grasp);
        assert_eq!((lift.object, lift.arm), (Some(1), Some(0)));
        assert_eq!(args, vec!["r1", "x"]);
        let held = m.fact(Relation::Held).unwrap();
        assert_eq!(
            held.render(&[(Slot::Body, "x"), (Slot::Arm, "r1")])
                .as_deref(),
            Some("(grip r1 x)")
        );
        assert_eq!(
            m.relation_of("(up x)").map(|r| r.0),
            Some(Relation::OnTable)
        );
        assert!(m.check_arms(2).is_ok());
    }

    #[test]
    fn a_wrong_declaration_is_refused_at_its_line() {
        let e = parse(&GOOD.replace("\"grip\"", "\"grab\"")).unwrap_err();
        assert_eq!((e.line, e.path.as_str()), (2, "facts.held"));
        assert!(e.message.contains("no predicate `grab`"), "{e}");
        let e = parse(&GOOD.replace(
            "\"object\": \"?b\", \"arm\": \"?a\" }",
            "\"object\": \"?z\" }",
        ))
        .unwrap_err();
        assert_eq!((e.line, e.path.as_str()), (4, "actions.lift.object"));
        assert!(e.message.contains("no parameter `?z`"), "{e}");
        let e = parse(&GOOD.replace(", \"onto\": \"table\"", "")).unwrap_err();
        assert_eq!((e.line, e.path.as_str()), (5, "actions.drop"));
        let e = parse(&GOOD.replace("\"hand_empty\": \"free\"", "\"hand_empty\": \"grip\""))
            .unwrap_err();
        assert!(
            e.message
                .contains("takes 2 arguments, the declaration gives 1"),
            "{e}"
        );
        let e = parse(&GOOD.replace("\"lift\"", "\"raise\"")).unwrap_err();
        assert!(e.message.contains("no action `raise`"), "{e}");
        let e = parse("{ \"facts\": { \"held\": 3 } }").unwrap_err();
        assert_eq!(e.path, "facts.held");
    }

    #[test]
    fn a_fact_of_the_wrong_form_says_what_was_expected_at_its_path() {
        let text = GOOD.replace(
            "\"held\": \"grip\"",
            "\"held\": { \"predicate\": \"grip\", \"args\": \"arm body\" }",
        );
        let e = parse(&text).unwrap_err();
        assert_eq!(
            (e.file.as_str(), e.path.as_str(), e.line),
            ("m.json", "facts.held", 2)
        );
        assert!(e.message.contains("`args` must be an array"), "{e}");
        assert!(!e.message.contains("untagged"), "{e}");
        let e = parse(&GOOD.replace("\"grip\"", "\"(grip ?a ?b)\"")).unwrap_err();
        assert_eq!(e.path, "facts.held");
        assert!(e.message.contains("got the string \"(grip ?a ?b)\""), "{e}");
        let e = parse(&GOOD.replace("\"held\": \"grip\"", "\"held\": [\"grip\"]")).unwrap_err();
        assert_eq!(e.path, "facts.held");
        assert!(
            e.message.contains(
                r#"an object {"predicate": "on", "args": ["body", "below"]}, got an array"#
            ),
            "{e}"
        );
    }

    #[test]
    fn an_undeclared_domain_action_is_reported_before_any_episode() {
        let text = GOOD.replace(
            ",\n    \"drop\": { \"motion\": \"release\", \"object\": \"?b\", \"arm\": \"?a\", \"onto\": \"table\" }",
            "",
        );
        let e = parse(&text).unwrap_err();
        assert_eq!(e.path, "actions");
        assert!(e.message.contains("`drop`"), "{e}");
    }

    #[test]
    fn leaving_out_the_arm_needs_a_one_arm_scene() {
        let text = GOOD.replace(
            "\"held\": \"grip\"",
            "\"held\": { \"predicate\": \"up\", \"args\": [\"body\"] }",
        );
        let m = parse(&text).unwrap();
        assert!(m.check_arms(1).is_ok());
        assert!(m.check_arms(2).unwrap_err().contains("facts.held"));
    }
}
