//! PDDL front end: a lexer with byte spans, a parser (one file per construct), the AST with spans,
//! and errors located as `file:line:col`.
//!
//! Supported: typed STRIPS with `:negative-preconditions`, `:equality`,
//! `:disjunctive-preconditions` (and or-goals), constants, and `:action-costs`
//! (`(increase (total-cost) N)` with N an integer or a static function term). Names are
//! case-insensitive and lower-cased. Every other construct (quantifiers, conditional effects,
//! numeric fluents, durative actions, derived predicates, constraints, preferences, unknown
//! requirements, …) is refused **by name** at its location — never silently ignored.
//!
//! ```
//! let d = logic_lfd::pddl::parse_domain(
//!     "(define (domain d) (:predicates (p ?x)) (:action a :parameters (?x) :precondition (p ?x) :effect (not (p ?x))))",
//!     "d.pddl",
//! ).unwrap();
//! let p = logic_lfd::pddl::parse_problem(
//!     "(define (problem q) (:domain d) (:objects o) (:init (P O)) (:goal (not (p o))))",
//!     "q.pddl",
//!     &d,
//! ).unwrap();
//! assert_eq!(p.init.len(), 1);
//! let e = logic_lfd::pddl::parse_domain("(define (domain d)\n (:derived (p) (q)))", "bad.pddl").unwrap_err();
//! assert_eq!(e.to_string(), "bad.pddl:2:3: `:derived` is not supported: derived predicates are not supported");
//! ```

mod ast;
mod brackets;
mod build;
mod common;
mod domain;
mod error;
mod formula;
mod lexer;
mod problem;
mod suggest;

pub use ast::{
    Action, Atom, CostAmount, CostIncrease, Domain, Effect, Formula, FunctionValue, Name, Problem,
    Signature, Term, TypeDecl, TypedName,
};
pub use build::{ObjectDecl, ProblemBuilder};
pub use domain::parse_domain;
pub use error::{decode_source, read_source, PddlError, Source, Span};
pub use problem::{parse_problem, LocatedFact};

pub(crate) use error::SourceMap;
pub(crate) use lexer::{read_many, SExpr};
pub(crate) use suggest::did_you_mean;
