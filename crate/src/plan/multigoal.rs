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
//! * [`MultiGoalMode::Prioritised`] (beyond the paper): minimise `cost(π) + c_k`. The heuristic
//!   is `h(s) = min_k (h_k(s) + c_k)` — the relaxation's artificial goal fact reached by one
//!   operator of cost `c_k` per goal — admissible whenever each `h_k` is, and the goal test is done
//!   at expansion, so `ucs` and A* with an admissible heuristic are optimal. (`bfs` runs as `ucs`
//!   here; `gbfs`/`lazy-gbfs` are satisficing and stop at the first goal state they meet.)
//!
//! If `S_C` satisfies goals, `FirstReached` returns the empty plan with the smallest `(c_k, k)`;
//! `Prioritised` returns it too unless another goal is strictly cheaper to reach and finish
//! (`cost(π) + c_j < c_k`), which cannot happen when the `c_k` are exact costs-to-go.

use crate::plan::clock::Clock;
use crate::plan::search::{run, Plan, SearchConfig, SearchOutcome, SearchStats};
use crate::plan::{Goal, State, Task};

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
    let r = run(
        task,
        start,
        goals,
        mode == MultiGoalMode::Prioritised,
        true,
        config,
        clock,
    );
    let total_cost = match (&r.outcome, r.goal_index) {
        (SearchOutcome::Plan(p), Some(k)) => Some(p.cost.saturating_add(goals[k].terminal_cost)),
        _ => None,
    };
    MultiGoalResult {
        outcome: r.outcome,
        goal_index: r.goal_index,
        total_cost,
        stats: r.stats,
        reached: r.reached,
    }
}
