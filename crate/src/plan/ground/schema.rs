//! The grounder's shared vocabulary: lifted literals and schemas, limits and the error.

use crate::pddl::PddlError;

/// Most DNF disjuncts accepted for one precondition or goal.
pub(super) const MAX_DISJUNCTS: usize = 4096;
/// Most ground operators accepted before grounding gives up.
pub(super) const MAX_OPERATORS: usize = 5_000_000;

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

pub(super) type Obj = u32;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Arg {
    Var(usize),
    Obj(Obj),
}

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(super) struct Lit {
    pub(super) pred: usize,
    pub(super) args: Vec<Arg>,
}

/// A literal of a DNF conjunction.
#[derive(Clone, Debug)]
pub(super) enum Literal {
    Pos(Lit),
    Neg(Lit),
    Eq(Arg, Arg),
    Neq(Arg, Arg),
}

/// One disjunct of one action's precondition.
pub(super) struct Schema {
    pub(super) action: usize,
    pub(super) pos: Vec<Lit>,
    pub(super) neg: Vec<Lit>,
    pub(super) eq: Vec<(Arg, Arg)>,
    pub(super) neq: Vec<(Arg, Arg)>,
}

/// A ground atom: predicate and object arguments.
pub(super) type GAtom = (usize, Vec<Obj>);

/// An argument with no object bound yet.
pub(super) const UNBOUND: Obj = Obj::MAX;

/// The object `a` stands for under the binding `b` ([`UNBOUND`] if its variable is unbound).
pub(super) fn value(a: Arg, b: &[Obj]) -> Obj {
    match a {
        Arg::Var(v) => b[v],
        Arg::Obj(o) => o,
    }
}
