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

mod config;
mod engine;
mod result;
mod space;
mod succ;

use crate::plan::clock::Clock;
use crate::plan::relevance::relevant_part;
use crate::plan::{State, Task};

pub use config::{Algorithm, SearchConfig};
pub(crate) use engine::{run_on, search_heuristic, Parts};
pub use result::{Budget, Plan, SearchOutcome, SearchResult, SearchStats};
pub(crate) use succ::SuccessorGenerator;

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
