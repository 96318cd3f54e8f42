//! The abstract syntax tree of a typed STRIPS domain and problem. Every name carries the byte
//! [`Span`] it was read from, so later stages (grounding, validation) can point at the source.
//! All names are lower case (PDDL is case-insensitive).

use super::error::{PddlError, SourceMap, Span};

/// A lower-cased name (or `?variable`) with where it was written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Name {
    /// The text, lower case; variables keep their `?`.
    pub text: String,
    /// Where it was written.
    pub span: Span,
}

/// A name with its declared type (`object` when untyped): parameters, constants, objects.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TypedName {
    /// The declared name.
    pub name: Name,
    /// Index of its type in [`Domain::types`].
    pub ty: usize,
}

/// A type and its parent in the hierarchy (`object` is index 0 and has no parent).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TypeDecl {
    /// The type's name.
    pub name: Name,
    /// Index of the parent type; `None` only for `object`.
    pub parent: Option<usize>,
}

/// A predicate or function signature.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Signature {
    /// Its name.
    pub name: Name,
    /// Typed parameters.
    pub params: Vec<TypedName>,
}

/// An argument: a variable (action parameter, by index) or an object/constant (by name).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Term {
    /// The `i`-th parameter of the enclosing action.
    Var(usize, Name),
    /// A constant of the domain or an object of the problem.
    Const(Name),
}

impl Term {
    /// The term as written (lower case).
    pub fn text(&self) -> &str {
        match self {
            Term::Var(_, n) | Term::Const(n) => &n.text,
        }
    }
}

/// An atomic formula `(predicate arg …)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Atom {
    /// Index of the predicate in [`Domain::predicates`].
    pub predicate: usize,
    /// The arguments, as many as the predicate's arity.
    pub args: Vec<Term>,
    /// The whole `( … )`.
    pub span: Span,
}

/// A condition (precondition or goal): `and`, `or`, `not`, `=` and atoms.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Formula {
    /// An atom.
    Atom(Atom),
    /// `(= a b)`: both terms denote the same object.
    Eq(Term, Term, Span),
    /// `(not φ)`.
    Not(Box<Formula>, Span),
    /// `(and φ …)`; empty is true.
    And(Vec<Formula>, Span),
    /// `(or φ …)`; empty is false.
    Or(Vec<Formula>, Span),
}

impl Formula {
    /// Where the formula was written.
    pub fn span(&self) -> Span {
        match self {
            Formula::Atom(a) => a.span,
            Formula::Eq(_, _, s) | Formula::Not(_, s) | Formula::And(_, s) | Formula::Or(_, s) => {
                *s
            }
        }
    }
}

/// The amount of an `(increase (total-cost) …)` effect.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CostAmount {
    /// A non-negative integer.
    Constant(u64),
    /// A static function term whose value is given by `(= (f a …) N)` in the problem's init.
    Function {
        /// Index of the function in [`Domain::functions`].
        function: usize,
        /// Its arguments.
        args: Vec<Term>,
    },
}

/// One `(increase (total-cost) amount)` effect.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CostIncrease {
    /// How much.
    pub amount: CostAmount,
    /// The whole `(increase …)`.
    pub span: Span,
}

/// The effect of an action: atoms made true, made false, and the cost increase.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Effect {
    /// Atoms made true.
    pub add: Vec<Atom>,
    /// Atoms made false (`(not …)`).
    pub del: Vec<Atom>,
    /// `(increase (total-cost) …)` effects (summed).
    pub cost: Vec<CostIncrease>,
}

/// An action schema.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Action {
    /// Its name.
    pub name: Name,
    /// Typed parameters; [`Term::Var`] indexes into this list.
    pub params: Vec<TypedName>,
    /// The precondition (an empty `and` when absent).
    pub precondition: Formula,
    /// The effect.
    pub effect: Effect,
    /// The whole `(:action …)`.
    pub span: Span,
}

/// A parsed domain.
#[derive(Clone, Debug)]
pub struct Domain {
    /// `(domain NAME)`.
    pub name: Name,
    /// Declared requirement flags (`:strips`, `:typing`, …).
    pub requirements: Vec<Name>,
    /// The type hierarchy; index 0 is `object`.
    pub types: Vec<TypeDecl>,
    /// Domain constants.
    pub constants: Vec<TypedName>,
    /// Predicate signatures.
    pub predicates: Vec<Signature>,
    /// Function signatures (`total-cost` and static cost functions).
    pub functions: Vec<Signature>,
    /// Action schemas.
    pub actions: Vec<Action>,
    pub(crate) source: SourceMap,
}

/// A value `(= (f a …) N)` of a static cost function in the problem's init.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FunctionValue {
    /// Index of the function in [`Domain::functions`].
    pub function: usize,
    /// The object arguments.
    pub args: Vec<Name>,
    /// The value.
    pub value: u64,
    /// The whole `(= …)`.
    pub span: Span,
}

/// A parsed problem (checked against its domain).
#[derive(Clone, Debug)]
pub struct Problem {
    /// `(problem NAME)`.
    pub name: Name,
    /// `(:domain NAME)`.
    pub domain_name: Name,
    /// Problem objects (the domain's constants are not repeated here).
    pub objects: Vec<TypedName>,
    /// Initial atoms (ground: every argument is [`Term::Const`]).
    pub init: Vec<Atom>,
    /// Initial values of cost functions.
    pub function_values: Vec<FunctionValue>,
    /// The goal (ground).
    pub goal: Formula,
    /// Whether the problem asks `(:metric minimize (total-cost))`.
    pub minimize_total_cost: bool,
    pub(crate) source: SourceMap,
}

impl Domain {
    /// Index of a type by (lower-case) name.
    pub fn type_index(&self, name: &str) -> Option<usize> {
        self.types.iter().position(|t| t.name.text == name)
    }

    /// Whether type `sub` is `sup` or one of its descendants.
    pub fn is_subtype(&self, sub: usize, sup: usize) -> bool {
        let mut t = Some(sub);
        // The hierarchy is checked acyclic at parse time; bound the walk anyway.
        for _ in 0..=self.types.len() {
            match t {
                Some(x) if x == sup => return true,
                Some(x) => t = self.types.get(x).and_then(|d| d.parent),
                None => return false,
            }
        }
        false
    }

    /// Index of a predicate by name.
    pub fn predicate_index(&self, name: &str) -> Option<usize> {
        self.predicates.iter().position(|p| p.name.text == name)
    }

    /// Index of an action by name.
    pub fn action_index(&self, name: &str) -> Option<usize> {
        self.actions.iter().position(|a| a.name.text == name)
    }

    /// The file name the domain was read from.
    pub fn file(&self) -> &str {
        &self.source.file
    }

    /// An error located at `span` of the domain file.
    pub fn error_at(&self, span: Span, message: impl Into<String>) -> PddlError {
        self.source.error(span, message)
    }

    /// An atom printed in IPC form, with `binding` substituted for the action's variables (a
    /// ground atom needs none).
    pub(crate) fn atom_text(&self, atom: &Atom, binding: &[&str]) -> String {
        let mut s = format!("({}", self.predicates[atom.predicate].name.text);
        for t in &atom.args {
            s.push(' ');
            match t {
                Term::Var(i, n) => s.push_str(binding.get(*i).copied().unwrap_or(&n.text)),
                Term::Const(n) => s.push_str(&n.text),
            }
        }
        s.push(')');
        s
    }
}

impl Problem {
    /// The file name the problem was read from.
    pub fn file(&self) -> &str {
        &self.source.file
    }

    /// An error located at `span` of the problem file.
    pub fn error_at(&self, span: Span, message: impl Into<String>) -> PddlError {
        self.source.error(span, message)
    }
}
