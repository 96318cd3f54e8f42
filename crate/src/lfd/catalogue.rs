//! The catalogue: every method, multi-goal mode, benchmark and disturbance level with its id (the
//! CLI and JSON name), a short label and a one-line description.
//!
//! The command line's help and value parsing, the npm package's `catalogue()` and the page's
//! selects, tables and tooltips all read it, so an entry is named and described here only. What
//! an entry does is code elsewhere: a method's behaviour is the match in `control/mod.rs` and
//! `session/tick.rs`, a mode's the multi-goal search of `logic.rs`, a level's the injector of
//! `disturb/mod.rs`, a benchmark's files and scene [`crate::sim::benchmark`].

use serde::{Deserialize, Serialize};

use crate::sim::Benchmark;

/// The method that closes the loop (the paper's method and its baselines).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify))]
pub enum Method {
    /// Logic-LfD (Algorithm 1): LogicIn, else multi-goal search + demo suffix.
    #[default]
    #[serde(rename = "logic-lfd")]
    LogicLfd,
    /// The demonstration's actions in order, skills re-targeted, no task-level feedback.
    #[serde(rename = "linear")]
    Linear,
    /// RLDS: jump backward/forward along the demonstration to the matching step; never a new plan.
    #[serde(rename = "rlds")]
    Rlds,
    /// TAMP from scratch at every task-level change (the paper's PDDLStream column).
    #[serde(rename = "tamp")]
    Tamp,
}

impl Method {
    /// All methods, in table order.
    pub const ALL: [Method; 4] = [Method::Linear, Method::Rlds, Method::Tamp, Method::LogicLfd];

    /// The name used on the CLI and in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            Method::LogicLfd => "logic-lfd",
            Method::Linear => "linear",
            Method::Rlds => "rlds",
            Method::Tamp => "tamp",
        }
    }

    /// Parses a CLI / JSON name.
    pub fn parse(s: &str) -> Option<Self> {
        Method::ALL.into_iter().find(|m| m.as_str() == s)
    }
}

/// How the multi-goal search picks among the demonstration states.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify))]
pub enum Mode {
    /// The paper: the first demonstration state reached, all goals of equal priority.
    #[default]
    Paper,
    /// Minimise (cost to reach L_k) + (demo actions left after k) in the same single search.
    Prioritised,
}

impl Mode {
    /// Both modes.
    pub const ALL: [Mode; 2] = [Mode::Paper, Mode::Prioritised];

    /// The name used on the CLI and in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            Mode::Paper => "paper",
            Mode::Prioritised => "prioritised",
        }
    }

    /// Parses `paper` or `prioritised` (also `prioritized`).
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "paper" => Some(Mode::Paper),
            "prioritised" | "prioritized" => Some(Mode::Prioritised),
            _ => None,
        }
    }
}

/// Disturbance levels of the paper (§IV-B); JSON and CLI: `l1`..`l4`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify))]
pub enum Level {
    /// Motion level: positions change, facts do not.
    L1,
    /// Slight task level: facts change to a state seen in the demonstration.
    L2,
    /// Severe task level: facts change to a state the demonstration never visits.
    L3,
    /// Extreme task level: a new block appears in the way.
    L4,
}

impl Level {
    /// All levels.
    pub const ALL: [Level; 4] = [Level::L1, Level::L2, Level::L3, Level::L4];

    /// `l1`..`l4`.
    pub fn as_str(self) -> &'static str {
        match self {
            Level::L1 => "l1",
            Level::L2 => "l2",
            Level::L3 => "l3",
            Level::L4 => "l4",
        }
    }

    /// Parses `l1`..`l4` (case-insensitive).
    pub fn parse(s: &str) -> Option<Level> {
        Level::ALL
            .into_iter()
            .find(|l| l.as_str().eq_ignore_ascii_case(s))
    }
}

/// A kind of name the catalogue lists: methods, modes, benchmarks, disturbance levels.
pub trait Listed: Copy + Eq + Serialize + 'static {
    /// What one is called in messages (`method`, `mode`, `benchmark`, `level`).
    const KIND: &'static str;

    /// Every one, in the order lists show them.
    fn all() -> &'static [Self];

    /// The CLI and JSON name.
    fn id(self) -> &'static str;

    /// A short label for people (a select's text, a table's row).
    fn label(self) -> &'static str;

    /// One sentence for people (a tooltip, a help line).
    fn description(self) -> &'static str;

    /// Parses an id, and the other spellings the kind accepts (`prioritized`, `b1-tower`, `L3`).
    fn parse_id(s: &str) -> Option<Self>;

    /// [`Listed::parse_id`], or an error that lists the ids.
    fn from_id(s: &str) -> Result<Self, UnknownId> {
        Self::parse_id(s).ok_or_else(|| UnknownId {
            kind: Self::KIND,
            given: s.to_string(),
            expected: Self::all().iter().map(|x| x.id()).collect(),
        })
    }

    /// The catalogue's entry.
    fn entry(self) -> CatalogueEntry<Self> {
        CatalogueEntry {
            id: self,
            label: self.label(),
            description: self.description(),
        }
    }
}

/// A name that is not in the catalogue.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown {kind} \"{given}\" (expected {})", expected.join(", "))]
pub struct UnknownId {
    /// What was being named (`method`, …).
    pub kind: &'static str,
    /// The name given.
    pub given: String,
    /// The ids of the kind, in list order.
    pub expected: Vec<&'static str>,
}

impl Listed for Method {
    const KIND: &'static str = "method";

    fn all() -> &'static [Self] {
        &Method::ALL
    }

    fn id(self) -> &'static str {
        self.as_str()
    }

    fn label(self) -> &'static str {
        match self {
            Method::LogicLfd => "Logic-LfD",
            Method::Linear => "Linear",
            Method::Rlds => "RLDS",
            Method::Tamp => "TAMP",
        }
    }

    fn description(self) -> &'static str {
        match self {
            Method::LogicLfd => {
                "Plans with PDDL to the nearest state of the demonstration (any L_k), then \
                 follows the rest of it; replans whenever the facts change."
            }
            Method::Linear => {
                "Replays the demonstrated actions in order, blind to the facts: a changed scene \
                 makes an action fail."
            }
            Method::Rlds => {
                "Jumps back or forward along the demonstration to the state that matches; never \
                 makes a new plan, so an unseen state stops it."
            }
            Method::Tamp => {
                "Plans from scratch to the goal G after every change, ignoring the demonstration \
                 (slower planning, same robot)."
            }
        }
    }

    fn parse_id(s: &str) -> Option<Self> {
        Method::parse(s)
    }
}

impl Listed for Mode {
    const KIND: &'static str = "mode";

    fn all() -> &'static [Self] {
        &Mode::ALL
    }

    fn id(self) -> &'static str {
        self.as_str()
    }

    fn label(self) -> &'static str {
        self.as_str()
    }

    fn description(self) -> &'static str {
        match self {
            Mode::Paper => {
                "As in the paper: the shortest plan to any demonstration state L_k, then the \
                 demonstration from k on."
            }
            Mode::Prioritised => {
                "Minimises the whole: the actions to reach L_k plus the demonstration actions \
                 left after k, so the merged plan is never longer than needed."
            }
        }
    }

    fn parse_id(s: &str) -> Option<Self> {
        Mode::parse(s)
    }
}

impl Listed for Benchmark {
    const KIND: &'static str = "benchmark";

    fn all() -> &'static [Self] {
        &Benchmark::ALL
    }

    fn id(self) -> &'static str {
        self.as_str()
    }

    fn label(self) -> &'static str {
        match self {
            Benchmark::B1 => "B1 · tower",
            Benchmark::B2 => "B2 · reach (hook)",
            Benchmark::B3 => "B3 · two arms",
        }
    }

    fn description(self) -> &'static str {
        match self {
            Benchmark::B1 => {
                "Tower construction: one arm stacks four blocks into the tower A on B on C on D."
            }
            Benchmark::B2 => {
                "Workspace reach: one arm puts two blocks on a shelf, pulling the one beyond its \
                 reach in with a hook."
            }
            Benchmark::B3 => {
                "Two arms: the blocks start where only the left arm reaches and the tower is \
                 built where only the right arm reaches, through a hand-over region."
            }
        }
    }

    fn parse_id(s: &str) -> Option<Self> {
        Benchmark::parse(s)
    }
}

impl Listed for Level {
    const KIND: &'static str = "level";

    fn all() -> &'static [Self] {
        &Level::ALL
    }

    fn id(self) -> &'static str {
        self.as_str()
    }

    fn label(self) -> &'static str {
        match self {
            // Words, not the paper's L1–L4: the page shows them beside the demonstration's
            // states L_k, and "L2" must not name both.
            Level::L1 => "Nudge",
            Level::L2 => "Set back",
            Level::L3 => "Scramble",
            Level::L4 => "New block",
        }
    }

    fn description(self) -> &'static str {
        match self {
            Level::L1 => {
                "Motion-level: move a block a little (or push the moving hand); the facts stay \
                 the same."
            }
            Level::L2 => "Facts change to a state seen in the demonstration.",
            Level::L3 => "Facts change to a state the demonstration never saw.",
            Level::L4 => "A new block appears in the way.",
        }
    }

    fn parse_id(s: &str) -> Option<Self> {
        Level::parse(s)
    }
}

/// One entry of the catalogue.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify))]
pub struct CatalogueEntry<T> {
    /// The CLI and JSON name.
    pub id: T,
    /// A short label for people (a select's text, a table's row).
    pub label: &'static str,
    /// One sentence for people (a tooltip, a help line).
    pub description: &'static str,
}

/// Every method, multi-goal mode, benchmark and disturbance level, each list in the order the
/// page and the tables show it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify))]
pub struct Catalogue {
    /// The methods, in table order (the baselines, then Logic-LfD).
    pub methods: Vec<CatalogueEntry<Method>>,
    /// The multi-goal modes of Logic-LfD.
    pub modes: Vec<CatalogueEntry<Mode>>,
    /// The paper's benchmarks.
    pub benchmarks: Vec<CatalogueEntry<Benchmark>>,
    /// The disturbance levels L1–L4.
    pub levels: Vec<CatalogueEntry<Level>>,
}

/// The whole catalogue.
pub fn catalogue() -> Catalogue {
    fn entries<T: Listed>() -> Vec<CatalogueEntry<T>> {
        T::all().iter().map(|x| x.entry()).collect()
    }
    Catalogue {
        methods: entries(),
        modes: entries(),
        benchmarks: entries(),
        levels: entries(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each list's ids, read back through serde as the kind's own type.
    fn ids_of<T: serde::de::DeserializeOwned>(json: &serde_json::Value, list: &str) -> Vec<T> {
        json[list]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| serde_json::from_value(e["id"].clone()).unwrap())
            .collect()
    }

    #[test]
    fn every_id_round_trips_through_serde_and_lists_all() {
        let json = serde_json::to_value(catalogue()).unwrap();
        assert_eq!(ids_of::<Method>(&json, "methods"), Method::ALL);
        assert_eq!(ids_of::<Mode>(&json, "modes"), Mode::ALL);
        assert_eq!(ids_of::<Benchmark>(&json, "benchmarks"), Benchmark::ALL);
        assert_eq!(ids_of::<Level>(&json, "levels"), Level::ALL);
    }

    fn check<T: Listed + std::fmt::Debug>() {
        for &x in T::all() {
            // The id is the serde name, and parses back.
            assert_eq!(serde_json::to_value(x).unwrap(), x.id(), "{x:?}");
            assert_eq!(T::from_id(x.id()), Ok(x));
            assert!(!x.label().is_empty() && x.description().ends_with('.'));
        }
    }

    #[test]
    fn ids_are_the_serde_names_and_every_entry_is_described() {
        check::<Method>();
        check::<Mode>();
        check::<Benchmark>();
        check::<Level>();
    }

    #[test]
    fn an_unknown_id_lists_the_known_ones() {
        let e = Method::from_id("lfd").unwrap_err();
        assert_eq!(
            e.to_string(),
            "unknown method \"lfd\" (expected linear, rlds, tamp, logic-lfd)"
        );
        assert_eq!(Mode::from_id("prioritized"), Ok(Mode::Prioritised));
    }
}
