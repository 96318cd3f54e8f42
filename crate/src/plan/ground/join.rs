//! The joins of the grounder: the index of the facts reached so far, and the search for every
//! binding of a schema's parameters that matches its positive atoms against the index (the atom
//! with the fewest candidates first) and satisfies its `=`, `≠` and static negative literals.

use crate::pddl::Domain;

use super::hash::HashSet;
use super::objects::Objects;
use super::schema::{value, Arg, GAtom, Lit, Obj, Schema, MAX_OPERATORS, UNBOUND};

/// Facts reached so far, indexed for joins.
pub(super) struct FactIndex {
    /// Per predicate: the argument tuples.
    facts: Vec<Vec<Vec<Obj>>>,
    /// Per predicate, per position, per object: indices into `facts[p]`.
    by_arg: Vec<Vec<Vec<Vec<u32>>>>,
}

impl FactIndex {
    /// An empty index.
    pub(super) fn new(domain: &Domain, nobj: usize) -> Self {
        FactIndex {
            facts: vec![Vec::new(); domain.predicates.len()],
            by_arg: domain
                .predicates
                .iter()
                .map(|p| vec![vec![Vec::new(); nobj]; p.params.len()])
                .collect(),
        }
    }

    /// Adds a fact.
    pub(super) fn insert(&mut self, pred: usize, args: &[Obj]) {
        let k = self.facts[pred].len() as u32;
        for (i, &o) in args.iter().enumerate() {
            self.by_arg[pred][i][o as usize].push(k);
        }
        self.facts[pred].push(args.to_vec());
    }
}

/// The joins of one round of the fixpoint, over the facts indexed so far.
pub(super) struct Grounder<'a> {
    pub(super) schemas: &'a [Schema],
    /// Per schema, the type of each parameter.
    pub(super) params_ty: &'a [Vec<usize>],
    pub(super) objs: &'a Objects,
    pub(super) index: &'a FactIndex,
    /// The initial facts of static predicates.
    pub(super) statics: &'a HashSet<GAtom>,
    /// Per predicate: whether it is fluent.
    pub(super) fluent_pred: &'a [bool],
}

impl Grounder<'_> {
    /// Every binding of schema `s` that extends `b` (atoms in `matched` already hold).
    pub(super) fn join(
        &self,
        s: usize,
        matched: &mut [bool],
        b: &mut Vec<Obj>,
        out: &mut Vec<Vec<Obj>>,
    ) {
        let sch = &self.schemas[s];
        if !self.constraints_ok(sch, b, false) {
            return;
        }
        // Next atom: the one with the fewest candidates.
        // (atom, candidate count, indexed (position, object) if any argument is bound)
        type Choice = (usize, usize, Option<(usize, Obj)>);
        let mut best: Option<Choice> = None;
        for (i, l) in sch.pos.iter().enumerate() {
            if matched[i] {
                continue;
            }
            let mut count = self.index.facts[l.pred].len();
            let mut key = None;
            for (pos, a) in l.args.iter().enumerate() {
                let o = value(*a, b);
                if o != UNBOUND {
                    let n = self.index.by_arg[l.pred][pos]
                        .get(o as usize)
                        .map_or(0, |v| v.len());
                    if key.is_none() || n < count {
                        count = n;
                        key = Some((pos, o));
                    }
                }
            }
            if best.is_none_or(|(_, c, _)| count < c) {
                best = Some((i, count, key));
            }
        }
        let Some((i, _, key)) = best else {
            self.free_vars(s, 0, b, out);
            return;
        };
        let l = &sch.pos[i];
        let facts = &self.index.facts[l.pred];
        let list: &[u32] = match key {
            Some((pos, o)) => self.index.by_arg[l.pred][pos]
                .get(o as usize)
                .map_or(&[], |v| v.as_slice()),
            None => &[],
        };
        let n = if key.is_some() {
            list.len()
        } else {
            facts.len()
        };
        matched[i] = true;
        let mut newly = Vec::new();
        for k in 0..n {
            let c = list.get(k).copied().unwrap_or(k as u32);
            let f = &facts[c as usize];
            if self.unify(s, l, f, b, &mut newly) {
                self.join(s, matched, b, out);
            }
            for v in newly.drain(..) {
                b[v] = UNBOUND;
            }
        }
        matched[i] = false;
    }

    /// Binds `l`'s variables to `f`; records what it bound in `newly` (undone by the caller).
    pub(super) fn unify(
        &self,
        s: usize,
        l: &Lit,
        f: &[Obj],
        b: &mut [Obj],
        newly: &mut Vec<usize>,
    ) -> bool {
        for (a, &o) in l.args.iter().zip(f) {
            match *a {
                Arg::Obj(c) => {
                    if c != o {
                        return false;
                    }
                }
                Arg::Var(v) => {
                    if b[v] == UNBOUND {
                        if !self.objs.is_a[o as usize][self.params_ty[s][v]] {
                            return false;
                        }
                        b[v] = o;
                        newly.push(v);
                    } else if b[v] != o {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// Checks `=`, `≠` and static negative literals whose arguments are bound (all when `full`).
    fn constraints_ok(&self, sch: &Schema, b: &[Obj], full: bool) -> bool {
        let bound = |a: Arg| value(a, b) != UNBOUND;
        for &(x, y) in &sch.eq {
            if bound(x) && bound(y) && value(x, b) != value(y, b) {
                return false;
            }
        }
        for &(x, y) in &sch.neq {
            if bound(x) && bound(y) && value(x, b) == value(y, b) {
                return false;
            }
        }
        if full {
            for l in &sch.neg {
                if !self.fluent_pred[l.pred] {
                    let g = (l.pred, l.args.iter().map(|&a| value(a, b)).collect());
                    if self.statics.contains(&g) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// Enumerates parameters not bound by atoms, by type.
    fn free_vars(&self, s: usize, from: usize, b: &mut Vec<Obj>, out: &mut Vec<Vec<Obj>>) {
        if out.len() > MAX_OPERATORS {
            return; // the caller reports the task as too large
        }
        let Some(v) = (from..b.len()).find(|&v| b[v] == UNBOUND) else {
            if self.constraints_ok(&self.schemas[s], b, true) {
                out.push(b.clone());
            }
            return;
        };
        for &o in &self.objs.of_type[self.params_ty[s][v]] {
            b[v] = o;
            if self.constraints_ok(&self.schemas[s], b, false) {
                self.free_vars(s, v + 1, b, out);
            }
        }
        b[v] = UNBOUND;
    }
}
