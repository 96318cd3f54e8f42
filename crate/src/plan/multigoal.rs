//! Multi-goal search, the planner core of Logic-LfD.
//!
//! Given the current state `S_C` and goals `G_0 … G_K` (in Logic-LfD: the demonstration states
//! `L_0 … L_N` and the task goal `G`), each a DNF condition with a terminal cost `c_k ≥ 0` (the
//! cost of the demonstration actions left after `L_k`), one forward search finds a plan `π` from
//! `S_C` to some `G_k`:
//!
//! * [`MultiGoalMode::FirstReached`] (the paper's): the search stops at the first state, in the
//!   algorithm's order, satisfying *any* goal; all goals are equal (`bfs` gives the shortest
//!   such `π`, `ucs`/A* the cheapest). Among goals holding in that state the one with the
//!   smallest `(c_k, k)` is returned.
//! * [`MultiGoalMode::Prioritised`] (beyond the paper): minimise `cost(π) + c_k`. `ucs` and A*
//!   with an admissible heuristic are optimal (`bfs` runs as `ucs` here); `gbfs`/`lazy-gbfs` are
//!   satisficing and stop at the first goal state they meet.
//!
//! # One task, one goal
//! Both modes compile into a single-goal task: the task's operators, a fresh fact `goal★`, and
//! per alternative of goal `k` one *goal operator* whose precondition is the alternative, whose
//! effect is `goal★` and whose cost is `c_k` (prioritised) or 0 (paper); the goal is `goal★`.
//! A plan of the compiled task is a plan to some `G_k` followed by its goal operator, and its cost
//! is `cost(π) + c_k` (prioritised), so every search and heuristic applies unchanged: one
//! heuristic evaluation per state for all goals, relevance pruning, and LM-cut admissible for the
//! prioritised objective. [`MultiGoalSearch`] compiles once (relevant part, successor generator,
//! heuristic templates) and answers any number of start states.
//!
//! If `S_C` satisfies goals, `FirstReached` returns the empty plan with the smallest `(c_k, k)`;
//! `Prioritised` returns it too unless another goal is strictly cheaper to reach and finish
//! (`cost(π) + c_j < c_k`), which cannot happen when the `c_k` are exact costs-to-go.

use std::sync::Mutex;

use crate::plan::clock::Clock;
use crate::plan::heuristic::{HeuristicEvaluator, HeuristicKind};
use crate::plan::relevance::{relevant_part, Relevance};
use crate::plan::search::{
    run_on, search_heuristic, Algorithm, Parts, Plan, SearchConfig, SearchOutcome, SearchStats,
    SuccessorGenerator,
};
use crate::plan::task::sanitize_goals;
use crate::plan::{Condition, Goal, Operator, State, Task};

/// How goals with terminal costs are compared.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash, Default)]
pub enum MultiGoalMode {
    /// Stop at the first state satisfying any goal (paper).
    #[default]
    FirstReached,
    /// Minimise plan cost plus the reached goal's terminal cost.
    Prioritised,
}

/// The result of [`search_multi_goal`].
#[derive(Clone, PartialEq, Debug)]
pub struct MultiGoalResult {
    /// Plan, proved unsolvable (no goal reachable), or budget exhausted.
    pub outcome: SearchOutcome,
    /// Index into `goals` of the goal the plan reaches.
    pub goal_index: Option<usize>,
    /// `cost(π) + c_k` of the returned plan.
    pub total_cost: Option<u64>,
    /// Statistics.
    pub stats: SearchStats,
    /// Per goal, the cost of the cheapest path to a state satisfying it that the search found
    /// (`None`: the search stopped before meeting one). Real paths, so never below the optimum;
    /// the returned goal's entry is its plan's cost in the optimal configurations.
    pub reached: Vec<Option<u64>>,
}

impl MultiGoalResult {
    /// The plan, if one was found.
    pub fn plan(&self) -> Option<&Plan> {
        self.outcome.plan()
    }
}

/// Searches from `start` to any of `goals` (see the module documentation for the modes).
///
/// ```
/// use logic_lfd::plan::{search_multi_goal, Algorithm, Condition, Goal, HeuristicKind,
///     MultiGoalMode, NoClock, Operator, SearchConfig, State, Task};
/// // A line p0 - p1 - p2 - p3; goals: p1 (3 demo steps left) or p3 (done).
/// let mv = |a: u32, b: u32| Operator { name: format!("(move p{a} p{b})"), pre: vec![a],
///     pre_neg: vec![], add: vec![b], del: vec![a], cost: 1 };
/// let at = |p: u32, c: u64| Goal { alternatives: vec![Condition { pos: vec![p], neg: vec![] }],
///     terminal_cost: c };
/// let task = Task::new((0..4).map(|i| format!("(at p{i})")).collect(),
///     vec![mv(0, 1), mv(1, 2), mv(2, 3)], State::from_facts(4, [0]), at(3, 0), vec![], false);
/// let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::HMax);
/// let goals = [at(1, 3), at(3, 0)];
/// let first = search_multi_goal(&task, &task.init, &goals, MultiGoalMode::FirstReached, &cfg, &NoClock);
/// assert_eq!((first.goal_index, first.total_cost), (Some(0), Some(4)));
/// let best = search_multi_goal(&task, &task.init, &goals, MultiGoalMode::Prioritised, &cfg, &NoClock);
/// assert_eq!((best.goal_index, best.total_cost), (Some(1), Some(3)));
/// ```
pub fn search_multi_goal(
    task: &Task,
    start: &State,
    goals: &[Goal],
    mode: MultiGoalMode,
    config: &SearchConfig,
    clock: &dyn Clock,
) -> MultiGoalResult {
    MultiGoalSearch::new(task, goals, mode).run(start, config, clock)
}

/// The name of the compiled task's goal fact; no PDDL atom is spelled so.
const GOAL_FACT: &str = "(<goal>)";

/// A multi-goal search compiled once for a task and its goals, run from any start state.
///
/// - [`MultiGoalSearch::new`] compiles the goals into one (see the module documentation), keeps
///   the relevant part of the compiled task and builds its successor generator;
/// - [`MultiGoalSearch::run`] searches from a state of the task; heuristic templates are built on
///   first use per heuristic and reused by later runs.
///
/// ```
/// use logic_lfd::plan::{Algorithm, Condition, Goal, HeuristicKind, MultiGoalMode,
///     MultiGoalSearch, NoClock, Operator, SearchConfig, State, Task};
/// let mv = |a: u32, b: u32| Operator { name: format!("(move p{a} p{b})"), pre: vec![a],
///     pre_neg: vec![], add: vec![b], del: vec![a], cost: 1 };
/// let at = |p: u32, c: u64| Goal { alternatives: vec![Condition { pos: vec![p], neg: vec![] }],
///     terminal_cost: c };
/// let task = Task::new((0..4).map(|i| format!("(at p{i})")).collect(),
///     vec![mv(0, 1), mv(1, 2), mv(2, 3)], State::from_facts(4, [0]), at(3, 0), vec![], false);
/// let search = MultiGoalSearch::new(&task, &[at(1, 3), at(3, 0)], MultiGoalMode::Prioritised);
/// let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut);
/// for (start, cost) in [(0, 3), (1, 2), (2, 1)] {
///     let r = search.run(&State::from_facts(4, [start]), &cfg, &NoClock);
///     assert_eq!((r.goal_index, r.total_cost), (Some(1), Some(cost)));
/// }
/// ```
#[derive(Clone, Debug)]
pub struct MultiGoalSearch {
    mode: MultiGoalMode,
    /// The goals, with facts the task does not know sanitised away.
    goals: Vec<Goal>,
    /// Fluent facts of the original task (the compiled task has one more).
    num_facts: usize,
    /// Operators of the original task; compiled operators past these are goal operators.
    num_ops: usize,
    /// The compiled task (its relevant part is searched when `rel` is set).
    compiled: Task,
    rel: Option<Relevance>,
    /// Per operator of the searched task, the goal of its goal operator (`u32::MAX`: none).
    goal_of_op: Vec<u32>,
    /// The goal operators of the searched task.
    goal_ops: Vec<u32>,
    succ: SuccessorGenerator,
    evaluators: EvaluatorPool,
    /// A goal every other goal leads to within its terminal cost, as a goal of the searched task
    /// (see [`MultiGoalSearch::with_lower_bound`]).
    bound: Option<Goal>,
}

impl MultiGoalSearch {
    /// Compiles `goals` over `task` (terminal costs counted in `Prioritised` mode).
    pub fn new(task: &Task, goals: &[Goal], mode: MultiGoalMode) -> Self {
        let n = task.facts.len();
        let goals = sanitize_goals(n, goals);
        let mut compiled = task.clone();
        let goal_fact = compiled.push_fact(GOAL_FACT.to_string());
        let mut goal_of: Vec<u32> = Vec::new();
        for (k, g) in goals.iter().enumerate() {
            let cost = match mode {
                MultiGoalMode::Prioritised => u32::try_from(g.terminal_cost).unwrap_or(u32::MAX),
                MultiGoalMode::FirstReached => 0,
            };
            for (i, alt) in g.alternatives.iter().enumerate() {
                compiled.operators.push(Operator {
                    name: format!("(<goal> {k} {i})"),
                    pre: alt.pos.clone(),
                    pre_neg: alt.neg.clone(),
                    add: vec![goal_fact],
                    del: vec![],
                    cost,
                });
                goal_of.push(k as u32);
            }
        }
        compiled.goal = Goal {
            alternatives: vec![Condition {
                pos: vec![goal_fact],
                neg: vec![],
            }],
            terminal_cost: 0,
        };
        let rel = relevant_part(&compiled);
        let num_ops = task.operators.len();
        let searched = rel.as_ref().map_or(&compiled, |r| &r.task);
        let goal_of_op = (0..searched.operators.len())
            .map(|i| {
                let o = rel.as_ref().map_or(i, |r| r.operators[i]);
                o.checked_sub(num_ops).map_or(u32::MAX, |j| goal_of[j])
            })
            .collect::<Vec<u32>>();
        let goal_ops = (0..goal_of_op.len() as u32)
            .filter(|&o| goal_of_op[o as usize] != u32::MAX)
            .collect();
        let succ = SuccessorGenerator::new(searched);
        MultiGoalSearch {
            mode,
            goals,
            num_facts: n,
            num_ops,
            compiled,
            rel,
            goal_of_op,
            goal_ops,
            succ,
            evaluators: EvaluatorPool::default(),
            bound: None,
        }
    }

    /// Declares that goal `j` bounds the others: it has terminal cost 0, and from every state of
    /// every goal `k` a plan of cost at most `c_k` reaches it (in Logic-LfD, `j` is the task goal
    /// G and that plan is the demonstration's suffix after L_k).
    ///
    /// Then every plan to a goal `k` followed by that plan reaches `G_j`, so the prioritised
    /// optimum from `s` is at least the cost of reaching `G_j` alone: A* with LM-cut in
    /// prioritised mode evaluates LM-cut to `G_j` (0 where a goal holds) instead of the compiled
    /// task's, whose cheapest goal is `G_j` at cost 0 and which is hardly ever larger. Other
    /// modes, algorithms and heuristics ignore the declaration, and so does an index out of
    /// range or a goal with a terminal cost.
    pub fn with_lower_bound(mut self, j: usize) -> Self {
        let Some(goal) = self.goals.get(j).filter(|g| g.terminal_cost == 0) else {
            return self;
        };
        if self.mode != MultiGoalMode::Prioritised {
            return self;
        }
        let project = |f: u32| match &self.rel {
            Some(r) => r.project_fact(f),
            None => Some(f),
        };
        let alternatives = goal
            .alternatives
            .iter()
            .filter_map(|c| {
                Some(Condition {
                    pos: c.pos.iter().map(|&f| project(f)).collect::<Option<_>>()?,
                    neg: c.neg.iter().filter_map(|&f| project(f)).collect(),
                })
            })
            .collect();
        self.bound = Some(Goal {
            alternatives,
            terminal_cost: 0,
        });
        self
    }

    /// The goals as searched (facts the task does not know sanitised away).
    pub fn goals(&self) -> &[Goal] {
        &self.goals
    }

    /// How the goals are compared.
    pub fn mode(&self) -> MultiGoalMode {
        self.mode
    }

    /// `start` (a state of the original task) as a state of the compiled task.
    fn compiled_state(&self, start: &State) -> State {
        let n = self.num_facts;
        State::from_facts(
            self.compiled.facts.len(),
            start.facts().filter(|&f| (f as usize) < n),
        )
    }

    /// `start` (a state of the original task) as a state of the searched task.
    fn project(&self, start: &State) -> State {
        let start = self.compiled_state(start);
        match &self.rel {
            Some(r) => r.project(&start),
            None => start,
        }
    }

    fn searched(&self) -> &Task {
        self.rel.as_ref().map_or(&self.compiled, |r| &r.task)
    }

    /// Searches from `start` (a state of the task this search was compiled for) to any goal.
    pub fn run(&self, start: &State, config: &SearchConfig, clock: &dyn Clock) -> MultiGoalResult {
        self.run_below(start, None, config, clock)
    }

    /// [`MultiGoalSearch::run`] for a plan whose compiled cost (`cost(π) + c_k` prioritised,
    /// `cost(π)` first-reached) is below `bound`, when a plan of cost `bound` is already known:
    /// with `ucs` and A* every state whose `f` reaches it is dropped, and the outcome is
    /// [`SearchOutcome::Unsolvable`] when no cheaper plan exists. The other searches ignore it.
    pub fn run_below(
        &self,
        start: &State,
        cost_below: Option<u64>,
        config: &SearchConfig,
        clock: &dyn Clock,
    ) -> MultiGoalResult {
        let mut config = *config;
        if self.mode == MultiGoalMode::Prioritised && config.algorithm == Algorithm::Bfs {
            config.algorithm = Algorithm::Ucs; // breadth-first order ignores terminal costs
        }
        let searched_start = self.project(start);
        let kind = search_heuristic(&config);
        let task = self.searched();
        // With a bound, prioritised A* + LM-cut evaluates the heuristic to the bounding goal
        // alone: admissible for the prioritised objective, and the compiled task's LM-cut, whose
        // cheapest goal is that goal at cost 0, is hardly ever above it (B1 with 12 blocks: the
        // same expansions at twice the time per state).
        let to_bound = match (&self.bound, config.algorithm, kind) {
            (Some(goal), Algorithm::Astar, HeuristicKind::LmCut) => Some(goal),
            _ => None,
        };
        let mut heur = self
            .evaluators
            .take(kind, to_bound.is_some())
            .unwrap_or_else(|| {
                let goal = to_bound.unwrap_or(&task.goal);
                HeuristicEvaluator::new(task, std::slice::from_ref(goal), kind)
            });
        let r = run_on(
            Parts {
                task,
                succ: &self.succ,
                heur: &mut heur,
                goal_of_op: &self.goal_of_op,
                num_goals: self.goals.len(),
                goal_ops: &self.goal_ops,
                cost_below,
            },
            &searched_start,
            &config,
            clock,
        );
        self.evaluators.put(heur, to_bound.is_some());
        let mut stats = r.stats;
        let mut reached = r.reached;
        let (outcome, goal_index, total_cost) = match r.outcome {
            SearchOutcome::Plan(p) => {
                let mut ops = self
                    .rel
                    .as_ref()
                    .map_or(p.operators.clone(), |r| r.lift(&p.operators));
                // A plan ends with a goal operator, except where the search stopped at a state in
                // which one applies (`Parts::goal_ops`).
                if ops.last().is_some_and(|&o| o >= self.num_ops) {
                    ops.pop();
                }
                debug_assert!(ops.iter().all(|&o| o < self.num_ops));
                let cost = self.compiled.cost_of(&ops);
                let mut end = self.compiled_state(start);
                for &o in &ops {
                    end = self.compiled.operators[o].apply(&end);
                }
                let k = self.cheapest_goal_at(&end);
                for (g, r) in self.goals.iter().zip(reached.iter_mut()) {
                    if g.holds(&end) && r.is_none_or(|r| cost < r) {
                        *r = Some(cost);
                    }
                }
                stats.plan_cost = Some(cost);
                stats.plan_length = Some(ops.len());
                let total = k.map(|k| cost.saturating_add(self.goals[k].terminal_cost));
                (
                    SearchOutcome::Plan(Plan {
                        operators: ops,
                        cost,
                    }),
                    k,
                    total,
                )
            }
            other => (other, None, None),
        };
        MultiGoalResult {
            outcome,
            goal_index,
            total_cost,
            stats,
            reached,
        }
    }

    /// The goal holding in `s` with the smallest `(c_k, k)`.
    fn cheapest_goal_at(&self, s: &State) -> Option<usize> {
        self.goals
            .iter()
            .enumerate()
            .filter(|(_, g)| g.holds(s))
            .min_by_key(|&(k, g)| (g.terminal_cost, k))
            .map(|(k, _)| k)
    }
}

/// Heuristic evaluators kept between runs (their templates are the expensive part to build),
/// by kind and by whether they evaluate the bound.
#[derive(Default)]
struct EvaluatorPool(Mutex<Vec<(bool, HeuristicEvaluator)>>);

impl EvaluatorPool {
    fn take(&self, kind: HeuristicKind, bound: bool) -> Option<HeuristicEvaluator> {
        let mut pool = self.0.lock().ok()?;
        let i = pool
            .iter()
            .position(|(b, e)| *b == bound && e.kind() == kind)?;
        Some(pool.swap_remove(i).1)
    }

    fn put(&self, e: HeuristicEvaluator, bound: bool) {
        if let Ok(mut pool) = self.0.lock() {
            if pool
                .iter()
                .all(|(b, x)| *b != bound || x.kind() != e.kind())
            {
                pool.push((bound, e));
            }
        }
    }
}

impl Clone for EvaluatorPool {
    /// A clone starts empty: its templates are rebuilt on first use.
    fn clone(&self) -> Self {
        EvaluatorPool::default()
    }
}

impl std::fmt::Debug for EvaluatorPool {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("EvaluatorPool")
    }
}
