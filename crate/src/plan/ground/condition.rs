//! Condition compilation: a precondition or goal formula to disjunctive normal form, and each
//! action's precondition to one [`Schema`] per disjunct.

use crate::pddl::{Domain, Formula, Problem};

use super::objects::{arg, lit, Objects};
use super::schema::{GroundError, Literal, Schema, MAX_DISJUNCTS};

/// The schemas of a domain with the type of each one's parameters.
pub(super) struct Schemas {
    /// One per DNF disjunct of each action's precondition, in action order.
    pub(super) list: Vec<Schema>,
    /// Per schema, the type of each parameter.
    pub(super) params_ty: Vec<Vec<usize>>,
}

/// One schema per DNF disjunct of each action's precondition (repeated positive atoms merged).
pub(super) fn compile_schemas(
    domain: &Domain,
    problem: &Problem,
    objs: &Objects,
) -> Result<Schemas, GroundError> {
    let too_large = |what: String| GroundError::TooLarge(problem.file().to_string(), what);
    let mut schemas = Vec::new();
    let mut params_ty = Vec::new();
    for (ai, a) in domain.actions.iter().enumerate() {
        let Some(d) = dnf(objs, &a.precondition, false) else {
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
    Ok(Schemas {
        list: schemas,
        params_ty,
    })
}

/// Disjunctive normal form of `f` (negated when `neg`), or `None` beyond [`MAX_DISJUNCTS`].
pub(super) fn dnf(objs: &Objects, f: &Formula, neg: bool) -> Option<Vec<Vec<Literal>>> {
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
