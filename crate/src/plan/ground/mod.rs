//! Grounding: lifted [`Domain`] + [`Problem`] → the bitset [`Task`].
//!
//! Relaxed reachability. Let `F⁺` be the facts reachable in the delete relaxation (negative
//! preconditions ignored): `F⁺₀ = I` and `F⁺ = F⁺ ∪ add(o)` for every grounding `o` of a schema
//! whose positive preconditions `pre⁺(o) ⊆ F⁺`, whose static negative literals and `=`/`≠` hold.
//! Only such `o` are kept. The fixpoint is computed semi-naively: a fact is joined with the
//! schemas' positive atoms when it is first reached, against the facts processed before it, so
//! every grounding is found once when its last precondition fact arrives. Joins pick the atom with
//! the fewest candidates next, using a per-(predicate, position, object) index, and only
//! parameters left unbound by atoms are enumerated by type.
//!
//! Disjunctive preconditions are compiled to DNF, one schema per disjunct (same name; identical
//! groundings deduplicated). A fact is *fluent* iff some kept operator adds or deletes it; all
//! other facts are static: true ones go to [`Task::static_facts`], and static literals are folded
//! out of preconditions and goals (an operator whose static part is false is dropped; a goal
//! alternative whose static part is false is dropped — no alternative left means unsolvable).
//! Costs: `cost(o) = Σ increase amounts` with `(:metric minimize (total-cost))`, else 1.
//!
//! Files: `objects.rs` (object and type tables), `condition.rs` (DNF compilation into schemas),
//! `join.rs` (the fact index and the joins that bind a schema's parameters), `reach.rs` (the
//! relaxed-reachability fixpoint), `instantiate.rs` (ground operators, fluent facts and goal
//! alternatives of the [`Task`]), `hash.rs` (the grounder's hasher).

mod condition;
mod hash;
mod instantiate;
mod join;
mod objects;
mod reach;

use crate::pddl::{Domain, PddlError, Problem};

use super::task::Task;

/// Most DNF disjuncts accepted for one precondition or goal.
const MAX_DISJUNCTS: usize = 4096;
/// Most ground operators accepted before grounding gives up.
const MAX_OPERATORS: usize = 5_000_000;

/// Why a task could not be grounded.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum GroundError {
    /// A located problem (e.g. a cost function without a value for some arguments).
    #[error("{0}")]
    Located(PddlError),
    /// The task is too large to ground.
    #[error("{0}: grounding stopped: {1}")]
    TooLarge(String, String),
}

type Obj = u32;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Arg {
    Var(usize),
    Obj(Obj),
}

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct Lit {
    pred: usize,
    args: Vec<Arg>,
}

/// A literal of a DNF conjunction.
#[derive(Clone, Debug)]
enum Literal {
    Pos(Lit),
    Neg(Lit),
    Eq(Arg, Arg),
    Neq(Arg, Arg),
}

/// One disjunct of one action's precondition.
struct Schema {
    action: usize,
    pos: Vec<Lit>,
    neg: Vec<Lit>,
    eq: Vec<(Arg, Arg)>,
    neq: Vec<(Arg, Arg)>,
}

/// A ground atom: predicate and object arguments.
type GAtom = (usize, Vec<Obj>);

/// An argument with no object bound yet.
const UNBOUND: Obj = Obj::MAX;

/// The object `a` stands for under the binding `b` ([`UNBOUND`] if its variable is unbound).
fn value(a: Arg, b: &[Obj]) -> Obj {
    match a {
        Arg::Var(v) => b[v],
        Arg::Obj(o) => o,
    }
}

/// Grounds a parsed problem into a [`Task`] (see the module header for the semantics).
pub fn ground(domain: &Domain, problem: &Problem) -> Result<Task, GroundError> {
    let objs = objects::objects(domain, problem);
    let fluent_pred = fluent_predicates(domain);
    let schemas = condition::compile_schemas(domain, problem, &objs)?;
    let reached = reach::reach(domain, problem, &objs, &schemas, &fluent_pred)?;
    instantiate::build_task(domain, problem, &objs, &schemas.list, reached, &fluent_pred)
}

/// Per predicate: whether some action adds or deletes it (else it is static).
fn fluent_predicates(domain: &Domain) -> Vec<bool> {
    let mut fluent_pred = vec![false; domain.predicates.len()];
    for a in &domain.actions {
        for at in a.effect.add.iter().chain(&a.effect.del) {
            fluent_pred[at.predicate] = true;
        }
    }
    fluent_pred
}
