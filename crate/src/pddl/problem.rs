//! `(define (problem …) (:domain …) …)`: objects, init (atoms and cost-function values), goal and
//! the `(:metric minimize (total-cost))`, checked against the domain.

use std::collections::HashMap;

use super::ast::{Atom, Domain, FunctionValue, Name, Problem, Term, TypedName};
use super::common::{define, list, name, non_negative_integer, refuse, requirements, typed_list};
use super::domain::{duplicate, resolve_type};
use super::error::Span;
use super::error::{PddlError, SourceMap};
use super::formula::Scope;
use super::lexer::{read_one, SExpr};
use super::suggest::did_you_mean;

/// Parses a problem file against its domain. `file` is used in error locations only.
pub fn parse_problem(text: &str, file: &str, domain: &Domain) -> Result<Problem, PddlError> {
    let src = SourceMap::new(text, file);
    let top = read_one(&src)?;
    let (pname, sections) = define(&src, &top, "problem")?;

    let mut seen: HashMap<String, Span> = HashMap::new();
    let mut dom = None;
    let mut objects_e = None;
    let mut init_e = None;
    let mut goal_e = None;
    let mut metric_e = None;
    for s in sections {
        let items = list(&src, s, "a problem section")?;
        let Some(kw) = items.first().and_then(|h| h.atom()) else {
            return Err(src.error(s.span(), "expected a section such as `(:init …)`"));
        };
        let kspan = items[0].span();
        let slot = match kw {
            ":domain" => &mut dom,
            ":requirements" => {
                requirements(&src, items)?;
                &mut None
            }
            ":objects" => &mut objects_e,
            ":init" => &mut init_e,
            ":goal" => &mut goal_e,
            ":metric" => &mut metric_e,
            ":constraints" => {
                return Err(refuse(
                    &src,
                    kspan,
                    ":constraints",
                    "PDDL3 constraints are not supported",
                ))
            }
            ":length" => {
                return Err(refuse(
                    &src,
                    kspan,
                    ":length",
                    "plan-length bounds are not supported",
                ))
            }
            _ => {
                let near = did_you_mean(kw, super::brackets::PROBLEM_SECTIONS);
                return Err(src.error(kspan, format!("unknown problem section `{kw}`{near}")));
            }
        };
        if let Some(prev) = seen.insert(kw.to_string(), kspan) {
            let (l, c) = src.line_col(prev.start);
            return Err(src.error(
                kspan,
                format!("duplicate section `{kw}` (first at {l}:{c})"),
            ));
        }
        *slot = Some((items, s.span()));
    }

    let Some((ditems, dspan)) = dom else {
        return Err(src.error(top.span(), "missing section `(:domain NAME)`"));
    };
    if ditems.len() != 2 {
        return Err(src.error(dspan, "expected `(:domain NAME)`"));
    }
    let domain_name = name(&src, &ditems[1], "the domain name")?;
    if domain_name.text != domain.name.text {
        return Err(src.error(
            domain_name.span,
            format!(
                "problem is for domain `{}`, but the domain is `{}`",
                domain_name.text, domain.name.text
            ),
        ));
    }

    // Objects and constants share one namespace.
    let mut objects = Vec::new();
    let mut names: HashMap<String, usize> = HashMap::new();
    let mut spans: HashMap<String, (Span, bool)> = HashMap::new();
    for c in &domain.constants {
        names.insert(c.name.text.clone(), c.ty);
        spans.insert(c.name.text.clone(), (c.name.span, true));
    }
    if let Some((items, _)) = objects_e {
        for (n, ty) in typed_list(&src, &items[1..], false)? {
            let ty = resolve_type(&src, domain, ty.as_ref())?;
            if let Some(&(prev, is_const)) = spans.get(&n.text) {
                if is_const {
                    return Err(src.error(
                        n.span,
                        format!("object `{}` is already a constant of the domain", n.text),
                    ));
                }
                return Err(duplicate(&src, "object", &n, prev));
            }
            spans.insert(n.text.clone(), (n.span, false));
            names.insert(n.text.clone(), ty);
            objects.push(TypedName { name: n, ty });
        }
    }

    let scope = Scope {
        src: &src,
        domain,
        params: &[],
        objects: &names,
        context: "goal",
    };

    let Some((init_items, _)) = init_e else {
        return Err(src.error(top.span(), "missing section `(:init …)`"));
    };
    let mut init = Vec::new();
    let mut function_values: Vec<FunctionValue> = Vec::new();
    for e in &init_items[1..] {
        match e.head() {
            Some("=") => {
                if let Some(v) = function_value(&src, domain, &names, e)? {
                    if let Some(prev) = function_values
                        .iter()
                        .find(|p| p.function == v.function && p.args == v.args)
                    {
                        let (l, c) = src.line_col(prev.span.start);
                        return Err(src.error(
                            v.span,
                            format!("function value given twice (first at {l}:{c})"),
                        ));
                    }
                    function_values.push(v);
                }
            }
            Some("not") => {
                return Err(src.error(
                    e.span(),
                    "`not` in `:init`: the initial state is closed-world, list only true atoms",
                ))
            }
            Some("at") if domain.predicate_index("at").is_none() => {
                return Err(refuse(
                    &src,
                    e.span(),
                    "at",
                    "timed initial literals are not supported",
                ))
            }
            _ => init.push(scope.atom(e)?),
        }
    }

    let Some((goal_items, gspan)) = goal_e else {
        return Err(src.error(top.span(), "missing section `(:goal …)`"));
    };
    if goal_items.len() != 2 {
        return Err(src.error(gspan, "expected `(:goal FORMULA)` with exactly one formula"));
    }
    let goal = scope.formula(&goal_items[1])?;

    let minimize_total_cost = match metric_e {
        None => false,
        Some((items, mspan)) => {
            metric(&src, domain, items, mspan)?;
            true
        }
    };

    Ok(Problem {
        name: pname,
        domain_name,
        objects,
        init,
        function_values,
        goal,
        minimize_total_cost,
        source: src,
    })
}

/// `(= (f a …) N)`; `(= (total-cost) N)` is accepted and dropped (plan cost starts at 0).
fn function_value(
    src: &SourceMap,
    domain: &Domain,
    names: &HashMap<String, usize>,
    e: &SExpr,
) -> Result<Option<FunctionValue>, PddlError> {
    let items = list(src, e, "`(= (f …) N)`")?;
    if items.len() != 3 {
        return Err(src.error(e.span(), "expected `(= (function arg …) value)`"));
    }
    let f = list(src, &items[1], "a function term `(f arg …)`")?;
    let Some(fname) = f.first().and_then(|x| x.atom()) else {
        return Err(src.error(items[1].span(), "expected a function name"));
    };
    let Some(fi) = domain.functions.iter().position(|s| s.name.text == fname) else {
        return Err(src.error(f[0].span(), format!("undeclared function `{fname}`")));
    };
    let sig = &domain.functions[fi];
    if f.len() - 1 != sig.params.len() {
        return Err(src.error(
            items[1].span(),
            format!(
                "function `{fname}` takes {} argument(s), found {}",
                sig.params.len(),
                f.len() - 1
            ),
        ));
    }
    let value = non_negative_integer(src, &items[2])?;
    let mut args = Vec::new();
    for (a, p) in f[1..].iter().zip(&sig.params) {
        let n = name(src, a, "an object")?;
        let Some(&ty) = names.get(&n.text) else {
            return Err(src.error(
                n.span,
                format!(
                    "undeclared object or constant `{}`{}",
                    n.text,
                    did_you_mean(&n.text, names.keys().map(String::as_str))
                ),
            ));
        };
        if !domain.is_subtype(ty, p.ty) {
            return Err(src.error(
                n.span,
                format!(
                    "argument `{}` of `{fname}` has type `{}`, expected `{}`",
                    n.text, domain.types[ty].name.text, domain.types[p.ty].name.text
                ),
            ));
        }
        args.push(n);
    }
    if fname == "total-cost" {
        return Ok(None);
    }
    Ok(Some(FunctionValue {
        function: fi,
        args,
        value,
        span: e.span(),
    }))
}

/// `(:metric minimize (total-cost))`, the only metric supported.
fn metric(src: &SourceMap, domain: &Domain, items: &[SExpr], span: Span) -> Result<(), PddlError> {
    let Some(dir) = items.get(1) else {
        return Err(src.error(span, "expected `(:metric minimize (total-cost))`"));
    };
    match dir.atom() {
        Some("minimize") => {}
        Some("maximize") => {
            return Err(refuse(
                src,
                dir.span(),
                "maximize",
                "only `minimize (total-cost)` is supported",
            ))
        }
        _ => return Err(src.error(dir.span(), "expected `minimize`")),
    }
    let ok = items.len() == 3
        && matches!(&items[2], SExpr::List(l, _) if l.len() == 1 && l[0].atom() == Some("total-cost"));
    if !ok {
        if let Some(SExpr::List(l, _)) = items.get(2) {
            if let Some(h) = l.first().and_then(|h| h.atom()) {
                if h != "total-cost" {
                    return Err(refuse(
                        src,
                        l[0].span(),
                        h,
                        "only `(:metric minimize (total-cost))` is supported",
                    ));
                }
            }
        }
        let at = items.get(2).map_or(span, |e| e.span());
        return Err(refuse(
            src,
            at,
            "metric",
            "only `(:metric minimize (total-cost))` is supported",
        ));
    }
    if !domain.functions.iter().any(|f| f.name.text == "total-cost") {
        return Err(src.error(
            items[2].span(),
            "the domain does not declare the function `(total-cost)`",
        ));
    }
    Ok(())
}

/// A ground atom read from a facts list, with where it was written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LocatedFact {
    /// The atom as printed by the grounder: `(on a b)`, lower case, single spaces.
    pub name: String,
    /// 1-based line of its `(`.
    pub line: usize,
    /// 1-based column of its `(`.
    pub col: usize,
}

impl Problem {
    /// A copy of this problem whose initial atoms are `facts` (`"(on a b)"` each, any case; the
    /// cost-function values are kept). For re-grounding from an observed state — e.g. a scene
    /// graph whose facts are unreachable from the original `:init`. Errors are located in the
    /// facts joined one per line, under the file name `<init>`.
    pub fn with_init(&self, domain: &Domain, facts: &[String]) -> Result<Problem, PddlError> {
        let src = SourceMap::new(&facts.join("\n"), "<init>");
        let init = self
            .atoms_in(domain, &src)?
            .into_iter()
            .map(|(a, _)| a)
            .collect();
        Ok(self.with_atoms(init))
    }

    /// This problem with `init` (its own initial atoms are not copied).
    fn with_atoms(&self, init: Vec<Atom>) -> Problem {
        Problem {
            name: self.name.clone(),
            domain_name: self.domain_name.clone(),
            objects: self.objects.clone(),
            init,
            function_values: self.function_values.clone(),
            goal: self.goal.clone(),
            minimize_total_cost: self.minimize_total_cost,
            source: self.source.clone(),
        }
    }

    /// [`Problem::with_init`] for atoms as the grounder prints them (`(on a b)`: lower case,
    /// single spaces) — a state of a grounding of this problem — without reading them as source
    /// text; anything else goes through [`Problem::with_init`] and its located errors.
    pub(crate) fn with_ground_init(
        &self,
        domain: &Domain,
        facts: &[String],
    ) -> Result<Problem, PddlError> {
        let objects: HashMap<&str, usize> = domain
            .constants
            .iter()
            .chain(&self.objects)
            .map(|o| (o.name.text.as_str(), o.ty))
            .collect();
        let atom = |fact: &str| -> Option<Atom> {
            let mut words = fact.strip_prefix('(')?.strip_suffix(')')?.split(' ');
            let pred = words.next()?;
            let predicate = domain.predicates.iter().position(|p| p.name.text == pred)?;
            let params = &domain.predicates[predicate].params;
            let mut args = Vec::with_capacity(params.len());
            for (word, param) in words.zip(params) {
                let &ty = objects.get(word)?;
                if !domain.is_subtype(ty, param.ty) {
                    return None;
                }
                args.push(Term::Const(Name {
                    text: word.to_string(),
                    span: Span::default(),
                }));
            }
            (args.len() == params.len() && fact.matches(' ').count() == args.len()).then_some(
                Atom {
                    predicate,
                    args,
                    span: Span::default(),
                },
            )
        };
        match facts.iter().map(|f| atom(f)).collect::<Option<Vec<Atom>>>() {
            Some(init) => Ok(self.with_atoms(init)),
            None => self.with_init(domain, facts),
        }
    }

    /// Reads a list of ground atoms of this problem — a state written as a user would, one
    /// `(predicate object …)` a line, `;` comments allowed.
    ///
    /// # Errors
    /// `file:line:col` of the first atom naming an undeclared predicate or object, with the wrong
    /// arity or a mistyped argument, or of anything that is not an atom.
    ///
    /// ```
    /// use logic_lfd::pddl::{parse_domain, parse_problem};
    /// let d = parse_domain("(define (domain d) (:predicates (p ?x)))", "d.pddl").unwrap();
    /// let p = parse_problem("(define (problem q) (:domain d) (:objects o) (:init) (:goal (p o)))", "q.pddl", &d).unwrap();
    /// let facts = p.read_facts(&d, "; now\n( P  O )", "s.facts").unwrap();
    /// assert_eq!((facts[0].name.as_str(), facts[0].line, facts[0].col), ("(p o)", 2, 1));
    /// let e = p.read_facts(&d, "(p x)", "s.facts").unwrap_err();
    /// assert_eq!(e.to_string(), "s.facts:1:4: undeclared object or constant `x`");
    /// ```
    pub fn read_facts(
        &self,
        domain: &Domain,
        text: &str,
        file: &str,
    ) -> Result<Vec<LocatedFact>, PddlError> {
        let src = SourceMap::new(text, file);
        Ok(self
            .atoms_in(domain, &src)?
            .into_iter()
            .map(|(a, span)| {
                let (line, col) = src.line_col(span.start);
                LocatedFact {
                    name: domain.atom_text(&a, &[]),
                    line,
                    col,
                }
            })
            .collect())
    }

    fn atoms_in(&self, domain: &Domain, src: &SourceMap) -> Result<Vec<(Atom, Span)>, PddlError> {
        let names: HashMap<String, usize> = domain
            .constants
            .iter()
            .chain(&self.objects)
            .map(|o| (o.name.text.clone(), o.ty))
            .collect();
        let scope = Scope {
            src,
            domain,
            params: &[],
            objects: &names,
            context: "state",
        };
        super::lexer::read_many(src)?
            .iter()
            .map(|e| scope.atom(e).map(|a| (a, e.span())))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::parse_domain;
    use super::*;

    const DOMAIN: &str = "(define (domain d) (:requirements :typing) (:types box room)
      (:predicates (in ?b - box ?r - room) (open ?r - room)))";
    const PROBLEM: &str = "(define (problem p) (:domain d) (:objects b1 - box r1 r2 - room)
      (:init (in b1 r1)) (:goal (in b1 r2)))";

    #[test]
    fn ground_atoms_give_the_init_that_reading_them_gives() {
        let d = parse_domain(DOMAIN, "d.pddl").unwrap();
        let p = parse_problem(PROBLEM, "p.pddl", &d).unwrap();
        let facts = ["(in b1 r2)".to_string(), "(open r1)".to_string()];
        let fast = p.with_ground_init(&d, &facts).unwrap();
        assert_eq!(fast.init.len(), 2);
        let read = p.with_init(&d, &facts).unwrap();
        let text = |q: &Problem| {
            q.init
                .iter()
                .map(|a| d.atom_text(a, &[]))
                .collect::<Vec<_>>()
        };
        assert_eq!(text(&fast), text(&read));
        // Not the grounder's spelling, a mistyped or unknown argument: read, and located.
        assert_eq!(
            text(
                &p.with_ground_init(&d, &["( OPEN  r1 )".to_string()])
                    .unwrap()
            ),
            ["(open r1)"]
        );
        for bad in ["(open b1)", "(open r3)", "(in b1)"] {
            let e = p.with_ground_init(&d, &[bad.to_string()]).unwrap_err();
            assert!(e.to_string().starts_with("<init>:1:"), "{bad}: {e}");
        }
    }
}
