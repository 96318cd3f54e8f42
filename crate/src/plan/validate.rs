//! The plan validator, working on the LIFTED domain so that it is independent of grounding.
//!
//! Semantics (PDDL, closed world): a state `s` is the set of all true ground atoms (static and
//! fluent). Step `a(o₁ … oₙ)` is applicable iff its precondition `φ[x⃗ := o⃗]` holds in `s`; then
//! `s' = (s \ del) ∪ add` (deletes first). The plan is valid iff every step is applicable in turn
//! and the goal holds in the final state. Its cost is `Σ (increase (total-cost) …)` amounts under
//! `(:metric minimize (total-cost))`, else the number of steps.
//!
//! The report names the first failing step and the precondition literals that are false there
//! (a false `or` is printed whole), or the goal literals that are false at the end.

use std::collections::{HashMap, HashSet};
use std::fmt;

use crate::pddl::{did_you_mean, CostAmount, Domain, Formula, PddlError, Problem, Span, Term};

/// A token of a plan file, lower case, with its location.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PlanToken {
    /// The text, lower case.
    pub text: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column (characters).
    pub col: usize,
}

/// One step `(action arg …)` of a plan, as read from a plan file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PlanStep {
    /// The plan file's name (for messages).
    pub file: String,
    /// The action name.
    pub action: PlanToken,
    /// The object arguments.
    pub args: Vec<PlanToken>,
    /// Location of the step's `(`.
    pub line: usize,
    /// Column of the step's `(`.
    pub col: usize,
}

impl PlanStep {
    /// The step as printed in plans: `(stack a b)`.
    pub fn text(&self) -> String {
        let mut s = format!("({}", self.action.text);
        for a in &self.args {
            s.push(' ');
            s.push_str(&a.text);
        }
        s.push(')');
        s
    }

    fn error(&self, tok: Option<&PlanToken>, message: String) -> PddlError {
        let (line, col) = tok.map_or((self.line, self.col), |t| (t.line, t.col));
        PddlError {
            file: self.file.clone(),
            line,
            col,
            message,
        }
    }
}

/// Parses a plan file: one `(action arg …)` per line, `;` comments and blank lines allowed,
/// case-insensitive. Names are checked against the domain by [`validate`].
pub fn parse_plan(text: &str, file: &str) -> Result<Vec<PlanStep>, PddlError> {
    let src = crate::pddl::SourceMap::new(text, file);
    let lists = crate::pddl::read_many(&src)?;
    let tok = |text: &str, span: Span| {
        let (line, col) = src.line_col(span.start);
        PlanToken {
            text: text.to_string(),
            line,
            col,
        }
    };
    let mut steps = Vec::with_capacity(lists.len());
    for l in lists {
        let crate::pddl::SExpr::List(items, span) = l else {
            continue;
        };
        let (line, col) = src.line_col(span.start);
        let Some(first) = items.first() else {
            return Err(src.error(span, "empty plan step `()`"));
        };
        let mut toks = items
            .iter()
            .map(|e| tok(e.atom().unwrap_or_default(), e.span()));
        let action = toks.next().unwrap_or_else(|| tok("", first.span()));
        steps.push(PlanStep {
            file: file.to_string(),
            action,
            args: toks.collect(),
            line,
            col,
        });
    }
    Ok(steps)
}

/// How a validation ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Every step applied and the goal holds.
    Valid,
    /// A step names an unknown action or object, has the wrong arity or a mistyped argument, or
    /// a cost function has no value: bad input, located.
    Malformed(PddlError),
    /// A step's precondition is false.
    PreconditionFalse {
        /// 1-based step number.
        step: usize,
        /// The step, `(stack a b)`.
        action: String,
        /// Where the step is in the plan file.
        location: String,
        /// The false precondition literals, printed ground.
        false_literals: Vec<String>,
    },
    /// All steps applied but the goal does not hold.
    GoalNotReached {
        /// The false goal literals.
        false_literals: Vec<String>,
    },
}

/// The result of [`validate`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ValidationReport {
    /// How it ended.
    pub outcome: Outcome,
    /// Steps applied before the end (all of them when valid).
    pub steps_applied: usize,
    /// Cost of the applied steps.
    pub cost: u64,
}

impl ValidationReport {
    /// Whether the plan is valid.
    pub fn is_valid(&self) -> bool {
        self.outcome == Outcome::Valid
    }

    /// The 1-based step whose precondition is false, if that is the verdict.
    pub fn failed_step(&self) -> Option<usize> {
        match &self.outcome {
            Outcome::PreconditionFalse { step, .. } => Some(*step),
            _ => None,
        }
    }

    /// The false precondition or goal literals of the verdict (none when valid or malformed).
    pub fn false_literals(&self) -> &[String] {
        match &self.outcome {
            Outcome::PreconditionFalse { false_literals, .. }
            | Outcome::GoalNotReached { false_literals } => false_literals,
            Outcome::Valid | Outcome::Malformed(_) => &[],
        }
    }
}

impl fmt::Display for ValidationReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.outcome {
            Outcome::Valid => write!(f, "Plan valid, cost {}", self.cost),
            Outcome::Malformed(e) => write!(f, "{e}"),
            Outcome::PreconditionFalse {
                step,
                action,
                location,
                false_literals,
            } => write!(
                f,
                "{location}: step {step} {action} is not applicable: false precondition(s): {}",
                false_literals.join(" ")
            ),
            Outcome::GoalNotReached { false_literals } => write!(
                f,
                "all {} step(s) applied (cost {}) but the goal does not hold: false goal literal(s): {}",
                self.steps_applied,
                self.cost,
                false_literals.join(" ")
            ),
        }
    }
}

type GroundAtom = (usize, Vec<u32>);

/// The lifted state a plan is replayed in: the objects by name and the true ground atoms.
struct LiftedState<'a> {
    domain: &'a Domain,
    names: Vec<&'a str>,
    index: HashMap<&'a str, (u32, usize)>,
    state: HashSet<GroundAtom>,
}

impl LiftedState<'_> {
    fn obj(&self, t: &Term, b: &[u32]) -> u32 {
        match t {
            Term::Var(i, _) => b.get(*i).copied().unwrap_or(u32::MAX),
            Term::Const(n) => self.index.get(n.text.as_str()).map_or(u32::MAX, |x| x.0),
        }
    }

    fn atom(&self, a: &crate::pddl::Atom, b: &[u32]) -> GroundAtom {
        (a.predicate, a.args.iter().map(|t| self.obj(t, b)).collect())
    }

    fn holds(&self, f: &Formula, b: &[u32]) -> bool {
        match f {
            Formula::Atom(a) => self.state.contains(&self.atom(a, b)),
            Formula::Eq(x, y, _) => self.obj(x, b) == self.obj(y, b),
            Formula::Not(g, _) => !self.holds(g, b),
            Formula::And(p, _) => p.iter().all(|g| self.holds(g, b)),
            Formula::Or(p, _) => p.iter().any(|g| self.holds(g, b)),
        }
    }

    fn term_text(&self, t: &Term, b: &[u32]) -> String {
        let o = self.obj(t, b);
        self.names
            .get(o as usize)
            .map_or_else(|| t.text().to_string(), |s| s.to_string())
    }

    fn render(&self, f: &Formula, b: &[u32]) -> String {
        match f {
            Formula::Atom(a) => {
                let mut s = format!("({}", self.domain.predicates[a.predicate].name.text);
                for t in &a.args {
                    s.push(' ');
                    s.push_str(&self.term_text(t, b));
                }
                s + ")"
            }
            Formula::Eq(x, y, _) => {
                format!("(= {} {})", self.term_text(x, b), self.term_text(y, b))
            }
            Formula::Not(g, _) => format!("(not {})", self.render(g, b)),
            Formula::And(p, _) | Formula::Or(p, _) => {
                let mut s = if matches!(f, Formula::And(..)) {
                    "(and".to_string()
                } else {
                    "(or".to_string()
                };
                for g in p {
                    s.push(' ');
                    s.push_str(&self.render(g, b));
                }
                s + ")"
            }
        }
    }

    /// The false parts of `f`: conjunctions are opened, anything else is printed whole.
    fn explain(&self, f: &Formula, b: &[u32], out: &mut Vec<String>) {
        if self.holds(f, b) {
            return;
        }
        match f {
            Formula::And(p, _) => p.iter().for_each(|g| self.explain(g, b, out)),
            _ => out.push(self.render(f, b)),
        }
    }
}

/// Replays `plan` from the problem's initial state and checks the goal (see the module header).
pub fn validate(domain: &Domain, problem: &Problem, plan: &[PlanStep]) -> ValidationReport {
    let all: Vec<_> = domain.constants.iter().chain(&problem.objects).collect();
    let names: Vec<&str> = all.iter().map(|o| o.name.text.as_str()).collect();
    let index: HashMap<&str, (u32, usize)> = all
        .iter()
        .enumerate()
        .map(|(i, o)| (o.name.text.as_str(), (i as u32, o.ty)))
        .collect();
    let mut w = LiftedState {
        domain,
        names,
        index,
        state: HashSet::new(),
    };
    for a in &problem.init {
        let g = w.atom(a, &[]);
        w.state.insert(g);
    }
    let values: HashMap<(usize, Vec<u32>), u64> = problem
        .function_values
        .iter()
        .map(|v| {
            let args = v
                .args
                .iter()
                .map(|n| w.index.get(n.text.as_str()).map_or(u32::MAX, |x| x.0))
                .collect();
            ((v.function, args), v.value)
        })
        .collect();
    let mut report = ValidationReport {
        outcome: Outcome::Valid,
        steps_applied: 0,
        cost: 0,
    };
    for (k, step) in plan.iter().enumerate() {
        let Some(ai) = domain.action_index(&step.action.text) else {
            report.outcome = Outcome::Malformed(step.error(
                Some(&step.action),
                format!(
                    "unknown action `{}`{}",
                    step.action.text,
                    did_you_mean(
                        &step.action.text,
                        domain.actions.iter().map(|a| a.name.text.as_str())
                    )
                ),
            ));
            return report;
        };
        let act = &domain.actions[ai];
        if step.args.len() != act.params.len() {
            report.outcome = Outcome::Malformed(step.error(
                None,
                format!(
                    "action `{}` takes {} argument(s), found {}",
                    act.name.text,
                    act.params.len(),
                    step.args.len()
                ),
            ));
            return report;
        }
        let mut b = Vec::with_capacity(step.args.len());
        for (tok, p) in step.args.iter().zip(&act.params) {
            let Some(&(o, ty)) = w.index.get(tok.text.as_str()) else {
                report.outcome = Outcome::Malformed(step.error(
                    Some(tok),
                    format!(
                        "unknown object `{}`{}",
                        tok.text,
                        did_you_mean(&tok.text, w.index.keys().copied())
                    ),
                ));
                return report;
            };
            if !domain.is_subtype(ty, p.ty) {
                report.outcome = Outcome::Malformed(step.error(
                    Some(tok),
                    format!(
                        "argument `{}` of `{}` has type `{}`, expected `{}`",
                        tok.text,
                        act.name.text,
                        domain.types[ty].name.text,
                        domain.types[p.ty].name.text
                    ),
                ));
                return report;
            }
            b.push(o);
        }
        if !w.holds(&act.precondition, &b) {
            let mut lits = Vec::new();
            w.explain(&act.precondition, &b, &mut lits);
            report.outcome = Outcome::PreconditionFalse {
                step: k + 1,
                action: step.text(),
                location: format!("{}:{}:{}", step.file, step.line, step.col),
                false_literals: lits,
            };
            return report;
        }
        let mut cost = 0u64;
        if problem.minimize_total_cost {
            for inc in &act.effect.cost {
                cost = cost.saturating_add(match &inc.amount {
                    CostAmount::Constant(c) => *c,
                    CostAmount::Function { function, args } => {
                        let key: Vec<u32> = args.iter().map(|t| w.obj(t, &b)).collect();
                        match values.get(&(*function, key)) {
                            Some(v) => *v,
                            None => {
                                let mut term =
                                    format!("({}", domain.functions[*function].name.text);
                                for t in args {
                                    term.push(' ');
                                    term.push_str(&w.term_text(t, &b));
                                }
                                term.push(')');
                                report.outcome = Outcome::Malformed(step.error(
                                    None,
                                    format!(
                                        "no value for `{term}` in the `:init` of {}",
                                        problem.file()
                                    ),
                                ));
                                return report;
                            }
                        }
                    }
                });
            }
        } else {
            cost = 1;
        }
        let del: Vec<GroundAtom> = act.effect.del.iter().map(|a| w.atom(a, &b)).collect();
        let add: Vec<GroundAtom> = act.effect.add.iter().map(|a| w.atom(a, &b)).collect();
        for g in &del {
            w.state.remove(g);
        }
        w.state.extend(add);
        report.steps_applied += 1;
        report.cost = report.cost.saturating_add(cost);
    }
    if !w.holds(&problem.goal, &[]) {
        let mut lits = Vec::new();
        w.explain(&problem.goal, &[], &mut lits);
        report.outcome = Outcome::GoalNotReached {
            false_literals: lits,
        };
    }
    report
}

/// Validates a plan given as operator names, `["(unstack a b)", "(put-down a)"]` — how searches
/// return plans.
pub fn validate_names(domain: &Domain, problem: &Problem, plan: &[String]) -> ValidationReport {
    match parse_plan(&plan.join("\n"), "<plan>") {
        Ok(steps) => validate(domain, problem, &steps),
        Err(e) => ValidationReport {
            outcome: Outcome::Malformed(e),
            steps_applied: 0,
            cost: 0,
        },
    }
}
