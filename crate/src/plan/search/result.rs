//! What a search returns: the plan, how it ended and what it cost.

use crate::plan::Task;
use std::fmt;

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

/// The result of [`search`](super::search()).
#[derive(Clone, PartialEq, Debug)]
pub struct SearchResult {
    /// Plan, proved unsolvable, or budget exhausted.
    pub outcome: SearchOutcome,
    /// Statistics.
    pub stats: SearchStats,
}
