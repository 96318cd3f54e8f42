//! Conditions (preconditions, goals) and effects: `and`, `or`, `not`, `=`, atoms,
//! `(increase (total-cost) N)`. Quantifiers, conditional effects, `imply` and numeric expressions
//! are refused by name at their location.

use std::collections::HashMap;

use super::ast::{Atom, CostAmount, CostIncrease, Domain, Effect, Formula, Name, Term, TypedName};
use super::common::{is_name, list, non_negative_integer, refuse};
use super::error::{PddlError, SourceMap};
use super::lexer::SExpr;
use super::suggest::did_you_mean;

/// What names mean where a formula is read.
pub(crate) struct Scope<'a> {
    pub(crate) src: &'a SourceMap,
    pub(crate) domain: &'a Domain,
    /// Action parameters (empty in a problem).
    pub(crate) params: &'a [TypedName],
    /// Object and constant names → type index.
    pub(crate) objects: &'a HashMap<String, usize>,
    /// `"goal"` or `"precondition"`, for messages.
    pub(crate) context: &'static str,
}

impl Scope<'_> {
    fn type_name(&self, t: usize) -> &str {
        &self.domain.types[t].name.text
    }

    /// A term and its type.
    pub(crate) fn term(&self, e: &SExpr) -> Result<(Term, usize), PddlError> {
        let Some(a) = e.atom() else {
            return Err(self.src.error(
                e.span(),
                "expected an object or a variable, found a list (function terms are only allowed in `(increase (total-cost) …)`)",
            ));
        };
        let name = Name {
            text: a.to_string(),
            span: e.span(),
        };
        if a.starts_with('?') {
            if self.params.is_empty() && self.context != "precondition" {
                return Err(self.src.error(
                    e.span(),
                    format!(
                        "variable `{a}` in the {} (quantifiers are not supported)",
                        self.context
                    ),
                ));
            }
            return match self.params.iter().position(|p| p.name.text == a) {
                Some(i) => Ok((Term::Var(i, name), self.params[i].ty)),
                None => Err(self.src.error(
                    e.span(),
                    format!(
                        "undeclared variable `{a}`{}",
                        did_you_mean(a, self.params.iter().map(|p| p.name.text.as_str()))
                    ),
                )),
            };
        }
        match self.objects.get(a) {
            Some(&t) => Ok((Term::Const(name), t)),
            None if is_name(a) => Err(self.src.error(
                e.span(),
                format!(
                    "undeclared object or constant `{a}`{}",
                    did_you_mean(a, self.objects.keys().map(String::as_str))
                ),
            )),
            None => Err(self.src.error(
                e.span(),
                format!("expected an object or a variable, found `{a}`"),
            )),
        }
    }

    /// Whether an argument of type `arg` may be passed for a parameter of type `param`: constants
    /// must be of a subtype; variables must overlap (one type below the other).
    fn type_fits(&self, term: &Term, arg: usize, param: usize) -> bool {
        match term {
            Term::Const(_) => self.domain.is_subtype(arg, param),
            Term::Var(..) => {
                self.domain.is_subtype(arg, param) || self.domain.is_subtype(param, arg)
            }
        }
    }

    /// `(predicate arg …)`.
    pub(crate) fn atom(&self, e: &SExpr) -> Result<Atom, PddlError> {
        let items = list(self.src, e, "an atom")?;
        let Some(head) = items.first() else {
            return Err(self.src.error(e.span(), "expected an atom, found `()`"));
        };
        let Some(p) = head.atom().and_then(|h| self.domain.predicate_index(h)) else {
            return Err(self.src.error(
                head.span(),
                match head.atom() {
                    Some(h) => format!(
                        "undeclared predicate `{h}`{}",
                        did_you_mean(
                            h,
                            self.domain.predicates.iter().map(|p| p.name.text.as_str())
                        )
                    ),
                    None => "expected a predicate name, found a list".to_string(),
                },
            ));
        };
        let sig = &self.domain.predicates[p];
        if items.len() - 1 != sig.params.len() {
            return Err(self.src.error(
                e.span(),
                format!(
                    "predicate `{}` takes {} argument(s), found {}",
                    sig.name.text,
                    sig.params.len(),
                    items.len() - 1
                ),
            ));
        }
        let mut args = Vec::with_capacity(sig.params.len());
        for (arg, param) in items[1..].iter().zip(&sig.params) {
            let (t, ty) = self.term(arg)?;
            if !self.type_fits(&t, ty, param.ty) {
                return Err(self.src.error(
                    arg.span(),
                    format!(
                        "argument `{}` of `{}` has type `{}`, expected `{}`",
                        t.text(),
                        sig.name.text,
                        self.type_name(ty),
                        self.type_name(param.ty)
                    ),
                ));
            }
            args.push(t);
        }
        Ok(Atom {
            predicate: p,
            args,
            span: e.span(),
        })
    }

    /// A condition: `and`, `or`, `not`, `=`, atoms; `()` is true.
    pub(crate) fn formula(&self, e: &SExpr) -> Result<Formula, PddlError> {
        let items = list(self.src, e, &format!("a {} formula", self.context))?;
        let span = e.span();
        let Some(head) = items.first() else {
            return Ok(Formula::And(Vec::new(), span));
        };
        let args = &items[1..];
        let kw = head.atom().unwrap_or("");
        match kw {
            "and" | "or" => {
                let parts = args
                    .iter()
                    .map(|a| self.formula(a))
                    .collect::<Result<Vec<_>, _>>()?;
                Ok(if kw == "and" {
                    Formula::And(parts, span)
                } else {
                    Formula::Or(parts, span)
                })
            }
            "not" => {
                if args.len() != 1 {
                    return Err(self.src.error(span, "`not` takes exactly one formula"));
                }
                Ok(Formula::Not(Box::new(self.formula(&args[0])?), span))
            }
            "=" => {
                if args.len() != 2 {
                    return Err(self.src.error(span, "`=` takes exactly two terms"));
                }
                if args.iter().any(|a| a.atom().is_none()) {
                    return Err(refuse(
                        self.src,
                        head.span(),
                        "=",
                        "numeric comparison of function terms (numeric fluents beyond total-cost)",
                    ));
                }
                let (a, _) = self.term(&args[0])?;
                let (b, _) = self.term(&args[1])?;
                Ok(Formula::Eq(a, b, span))
            }
            "imply" => Err(refuse(
                self.src,
                head.span(),
                "imply",
                "write `(or (not A) B)` instead",
            )),
            "forall" | "exists" => Err(refuse(
                self.src,
                head.span(),
                kw,
                "quantified conditions are not supported",
            )),
            "preference" => Err(refuse(
                self.src,
                head.span(),
                "preference",
                "PDDL3 preferences are not supported",
            )),
            "when" => Err(refuse(
                self.src,
                head.span(),
                "when",
                "conditional effects are not supported (and `when` is not a condition)",
            )),
            "<" | ">" | "<=" | ">=" => Err(refuse(
                self.src,
                head.span(),
                kw,
                "numeric conditions (numeric fluents beyond total-cost) are not supported",
            )),
            "at" | "over"
                if args
                    .first()
                    .and_then(|a| a.atom())
                    .is_some_and(|a| matches!(a, "start" | "end" | "all"))
                    && self.domain.predicate_index(kw).is_none() =>
            {
                Err(refuse(
                    self.src,
                    head.span(),
                    kw,
                    "temporal conditions (durative actions) are not supported",
                ))
            }
            _ => Ok(Formula::Atom(self.atom(e)?)),
        }
    }

    /// An effect: a conjunction of atoms, `(not atom)` and `(increase (total-cost) N)`.
    pub(crate) fn effect(&self, e: &SExpr) -> Result<Effect, PddlError> {
        let mut out = Effect::default();
        self.effect_into(e, &mut out)?;
        Ok(out)
    }

    fn effect_into(&self, e: &SExpr, out: &mut Effect) -> Result<(), PddlError> {
        let items = list(self.src, e, "an effect")?;
        let span = e.span();
        let Some(head) = items.first() else {
            return Ok(());
        };
        let args = &items[1..];
        let kw = head.atom().unwrap_or("");
        match kw {
            "and" => {
                for a in args {
                    self.effect_into(a, out)?;
                }
                Ok(())
            }
            "not" => {
                if args.len() != 1 {
                    return Err(self.src.error(span, "`not` takes exactly one atom"));
                }
                if args[0].head() == Some("=") {
                    return Err(self.src.error(span, "`=` cannot be an effect"));
                }
                out.del.push(self.atom(&args[0])?);
                Ok(())
            }
            "increase" => {
                out.cost.push(self.increase(head, args, span)?);
                Ok(())
            }
            "decrease" | "assign" | "scale-up" | "scale-down" => Err(refuse(
                self.src,
                head.span(),
                kw,
                "numeric effects other than `(increase (total-cost) N)` are not supported",
            )),
            "when" => Err(refuse(
                self.src,
                head.span(),
                "when",
                "conditional effects are not supported",
            )),
            "forall" => Err(refuse(
                self.src,
                head.span(),
                "forall",
                "universally quantified effects are not supported",
            )),
            "or" | "=" | "exists" | "imply" => Err(self
                .src
                .error(head.span(), format!("`{kw}` cannot be an effect"))),
            _ => {
                out.add.push(self.atom(e)?);
                Ok(())
            }
        }
    }

    fn increase(
        &self,
        head: &SExpr,
        args: &[SExpr],
        span: super::error::Span,
    ) -> Result<CostIncrease, PddlError> {
        if args.len() != 2 {
            return Err(self
                .src
                .error(span, "`increase` takes a function and an amount"));
        }
        let target = &args[0];
        match target {
            SExpr::List(t, _) if t.len() == 1 && t[0].atom() == Some("total-cost") => {}
            SExpr::List(t, _) if t.first().and_then(|x| x.atom()).is_some() => {
                let f = t[0].atom().unwrap_or_default();
                return Err(refuse(
                    self.src,
                    head.span(),
                    "increase",
                    &format!("only `(total-cost)` may be increased, not `{f}` (numeric fluents beyond total-cost)"),
                ));
            }
            _ => {
                return Err(self
                    .src
                    .error(target.span(), "expected `(total-cost)` after `increase`"))
            }
        }
        if !self
            .domain
            .functions
            .iter()
            .any(|f| f.name.text == "total-cost")
        {
            return Err(self.src.error(
                target.span(),
                "function `total-cost` is not declared in `(:functions …)`",
            ));
        }
        let amount = &args[1];
        let amount = match amount {
            SExpr::Atom(..) => CostAmount::Constant(non_negative_integer(self.src, amount)?),
            SExpr::List(items, _) => {
                let Some(fname) = items.first().and_then(|x| x.atom()) else {
                    return Err(self.src.error(
                        amount.span(),
                        "expected a cost: an integer or `(function arg …)`",
                    ));
                };
                if matches!(fname, "+" | "-" | "*" | "/") {
                    return Err(refuse(
                        self.src,
                        items[0].span(),
                        fname,
                        "arithmetic in costs is not supported",
                    ));
                }
                let Some(fi) = self
                    .domain
                    .functions
                    .iter()
                    .position(|f| f.name.text == fname && fname != "total-cost")
                else {
                    return Err(self
                        .src
                        .error(items[0].span(), format!("undeclared function `{fname}`")));
                };
                let sig = &self.domain.functions[fi];
                if items.len() - 1 != sig.params.len() {
                    return Err(self.src.error(
                        amount.span(),
                        format!(
                            "function `{fname}` takes {} argument(s), found {}",
                            sig.params.len(),
                            items.len() - 1
                        ),
                    ));
                }
                let mut targs = Vec::new();
                for (a, p) in items[1..].iter().zip(&sig.params) {
                    let (t, ty) = self.term(a)?;
                    if !self.type_fits(&t, ty, p.ty) {
                        return Err(self.src.error(
                            a.span(),
                            format!(
                                "argument `{}` of `{fname}` has type `{}`, expected `{}`",
                                t.text(),
                                self.type_name(ty),
                                self.type_name(p.ty)
                            ),
                        ));
                    }
                    targs.push(t);
                }
                CostAmount::Function {
                    function: fi,
                    args: targs,
                }
            }
        };
        Ok(CostIncrease { amount, span })
    }
}
