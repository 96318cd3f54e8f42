//! Instantiation: the reached groundings become the [`Task`]'s operators (fluent
//! preconditions and effects renumbered, costs from `:action-costs`, duplicates dropped), the
//! fluent facts are numbered in (predicate, arguments) order, and the goal's DNF alternatives are
//! folded over the static facts.

use crate::pddl::{CostAmount, Domain, Problem};

use super::super::task::{Condition, FactId, Goal, Operator, State, Task};
use super::condition::dnf;
use super::hash::{HashMap, HashSet};
use super::objects::{arg, lit, Objects};
use super::reach::Reached;
use super::schema::{value, GAtom, GroundError, Lit, Literal, Obj, Schema, MAX_DISJUNCTS};

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

/// The ground atom of `l` under the binding `b`.
fn ground_lit(l: &Lit, b: &[Obj]) -> GAtom {
    (l.pred, l.args.iter().map(|&a| value(a, b)).collect())
}

/// Truth of a ground literal's atom: fluent fact id, or a constant truth value.
enum Truth {
    Fluent(FactId),
    Const(bool),
}

/// A grounding with its fact lists in reached-fact ids (before the fluent renumbering).
struct Raw {
    action: usize,
    binding: Vec<Obj>,
    pre: Vec<u32>,
    neg: Vec<u32>,
    add: Vec<u32>,
    del: Vec<u32>,
    cost: u32,
}

/// The numbering of the fluent facts: the reached facts some operator adds or deletes.
struct Fluents {
    /// Per reached fact: whether some operator adds or deletes it.
    touched: Vec<bool>,
    /// Per reached fact: its fluent id (`u32::MAX` if untouched).
    new_id: Vec<u32>,
}

/// Builds the [`Task`] from what the fixpoint reached (see the module header).
pub(super) fn build_task(
    domain: &Domain,
    problem: &Problem,
    objs: &Objects,
    schemas: &[Schema],
    reached: Reached,
    fluent_pred: &[bool],
) -> Result<Task, GroundError> {
    let Reached {
        mut found,
        fact_ids,
        fact_list,
        statics,
        init_fluent,
    } = reached;
    let uses_costs = problem.minimize_total_cost;
    let values = function_values(problem, objs);
    found.sort_by(|(s1, b1), (s2, b2)| {
        (schemas[*s1].action, b1, *s1).cmp(&(schemas[*s2].action, b2, *s2))
    });
    let mut raws = Vec::with_capacity(found.len());
    let mut touched = vec![false; fact_list.len()];
    for (s, b) in found {
        let raw = raw_operator(
            domain,
            problem,
            objs,
            &schemas[s],
            b,
            &fact_ids,
            fluent_pred,
            uses_costs.then_some(&values),
        )?;
        for &f in raw.add.iter().chain(&raw.del) {
            touched[f as usize] = true;
        }
        raws.push(raw);
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
    let fluents = Fluents { touched, new_id };
    let static_facts = static_facts(domain, objs, &statics, &fact_list, &fluents);
    let operators = operators(domain, objs, raws, &fluents);
    let alternatives =
        goal_alternatives(problem, objs, &fact_ids, &statics, fluent_pred, &fluents)?;
    let init = State::from_facts(
        nf,
        init_fluent
            .iter()
            .filter(|&&f| fluents.touched[f as usize])
            .map(|&f| fluents.new_id[f as usize]),
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

/// The values of the problem's cost functions, by (function, arguments).
fn function_values(problem: &Problem, objs: &Objects) -> HashMap<(usize, Vec<Obj>), u64> {
    problem
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
        .collect()
}

/// The grounding `b` of schema `sch`: its fluent preconditions and its effects as reached-fact
/// ids, and its cost (the sum of its increases with `values`, else 1).
#[allow(clippy::too_many_arguments)]
fn raw_operator(
    domain: &Domain,
    problem: &Problem,
    objs: &Objects,
    sch: &Schema,
    b: Vec<Obj>,
    fact_ids: &HashMap<GAtom, u32>,
    fluent_pred: &[bool],
    values: Option<&HashMap<(usize, Vec<Obj>), u64>>,
) -> Result<Raw, GroundError> {
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
    let cost = match values {
        Some(values) => operator_cost(domain, problem, objs, sch.action, &b, values)?,
        None => 1,
    };
    Ok(Raw {
        action: sch.action,
        binding: b,
        pre,
        neg,
        add,
        del,
        cost,
    })
}

/// `cost(o) = Σ increase amounts` of action `action` under the binding `b`; an error names a
/// cost function without a value or a total beyond `u32`.
fn operator_cost(
    domain: &Domain,
    problem: &Problem,
    objs: &Objects,
    action: usize,
    b: &[Obj],
    values: &HashMap<(usize, Vec<Obj>), u64>,
) -> Result<u32, GroundError> {
    let act = &domain.actions[action];
    let mut total: u64 = 0;
    for inc in &act.effect.cost {
        let v = match &inc.amount {
            CostAmount::Constant(c) => *c,
            CostAmount::Function { function, args } => {
                let key: Vec<Obj> = args.iter().map(|t| value(arg(objs, t), b)).collect();
                match values.get(&(*function, key.clone())) {
                    Some(v) => *v,
                    None => {
                        let term = atom_name_fn(domain, objs, *function, &key);
                        return Err(GroundError::Located(domain.error_at(
                            inc.span,
                            format!(
                                "no value for `{term}` in the `:init` of {} (needed by `{}`)",
                                problem.file(),
                                op_name(domain, objs, action, b)
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
                op_name(domain, objs, action, b),
                u32::MAX
            ),
        ))
    })
}

/// The static facts, sorted: the initial facts of static predicates, and the reached facts no
/// operator touches (initial facts that never change: true forever).
fn static_facts(
    domain: &Domain,
    objs: &Objects,
    statics: &HashSet<GAtom>,
    fact_list: &[GAtom],
    fluents: &Fluents,
) -> Vec<String> {
    let mut static_atoms: Vec<&GAtom> = statics.iter().collect();
    static_atoms.extend(
        (0..fact_list.len())
            .filter(|&f| !fluents.touched[f])
            .map(|f| &fact_list[f]),
    );
    static_atoms.sort();
    static_atoms.dedup();
    static_atoms
        .iter()
        .map(|g| atom_name(domain, objs, g))
        .collect()
}

/// The operators in fluent ids: static preconditions folded out (an operator with a negative
/// precondition on a fact that is always true is dropped, as is one that needs a fact and its
/// negation), deletes of added facts dropped, and groundings of the same action and binding
/// (from different disjuncts) kept once when equal.
fn operators(domain: &Domain, objs: &Objects, raws: Vec<Raw>, fluents: &Fluents) -> Vec<Operator> {
    let (touched, new_id) = (&fluents.touched, &fluents.new_id);
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
    operators
}

/// The goal's DNF alternatives in fluent ids, static literals folded out: an alternative whose
/// static part is false is dropped (none left: the task is unsolvable).
fn goal_alternatives(
    problem: &Problem,
    objs: &Objects,
    fact_ids: &HashMap<GAtom, u32>,
    statics: &HashSet<GAtom>,
    fluent_pred: &[bool],
    fluents: &Fluents,
) -> Result<Vec<Condition>, GroundError> {
    let truth = |g: GAtom| -> Truth {
        let pred = g.0;
        if fluent_pred[pred] {
            match fact_ids.get(&g) {
                Some(&f) if fluents.touched[f as usize] => {
                    Truth::Fluent(fluents.new_id[f as usize])
                }
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
    Ok(alternatives)
}

/// The operator name `(action o1 o2 …)` of a binding.
fn op_name(domain: &Domain, objs: &Objects, action: usize, b: &[Obj]) -> String {
    let mut s = format!("({}", domain.actions[action].name.text);
    for &o in b {
        s.push(' ');
        s.push_str(&objs.names[o as usize]);
    }
    s.push(')');
    s
}

/// A cost function's term `(f o1 o2 …)`, `?` for an unknown object.
fn atom_name_fn(domain: &Domain, objs: &Objects, f: usize, args: &[Obj]) -> String {
    let mut s = format!("({}", domain.functions[f].name.text);
    for &o in args {
        s.push(' ');
        s.push_str(objs.names.get(o as usize).map_or("?", |n| n.as_str()));
    }
    s.push(')');
    s
}
