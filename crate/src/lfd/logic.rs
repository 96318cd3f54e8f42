//! LogicIn, suffix merging and Logic-LfD planning (paper §III-C/D, Algorithm 1 lines 8–13).
//!
//! With the multi-goal specification 𝒢 = {L_0..L_N, G} (see [`super::demo`]) and the current
//! fluents S_C:
//!
//! ```text
//!   LogicIn(S_C, 𝒢) = max { k : L_k ⊆ S_C }                 (the match closest to the goal)
//!   if LogicIn holds:     𝒫 = a_{k+1} … a_N                  (the demo suffix)
//!   else:                 (π, k) = MultiGoalSearch(S_C, 𝒢)   (one search, goal test "any L_k")
//!                         𝒫 = π ⧺ a_{k+1} … a_N
//! ```
//!
//! Two modes of the multi-goal search:
//! * `paper`: the first goal reached wins, all goals have equal priority (the paper);
//! * `prioritised`: minimise g(π) + c_k with c_k the cost of the demo left after L_k, so the merged
//!   plan is never longer than needed (the paper's stated drawback, fixed in the same search).
//!
//! Every merged plan is replayed on the task before it is returned: with negative preconditions a
//! suffix from a superset of L_k is not guaranteed applicable, and then the search is used instead.

use serde::{Deserialize, Serialize};

use crate::plan::{
    self, replay, BannedTask, Clock, MultiGoalMode, MultiGoalSearch, SearchConfig, SearchOutcome,
    SearchStats, State, Task,
};

use super::alternatives::{self, Alternative};
use super::catalogue::Mode;
use super::demo::MultiGoalSpec;
use super::LfdError;

/// Where a Logic-LfD plan came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify))]
pub enum PlanSource {
    /// The goal already holds: empty plan.
    GoalHolds,
    /// LogicIn matched L_k: the plan is the demo suffix.
    LogicIn,
    /// A multi-goal search found a prefix to L_k, merged with the suffix.
    MultiGoal,
}

/// A plan produced by Logic-LfD: a new prefix to L_k merged with the demonstration after L_k.
#[derive(Clone, Debug, PartialEq)]
pub struct LfdPlan {
    /// Operator indices into the task, in execution order.
    pub ops: Vec<usize>,
    /// The same plan as `(action args)` names.
    pub names: Vec<String>,
    /// The demonstration state index the plan joins (`None` when it goes to G directly).
    pub k: Option<usize>,
    /// How many leading actions are new (not from the demonstration).
    pub prefix_len: usize,
    /// Where the plan came from.
    pub source: PlanSource,
    /// Cost of the whole merged plan (= cost of the prefix + c_k).
    pub cost: u64,
    /// The multi-goal search's statistics (all zero when no search ran).
    pub stats: SearchStats,
    /// Every candidate L_k (and G) with what the search found for it (empty when the goal
    /// already held).
    pub alternatives: Vec<Alternative>,
}

impl LfdPlan {
    /// The new actions that lead to L_k.
    pub fn prefix(&self) -> &[String] {
        &self.names[..self.prefix_len]
    }

    /// The demonstration's actions after L_k.
    pub fn suffix(&self) -> &[String] {
        &self.names[self.prefix_len..]
    }

    fn new(
        task: &Task,
        ops: Vec<usize>,
        k: Option<usize>,
        prefix_len: usize,
        source: PlanSource,
        stats: SearchStats,
    ) -> Self {
        LfdPlan {
            names: ops
                .iter()
                .map(|&o| task.operators[o].name.clone())
                .collect(),
            cost: task.cost_of(&ops),
            ops,
            k,
            prefix_len,
            source,
            stats,
            alternatives: vec![],
        }
    }
}

/// LogicIn(S_C, 𝒢): the largest k with L_k ⊆ S_C, if any.
pub fn logic_in(spec: &MultiGoalSpec, s: &State) -> Option<usize> {
    spec.states
        .iter()
        .enumerate()
        .rev()
        .find(|(_, l)| l.as_ref().is_some_and(|c| c.holds(s)))
        .map(|(k, _)| k)
}

/// `prefix ⧺ a_{k+1}..a_N`, if the result is applicable from `s` and reaches the goal.
pub fn merge_suffix(
    task: &Task,
    spec: &MultiGoalSpec,
    s: &State,
    prefix: &[usize],
    k: usize,
) -> Option<Vec<usize>> {
    let mut ops = prefix.to_vec();
    ops.extend(spec.suffix(k)?);
    match replay(task, s, &ops) {
        Ok(end) if task.goal.holds(&end) => Some(ops),
        _ => None,
    }
}

/// Logic-LfD planning from `s`: the demo suffix when LogicIn holds, else one multi-goal search
/// merged with the suffix. `config` bounds the search (nodes / seconds on `clock`).
pub fn plan_logic_lfd(
    task: &Task,
    spec: &MultiGoalSpec,
    s: &State,
    mode: Mode,
    config: &SearchConfig,
    clock: &dyn Clock,
) -> Result<LfdPlan, LfdError> {
    plan_logic_lfd_avoiding(task, spec, s, mode, config, clock, None, 0)
}

/// The multi-goal search of `spec` over `task` in `mode`, compiled once to answer many states
/// (pass it to [`plan_logic_lfd_prepared`]).
///
/// In prioritised mode G bounds the other goals (the suffix after L_k reaches it at cost c_k),
/// so A* also takes the heuristic to G alone.
pub fn prepare_search(task: &Task, spec: &MultiGoalSpec, mode: Mode) -> MultiGoalSearch {
    MultiGoalSearch::new(task, &spec.goals, search_mode(mode)).with_lower_bound(spec.goal_index())
}

fn search_mode(mode: Mode) -> MultiGoalMode {
    match mode {
        Mode::Paper => MultiGoalMode::FirstReached,
        Mode::Prioritised => MultiGoalMode::Prioritised,
    }
}

/// [`plan_logic_lfd`] whose multi-goal search runs on `banned` if given (the task with operators banned
/// at the states where their binding failed) and joins the demonstration at L_`first_k` or later
/// only (an action a_j of the suffix could not be bound: `first_k` = j, so the search plans past
/// it with actions of its own); the demo suffix and the merged plan are checked on `task` itself,
/// and the plan is in `task`'s operators.
#[allow(clippy::too_many_arguments)]
pub fn plan_logic_lfd_avoiding(
    task: &Task,
    spec: &MultiGoalSpec,
    s: &State,
    mode: Mode,
    config: &SearchConfig,
    clock: &dyn Clock,
    banned: Option<&BannedTask>,
    first_k: usize,
) -> Result<LfdPlan, LfdError> {
    let request = Request {
        mode,
        banned,
        first_k,
        ..Request::default()
    };
    plan_with(task, spec, s, config, clock, request).0
}

/// [`plan_logic_lfd`] with a search from [`prepare_search`] (same task, spec and mode): nothing
/// is compiled or built per call.
pub fn plan_logic_lfd_prepared(
    task: &Task,
    spec: &MultiGoalSpec,
    s: &State,
    search: &MultiGoalSearch,
    config: &SearchConfig,
    clock: &dyn Clock,
) -> Result<LfdPlan, LfdError> {
    let mode = match search.mode() {
        MultiGoalMode::FirstReached => Mode::Paper,
        MultiGoalMode::Prioritised => Mode::Prioritised,
    };
    let request = Request {
        mode,
        prepared: Some(search),
        ..Request::default()
    };
    plan_with(task, spec, s, config, clock, request).0
}

/// What [`plan_with`] plans: the mode and, for the reactive loop, the bans, the first L_k a
/// plan may join, a compiled search to reuse and a cost the plan must stay below.
#[derive(Clone, Copy, Default)]
pub(crate) struct Request<'a> {
    pub mode: Mode,
    /// Operators banned at the states where their binding failed.
    pub banned: Option<&'a BannedTask>,
    /// The first demonstration state a plan may join.
    pub first_k: usize,
    /// The compiled search of `mode` (used when nothing is banned and `first_k` is 0).
    pub prepared: Option<&'a MultiGoalSearch>,
    /// A merged plan of this cost is known: optimal searches drop every state that cannot beat
    /// it, and [`LfdError::NoPlan`] then means none can.
    pub below: Option<u64>,
}

/// Logic-LfD planning for `request`; the multi-goal search's statistics come back whatever the
/// outcome (zero when no search ran).
pub(crate) fn plan_with(
    task: &Task,
    spec: &MultiGoalSpec,
    s: &State,
    config: &SearchConfig,
    clock: &dyn Clock,
    request: Request<'_>,
) -> (Result<LfdPlan, LfdError>, SearchStats) {
    let Request {
        mode,
        banned,
        first_k,
        prepared,
        below,
    } = request;
    let none = SearchStats::default();
    if task.goal.holds(s) {
        let plan = LfdPlan::new(task, vec![], None, 0, PlanSource::GoalHolds, none);
        return (Ok(plan), none);
    }
    if let Some(k) = logic_in(spec, s).filter(|&k| k >= first_k) {
        if let Some(ops) = merge_suffix(task, spec, s, &[], k) {
            let mut plan = LfdPlan::new(task, ops, Some(k), 0, PlanSource::LogicIn, none);
            plan.alternatives = alternatives::after_logic_in(spec, k);
            return (Ok(plan), none);
        }
    }
    let search_task = banned.map_or(task, |b| &b.task);
    let goals: std::borrow::Cow<[plan::Goal]> = if first_k == 0 {
        std::borrow::Cow::Borrowed(&spec.goals)
    } else {
        // L_0..L_{first_k − 1} are no goals (no alternatives: never reached); G stays one.
        let mut g = spec.goals.clone();
        for goal in g.iter_mut().take(first_k.min(spec.len() + 1)) {
            goal.alternatives.clear();
        }
        std::borrow::Cow::Owned(g)
    };
    let lifted = banned.map(|b| b.lift(s));
    let start = lifted.as_ref().unwrap_or(s);
    let found = match prepared {
        Some(search) if banned.is_none() && first_k == 0 => {
            search.run_below(start, below, config, clock)
        }
        _ => {
            let search = MultiGoalSearch::new(search_task, &goals, search_mode(mode));
            // The suffix after L_k reaches G at c_k on the task itself; a banned task may lack
            // its operators, so G bounds the other goals only without bans.
            let search = match banned {
                None => search.with_lower_bound(spec.goal_index()),
                Some(_) => search,
            };
            search.run_below(start, below, config, clock)
        }
    };
    let stats = found.stats;
    let (prefix, k) = match (&found.outcome, found.goal_index) {
        (SearchOutcome::Plan(p), Some(k)) => (
            banned.map_or_else(|| p.operators.clone(), |b| b.original(&p.operators)),
            k,
        ),
        (SearchOutcome::BudgetExhausted { which }, _) => {
            return (Err(LfdError::Budget(*which)), stats)
        }
        _ => {
            let why = match below {
                Some(c) => format!("no merged plan cheaper than {c}"),
                None => "no demonstration state is reachable".into(),
            };
            return (Err(LfdError::NoPlan(why)), stats);
        }
    };
    let Some(ops) = merge_suffix(task, spec, s, &prefix, k) else {
        return (Err(LfdError::MergeFailed { k }), stats);
    };
    let prefix_cost = task.cost_of(&prefix);
    let mut plan = LfdPlan::new(
        task,
        ops,
        (k <= spec.len()).then_some(k),
        prefix.len(),
        PlanSource::MultiGoal,
        stats,
    );
    plan.alternatives = alternatives::after_search(spec, &goals, &found.reached, k, prefix_cost);
    (Ok(plan), stats)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lfd::testing::{b1_template, state};
    use crate::lfd::{DemoTrace, MultiGoalSpec};

    fn spec() -> (Task, MultiGoalSpec) {
        let (task, demo) = b1_template();
        let trace = DemoTrace::derive(&task, &demo).unwrap();
        (task.clone(), MultiGoalSpec::new(&task, &trace))
    }

    #[test]
    fn demo_states_are_derived_by_applying_the_actions() {
        let (task, demo) = b1_template();
        let trace = DemoTrace::derive(&task, &demo).unwrap();
        assert_eq!(trace.states.len(), 7);
        assert!(trace.states[2].contains("(on c d)"));
        assert!(!trace.states[2].contains("(clear d)"));
        assert!(trace.states[1].contains("(holding c)"));
        assert!(trace.states[6].contains("(on a b)"));
    }

    #[test]
    fn a_demo_with_an_inapplicable_action_is_refused_with_its_index() {
        let (task, mut demo) = b1_template();
        demo.swap(0, 1);
        match DemoTrace::derive(&task, &demo) {
            Err(LfdError::DemoNotApplicable {
                index: 0, action, ..
            }) => {
                assert_eq!(action, "(stack c d)")
            }
            other => panic!("{other:?}"),
        }
        let mut demo2 = b1_template().1;
        demo2[3] = "(fly b)".into();
        assert!(matches!(
            DemoTrace::derive(&task, &demo2),
            Err(LfdError::UnknownAction { index: 3, .. })
        ));
    }

    #[test]
    fn demo_action_spelling_is_normalised() {
        assert_eq!(crate::lfd::normalize_action("  STACK  a B "), "(stack a b)");
        assert_eq!(crate::lfd::normalize_action("(pick c)"), "(pick c)");
    }

    #[test]
    fn logic_in_returns_the_match_closest_to_the_goal() {
        let (task, spec) = spec();
        // L_2: C on D, A and B on the table, hand empty.
        let l2 = state(
            &task,
            &[
                "(handempty)",
                "(ontable a)",
                "(ontable b)",
                "(ontable d)",
                "(on c d)",
                "(clear a)",
                "(clear b)",
                "(clear c)",
            ],
        );
        assert_eq!(logic_in(&spec, &l2), Some(2));
        assert_eq!(logic_in(&spec, &task.init), Some(0));
        // An unseen state: D on A.
        let unseen = state(
            &task,
            &[
                "(handempty)",
                "(ontable a)",
                "(ontable b)",
                "(ontable c)",
                "(on d a)",
                "(clear d)",
                "(clear b)",
                "(clear c)",
            ],
        );
        assert_eq!(logic_in(&spec, &unseen), None);
    }

    #[test]
    fn logic_in_is_a_subset_test_so_extra_facts_do_not_hide_a_match() {
        let (task, spec) = spec();
        let mut s = task.init.clone();
        // An extra fact the demo never mentions (e.g. about another object) keeps L_0.
        s.insert(task.fact_id("(on a b)").unwrap());
        assert_eq!(logic_in(&spec, &s), Some(0));
    }

    #[test]
    fn merging_the_suffix_reaches_the_goal_and_a_wrong_k_is_refused() {
        let (task, spec) = spec();
        let ops = merge_suffix(&task, &spec, &task.init, &[], 0).unwrap();
        assert_eq!(ops.len(), 6);
        let end = replay(&task, &task.init, &ops).unwrap();
        assert!(task.goal.holds(&end));
        // From L_0 the suffix after L_3 is not applicable (nothing is held).
        assert!(merge_suffix(&task, &spec, &task.init, &[], 3).is_none());
        // The empty suffix of G from the goal state is fine.
        assert_eq!(
            merge_suffix(&task, &spec, &end, &[], spec.goal_index()),
            Some(vec![])
        );
    }

    #[test]
    fn terminal_costs_count_the_demo_left_after_k() {
        let (_, spec) = spec();
        let costs: Vec<u64> = spec.goals.iter().map(|g| g.terminal_cost).collect();
        assert_eq!(costs, vec![6, 5, 4, 3, 2, 1, 0, 0]);
        assert_eq!(spec.suffix(4).unwrap().len(), 2);
    }

    fn cfg() -> SearchConfig {
        SearchConfig::new(plan::Algorithm::Astar, plan::HeuristicKind::HMax)
    }

    #[test]
    fn an_unseen_state_gets_a_multi_goal_prefix_merged_with_the_suffix() {
        let (task, spec) = spec();
        // D on A, the rest on the table: no L_k holds.
        let s = state(
            &task,
            &[
                "(handempty)",
                "(ontable a)",
                "(ontable b)",
                "(ontable c)",
                "(on d a)",
                "(clear d)",
                "(clear b)",
                "(clear c)",
            ],
        );
        for mode in [Mode::Paper, Mode::Prioritised] {
            let p = plan_logic_lfd(&task, &spec, &s, mode, &cfg(), &plan::NoClock).unwrap();
            assert_eq!(p.source, PlanSource::MultiGoal);
            assert!(p.prefix_len > 0);
            let end = replay(&task, &s, &p.ops).expect("merged plan applicable");
            assert!(task.goal.holds(&end), "{mode:?}");
            // The prefix ends in L_k.
            let mid = replay(&task, &s, &p.ops[..p.prefix_len]).unwrap();
            let k = p.k.expect("joins the demo");
            assert!(spec.states[k].as_ref().unwrap().holds(&mid));
            assert_eq!(p.ops.len(), 8);
            // Paper mode: unstack d a, place d, then L_0 holds (prioritised mode may join a
            // later L_k at the same cost).
            if mode == Mode::Paper {
                assert_eq!(p.prefix_len, 2);
                assert_eq!(p.k, Some(0));
            }
        }
    }

    #[test]
    fn prioritised_mode_never_returns_a_longer_merged_plan_than_paper_mode() {
        let (task, spec) = spec();
        let cases: [&[&str]; 3] = [
            &[
                "(holding a)",
                "(ontable b)",
                "(ontable d)",
                "(on c d)",
                "(clear b)",
                "(clear c)",
            ],
            &[
                "(handempty)",
                "(ontable c)",
                "(ontable d)",
                "(on b c)",
                "(on a d)",
                "(clear a)",
                "(clear b)",
            ],
            &[
                "(handempty)",
                "(ontable d)",
                "(on c d)",
                "(on a c)",
                "(ontable b)",
                "(clear a)",
                "(clear b)",
            ],
        ];
        for facts in cases {
            let s = state(&task, facts);
            let paper =
                plan_logic_lfd(&task, &spec, &s, Mode::Paper, &cfg(), &plan::NoClock).unwrap();
            let prio = plan_logic_lfd(&task, &spec, &s, Mode::Prioritised, &cfg(), &plan::NoClock)
                .unwrap();
            for p in [&paper, &prio] {
                assert!(task.goal.holds(&replay(&task, &s, &p.ops).unwrap()));
            }
            assert!(prio.ops.len() <= paper.ops.len(), "{facts:?}");
        }
        // Prioritised mode with exact terminal costs returns an optimal merged plan.
        let s = state(&task, cases[0]);
        let prio =
            plan_logic_lfd(&task, &spec, &s, Mode::Prioritised, &cfg(), &plan::NoClock).unwrap();
        let opt = plan::search_from(&task, &s, &cfg(), &plan::NoClock);
        assert_eq!(prio.ops.len(), opt.outcome.plan().unwrap().len());
    }

    #[test]
    fn a_first_k_makes_the_search_join_the_demo_after_a_failed_suffix_action() {
        let (task, spec) = spec();
        // At L_0 LogicIn gives the whole demo; with first_k = 2 (a_2 could not be bound) the
        // search plans a_1 and a_2's step itself and joins at L_2 or later.
        let s0 = task.init.clone();
        assert_eq!(logic_in(&spec, &s0), Some(0));
        for mode in [Mode::Paper, Mode::Prioritised] {
            let p =
                plan_logic_lfd_avoiding(&task, &spec, &s0, mode, &cfg(), &plan::NoClock, None, 2)
                    .unwrap();
            assert_eq!(p.source, PlanSource::MultiGoal, "{mode:?}");
            let k = p.k.unwrap_or(spec.goal_index());
            assert!(k >= 2, "{mode:?}: joined at {k}");
            assert!(p.prefix_len >= 2);
            let mid = replay(&task, &s0, &p.ops[..p.prefix_len]).unwrap();
            if let Some(k) = p.k {
                assert!(spec.states[k].as_ref().unwrap().holds(&mid));
            }
            let end = replay(&task, &s0, &p.ops).expect("merged plan applicable");
            assert!(task.goal.holds(&end), "{mode:?}");
            // Without it the suffix from L_0 is the plan.
            let q =
                plan_logic_lfd_avoiding(&task, &spec, &s0, mode, &cfg(), &plan::NoClock, None, 0)
                    .unwrap();
            assert_eq!(q.source, PlanSource::LogicIn);
            assert_eq!(q.k, Some(0));
        }
    }
}
