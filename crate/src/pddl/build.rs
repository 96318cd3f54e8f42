//! Problems assembled without PDDL text: objects and initial atoms from a program (a scene), the
//! goal, metric and cost values from a template problem or none.
//!
//! The loop re-grounds whenever its world holds objects the template problem does not declare;
//! the recorder grounds the scene it is given. Both assemble a [`Problem`] here instead of
//! writing PDDL text and parsing it again.

use std::collections::{BTreeSet, HashMap};

use super::ast::{Domain, Formula, Name, Problem, Term, TypedName};
use super::error::{PddlError, SourceMap, Span};

/// An object to declare: its name and the name of its type (lower case).
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ObjectDecl {
    /// The object's name.
    pub name: String,
    /// Its type, declared by the domain.
    pub ty: String,
}

/// Assembles a [`Problem`] of a domain from objects and ground atoms.
///
/// * [`ProblemBuilder::new`] starts from nothing (goal `(and)`, no metric);
///   [`ProblemBuilder::from_template`] keeps a parsed problem's name, goal, metric and the cost
///   values of objects that stay declared.
/// * A name that is a domain constant is not declared again.
/// * [`ProblemBuilder::build`] checks every object's type, every atom against the predicates
///   and objects, and that the goal names declared objects only.
///
/// ```
/// use logic_lfd::pddl::{parse_domain, ObjectDecl, ProblemBuilder};
/// let d = parse_domain("(define (domain d) (:types box) (:predicates (in ?b - box)))", "d.pddl")
///     .unwrap();
/// let p = ProblemBuilder::new(&d, "now")
///     .objects([ObjectDecl { name: "b1".into(), ty: "box".into() }])
///     .init(["(in b1)".to_string()])
///     .build()
///     .unwrap();
/// assert_eq!((p.objects.len(), p.init.len()), (1, 1));
/// ```
#[derive(Clone, Debug)]
pub struct ProblemBuilder<'d> {
    domain: &'d Domain,
    template: Option<&'d Problem>,
    name: String,
    objects: Vec<ObjectDecl>,
    init: Vec<String>,
}

impl<'d> ProblemBuilder<'d> {
    /// A problem named `name` with no objects, no initial atoms and the empty goal.
    pub fn new(domain: &'d Domain, name: &str) -> Self {
        ProblemBuilder {
            domain,
            template: None,
            name: name.to_string(),
            objects: Vec::new(),
            init: Vec::new(),
        }
    }

    /// A problem with `template`'s name, goal and metric (and the cost values of its objects
    /// that are declared again), but objects and initial atoms still to give.
    pub fn from_template(domain: &'d Domain, template: &'d Problem) -> Self {
        ProblemBuilder {
            domain,
            template: Some(template),
            name: template.name.text.clone(),
            objects: Vec::new(),
            init: Vec::new(),
        }
    }

    /// Declares objects (in order; a repeated name is declared once).
    pub fn objects(mut self, objects: impl IntoIterator<Item = ObjectDecl>) -> Self {
        self.objects.extend(objects);
        self
    }

    /// Adds initial atoms, `(predicate object …)` each.
    pub fn init(mut self, atoms: impl IntoIterator<Item = String>) -> Self {
        self.init.extend(atoms);
        self
    }

    /// The problem.
    ///
    /// # Errors
    /// An object whose type the domain does not declare (file `<objects>`); an atom naming an
    /// unknown predicate or object, or mistyped (located in the atoms joined one a line, file
    /// `<init>`); a goal atom naming an object no longer declared (located in the template).
    pub fn build(self) -> Result<Problem, PddlError> {
        let domain = self.domain;
        let constants: BTreeSet<&str> = domain
            .constants
            .iter()
            .map(|c| c.name.text.as_str())
            .collect();
        let mut seen = BTreeSet::new();
        let mut objects = Vec::new();
        for (i, o) in self.objects.iter().enumerate() {
            if constants.contains(o.name.as_str()) || !seen.insert(o.name.as_str()) {
                continue;
            }
            let ty = domain.type_index(&o.ty).ok_or_else(|| PddlError {
                file: "<objects>".into(),
                line: i + 1,
                col: 1,
                message: format!(
                    "object `{}` has type `{}`, which the domain does not declare",
                    o.name, o.ty
                ),
            })?;
            objects.push(TypedName {
                name: unlocated(&o.name),
                ty,
            });
        }
        let declared: HashMap<&str, usize> = domain
            .constants
            .iter()
            .chain(&objects)
            .map(|o| (o.name.text.as_str(), o.ty))
            .collect();
        let (goal, function_values, minimize_total_cost, source) = match self.template {
            Some(t) => {
                check_goal_objects(&t.goal, &declared, &t.source)?;
                let values = t
                    .function_values
                    .iter()
                    .filter(|v| {
                        v.args
                            .iter()
                            .all(|a| declared.contains_key(a.text.as_str()))
                    })
                    .cloned()
                    .collect();
                (
                    t.goal.clone(),
                    values,
                    t.minimize_total_cost,
                    t.source.clone(),
                )
            }
            None => (
                Formula::And(Vec::new(), Span::default()),
                Vec::new(),
                false,
                SourceMap::new("", "<problem>"),
            ),
        };
        let shell = Problem {
            name: unlocated(&self.name),
            domain_name: unlocated(&domain.name.text),
            objects,
            init: Vec::new(),
            function_values,
            goal,
            minimize_total_cost,
            source,
        };
        shell.with_ground_init(domain, &self.init)
    }
}

fn unlocated(text: &str) -> Name {
    Name {
        text: text.to_string(),
        span: Span::default(),
    }
}

/// Every object the goal names must be declared (it was, in the template's own objects).
fn check_goal_objects(
    goal: &Formula,
    declared: &HashMap<&str, usize>,
    src: &SourceMap,
) -> Result<(), PddlError> {
    // A variable never occurs in a ground goal; a constant must be declared.
    let declared_term = |t: &Term| -> Result<(), PddlError> {
        match t {
            Term::Const(name) if !declared.contains_key(name.text.as_str()) => Err(src.error(
                name.span,
                format!(
                    "the goal names `{}`, which is no longer an object of the problem",
                    name.text
                ),
            )),
            _ => Ok(()),
        }
    };
    match goal {
        Formula::Atom(a) => a.args.iter().try_for_each(declared_term),
        Formula::Eq(a, b, _) => [a, b].into_iter().try_for_each(declared_term),
        Formula::Not(f, _) => check_goal_objects(f, declared, src),
        Formula::And(fs, _) | Formula::Or(fs, _) => fs
            .iter()
            .try_for_each(|f| check_goal_objects(f, declared, src)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pddl::{parse_domain, parse_problem};

    const DOMAIN: &str = "(define (domain d) (:requirements :typing :action-costs)
      (:types box room) (:constants hall - room)
      (:predicates (in ?b - box ?r - room) (open ?r - room))
      (:functions (total-cost) (weight ?b - box)))";
    const PROBLEM: &str = "(define (problem p) (:domain d) (:objects b1 b2 - box r1 - room)
      (:init (in b1 r1) (= (weight b1) 3) (= (weight b2) 4))
      (:goal (and (in b1 hall) (open r1))) (:metric minimize (total-cost)))";

    fn decl(name: &str, ty: &str) -> ObjectDecl {
        ObjectDecl {
            name: name.into(),
            ty: ty.into(),
        }
    }

    #[test]
    fn a_built_problem_equals_the_parsed_text_of_the_same_problem() {
        let d = parse_domain(DOMAIN, "d.pddl").unwrap();
        let t = parse_problem(PROBLEM, "p.pddl", &d).unwrap();
        let built = ProblemBuilder::from_template(&d, &t)
            .objects([decl("b1", "box"), decl("r1", "room"), decl("hall", "room")])
            .init(["(in b1 r1)".to_string(), "(open hall)".to_string()])
            .build()
            .unwrap();
        let text = "(define (problem p) (:domain d) (:objects b1 - box r1 - room)
          (:init (in b1 r1) (open hall) (= (weight b1) 3))
          (:goal (and (in b1 hall) (open r1))) (:metric minimize (total-cost)))";
        let parsed = parse_problem(text, "q.pddl", &d).unwrap();
        let names = |p: &Problem| -> Vec<String> {
            p.objects.iter().map(|o| o.name.text.clone()).collect()
        };
        assert_eq!(
            names(&built),
            names(&parsed),
            "the constant `hall` is not redeclared"
        );
        let atoms =
            |p: &Problem| -> Vec<String> { p.init.iter().map(|a| d.atom_text(a, &[])).collect() };
        assert_eq!(atoms(&built), atoms(&parsed));
        assert_eq!(built.function_values.len(), 1, "b2's weight goes with b2");
        assert_eq!(built.function_values[0].value, 3);
        assert!(built.minimize_total_cost);
        assert_eq!(built.goal, t.goal, "the template's goal");
    }

    #[test]
    fn bad_parts_are_refused_with_where_and_what() {
        let d = parse_domain(DOMAIN, "d.pddl").unwrap();
        let t = parse_problem(PROBLEM, "p.pddl", &d).unwrap();
        let e = ProblemBuilder::from_template(&d, &t)
            .objects([decl("b1", "box"), decl("x", "crate")])
            .build()
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "<objects>:2:1: object `x` has type `crate`, which the domain does not declare"
        );
        let e = ProblemBuilder::from_template(&d, &t)
            .objects([decl("b1", "box")])
            .build()
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "p.pddl:3:38: the goal names `r1`, which is no longer an object of the problem"
        );
        let e = ProblemBuilder::new(&d, "s")
            .objects([decl("b1", "box")])
            .init(["(in b1 b1)".to_string()])
            .build()
            .unwrap_err();
        assert!(e.to_string().starts_with("<init>:1:"), "{e}");
    }
}
