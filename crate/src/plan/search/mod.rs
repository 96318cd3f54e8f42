//! Forward state-space search on a grounded [`Task`]: breadth-first, uniform cost, A*, eager
//! greedy best-first and lazy greedy best-first with preferred operators.
//!
//! Notation: `g(s)` cost of the best known path from the start to `s`, `h(s)` the heuristic,
//! `f(s) = g(s) + h(s)`.
//!
//! * `bfs`: FIFO queue, goal test at generation; optimal in plan length.
//! * `ucs`: best-first on `g`, goal test at expansion; optimal in cost.
//! * `astar`: best-first on `f`, goal test at expansion, closed states reopened when a cheaper
//!   path is found; optimal in cost with an admissible heuristic (blind, hmax, lmcut).
//! * `gbfs`: eager greedy best-first on `h`, goal test at generation, no reopening.
//! * `lazy-gbfs`: lazy greedy best-first: successors are queued with their parent's `h` and
//!   evaluated when dequeued; with `hff`/`hadd`, successors reached by *preferred operators*
//!   (operators of the relaxed plan applicable in the parent) also enter a second queue, the two
//!   queues alternate and the preferred one gets 1000 extra turns whenever `h` improves.
//!
//! Tie-breaking is deterministic: among equal `f` (A*) or `g` (UCS) a goal state comes first,
//! then the smaller `h`; among equal keys after that (and equal `h` for GBFS) the entry inserted
//! last is taken (LIFO: on a plateau the search follows the newest, deepest path; on B1 with 12
//! blocks prioritised A* expanded 5 states where first-in-first-out expanded 18), except among
//! goal states, where the first inserted wins. Successors are generated in increasing operator
//! index. States whose heuristic is `∞` (no goal reachable even in the delete
//! relaxation) are pruned, which is safe, so an exhausted open list proves unsolvability.
//!
//! Every search has one goal (a DNF condition). Several goals with terminal costs are compiled
//! into one by [`crate::plan::MultiGoalSearch`] (a goal operator per goal), so the loops here
//! know nothing of them.
//!
//! Budgets: `max_nodes` bounds expansions, `time_limit_secs` is measured with the caller's
//! [`Clock`] (checked before each expansion); the library never reads the system time.

mod engine;
mod space;
mod succ;

use crate::plan::clock::Clock;
use crate::plan::heuristic::{HeuristicKind, UnknownName};
use crate::plan::relevance::relevant_part;
use crate::plan::{State, Task};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

pub(crate) use engine::{run_on, sanitize_goals, search_heuristic, Parts};
pub(crate) use succ::SuccessorGenerator;

/// The search algorithm of a configuration (JSON: its command-line name).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify))]
#[serde(rename_all = "kebab-case")]
pub enum Algorithm {
    /// Breadth-first search (optimal plan length).
    Bfs,
    /// Uniform-cost search (optimal cost).
    Ucs,
    /// A* (optimal cost with an admissible heuristic).
    Astar,
    /// Eager greedy best-first search.
    Gbfs,
    /// Lazy greedy best-first search with preferred operators.
    LazyGbfs,
}

impl Algorithm {
    /// All algorithms.
    pub const ALL: [Algorithm; 5] = [
        Algorithm::Bfs,
        Algorithm::Ucs,
        Algorithm::Astar,
        Algorithm::Gbfs,
        Algorithm::LazyGbfs,
    ];

    /// The command-line name: `bfs|ucs|astar|gbfs|lazy-gbfs`.
    pub fn name(self) -> &'static str {
        match self {
            Algorithm::Bfs => "bfs",
            Algorithm::Ucs => "ucs",
            Algorithm::Astar => "astar",
            Algorithm::Gbfs => "gbfs",
            Algorithm::LazyGbfs => "lazy-gbfs",
        }
    }

    /// Whether the algorithm uses the configured heuristic (`bfs` and `ucs` do not).
    pub fn uses_heuristic(self) -> bool {
        !matches!(self, Algorithm::Bfs | Algorithm::Ucs)
    }
}

impl fmt::Display for Algorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Algorithm {
    type Err = UnknownName;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Algorithm::ALL
            .into_iter()
            .find(|a| a.name() == s)
            .ok_or_else(|| UnknownName {
                what: "search algorithm",
                name: s.to_string(),
                expected: "bfs|ucs|astar|gbfs|lazy-gbfs",
            })
    }
}

/// What to run and within which budget.
#[derive(Clone, Copy, PartialEq, Debug)]
pub struct SearchConfig {
    /// The search algorithm.
    pub algorithm: Algorithm,
    /// The heuristic (ignored by `bfs` and `ucs`).
    pub heuristic: HeuristicKind,
    /// Maximum number of expanded states; `None` = unbounded.
    pub max_nodes: Option<u64>,
    /// Maximum search time in seconds, measured with the caller's clock; `None` = unbounded.
    pub time_limit_secs: Option<f64>,
}

impl Default for SearchConfig {
    /// A* with LM-cut (optimal), no budget.
    fn default() -> Self {
        SearchConfig {
            algorithm: Algorithm::Astar,
            heuristic: HeuristicKind::LmCut,
            max_nodes: None,
            time_limit_secs: None,
        }
    }
}

impl SearchConfig {
    /// A configuration without budgets.
    pub fn new(algorithm: Algorithm, heuristic: HeuristicKind) -> Self {
        SearchConfig {
            algorithm,
            heuristic,
            ..SearchConfig::default()
        }
    }

    /// Whether the configuration returns cost-optimal plans (`bfs` only on unit costs).
    pub fn is_optimal(&self) -> bool {
        match self.algorithm {
            Algorithm::Bfs | Algorithm::Ucs => true,
            Algorithm::Astar => self.heuristic.is_admissible(),
            Algorithm::Gbfs | Algorithm::LazyGbfs => false,
        }
    }
}

/// A sequence of operators of a task.
#[derive(Clone, PartialEq, Eq, Debug, Default)]
pub struct Plan {
    /// Indices into [`Task::operators`], in execution order.
    pub operators: Vec<usize>,
    /// Sum of the operators' costs (terminal costs excluded).
    pub cost: u64,
}

impl Plan {
    /// Number of actions.
    pub fn len(&self) -> usize {
        self.operators.len()
    }

    /// Whether the plan has no action.
    pub fn is_empty(&self) -> bool {
        self.operators.is_empty()
    }

    /// The actions as IPC planners print them, `(stack a b)`.
    pub fn names<'t>(&self, task: &'t Task) -> Vec<&'t str> {
        self.operators
            .iter()
            .map(|&o| task.operators[o].name.as_str())
            .collect()
    }
}

/// Which budget ran out.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Budget {
    /// `max_nodes` expansions were done.
    Nodes,
    /// `time_limit_secs` elapsed.
    Time,
}

impl fmt::Display for Budget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Budget::Nodes => "node budget",
            Budget::Time => "time limit",
        })
    }
}

/// How a search ended.
#[derive(Clone, PartialEq, Eq, Debug)]
pub enum SearchOutcome {
    /// A plan was found.
    Plan(Plan),
    /// The reachable state space holds no goal state (proved by exhausting it).
    Unsolvable,
    /// A budget ran out first.
    BudgetExhausted {
        /// The budget that ran out.
        which: Budget,
    },
}

impl SearchOutcome {
    /// The plan, if one was found.
    pub fn plan(&self) -> Option<&Plan> {
        match self {
            SearchOutcome::Plan(p) => Some(p),
            _ => None,
        }
    }
}

/// Search statistics.
#[derive(Clone, Copy, PartialEq, Debug, Default)]
pub struct SearchStats {
    /// States expanded (successors generated).
    pub expanded: u64,
    /// Successor states generated (duplicates included).
    pub generated: u64,
    /// Heuristic evaluations.
    pub evaluated: u64,
    /// Closed states reopened because a cheaper path was found (A* with inconsistent h).
    pub reopened: u64,
    /// Distinct states stored.
    pub states: u64,
    /// Cost of the returned plan (terminal cost excluded).
    pub plan_cost: Option<u64>,
    /// Length of the returned plan.
    pub plan_length: Option<usize>,
    /// Search time in seconds, by the caller's clock.
    pub time_secs: f64,
}

/// The result of [`search`].
#[derive(Clone, PartialEq, Debug)]
pub struct SearchResult {
    /// Plan, proved unsolvable, or budget exhausted.
    pub outcome: SearchOutcome,
    /// Statistics.
    pub stats: SearchStats,
}

/// Searches `task` from its initial state to its goal (its terminal cost plays no role).
///
/// The search runs on the task's relevant part ([`crate::plan::relevant_part`]): facts and
/// operators the goal never depends on are left out, so the statistics count states of that part;
/// the plan's operators are indices into `task`.
///
/// ```
/// use logic_lfd::plan::{search, Algorithm, Condition, Goal, HeuristicKind, NoClock, Operator,
///     SearchConfig, State, Task};
/// // A chain 0 → 1 → 2 of "at" facts.
/// let mv = |a: u32, b: u32| Operator { name: format!("(move p{a} p{b})"), pre: vec![a],
///     pre_neg: vec![], add: vec![b], del: vec![a], cost: 1 };
/// let goal = Goal { alternatives: vec![Condition { pos: vec![2], neg: vec![] }], terminal_cost: 0 };
/// let task = Task::new((0..3).map(|i| format!("(at p{i})")).collect(), vec![mv(0, 1), mv(1, 2)],
///     State::from_facts(3, [0]), goal, vec![], false);
/// let r = search(&task, &SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut), &NoClock);
/// assert_eq!(r.outcome.plan().unwrap().names(&task), ["(move p0 p1)", "(move p1 p2)"]);
/// ```
pub fn search(task: &Task, config: &SearchConfig, clock: &dyn Clock) -> SearchResult {
    search_from(task, &task.init, config, clock)
}

/// [`search`] from `start` instead of the task's initial state.
pub fn search_from(
    task: &Task,
    start: &State,
    config: &SearchConfig,
    clock: &dyn Clock,
) -> SearchResult {
    // Facts the goal never depends on only split states; search the relevant part instead (its
    // plans are plans of `task`, at the same optimal cost: see `relevant_part`).
    let Some(rel) = relevant_part(task) else {
        return run_one(task, start, config, clock);
    };
    let mut r = run_one(&rel.task, &rel.project(start), config, clock);
    if let SearchOutcome::Plan(p) = &mut r.outcome {
        p.operators = rel.lift(&p.operators);
    }
    r
}

fn run_one(task: &Task, start: &State, config: &SearchConfig, clock: &dyn Clock) -> SearchResult {
    let r = engine::run(task, start, config, clock);
    SearchResult {
        outcome: r.outcome,
        stats: r.stats,
    }
}
