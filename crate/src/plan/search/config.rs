//! What a search runs: the algorithm, its heuristic and budgets.

use crate::plan::heuristic::{HeuristicKind, UnknownName};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

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
