//! Observed states: any set of ground atoms over the problem's objects and the domain's
//! predicates is a state (what a camera or the simulator's L3 disturbance produces), including
//! facts no action adds and static facts that differ from the problem's `:init`.
//!
//! The grounded task holds only the fluents reachable from `:init`, so its bitset states cannot
//! hold such facts. A state whose atoms the task already knows (fluents, or static facts it
//! holds) stays a state of that task: nothing is re-grounded. Any other state becomes the initial
//! state of the problem re-grounded with the observed atoms as `:init`: that task knows the
//! observed facts and the operators they enable, drops the operators whose static preconditions
//! the observation made false, and compiles the demonstration's L_k from their fact names, so
//! LogicIn, replanning and the lifted validator all run on the state as observed.
//!
//! Static predicates (no action adds or deletes them): the state's atoms of such a predicate
//! replace the problem's; a static predicate the state does not mention keeps its `:init` atoms.
//! Atoms the problem makes true and no action changes may be listed or left out.

use std::collections::{BTreeMap, BTreeSet};

use crate::pddl::{Domain, Formula, LocatedFact, PddlError, Problem};
use crate::plan::{self, Clock, FactId, SearchConfig, SearchResult, State, Task, ValidationReport};

use super::super::catalogue::Mode;
use super::super::logic::LfdPlan;
use super::super::LfdError;
use super::{unlocated_facts, LogicLfd};

/// A state read by [`LogicLfd::state`], with the [`LogicLfd`] whose task it is a state of: the
/// one it was read by, or one re-grounded with the observed atoms as `:init`.
///
/// Its methods (LogicIn, replanning, validation) run on that instance, so a plan found for an
/// observed state is a plan from the state as observed.
#[derive(Clone, Debug)]
pub struct Observed<'a> {
    instance: Instance<'a>,
    state: State,
}

#[derive(Clone, Debug)]
enum Instance<'a> {
    /// The state is a state of the reader's own task.
    Known(&'a LogicLfd),
    /// The problem re-grounded from the observed atoms, and the state's atoms by name.
    Regrounded(Box<LogicLfd>, Vec<String>),
}

/// Observed states of a [`LogicLfd`] instance.
impl LogicLfd {
    /// Reads a state written as PDDL atoms (one a line or space-separated; `;` comments). Any
    /// set of atoms over the problem's objects and the domain's predicates is a state: facts no
    /// action adds and static facts that differ from the problem's `:init` are kept (see
    /// [`Observed`]). Locations refer to a file `state`.
    ///
    /// # Errors
    /// [`LfdError::Input`] naming the atom, at `line:col`: an undeclared predicate or object, or
    /// a wrong arity or type; [`LfdError::Model`] when the problem cannot be grounded again from
    /// the observed atoms.
    pub fn state(&self, facts: &str) -> Result<Observed<'_>, LfdError> {
        self.state_in("state", facts)
    }

    /// [`LogicLfd::state`] with the file name used in error locations.
    pub fn state_in(&self, file: &str, facts: &str) -> Result<Observed<'_>, LfdError> {
        let located = match self.source.as_deref() {
            Some((d, p)) => p.read_facts(d, facts, file)?,
            None => unlocated_facts(facts, file)?,
        };
        observe(self, file, located)
    }

    /// A state of this instance's task (e.g. [`LogicLfd::state_after`]'s, or the initial
    /// state) as an [`Observed`] state.
    pub fn observed(&self, state: State) -> Observed<'_> {
        Observed::known(self, state)
    }
}

impl<'a> Observed<'a> {
    /// A state of `lfd`'s own task.
    pub(super) fn known(lfd: &'a LogicLfd, state: State) -> Self {
        Observed {
            instance: Instance::Known(lfd),
            state,
        }
    }

    /// The instance the state belongs to (its task, demonstration states and lifted problem).
    pub fn lfd(&self) -> &LogicLfd {
        match &self.instance {
            Instance::Known(l) => l,
            Instance::Regrounded(l, _) => l,
        }
    }

    /// The state, in the task of [`Observed::lfd`].
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Whether the observation needed a task of its own (facts the problem's task cannot hold,
    /// or static facts that differ from its `:init`).
    pub fn is_regrounded(&self) -> bool {
        matches!(self.instance, Instance::Regrounded(..))
    }

    /// The atoms of the state by name, sorted: its fluents, and for a re-grounded state also
    /// the observed atoms that only its own task holds as static facts (a fact no action adds
    /// or deletes, a static fact the problem's `:init` does not have).
    pub fn names(&self) -> Vec<String> {
        match &self.instance {
            Instance::Known(l) => l.names(&self.state),
            Instance::Regrounded(_, names) => names.clone(),
        }
    }

    /// The actions applicable in the state, in operator order.
    pub fn applicable(&self) -> impl Iterator<Item = &str> {
        let s = &self.state;
        let ops = &self.lfd().task().operators;
        ops.iter()
            .filter(|o| o.applicable(s))
            .map(|o| o.name.as_str())
    }

    /// LogicIn(S_C, 𝒢): the largest k with L_k ⊆ S_C, if any ([`LogicLfd::logic_in`]); `None`
    /// when the observed static facts make the goal false for ever.
    pub fn logic_in(&self) -> Option<usize> {
        if self.goal_impossible() {
            return None;
        }
        self.lfd().logic_in(&self.state)
    }

    /// Whether grounding found the goal false whatever the actions do (a static literal of
    /// every alternative is false): the demonstration's suffixes cannot reach it either.
    fn goal_impossible(&self) -> bool {
        self.lfd().task().goal.alternatives.is_empty()
    }

    /// Logic-LfD from the state ([`LogicLfd::replan`]). When neither a demonstration state nor
    /// the goal can be reached, the error names the goal literals no action can make true any
    /// more, when the relaxed reachability analysis finds some.
    ///
    /// # Errors
    /// [`LfdError::NoPlan`] or [`LfdError::Budget`], as [`LogicLfd::replan`].
    pub fn replan(
        &self,
        mode: Mode,
        config: &SearchConfig,
        clock: &dyn Clock,
    ) -> Result<LfdPlan, LfdError> {
        let found = if self.goal_impossible() {
            Err(LfdError::NoPlan("the goal can never hold".into()))
        } else {
            self.lfd().replan(&self.state, mode, config, clock)
        };
        match found {
            Err(LfdError::NoPlan(why)) => {
                let lost = self.unreachable_goal_literals();
                Err(LfdError::NoPlan(if lost.is_empty() {
                    why
                } else {
                    format!(
                        "no demonstration state and not the goal can be reached from this state: \
                         no action can make the goal literal(s) {} true",
                        lost.join(" ")
                    )
                }))
            }
            other => other,
        }
    }

    /// Planning from the state straight to G ([`LogicLfd::plan_from_scratch`]).
    pub fn plan_from_scratch(&self, config: &SearchConfig, clock: &dyn Clock) -> SearchResult {
        self.lfd().plan_from_scratch(&self.state, config, clock)
    }

    /// Replays `plan` from the state on the lifted domain ([`LogicLfd::validate`]).
    ///
    /// # Errors
    /// [`LfdError::Model`] for an instance built without its PDDL.
    pub fn validate(&self, plan: &[String]) -> Result<ValidationReport, LfdError> {
        self.lfd().validate(&self.state, plan)
    }

    /// The goal literals that no sequence of actions can make true from the state, by relaxed
    /// reachability (negative preconditions ignored): a positive literal no reachable action
    /// adds, or a negative one whose atom holds and no reachable action deletes. Empty when the
    /// analysis finds none, or for an instance built without its PDDL.
    pub fn unreachable_goal_literals(&self) -> Vec<String> {
        let lfd = self.lfd();
        let Some((d, p)) = lfd.source.as_deref() else {
            return vec![];
        };
        let reach = Reach::new(lfd.task(), &self.state);
        let mut lost = vec![];
        reach.lost(d, &p.goal, &mut lost);
        lost.dedup();
        lost
    }
}

/// Reads located atoms as a state of `lfd` (see the module header).
pub(super) fn observe<'a>(
    lfd: &'a LogicLfd,
    file: &str,
    atoms: Vec<LocatedFact>,
) -> Result<Observed<'a>, LfdError> {
    let task = lfd.task();
    let source = lfd.source.as_deref();
    let mut statics: Option<StaticPredicates> = None;
    let mut s = task.empty_state();
    let mut unknown = false;
    let mut listed_statics: BTreeMap<usize, BTreeSet<String>> = BTreeMap::new();
    for f in &atoms {
        if let Some(id) = task.fact_id(&f.name) {
            s.insert(id);
            continue;
        }
        let Some((d, _)) = source else {
            if task.static_facts.contains(&f.name) {
                continue;
            }
            return Err(PddlError {
                file: file.to_string(),
                line: f.line,
                col: f.col,
                message: format!(
                    "`{}` is not a fact of this task, which was built without its PDDL and \
                     cannot be re-grounded",
                    f.name
                ),
            }
            .into());
        };
        let statics = statics.get_or_insert_with(|| StaticPredicates::of(d));
        match statics.index(plan::fact_args(&f.name).0) {
            Some(p) => {
                listed_statics.entry(p).or_default().insert(f.name.clone());
            }
            None if task.static_facts.contains(&f.name) => {}
            None => unknown = true,
        }
    }
    let Some((d, p)) = source.filter(|_| unknown || !listed_statics.is_empty()) else {
        return Ok(Observed::known(lfd, s));
    };
    let statics = statics.unwrap_or_else(|| StaticPredicates::of(d));
    let init_statics = init_static_atoms(d, p, &statics);
    let same_statics = listed_statics
        .iter()
        .all(|(pred, listed)| init_statics.get(pred) == Some(listed));
    if !unknown && same_statics {
        return Ok(Observed::known(lfd, s));
    }
    // The observed `:init`: the listed atoms, the static predicates the state leaves out as in
    // the problem, and the atoms the problem makes true that no action changes.
    let mut init: BTreeSet<String> = atoms.into_iter().map(|f| f.name).collect();
    for (pred, atoms) in init_statics {
        if !listed_statics.contains_key(&pred) {
            init.extend(atoms);
        }
    }
    let unchanged: Vec<String> = task
        .static_facts
        .iter()
        .filter(|f| statics.index(plan::fact_args(f).0).is_none())
        .cloned()
        .collect();
    init.extend(unchanged.iter().cloned());
    regrounded(lfd, d, p, &init.into_iter().collect::<Vec<_>>(), &unchanged)
}

/// `lfd`'s problem grounded again from `init`; its initial state is the observed state.
/// `unchanged` are the fluent-predicate atoms no action of `lfd`'s task changes: they held
/// throughout the demonstration, and the new task may let an action change them.
fn regrounded<'a>(
    lfd: &LogicLfd,
    d: &Domain,
    p: &Problem,
    init: &[String],
    unchanged: &[String],
) -> Result<Observed<'a>, LfdError> {
    let problem = p.with_init(d, init)?;
    let task = plan::ground(d, &problem).map_err(|e| LfdError::Model(e.to_string()))?;
    let mut trace = lfd.trace.clone();
    for l in &mut trace.states {
        l.extend(unchanged.iter().cloned());
    }
    let mut own = LogicLfd::from_task(task, trace);
    own.source = Some(Box::new((d.clone(), problem)));
    let state = own.task.init.clone();
    let mut names = own.names(&state);
    names.extend(
        own.task
            .static_facts
            .iter()
            .filter(|f| !lfd.task.static_facts.contains(f))
            .cloned(),
    );
    names.sort();
    Ok(Observed {
        state,
        instance: Instance::Regrounded(Box::new(own), names),
    })
}

/// The problem's `:init` atoms of static predicates, by predicate.
fn init_static_atoms(
    d: &Domain,
    p: &Problem,
    statics: &StaticPredicates,
) -> BTreeMap<usize, BTreeSet<String>> {
    let mut out: BTreeMap<usize, BTreeSet<String>> = BTreeMap::new();
    for a in p.init.iter().filter(|a| !statics.fluent[a.predicate]) {
        out.entry(a.predicate)
            .or_default()
            .insert(d.atom_text(a, &[]));
    }
    out
}

/// The domain's static predicates: those no action adds or deletes.
struct StaticPredicates<'d> {
    domain: &'d Domain,
    fluent: Vec<bool>,
}

impl<'d> StaticPredicates<'d> {
    fn of(domain: &'d Domain) -> Self {
        let mut fluent = vec![false; domain.predicates.len()];
        for a in &domain.actions {
            for at in a.effect.add.iter().chain(&a.effect.del) {
                fluent[at.predicate] = true;
            }
        }
        StaticPredicates { domain, fluent }
    }

    /// The index of `name` when it is a static predicate.
    fn index(&self, name: &str) -> Option<usize> {
        let p = self
            .domain
            .predicates
            .iter()
            .position(|s| s.name.text == name)?;
        (!self.fluent[p]).then_some(p)
    }
}

/// Relaxed reachability from a state: the facts some sequence of actions could make true if
/// no action deleted anything, and which of them a reachable action deletes.
struct Reach<'t> {
    task: &'t Task,
    state: &'t State,
    reached: Vec<bool>,
    deleted: Vec<bool>,
}

impl<'t> Reach<'t> {
    fn new(task: &'t Task, state: &'t State) -> Self {
        let n = task.facts.len();
        let mut reached: Vec<bool> = (0..n).map(|f| state.contains(f as FactId)).collect();
        let mut used = vec![false; task.operators.len()];
        let mut changed = true;
        while changed {
            changed = false;
            for (o, op) in task.operators.iter().enumerate() {
                if used[o] || !op.pre.iter().all(|&f| reached[f as usize]) {
                    continue;
                }
                used[o] = true;
                for &f in &op.add {
                    changed |= !std::mem::replace(&mut reached[f as usize], true);
                }
            }
        }
        let mut deleted = vec![false; n];
        for (op, _) in task.operators.iter().zip(&used).filter(|(_, &u)| u) {
            for &f in &op.del {
                deleted[f as usize] = true;
            }
        }
        Reach {
            task,
            state,
            reached,
            deleted,
        }
    }

    /// Whether the atom can become true (`positive`) or false again.
    fn possible(&self, atom: &str, positive: bool) -> bool {
        match self.task.fact_id(atom).map(|f| f as usize) {
            Some(f) if positive => self.reached[f],
            Some(f) => !self.state.contains(f as FactId) || self.deleted[f],
            // Not a fluent: true forever if a static fact of the task, else false forever.
            None => self.task.static_facts.iter().any(|f| f == atom) == positive,
        }
    }

    /// Whether `goal` can no longer be made true; if so, pushes the literals that cannot.
    fn lost(&self, d: &Domain, goal: &Formula, out: &mut Vec<String>) -> bool {
        match goal {
            Formula::Atom(a) => {
                let text = d.atom_text(a, &[]);
                let lost = !self.possible(&text, true);
                if lost {
                    out.push(text);
                }
                lost
            }
            Formula::Not(inner, _) => match inner.as_ref() {
                Formula::Atom(a) => {
                    let text = d.atom_text(a, &[]);
                    let lost = !self.possible(&text, false);
                    if lost {
                        out.push(format!("(not {text})"));
                    }
                    lost
                }
                Formula::Eq(a, b, _) if a.text() == b.text() => {
                    out.push(format!("(not (= {} {}))", a.text(), b.text()));
                    true
                }
                _ => false,
            },
            Formula::Eq(a, b, _) => {
                let lost = a.text() != b.text();
                if lost {
                    out.push(format!("(= {} {})", a.text(), b.text()));
                }
                lost
            }
            Formula::And(parts, _) => parts
                .iter()
                .fold(false, |lost, part| self.lost(d, part, out) | lost),
            Formula::Or(parts, _) => {
                let mut each = vec![];
                if parts.iter().all(|part| self.lost(d, part, &mut each)) {
                    out.extend(each);
                    true
                } else {
                    false
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{Algorithm, HeuristicKind, NoClock};

    /// Lamps are switched on; a broken lamp stays broken (no action adds or deletes `broken`).
    const DOMAIN: &str = "(define (domain lamps) (:requirements :strips :negative-preconditions)
      (:predicates (at ?r) (lit ?r) (broken ?r) (door ?a ?b))
      (:action go :parameters (?a ?b) :precondition (and (at ?a) (door ?a ?b))
        :effect (and (at ?b) (not (at ?a))))
      (:action switch-on :parameters (?r) :precondition (and (at ?r) (not (broken ?r)))
        :effect (lit ?r)))";
    const PROBLEM: &str = "(define (problem p) (:domain lamps) (:objects r1 r2)
      (:init (at r1) (door r1 r2) (door r2 r1))
      (:goal (and (lit r2) (not (broken r1)))))";
    const DEMO: &str = "(go r1 r2)\n(switch-on r2)\n";

    fn cfg() -> SearchConfig {
        SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut)
    }

    #[test]
    fn a_fact_no_action_removes_that_the_goal_needs_false_is_named() {
        let lfd = LogicLfd::new(DOMAIN, PROBLEM, DEMO).unwrap();
        let s = lfd.state("(at r1) (broken r1)").unwrap();
        assert!(s.is_regrounded());
        assert_eq!(s.unreachable_goal_literals(), ["(not (broken r1))"]);
        assert_eq!(
            s.logic_in(),
            None,
            "L_0 holds, but its suffix cannot reach the goal"
        );
        let e = s.replan(Mode::Paper, &cfg(), &NoClock).unwrap_err();
        assert!(e.to_string().contains("(not (broken r1))"), "{e}");
    }

    #[test]
    fn a_static_fact_that_disables_the_only_way_names_the_goal_atom() {
        let lfd = LogicLfd::new(DOMAIN, PROBLEM, DEMO).unwrap();
        // r2's lamp is broken: nothing can light it.
        let s = lfd.state("(at r1) (broken r2)").unwrap();
        assert!(s.is_regrounded());
        assert_eq!(s.unreachable_goal_literals(), ["(lit r2)"]);
        // Without its doors the robot cannot reach r2 either; a state with the doors as in
        // the problem is the problem's own state.
        let s = lfd.state("(at r1) (door r2 r1)").unwrap();
        assert_eq!(s.unreachable_goal_literals(), ["(lit r2)"]);
        let same = lfd.state("(at r1) (door r1 r2) (door r2 r1)").unwrap();
        assert!(!same.is_regrounded());
        assert!(same.unreachable_goal_literals().is_empty());
        let p = same.replan(Mode::Paper, &cfg(), &NoClock).unwrap();
        assert!(same.validate(&p.names).unwrap().is_valid());
    }
}
