//! The object table of a grounding (constants, then the problem's objects; each one's types)
//! and the resolution of terms and atoms against it.

use crate::pddl::{Atom, Domain, Problem, Term};

use super::hash::HashMap;
use super::schema::{Arg, Lit, Obj};

/// The objects of a grounding by index, with their types.
pub(super) struct Objects {
    /// Names, by index.
    pub(super) names: Vec<String>,
    /// Index of each name.
    pub(super) index: HashMap<String, Obj>,
    /// `is_a[o][t]`: object `o` is of type `t` (or a subtype).
    pub(super) is_a: Vec<Vec<bool>>,
    /// Objects of each type, in declaration order.
    pub(super) of_type: Vec<Vec<Obj>>,
}

/// The object table of `problem` under `domain`.
pub(super) fn objects(domain: &Domain, problem: &Problem) -> Objects {
    let all: Vec<_> = domain.constants.iter().chain(&problem.objects).collect();
    let names: Vec<String> = all.iter().map(|o| o.name.text.clone()).collect();
    let index = names
        .iter()
        .enumerate()
        .map(|(i, n)| (n.clone(), i as Obj))
        .collect();
    let nt = domain.types.len();
    let is_a: Vec<Vec<bool>> = all
        .iter()
        .map(|o| (0..nt).map(|t| domain.is_subtype(o.ty, t)).collect())
        .collect();
    let of_type = (0..nt)
        .map(|t| {
            (0..all.len() as Obj)
                .filter(|&o| is_a[o as usize][t])
                .collect()
        })
        .collect();
    Objects {
        names,
        index,
        is_a,
        of_type,
    }
}

/// The argument a term stands for: a parameter, or a constant's object.
pub(super) fn arg(objs: &Objects, t: &Term) -> Arg {
    match t {
        Term::Var(i, _) => Arg::Var(*i),
        // The parser checked every constant against the domain's and problem's objects.
        Term::Const(n) => Arg::Obj(objs.index.get(&n.text).copied().unwrap_or(Obj::MAX)),
    }
}

/// The lifted literal of an atom.
pub(super) fn lit(objs: &Objects, a: &Atom) -> Lit {
    Lit {
        pred: a.predicate,
        args: a.args.iter().map(|t| arg(objs, t)).collect(),
    }
}
