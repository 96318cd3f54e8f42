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

use std::collections::VecDeque;
use std::hash::{BuildHasherDefault, Hasher};

use crate::pddl::{Atom, CostAmount, Domain, Formula, PddlError, Problem, Term};

use super::task::{Condition, FactId, Goal, Operator, State, Task};

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

/// A small multiplicative hasher (the grounder hashes millions of short integer tuples; SipHash's
/// DoS resistance is not needed for them).
#[derive(Default, Clone, Copy)]
struct FastHasher(u64);

impl FastHasher {
    #[inline]
    fn add(&mut self, w: u64) {
        self.0 = (self.0.rotate_left(5) ^ w).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
}

impl Hasher for FastHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut w = [0u8; 8];
            w[..chunk.len()].copy_from_slice(chunk);
            self.add(u64::from_le_bytes(w));
        }
    }
    fn write_u32(&mut self, i: u32) {
        self.add(u64::from(i));
    }
    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }
    fn finish(&self) -> u64 {
        self.0
    }
}

type HashMap<K, V> = std::collections::HashMap<K, V, BuildHasherDefault<FastHasher>>;
type HashSet<K> = std::collections::HashSet<K, BuildHasherDefault<FastHasher>>;

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

struct Objects {
    names: Vec<String>,
    index: HashMap<String, Obj>,
    /// `is_a[o][t]`: object `o` is of type `t` (or a subtype).
    is_a: Vec<Vec<bool>>,
    /// Objects of each type, in declaration order.
    of_type: Vec<Vec<Obj>>,
}

fn objects(domain: &Domain, problem: &Problem) -> Objects {
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

fn arg(objs: &Objects, t: &Term) -> Arg {
    match t {
        Term::Var(i, _) => Arg::Var(*i),
        // The parser checked every constant against the domain's and problem's objects.
        Term::Const(n) => Arg::Obj(objs.index.get(&n.text).copied().unwrap_or(Obj::MAX)),
    }
}

fn lit(objs: &Objects, a: &Atom) -> Lit {
    Lit {
        pred: a.predicate,
        args: a.args.iter().map(|t| arg(objs, t)).collect(),
    }
}

/// Disjunctive normal form of `f` (negated when `neg`), or `None` beyond [`MAX_DISJUNCTS`].
fn dnf(objs: &Objects, f: &Formula, neg: bool) -> Option<Vec<Vec<Literal>>> {
    Some(match f {
        Formula::Atom(a) => {
            let l = lit(objs, a);
            vec![vec![if neg {
                Literal::Neg(l)
            } else {
                Literal::Pos(l)
            }]]
        }
        Formula::Eq(a, b, _) => {
            let (a, b) = (arg(objs, a), arg(objs, b));
            vec![vec![if neg {
                Literal::Neq(a, b)
            } else {
                Literal::Eq(a, b)
            }]]
        }
        Formula::Not(g, _) => dnf(objs, g, !neg)?,
        Formula::And(parts, _) | Formula::Or(parts, _) => {
            let conj = matches!(f, Formula::And(..)) != neg;
            if conj {
                let mut acc: Vec<Vec<Literal>> = vec![Vec::new()];
                for p in parts {
                    let d = dnf(objs, p, neg)?;
                    if acc.len().saturating_mul(d.len()) > MAX_DISJUNCTS {
                        return None;
                    }
                    let mut next = Vec::with_capacity(acc.len() * d.len());
                    for a in &acc {
                        for b in &d {
                            next.push(a.iter().chain(b).cloned().collect());
                        }
                    }
                    if next.len() > MAX_DISJUNCTS {
                        return None;
                    }
                    acc = next;
                }
                acc
            } else {
                let mut acc = Vec::new();
                for p in parts {
                    acc.extend(dnf(objs, p, neg)?);
                    if acc.len() > MAX_DISJUNCTS {
                        return None;
                    }
                }
                acc
            }
        }
    })
}

/// Facts reached so far, indexed for joins.
struct FactIndex {
    /// Per predicate: the argument tuples.
    facts: Vec<Vec<Vec<Obj>>>,
    /// Per predicate, per position, per object: indices into `facts[p]`.
    by_arg: Vec<Vec<Vec<Vec<u32>>>>,
}

impl FactIndex {
    fn new(domain: &Domain, nobj: usize) -> Self {
        FactIndex {
            facts: vec![Vec::new(); domain.predicates.len()],
            by_arg: domain
                .predicates
                .iter()
                .map(|p| vec![vec![Vec::new(); nobj]; p.params.len()])
                .collect(),
        }
    }

    fn insert(&mut self, pred: usize, args: &[Obj]) {
        let k = self.facts[pred].len() as u32;
        for (i, &o) in args.iter().enumerate() {
            self.by_arg[pred][i][o as usize].push(k);
        }
        self.facts[pred].push(args.to_vec());
    }
}

const UNBOUND: Obj = Obj::MAX;

fn value(a: Arg, b: &[Obj]) -> Obj {
    match a {
        Arg::Var(v) => b[v],
        Arg::Obj(o) => o,
    }
}

struct Grounder<'a> {
    schemas: &'a [Schema],
    params_ty: &'a [Vec<usize>],
    objs: &'a Objects,
    index: &'a FactIndex,
    statics: &'a HashSet<GAtom>,
    fluent_pred: &'a [bool],
}

impl Grounder<'_> {
    /// Every binding of schema `s` that extends `b` (atoms in `matched` already hold).
    fn join(&self, s: usize, matched: &mut [bool], b: &mut Vec<Obj>, out: &mut Vec<Vec<Obj>>) {
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
    fn unify(&self, s: usize, l: &Lit, f: &[Obj], b: &mut [Obj], newly: &mut Vec<usize>) -> bool {
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

/// Grounds a parsed problem into a [`Task`] (see the module header for the semantics).
pub fn ground(domain: &Domain, problem: &Problem) -> Result<Task, GroundError> {
    let objs = objects(domain, problem);
    let nobj = objs.names.len();
    let too_large = |what: String| GroundError::TooLarge(problem.file().to_string(), what);

    // Schemas: one per DNF disjunct of each action's precondition.
    let mut fluent_pred = vec![false; domain.predicates.len()];
    for a in &domain.actions {
        for at in a.effect.add.iter().chain(&a.effect.del) {
            fluent_pred[at.predicate] = true;
        }
    }
    let mut schemas = Vec::new();
    let mut params_ty = Vec::new();
    for (ai, a) in domain.actions.iter().enumerate() {
        let Some(d) = dnf(&objs, &a.precondition, false) else {
            return Err(too_large(format!(
                "the precondition of `{}` has more than {MAX_DISJUNCTS} disjuncts",
                a.name.text
            )));
        };
        for conj in d {
            let mut sch = Schema {
                action: ai,
                pos: Vec::new(),
                neg: Vec::new(),
                eq: Vec::new(),
                neq: Vec::new(),
            };
            for l in conj {
                match l {
                    Literal::Pos(l) => {
                        if !sch.pos.contains(&l) {
                            sch.pos.push(l)
                        }
                    }
                    Literal::Neg(l) => sch.neg.push(l),
                    Literal::Eq(x, y) => sch.eq.push((x, y)),
                    Literal::Neq(x, y) => sch.neq.push((x, y)),
                }
            }
            schemas.push(sch);
            params_ty.push(a.params.iter().map(|p| p.ty).collect::<Vec<_>>());
        }
    }

    // Initial facts: static ones preloaded into the index, fluent ones queued.
    let mut statics: HashSet<GAtom> = HashSet::default();
    let mut index = FactIndex::new(domain, nobj);
    let mut fact_ids: HashMap<GAtom, u32> = HashMap::default();
    let mut fact_list: Vec<GAtom> = Vec::new();
    let mut queue: VecDeque<u32> = VecDeque::new();
    let mut init_fluent: Vec<u32> = Vec::new();
    for a in &problem.init {
        let g: GAtom = (
            a.predicate,
            a.args.iter().map(|t| value(arg(&objs, t), &[])).collect(),
        );
        if fluent_pred[a.predicate] {
            if !fact_ids.contains_key(&g) {
                let id = fact_list.len() as u32;
                fact_ids.insert(g.clone(), id);
                fact_list.push(g);
                queue.push_back(id);
                init_fluent.push(id);
            }
        } else if statics.insert(g.clone()) {
            index.insert(g.0, &g.1);
        }
    }

    // Trigger lists: (schema, positive atom) per fluent predicate.
    let mut triggers: Vec<Vec<(usize, usize)>> = vec![Vec::new(); domain.predicates.len()];
    let mut untriggered = Vec::new();
    for (s, sch) in schemas.iter().enumerate() {
        let mut any = false;
        for (i, l) in sch.pos.iter().enumerate() {
            if fluent_pred[l.pred] {
                triggers[l.pred].push((s, i));
                any = true;
            }
        }
        if !any {
            untriggered.push(s);
        }
    }

    let mut found: Vec<(usize, Vec<Obj>)> = Vec::new();
    let mut seen: HashSet<(usize, Vec<Obj>)> = HashSet::default();
    let emit = |s: usize,
                bindings: Vec<Vec<Obj>>,
                found: &mut Vec<(usize, Vec<Obj>)>,
                seen: &mut HashSet<(usize, Vec<Obj>)>,
                fact_ids: &mut HashMap<GAtom, u32>,
                fact_list: &mut Vec<GAtom>,
                queue: &mut VecDeque<u32>|
     -> Result<(), GroundError> {
        for b in bindings {
            if !seen.insert((s, b.clone())) {
                continue;
            }
            for at in &domain.actions[schemas[s].action].effect.add {
                let g: GAtom = (
                    at.predicate,
                    at.args.iter().map(|t| value(arg(&objs, t), &b)).collect(),
                );
                if !fact_ids.contains_key(&g) {
                    let id = fact_list.len() as u32;
                    fact_ids.insert(g.clone(), id);
                    fact_list.push(g);
                    queue.push_back(id);
                }
            }
            found.push((s, b));
            if found.len() > MAX_OPERATORS {
                return Err(too_large(format!("more than {MAX_OPERATORS} operators")));
            }
        }
        Ok(())
    };

    for &s in &untriggered {
        let g = Grounder {
            schemas: &schemas,
            params_ty: &params_ty,
            objs: &objs,
            index: &index,
            statics: &statics,
            fluent_pred: &fluent_pred,
        };
        let mut out = Vec::new();
        let mut b = vec![UNBOUND; params_ty[s].len()];
        let mut matched = vec![false; schemas[s].pos.len()];
        g.join(s, &mut matched, &mut b, &mut out);
        emit(
            s,
            out,
            &mut found,
            &mut seen,
            &mut fact_ids,
            &mut fact_list,
            &mut queue,
        )?;
    }
    while let Some(f) = queue.pop_front() {
        let (pred, args) = fact_list[f as usize].clone();
        index.insert(pred, &args);
        for &(s, i) in &triggers[pred] {
            let g = Grounder {
                schemas: &schemas,
                params_ty: &params_ty,
                objs: &objs,
                index: &index,
                statics: &statics,
                fluent_pred: &fluent_pred,
            };
            let mut out = Vec::new();
            let mut b = vec![UNBOUND; params_ty[s].len()];
            let mut matched = vec![false; schemas[s].pos.len()];
            let mut newly = Vec::new();
            if g.unify(s, &schemas[s].pos[i], &args, &mut b, &mut newly) {
                matched[i] = true;
                g.join(s, &mut matched, &mut b, &mut out);
            }
            emit(
                s,
                out,
                &mut found,
                &mut seen,
                &mut fact_ids,
                &mut fact_list,
                &mut queue,
            )?;
        }
    }

    build_task(
        domain,
        problem,
        &objs,
        &schemas,
        found,
        &fact_ids,
        &fact_list,
        &statics,
        &fluent_pred,
        &init_fluent,
    )
}

/// Ground atom printed in IPC form: `(on a b)`.
fn atom_name(domain: &Domain, objs: &Objects, g: &GAtom) -> String {
    let mut s = format!("({}", domain.predicates[g.0].name.text);
    for &o in &g.1 {
        s.push(' ');
        s.push_str(&objs.names[o as usize]);
    }
    s.push(')');
    s
}

fn ground_lit(l: &Lit, b: &[Obj]) -> GAtom {
    (l.pred, l.args.iter().map(|&a| value(a, b)).collect())
}

/// Truth of a ground literal's atom: fluent fact id, or a constant truth value.
enum Truth {
    Fluent(FactId),
    Const(bool),
}

#[allow(clippy::too_many_arguments)]
fn build_task(
    domain: &Domain,
    problem: &Problem,
    objs: &Objects,
    schemas: &[Schema],
    mut found: Vec<(usize, Vec<Obj>)>,
    fact_ids: &HashMap<GAtom, u32>,
    fact_list: &[GAtom],
    statics: &HashSet<GAtom>,
    fluent_pred: &[bool],
    init_fluent: &[u32],
) -> Result<Task, GroundError> {
    let uses_costs = problem.minimize_total_cost;
    let values: HashMap<(usize, Vec<Obj>), u64> = problem
        .function_values
        .iter()
        .map(|v| {
            let args = v
                .args
                .iter()
                .map(|n| objs.index.get(&n.text).copied().unwrap_or(Obj::MAX))
                .collect();
            ((v.function, args), v.value)
        })
        .collect();
    found.sort_by(|(s1, b1), (s2, b2)| {
        (schemas[*s1].action, b1, *s1).cmp(&(schemas[*s2].action, b2, *s2))
    });

    struct Raw {
        action: usize,
        binding: Vec<Obj>,
        pre: Vec<u32>,
        neg: Vec<u32>,
        add: Vec<u32>,
        del: Vec<u32>,
        cost: u32,
    }
    let mut raws = Vec::with_capacity(found.len());
    let mut touched = vec![false; fact_list.len()];
    for (s, b) in found {
        let sch = &schemas[s];
        let act = &domain.actions[sch.action];
        let id = |l: &Lit| fact_ids.get(&ground_lit(l, &b)).copied();
        let pre: Vec<u32> = sch
            .pos
            .iter()
            .filter(|l| fluent_pred[l.pred])
            .filter_map(id)
            .collect();
        let neg: Vec<u32> = sch
            .neg
            .iter()
            .filter(|l| fluent_pred[l.pred])
            .filter_map(id)
            .collect();
        let add: Vec<u32> = act
            .effect
            .add
            .iter()
            .filter_map(|a| id(&lit(objs, a)))
            .collect();
        let del: Vec<u32> = act
            .effect
            .del
            .iter()
            .filter_map(|a| id(&lit(objs, a)))
            .collect();
        for &f in add.iter().chain(&del) {
            touched[f as usize] = true;
        }
        let cost = if uses_costs {
            let mut total: u64 = 0;
            for inc in &act.effect.cost {
                let v = match &inc.amount {
                    CostAmount::Constant(c) => *c,
                    CostAmount::Function { function, args } => {
                        let key: Vec<Obj> = args.iter().map(|t| value(arg(objs, t), &b)).collect();
                        match values.get(&(*function, key.clone())) {
                            Some(v) => *v,
                            None => {
                                let term = atom_name_fn(domain, objs, *function, &key);
                                return Err(GroundError::Located(domain.error_at(
                                    inc.span,
                                    format!(
                                        "no value for `{term}` in the `:init` of {} (needed by `{}`)",
                                        problem.file(),
                                        op_name(domain, objs, sch.action, &b)
                                    ),
                                )));
                            }
                        }
                    }
                };
                total = total.saturating_add(v);
            }
            u32::try_from(total).map_err(|_| {
                GroundError::Located(domain.error_at(
                    act.span,
                    format!(
                        "cost {total} of `{}` exceeds {}",
                        op_name(domain, objs, sch.action, &b),
                        u32::MAX
                    ),
                ))
            })?
        } else {
            1
        };
        raws.push(Raw {
            action: sch.action,
            binding: b,
            pre,
            neg,
            add,
            del,
            cost,
        });
    }

    // Fluent facts: those some operator adds or deletes, in (predicate, arguments) order.
    let mut fluent: Vec<u32> = (0..fact_list.len() as u32)
        .filter(|&f| touched[f as usize])
        .collect();
    fluent.sort_by(|&a, &b| fact_list[a as usize].cmp(&fact_list[b as usize]));
    let mut new_id = vec![u32::MAX; fact_list.len()];
    for (i, &f) in fluent.iter().enumerate() {
        new_id[f as usize] = i as FactId;
    }
    let facts: Vec<String> = fluent
        .iter()
        .map(|&f| atom_name(domain, objs, &fact_list[f as usize]))
        .collect();
    let nf = facts.len();
    // Reached but untouched facts are initial facts that never change: true forever.
    let mut static_atoms: Vec<&GAtom> = statics.iter().collect();
    static_atoms.extend(
        (0..fact_list.len())
            .filter(|&f| !touched[f])
            .map(|f| &fact_list[f]),
    );
    static_atoms.sort();
    static_atoms.dedup();
    let static_facts = static_atoms
        .iter()
        .map(|g| atom_name(domain, objs, g))
        .collect();

    let mut operators: Vec<Operator> = Vec::with_capacity(raws.len());
    let mut group_start = 0;
    let mut last_key: Option<(usize, Vec<Obj>)> = None;
    'ops: for r in raws {
        let mut pre = Vec::with_capacity(r.pre.len());
        for f in r.pre {
            if touched[f as usize] {
                pre.push(new_id[f as usize]);
            }
        }
        let mut pre_neg = Vec::with_capacity(r.neg.len());
        for f in r.neg {
            if touched[f as usize] {
                pre_neg.push(new_id[f as usize]);
            } else {
                continue 'ops; // an initial fact that never changes: never applicable
            }
        }
        let mut add: Vec<FactId> = r.add.iter().map(|&f| new_id[f as usize]).collect();
        let mut del: Vec<FactId> = r.del.iter().map(|&f| new_id[f as usize]).collect();
        for v in [&mut pre, &mut pre_neg, &mut add, &mut del] {
            v.sort_unstable();
            v.dedup();
        }
        if pre.iter().any(|f| pre_neg.binary_search(f).is_ok()) {
            continue;
        }
        del.retain(|f| add.binary_search(f).is_err());
        let op = Operator {
            name: op_name(domain, objs, r.action, &r.binding),
            pre,
            pre_neg,
            add,
            del,
            cost: r.cost,
        };
        let key = (r.action, r.binding);
        if last_key.as_ref() != Some(&key) {
            group_start = operators.len();
            last_key = Some(key);
        } else if operators[group_start..].contains(&op) {
            continue;
        }
        operators.push(op);
    }

    let truth = |g: GAtom| -> Truth {
        let pred = g.0;
        if fluent_pred[pred] {
            match fact_ids.get(&g) {
                Some(&f) if touched[f as usize] => Truth::Fluent(new_id[f as usize]),
                Some(_) => Truth::Const(true),
                None => Truth::Const(false),
            }
        } else {
            Truth::Const(statics.contains(&g))
        }
    };
    let Some(goal_dnf) = dnf(objs, &problem.goal, false) else {
        return Err(GroundError::TooLarge(
            problem.file().to_string(),
            format!("the goal has more than {MAX_DISJUNCTS} disjuncts"),
        ));
    };
    let mut alternatives: Vec<Condition> = Vec::new();
    'alts: for conj in goal_dnf {
        let mut c = Condition::default();
        for l in conj {
            match l {
                Literal::Pos(l) => match truth(ground_lit(&l, &[])) {
                    Truth::Fluent(f) => c.pos.push(f),
                    Truth::Const(true) => {}
                    Truth::Const(false) => continue 'alts,
                },
                Literal::Neg(l) => match truth(ground_lit(&l, &[])) {
                    Truth::Fluent(f) => c.neg.push(f),
                    Truth::Const(false) => {}
                    Truth::Const(true) => continue 'alts,
                },
                Literal::Eq(x, y) => {
                    if value(x, &[]) != value(y, &[]) {
                        continue 'alts;
                    }
                }
                Literal::Neq(x, y) => {
                    if value(x, &[]) == value(y, &[]) {
                        continue 'alts;
                    }
                }
            }
        }
        c.pos.sort_unstable();
        c.pos.dedup();
        c.neg.sort_unstable();
        c.neg.dedup();
        if c.pos.iter().any(|f| c.neg.binary_search(f).is_ok()) {
            continue;
        }
        if !alternatives.contains(&c) {
            alternatives.push(c);
        }
    }

    let init = State::from_facts(
        nf,
        init_fluent
            .iter()
            .filter(|&&f| touched[f as usize])
            .map(|&f| new_id[f as usize]),
    );
    Ok(Task::new(
        facts,
        operators,
        init,
        Goal {
            alternatives,
            terminal_cost: 0,
        },
        static_facts,
        uses_costs,
    ))
}

fn op_name(domain: &Domain, objs: &Objects, action: usize, b: &[Obj]) -> String {
    let mut s = format!("({}", domain.actions[action].name.text);
    for &o in b {
        s.push(' ');
        s.push_str(&objs.names[o as usize]);
    }
    s.push(')');
    s
}

fn atom_name_fn(domain: &Domain, objs: &Objects, f: usize, args: &[Obj]) -> String {
    let mut s = format!("({}", domain.functions[f].name.text);
    for &o in args {
        s.push(' ');
        s.push_str(objs.names.get(o as usize).map_or("?", |n| n.as_str()));
    }
    s.push(')');
    s
}
