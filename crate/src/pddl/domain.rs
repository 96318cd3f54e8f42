//! `(define (domain …) …)`: requirements, the type hierarchy, constants, predicates, functions and
//! action schemas. Sections may come in any order, each at most once (actions repeat).

use std::collections::HashMap;

use super::ast::{Action, Domain, Formula, Name, Signature, TypeDecl, TypedName};
use super::common::{define, list, name, refuse, requirements, typed_list};
use super::error::Span;
use super::error::{PddlError, SourceMap};
use super::formula::Scope;
use super::lexer::{read_one, SExpr};
use super::suggest::did_you_mean;

/// Parses a domain file. `file` is used in error locations only.
pub fn parse_domain(text: &str, file: &str) -> Result<Domain, PddlError> {
    let src = SourceMap::new(text, file);
    let top = read_one(&src)?;
    let (dname, sections) = define(&src, &top, "domain")?;

    let mut seen: HashMap<&str, Span> = HashMap::new();
    let mut reqs = None;
    let mut types = None;
    let mut constants = None;
    let mut predicates = None;
    let mut functions = None;
    let mut actions = Vec::new();
    for s in sections {
        let items = list(&src, s, "a domain section")?;
        let Some(kw) = items.first().and_then(|h| h.atom()) else {
            return Err(src.error(s.span(), "expected a section such as `(:predicates …)`"));
        };
        let kspan = items[0].span();
        match kw {
            ":requirements" | ":types" | ":constants" | ":predicates" | ":functions" => {
                if let Some(prev) = seen.insert(kw, kspan) {
                    let (l, c) = src.line_col(prev.start);
                    return Err(src.error(
                        kspan,
                        format!("duplicate section `{kw}` (first at {l}:{c})"),
                    ));
                }
                let slot = match kw {
                    ":requirements" => &mut reqs,
                    ":types" => &mut types,
                    ":constants" => &mut constants,
                    ":predicates" => &mut predicates,
                    _ => &mut functions,
                };
                *slot = Some(items);
            }
            ":action" => actions.push(s),
            ":derived" => {
                return Err(refuse(
                    &src,
                    kspan,
                    ":derived",
                    "derived predicates are not supported",
                ))
            }
            ":durative-action" | ":process" | ":event" => {
                return Err(refuse(
                    &src,
                    kspan,
                    kw,
                    "temporal and hybrid planning are not supported",
                ))
            }
            ":constraints" => {
                return Err(refuse(
                    &src,
                    kspan,
                    ":constraints",
                    "PDDL3 constraints are not supported",
                ))
            }
            _ => {
                let near = did_you_mean(kw, super::brackets::DOMAIN_SECTIONS);
                return Err(src.error(kspan, format!("unknown domain section `{kw}`{near}")));
            }
        }
    }

    let requirements = match reqs {
        Some(items) => requirements(&src, items)?,
        None => Vec::new(),
    };
    let types = match types {
        Some(items) => type_hierarchy(&src, &items[1..])?,
        None => vec![object_type()],
    };
    let mut domain = Domain {
        name: dname,
        requirements,
        types,
        constants: Vec::new(),
        predicates: Vec::new(),
        functions: Vec::new(),
        actions: Vec::new(),
        source: src.clone(),
    };
    if let Some(items) = constants {
        let mut seen = HashMap::new();
        for (n, ty) in typed_list(&src, &items[1..], false)? {
            let ty = resolve_type(&src, &domain, ty.as_ref())?;
            if let Some(prev) = seen.insert(n.text.clone(), n.span) {
                return Err(duplicate(&src, "constant", &n, prev));
            }
            domain.constants.push(TypedName { name: n, ty });
        }
    }
    if let Some(items) = predicates {
        domain.predicates = signatures(&src, &domain, &items[1..], "predicate")?;
    }
    if let Some(items) = functions {
        domain.functions = function_signatures(&src, &domain, &items[1..])?;
    }
    let consts: HashMap<String, usize> = domain
        .constants
        .iter()
        .map(|c| (c.name.text.clone(), c.ty))
        .collect();
    let mut parsed: Vec<Action> = Vec::new();
    for a in actions {
        let act = action(&src, &domain, &consts, a)?;
        if let Some(prev) = parsed.iter().find(|p| p.name.text == act.name.text) {
            return Err(duplicate(&src, "action", &act.name, prev.name.span));
        }
        parsed.push(act);
    }
    domain.actions = parsed;
    Ok(domain)
}

fn object_type() -> TypeDecl {
    TypeDecl {
        name: Name {
            text: "object".into(),
            span: Span::default(),
        },
        parent: None,
    }
}

pub(crate) fn duplicate(src: &SourceMap, what: &str, n: &Name, prev: Span) -> PddlError {
    let (l, c) = src.line_col(prev.start);
    src.error(
        n.span,
        format!("duplicate {what} `{}` (first declared at {l}:{c})", n.text),
    )
}

/// `(:types a b - c c d - object)`: parents are declared implicitly.
///
/// A type may be declared more than once, as Fast Downward reads it: with the same parent, or
/// with parents of which one descends from the other (IPC-2006 storage writes `area - object`
/// and `area - surface`), when it takes the most specific. Two unrelated parents (multiple
/// inheritance) and cycles are errors.
fn type_hierarchy(src: &SourceMap, items: &[SExpr]) -> Result<Vec<TypeDecl>, PddlError> {
    let mut types = vec![object_type()];
    let mut explicit: Vec<bool> = vec![true];
    // Every parent each type was declared under, with the name that declared it.
    let mut parents: Vec<Vec<(usize, Name)>> = vec![vec![]];
    fn index(
        types: &mut Vec<TypeDecl>,
        explicit: &mut Vec<bool>,
        parents: &mut Vec<Vec<(usize, Name)>>,
        n: &Name,
    ) -> usize {
        match types.iter().position(|t| t.name.text == n.text) {
            Some(i) => i,
            None => {
                types.push(TypeDecl {
                    name: n.clone(),
                    parent: Some(0),
                });
                explicit.push(false);
                parents.push(vec![]);
                types.len() - 1
            }
        }
    }
    for (n, parent) in typed_list(src, items, false)? {
        if n.text == "object" {
            if parent.is_some() {
                return Err(src.error(n.span, "type `object` cannot have a parent"));
            }
            continue;
        }
        let i = index(&mut types, &mut explicit, &mut parents, &n);
        if !explicit[i] {
            explicit[i] = true;
            types[i].name.span = n.span;
        }
        let p = match &parent {
            Some(p) => index(&mut types, &mut explicit, &mut parents, p),
            None => 0,
        };
        if !parents[i].iter().any(|(q, _)| *q == p) {
            parents[i].push((p, n));
        }
    }
    check_acyclic(src, &types, &parents)?;
    for i in 1..types.len() {
        let declared = &parents[i];
        // Keep the parents that no other declared parent descends from.
        let specific: Vec<&(usize, Name)> = declared
            .iter()
            .filter(|(p, _)| {
                !declared
                    .iter()
                    .any(|(q, _)| q != p && descends(&parents, *q, *p))
            })
            .collect();
        match specific.as_slice() {
            [] => types[i].parent = Some(0),
            [(p, _)] => types[i].parent = Some(*p),
            [(a, _), (b, n), ..] => {
                return Err(src.error(
                    n.span,
                    format!(
                        "type `{}` is declared under both `{}` and `{}`, neither a subtype of \
                         the other: a type with two parents is not supported",
                        types[i].name.text, types[*a].name.text, types[*b].name.text
                    ),
                ))
            }
        }
    }
    Ok(types)
}

/// Whether type `sub` descends from `sup` through any declared parent (the declarations are
/// acyclic). Iterative: a file may chain thousands of types.
fn descends(parents: &[Vec<(usize, Name)>], sub: usize, sup: usize) -> bool {
    let mut seen = vec![false; parents.len()];
    let mut todo = vec![sub];
    while let Some(t) = todo.pop() {
        if t == sup || sup == 0 {
            return true;
        }
        if !std::mem::replace(&mut seen[t], true) {
            todo.extend(parents[t].iter().map(|(p, _)| *p));
        }
    }
    false
}

/// Every chain of declared parents must reach `object`: a type declared (indirectly) under
/// itself is an error.
fn check_acyclic(
    src: &SourceMap,
    types: &[TypeDecl],
    parents: &[Vec<(usize, Name)>],
) -> Result<(), PddlError> {
    // Iterative depth-first search with colours: 0 unvisited, 1 on the path, 2 done.
    let mut colour = vec![0u8; types.len()];
    for root in 0..types.len() {
        if colour[root] != 0 {
            continue;
        }
        // (type, index of the next parent to visit)
        let mut path = vec![(root, 0usize)];
        colour[root] = 1;
        while let Some(&mut (t, ref mut next)) = path.last_mut() {
            match parents[t].get(*next) {
                Some((p, _)) => {
                    *next += 1;
                    let p = *p;
                    match colour[p] {
                        1 => {
                            return Err(src.error(
                                types[p].name.span,
                                format!(
                                    "the type hierarchy has a cycle through `{}`",
                                    types[p].name.text
                                ),
                            ))
                        }
                        0 => {
                            colour[p] = 1;
                            path.push((p, 0));
                        }
                        _ => {}
                    }
                }
                None => {
                    colour[t] = 2;
                    path.pop();
                }
            }
        }
    }
    Ok(())
}

/// The type index of a declared type name (`object` when absent).
pub(crate) fn resolve_type(
    src: &SourceMap,
    domain: &Domain,
    ty: Option<&Name>,
) -> Result<usize, PddlError> {
    match ty {
        None => Ok(0),
        Some(n) => domain.type_index(&n.text).ok_or_else(|| {
            let near = did_you_mean(&n.text, domain.types.iter().map(|t| t.name.text.as_str()));
            src.error(n.span, format!("undeclared type `{}`{near}", n.text))
        }),
    }
}

/// Typed `?x` parameters; action parameters must have unique names (predicate signatures need
/// not: the IPC logistics domain declares `(in ?obj ?obj)`).
fn parameters(
    src: &SourceMap,
    domain: &Domain,
    items: &[SExpr],
    unique: bool,
) -> Result<Vec<TypedName>, PddlError> {
    let mut out: Vec<TypedName> = Vec::new();
    for (n, ty) in typed_list(src, items, true)? {
        let ty = resolve_type(src, domain, ty.as_ref())?;
        if let Some(prev) = out.iter().find(|p| unique && p.name.text == n.text) {
            return Err(duplicate(src, "parameter", &n, prev.name.span));
        }
        out.push(TypedName { name: n, ty });
    }
    Ok(out)
}

fn signatures(
    src: &SourceMap,
    domain: &Domain,
    items: &[SExpr],
    what: &str,
) -> Result<Vec<Signature>, PddlError> {
    let mut out: Vec<Signature> = Vec::new();
    for e in items {
        let l = list(src, e, &format!("a {what} `(name ?x …)`"))?;
        let Some(h) = l.first() else {
            return Err(src.error(e.span(), format!("expected a {what} `(name ?x …)`")));
        };
        let n = name(src, h, &format!("a {what} name"))?;
        if let Some(prev) = out.iter().find(|p| p.name.text == n.text) {
            return Err(duplicate(src, what, &n, prev.name.span));
        }
        let params = parameters(src, domain, &l[1..], false)?;
        out.push(Signature { name: n, params });
    }
    Ok(out)
}

/// `(:functions (total-cost) - number (f ?x - t) - number)`; only `number` functions.
fn function_signatures(
    src: &SourceMap,
    domain: &Domain,
    items: &[SExpr],
) -> Result<Vec<Signature>, PddlError> {
    let mut lists = Vec::new();
    let mut i = 0;
    while i < items.len() {
        if items[i].atom() == Some("-") {
            match items.get(i + 1).and_then(|t| t.atom()) {
                Some("number") => {}
                Some(t) => {
                    return Err(refuse(
                        src,
                        items[i + 1].span(),
                        t,
                        "only `number` functions are supported (object fluents are not)",
                    ))
                }
                None => return Err(src.error(items[i].span(), "expected `number` after `-`")),
            }
            i += 2;
        } else {
            lists.push(items[i].clone());
            i += 1;
        }
    }
    let sigs = signatures(src, domain, &lists, "function")?;
    for s in &sigs {
        if s.name.text == "total-cost" && !s.params.is_empty() {
            return Err(src.error(s.name.span, "`total-cost` takes no arguments"));
        }
    }
    Ok(sigs)
}

/// `(:action NAME :parameters (…) :precondition φ :effect ε)`.
fn action(
    src: &SourceMap,
    domain: &Domain,
    consts: &HashMap<String, usize>,
    e: &SExpr,
) -> Result<Action, PddlError> {
    let items = list(src, e, "an action")?;
    let Some(nm) = items.get(1) else {
        return Err(src.error(e.span(), "expected an action name after `:action`"));
    };
    let aname = name(src, nm, "an action name")?;
    let mut params_e = None;
    let mut pre_e = None;
    let mut eff_e = None;
    let mut i = 2;
    while i < items.len() {
        let key = &items[i];
        let Some(k) = key.atom() else {
            return Err(src.error(
                key.span(),
                "expected `:parameters`, `:precondition` or `:effect`",
            ));
        };
        let slot = match k {
            ":parameters" => &mut params_e,
            ":precondition" => &mut pre_e,
            ":effect" => &mut eff_e,
            ":duration" | ":condition" => {
                return Err(refuse(src, key.span(), k, "durative actions are not supported"))
            }
            _ => {
                return Err(src.error(
                    key.span(),
                    format!(
                        "unknown action key `{k}`{} (expected `:parameters`, `:precondition` or `:effect`)",
                        did_you_mean(k, super::brackets::ACTION_KEYS)
                    ),
                ))
            }
        };
        let Some(v) = items.get(i + 1) else {
            return Err(src.error(key.span(), format!("`{k}` has no value")));
        };
        if slot.is_some() {
            return Err(src.error(
                key.span(),
                format!("duplicate `{k}` in action `{}`", aname.text),
            ));
        }
        *slot = Some(v);
        i += 2;
    }
    let params = match params_e {
        Some(p) => parameters(src, domain, list(src, p, "a parameter list")?, true)?,
        None => Vec::new(),
    };
    let scope = Scope {
        src,
        domain,
        params: &params,
        objects: consts,
        context: "precondition",
    };
    let precondition = match pre_e {
        Some(p) => scope.formula(p)?,
        None => Formula::And(Vec::new(), e.span()),
    };
    let effect = match eff_e {
        Some(x) => scope.effect(x)?,
        None => Default::default(),
    };
    Ok(Action {
        name: aname,
        params,
        precondition,
        effect,
        span: e.span(),
    })
}
