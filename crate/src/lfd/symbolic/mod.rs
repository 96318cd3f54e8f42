//! Logic-LfD on any PDDL domain: a domain, a problem and one demonstration plan in, merged plans
//! out (paper §III-C/D without the robot).
//!
//! [`LogicLfd`] is the one implementation of the method's task level: the reactive loop's
//! `Controller` holds one, the CLI's `lfd` command, the npm `logicLfd` and the page's PDDL tab
//! build one from text.

use crate::pddl::Source;
use std::collections::BTreeSet;
use std::sync::OnceLock;

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use crate::pddl::{self, Domain, Problem};
use crate::plan::{
    self, parse_plan, replay, validate, validate_names, BannedTask, Clock, MultiGoalSearch,
    Outcome, SearchConfig, SearchResult, State, Task, ValidationReport,
};

use super::catalogue::Mode;
use super::demo::{DemoTrace, MultiGoalSpec};
use super::logic::{plan_with, LfdPlan, PlanSource, Request};
use super::LfdError;
use crate::plan::SearchStats;

pub(super) mod observed;

/// Symbolic Logic-LfD: one demonstration of a PDDL task turned into the multi-goal
/// specification L_0 … L_N, G, and replanning from any state to the best L_k it can reach.
///
/// - [`LogicLfd::new`] reads a domain, a problem and the demonstration as an IPC plan file;
/// - [`LogicLfd::state`] / [`LogicLfd::state_after`] read a state (any atoms, or a plan prefix);
/// - [`LogicLfd::logic_in`] is LogicIn, [`LogicLfd::replan`] the multi-goal search merged with
///   the demonstration's suffix; [`LogicLfd::validate`] replays a plan on the lifted domain.
///
/// ```
/// use logic_lfd::prelude::*;
/// let domain = "(define (domain corridor) (:requirements :strips :typing) (:types room)
///   (:predicates (at ?r - room) (door ?a ?b - room) (lit ?r - room))
///   (:action go :parameters (?a ?b - room) :precondition (and (at ?a) (door ?a ?b))
///     :effect (and (at ?b) (not (at ?a))))
///   (:action switch-on :parameters (?r - room) :precondition (at ?r) :effect (lit ?r)))";
/// let problem = "(define (problem p) (:domain corridor) (:objects r1 r2 r3 - room)
///   (:init (at r1) (door r1 r2) (door r2 r1) (door r2 r3) (door r3 r2))
///   (:goal (and (lit r2) (lit r3))))";
/// let demo = "(go r1 r2)\n(switch-on r2)\n(go r2 r3)\n(switch-on r3)\n";
/// let lfd = LogicLfd::new(domain, problem, demo).unwrap();
/// assert_eq!(lfd.demo_states().len(), 5); // L_0 … L_4
/// // Someone carried the robot to r3 and it switched r3 on; r2 is still dark.
/// let s = lfd.state("(at r3)\n(lit r3)").unwrap();
/// assert_eq!(s.logic_in(), None); // no L_k ⊆ S_C
/// let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut);
/// // The paper's mode: the first demonstration state reached, then the rest of the demo.
/// let r = s.replan(Mode::Paper, &cfg, &NoClock).unwrap();
/// assert_eq!((r.k, r.prefix()), (Some(1), &["(go r3 r2)".to_string()][..]));
/// assert_eq!(r.suffix(), ["(switch-on r2)", "(go r2 r3)", "(switch-on r3)"]);
/// // Prioritised: the cheapest prefix + demo left; here going to G directly (k = None).
/// let p = s.replan(Mode::Prioritised, &cfg, &NoClock).unwrap();
/// assert_eq!((p.k, p.cost), (None, 2));
/// assert!(s.validate(&p.names).unwrap().is_valid());
/// assert!(s.validate(&r.names).unwrap().is_valid());
/// ```
#[derive(Clone, Debug)]
pub struct LogicLfd {
    task: Task,
    trace: DemoTrace,
    spec: MultiGoalSpec,
    /// L_0 … L_N as states of `task` (`None`: not expressible in it).
    demo_states: Vec<Option<State>>,
    /// The lifted domain and problem, when built from text (states and plans can be read).
    source: Option<Box<(Domain, Problem)>>,
    /// The multi-goal search per mode (paper, prioritised), compiled on first use and reused by
    /// every later replan.
    searches: [OnceLock<MultiGoalSearch>; 2],
}

/// One state drawn by [`LogicLfd::perturb`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Perturbed {
    /// The state.
    pub state: State,
    /// The demonstration state the random walk started from.
    pub from_k: usize,
    /// Number of random actions walked.
    pub steps: usize,
}

impl LogicLfd {
    /// Reads the domain, the problem and the demonstration (one `(action args)` a line, `;`
    /// comments); errors are located in `domain.pddl`, `problem.pddl` and `demo.plan`.
    ///
    /// # Errors
    /// - [`LfdError::Input`]: a file does not parse, or a demonstration step names an unknown
    ///   action or object (`file:line:col: message`);
    /// - [`LfdError::DemoNotApplicable`]: a step's precondition is false where the demo applies it
    ///   (the step and the false literals);
    /// - [`LfdError::DemoMissesGoal`]: the demonstration ends where the goal does not hold;
    /// - [`LfdError::Model`]: the task cannot be grounded.
    pub fn new(domain: &str, problem: &str, demo: &str) -> Result<Self, LfdError> {
        Self::named(
            &Source::new("domain.pddl", domain),
            &Source::new("problem.pddl", problem),
            &Source::new("demo.plan", demo),
        )
    }

    /// [`LogicLfd::new`] with the file names used in error locations.
    pub fn named(domain: &Source, problem: &Source, demo: &Source) -> Result<Self, LfdError> {
        let d = pddl::parse_domain(&domain.text, &domain.file)?;
        let p = pddl::parse_problem(&problem.text, &problem.file, &d)?;
        let steps = parse_plan(&demo.text, &demo.file)?;
        let applied = every_step_applies(
            validate(&d, &p, &steps).outcome,
            |step, action, at, lits| LfdError::DemoNotApplicable {
                index: step - 1,
                action,
                false_literals: lits,
                location: Some(at),
            },
        )?;
        if let Outcome::GoalNotReached { false_literals } = applied {
            return Err(LfdError::DemoMissesGoal { false_literals });
        }
        let task = plan::ground(&d, &p).map_err(|e| LfdError::Model(e.to_string()))?;
        let actions: Vec<String> = steps.iter().map(|s| s.text()).collect();
        let trace = DemoTrace::derive(&task, &actions)?;
        let mut lfd = Self::from_task(task, trace);
        lfd.source = Some(Box::new((d, p)));
        Ok(lfd)
    }

    /// Logic-LfD on an already grounded task with a demonstration derived on it (or on another
    /// grounding of the same domain: the trace is matched by fact and action names).
    pub fn from_task(task: Task, trace: DemoTrace) -> Self {
        let spec = MultiGoalSpec::new(&task, &trace);
        let demo_states = trace
            .states
            .iter()
            .map(|l| {
                let mut s = task.empty_state();
                for f in l {
                    s.insert(task.fact_id(f)?);
                }
                Some(s)
            })
            .collect();
        LogicLfd {
            task,
            trace,
            spec,
            demo_states,
            source: None,
            searches: Default::default(),
        }
    }

    /// The grounded task.
    pub fn task(&self) -> &Task {
        &self.task
    }

    /// The demonstration: its actions a_1 … a_N and the states L_0 … L_N by fact name.
    pub fn trace(&self) -> &DemoTrace {
        &self.trace
    }

    /// The multi-goal specification compiled against [`LogicLfd::task`].
    pub fn spec(&self) -> &MultiGoalSpec {
        &self.spec
    }

    /// The demonstrated actions a_1 … a_N, `(action args)` each.
    pub fn demo_actions(&self) -> &[String] {
        &self.trace.actions
    }

    /// L_0 … L_N: the fluents that hold before a_1, after a_1, …, after a_N, sorted by name.
    pub fn demo_states(&self) -> &[BTreeSet<String>] {
        &self.trace.states
    }

    /// L_k as a state of the task (`None` when k > N or L_k has a fact the task cannot express).
    pub fn demo_state(&self, k: usize) -> Option<&State> {
        self.demo_states.get(k)?.as_ref()
    }

    /// The static facts of the problem (true in every state, never part of one).
    pub fn static_facts(&self) -> &[String] {
        &self.task.static_facts
    }

    /// The fluents of `s` by name, sorted.
    pub fn names(&self, s: &State) -> Vec<String> {
        super::demo::state_names(&self.task, s)
    }

    /// The state reached from the problem's initial state by a plan prefix (one `(action args)` a
    /// line), e.g. a demonstration that was interrupted and then disturbed.
    ///
    /// # Errors
    /// [`LfdError::Input`] for a malformed step; [`LfdError::PrefixNotApplicable`] naming the
    /// step and its false preconditions.
    pub fn state_after(&self, file: &str, plan_text: &str) -> Result<State, LfdError> {
        let (d, p) = self.source()?;
        let steps = parse_plan(plan_text, file)?;
        every_step_applies(
            validate(d, p, &steps).outcome,
            |step, action, location, lits| LfdError::PrefixNotApplicable {
                step,
                action,
                location,
                false_literals: lits,
            },
        )?;
        let mut s = self.task.init.clone();
        for step in &steps {
            let name = step.text();
            let op = super::demo::operator_index(&self.task, &name)
                .ok_or_else(|| LfdError::Model(format!("`{name}` was not grounded")))?;
            s = self.task.operators[op].apply(&s);
        }
        Ok(s)
    }

    /// LogicIn(S_C, 𝒢): the largest k with L_k ⊆ S_C (the match closest to the goal), if any.
    pub fn logic_in(&self, s: &State) -> Option<usize> {
        super::logic::logic_in(&self.spec, s)
    }

    /// Logic-LfD from `s`: the demonstration's suffix when LogicIn holds, else one multi-goal
    /// search to the first (`paper`) or cheapest-to-finish (`prioritised`) L_k, merged with the
    /// rest of the demonstration. `config` bounds the search by nodes and seconds on `clock`.
    ///
    /// # Errors
    /// [`LfdError::NoPlan`] (no demonstration state and not G reachable: proved) or
    /// [`LfdError::Budget`].
    pub fn replan(
        &self,
        s: &State,
        mode: Mode,
        config: &SearchConfig,
        clock: &dyn Clock,
    ) -> Result<LfdPlan, LfdError> {
        self.replan_avoiding(s, mode, config, clock, None, 0)
    }

    /// The compiled multi-goal search of `mode`, built on first use.
    pub fn search(&self, mode: Mode) -> &MultiGoalSearch {
        self.searches[mode as usize]
            .get_or_init(|| super::logic::prepare_search(&self.task, &self.spec, mode))
    }

    /// [`LogicLfd::replan`] on `banned` (operators banned where their binding failed), joining
    /// the demonstration at L_`first_k` or later (the reactive loop's retries).
    pub(crate) fn replan_avoiding(
        &self,
        s: &State,
        mode: Mode,
        config: &SearchConfig,
        clock: &dyn Clock,
        banned: Option<&BannedTask>,
        first_k: usize,
    ) -> Result<LfdPlan, LfdError> {
        let plain = banned.is_none() && first_k == 0;
        let run = |mode, below| {
            let request = Request {
                mode,
                banned,
                first_k,
                prepared: plain.then(|| self.search(mode)),
                below,
            };
            plan_with(&self.task, &self.spec, s, config, clock, request)
        };
        let (paper, paper_stats) = run(Mode::Paper, None);
        if mode == Mode::Paper {
            return paper;
        }
        // Among plans of equal cost the paper plan follows the demonstration longest (the
        // prioritised search may tie-break towards G), and with a satisficing search it may
        // even be cheaper: prioritised mode returns it unless its own plan is strictly cheaper,
        // so the optimal searches only look for plans below its cost.
        let paper = match paper {
            Ok(p) if p.source != PlanSource::MultiGoal => return Ok(p),
            Err(_) => return run(Mode::Prioritised, None).0,
            Ok(p) => p,
        };
        let (prio, mut stats) = run(Mode::Prioritised, Some(paper.cost));
        stats.expanded += paper_stats.expanded;
        match prio {
            Ok(mut prio) if prio.cost < paper.cost => {
                prio.stats = stats;
                Ok(prio)
            }
            Ok(prio) => Ok(self.keep_paper(paper, prio.alternatives, stats)),
            Err(LfdError::NoPlan(_)) => {
                let mut p = self.keep_paper(paper, vec![], stats);
                // Below the bound an optimal search's exhausted open list is a proof.
                if config.is_optimal() {
                    super::alternatives::proved_not_cheaper(&mut p.alternatives);
                }
                Ok(p)
            }
            Err(e) => Err(e),
        }
    }

    /// The paper plan as prioritised mode's answer, with the prioritised search's statistics
    /// and, when it found some, its candidates (which weighed more of them).
    fn keep_paper(
        &self,
        mut paper: LfdPlan,
        alternatives: Vec<super::alternatives::Alternative>,
        stats: SearchStats,
    ) -> LfdPlan {
        paper.stats = stats;
        if !alternatives.is_empty() {
            paper.alternatives = alternatives;
            let prefix = self.task.cost_of(&paper.ops[..paper.prefix_len]);
            super::alternatives::rejoin(&mut paper.alternatives, paper.k, prefix);
        }
        paper
    }

    /// Classical planning from `s` to G with the same search (the baseline Logic-LfD is compared
    /// with).
    pub fn plan_from_scratch(
        &self,
        s: &State,
        config: &SearchConfig,
        clock: &dyn Clock,
    ) -> SearchResult {
        plan::search_from(&self.task, s, config, clock)
    }

    /// Replays `plan` (`(action args)` names) from `s` on the lifted domain — independent of the
    /// grounding — and reports the first failing step or the goal literals left false.
    pub fn validate(&self, s: &State, plan: &[String]) -> Result<ValidationReport, LfdError> {
        let (d, p) = self.source()?;
        let mut init = self.names(s);
        init.extend(self.task.static_facts.iter().cloned());
        let problem = p.with_ground_init(d, &init)?;
        Ok(validate_names(d, &problem, plan))
    }

    /// `count` states drawn by seeded random walks with the domain's own actions: even draws
    /// walk from L_0, odd ones from a random L_k; each walks 1 … `max_steps` random applicable
    /// actions and avoids states where the goal already holds (up to 20 tries each).
    pub fn perturb(&self, count: usize, seed: u64, max_steps: usize) -> Vec<Perturbed> {
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let starts: Vec<usize> = (0..self.demo_states.len())
            .filter(|&k| self.demo_states[k].is_some())
            .collect();
        let mut out = Vec::with_capacity(count);
        let mut applicable = Vec::new();
        for i in 0..count {
            let mut best = None;
            for _ in 0..20 {
                let from_k = if i % 2 == 0 || starts.is_empty() {
                    0
                } else {
                    starts[rng.random_range(0..starts.len())]
                };
                let mut s = match self.demo_state(from_k) {
                    Some(s) => s.clone(),
                    None => self.task.init.clone(),
                };
                let len = rng.random_range(1..=max_steps.max(1));
                let mut steps = 0;
                for _ in 0..len {
                    applicable.clear();
                    applicable.extend(
                        (0..self.task.operators.len())
                            .filter(|&o| self.task.operators[o].applicable(&s)),
                    );
                    if applicable.is_empty() {
                        break;
                    }
                    let o = applicable[rng.random_range(0..applicable.len())];
                    s = self.task.operators[o].apply(&s);
                    steps += 1;
                }
                let done = self.task.goal.holds(&s);
                best = Some(Perturbed {
                    state: s,
                    from_k,
                    steps,
                });
                if !done {
                    break;
                }
            }
            out.extend(best);
        }
        out
    }

    /// Whether `ops` is applicable from `s` and reaches the goal (grounded replay).
    pub fn reaches_goal(&self, s: &State, ops: &[usize]) -> bool {
        replay(&self.task, s, ops).is_ok_and(|e| self.task.goal.holds(&e))
    }

    fn source(&self) -> Result<(&Domain, &Problem), LfdError> {
        self.source
            .as_deref()
            .map(|(d, p)| (d, p))
            .ok_or_else(|| LfdError::Model("built from a grounded task: no PDDL to read".into()))
    }
}

/// The validator's outcome when every step of the plan applied (`Valid` or `GoalNotReached`);
/// a malformed step is an input error, and a false precondition the error `not_applicable`
/// makes of (1-based step, action, `file:line:col`, false literals).
fn every_step_applies(
    outcome: Outcome,
    not_applicable: impl FnOnce(usize, String, String, Vec<String>) -> LfdError,
) -> Result<Outcome, LfdError> {
    match outcome {
        Outcome::Malformed(e) => Err(e.into()),
        Outcome::PreconditionFalse {
            step,
            action,
            location,
            false_literals,
        } => Err(not_applicable(step, action, location, false_literals)),
        applied => Ok(applied),
    }
}

/// Atoms of a facts text without a domain to check them against (a [`LogicLfd`] built from a
/// grounded task): names normalised, located.
pub(super) fn unlocated_facts(text: &str, file: &str) -> Result<Vec<pddl::LocatedFact>, LfdError> {
    let steps = parse_plan(text, file)?;
    Ok(steps
        .into_iter()
        .map(|s| pddl::LocatedFact {
            name: s.text(),
            line: s.line,
            col: s.col,
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{Algorithm, HeuristicKind, NoClock};

    const DOMAIN: &str = "(define (domain prep) (:requirements :strips :negative-preconditions)
      (:predicates (chopped ?v) (served ?v))
      (:action chop :parameters (?v) :precondition (not (chopped ?v)) :effect (chopped ?v))
      (:action serve :parameters (?v) :precondition (chopped ?v) :effect (served ?v)))";
    const PROBLEM: &str = "(define (problem p) (:domain prep) (:objects a b) (:init)
      (:goal (and (served a) (served b))))";
    const DEMO: &str = "(chop a)\n(serve a)\n(chop b)\n(serve b)\n";

    #[test]
    fn a_state_holding_more_than_l_k_joins_where_the_suffix_still_applies() {
        let lfd = LogicLfd::new(DOMAIN, PROBLEM, DEMO).unwrap();
        // b was chopped early: L_0 ⊆ S_C, but a_3 (chop b) cannot apply any more, so LogicIn
        // does not match L_0 and the search joins where the rest of the demo still applies.
        let observed = lfd.state("(chopped b)").unwrap();
        assert!(!observed.is_regrounded(), "known fluents keep the task");
        let s = observed.state();
        assert_eq!(lfd.logic_in(s), None);
        let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut);
        for mode in [Mode::Paper, Mode::Prioritised] {
            let r = lfd.replan(s, mode, &cfg, &NoClock).unwrap();
            assert_eq!(r.k, Some(3), "{mode:?}");
            assert_eq!(r.names, ["(chop a)", "(serve a)", "(serve b)"]);
            assert!(lfd.validate(s, &r.names).unwrap().is_valid());
        }
        // The reactive loop's instance (built from a grounded task) has the same goals.
        let plain = LogicLfd::from_task(lfd.task().clone(), lfd.trace().clone());
        let r = plain.replan(s, Mode::Paper, &cfg, &NoClock).unwrap();
        assert_eq!(r.k, Some(3));
    }
}
