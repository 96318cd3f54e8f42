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
mod schema;

use crate::pddl::{Domain, Problem};

use super::task::Task;

pub use schema::GroundError;

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
