//! The grounded task every search works on.
//!
//! A state is the set of *fluent* facts that hold, packed as a bitset over [`FactId`]s. Static facts
//! (never added or deleted by any operator) are folded away during grounding, so they appear neither
//! in states nor in preconditions. Operators are STRIPS operators with optional negative
//! preconditions: `applicable(s) ⇔ pre ⊆ s ∧ pre_neg ∩ s = ∅`, `succ(s) = (s \ del) ∪ add`
//! (delete before add, as in PDDL semantics).
//! Goals are in disjunctive normal form: a goal holds when any of its alternatives (a conjunction
//! of positive and negative literals) holds.

use std::collections::HashMap;

/// Index of a grounded fluent fact in [`Task::facts`].
pub type FactId = u32;

/// A set of facts packed one bit per [`FactId`].
#[derive(Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Debug, Default)]
pub struct State {
    words: Vec<u64>,
}

impl State {
    /// The empty set over `num_facts` facts.
    pub fn empty(num_facts: usize) -> Self {
        State {
            words: vec![0; num_facts.div_ceil(64)],
        }
    }

    /// The set holding exactly `facts`.
    pub fn from_facts(num_facts: usize, facts: impl IntoIterator<Item = FactId>) -> Self {
        let mut s = State::empty(num_facts);
        for f in facts {
            s.insert(f);
        }
        s
    }

    /// Whether fact `f` holds.
    #[inline]
    pub fn contains(&self, f: FactId) -> bool {
        let f = f as usize;
        self.words[f / 64] >> (f % 64) & 1 == 1
    }

    /// Makes fact `f` hold.
    #[inline]
    pub fn insert(&mut self, f: FactId) {
        let f = f as usize;
        self.words[f / 64] |= 1 << (f % 64);
    }

    /// Makes fact `f` false.
    #[inline]
    pub fn remove(&mut self, f: FactId) {
        let f = f as usize;
        self.words[f / 64] &= !(1 << (f % 64));
    }

    /// The facts that hold, in increasing order.
    pub fn facts(&self) -> impl Iterator<Item = FactId> + '_ {
        self.words.iter().enumerate().flat_map(|(i, &w)| {
            let mut w = w;
            std::iter::from_fn(move || {
                if w == 0 {
                    return None;
                }
                let b = w.trailing_zeros();
                w &= w - 1;
                Some((i * 64) as FactId + b)
            })
        })
    }

    /// Number of facts that hold.
    pub fn len(&self) -> usize {
        self.words.iter().map(|w| w.count_ones() as usize).sum()
    }

    /// Whether no fact holds.
    pub fn is_empty(&self) -> bool {
        self.words.iter().all(|&w| w == 0)
    }

    /// The packed words (64 facts each), for hashing into compact tables.
    pub fn words(&self) -> &[u64] {
        &self.words
    }

    /// The same facts in a set sized for `num_facts` facts (never smaller than it is).
    pub(crate) fn widened(&self, num_facts: usize) -> State {
        let mut words = self.words.clone();
        if words.len() < num_facts.div_ceil(64) {
            words.resize(num_facts.div_ceil(64), 0);
        }
        State { words }
    }
}

/// A conjunction of literals over fluent facts.
#[derive(Clone, PartialEq, Eq, Debug, Default)]
pub struct Condition {
    /// Facts that must hold.
    pub pos: Vec<FactId>,
    /// Facts that must not hold.
    pub neg: Vec<FactId>,
}

impl Condition {
    /// Whether the conjunction holds in `s`.
    #[inline]
    pub fn holds(&self, s: &State) -> bool {
        self.pos.iter().all(|&f| s.contains(f)) && !self.neg.iter().any(|&f| s.contains(f))
    }
}

/// A goal in disjunctive normal form with a terminal cost.
///
/// In the multi-goal search of Logic-LfD, goal `k` is the demonstration state `L_k` and its
/// terminal cost `c_k ≥ 0` is what remains to be executed after reaching it.
#[derive(Clone, PartialEq, Eq, Debug, Default)]
pub struct Goal {
    /// The goal holds when any alternative holds. No alternative: the goal is unreachable.
    pub alternatives: Vec<Condition>,
    /// Cost added once the goal is reached (`c_k`); 0 for an ordinary goal.
    pub terminal_cost: u64,
}

impl Goal {
    /// Whether any alternative holds in `s`.
    pub fn holds(&self, s: &State) -> bool {
        self.alternatives.iter().any(|c| c.holds(s))
    }
}

/// A grounded STRIPS operator.
#[derive(Clone, PartialEq, Eq, Debug)]
pub struct Operator {
    /// The action as IPC planners print it, lower case: `(stack a b)`.
    pub name: String,
    /// Facts that must hold.
    pub pre: Vec<FactId>,
    /// Facts that must not hold (`:negative-preconditions`).
    pub pre_neg: Vec<FactId>,
    /// Facts made true.
    pub add: Vec<FactId>,
    /// Facts made false (applied before `add`).
    pub del: Vec<FactId>,
    /// Non-negative cost (1 without `:action-costs`).
    pub cost: u32,
}

impl Operator {
    /// Whether the operator is applicable in `s`.
    #[inline]
    pub fn applicable(&self, s: &State) -> bool {
        self.pre.iter().all(|&f| s.contains(f)) && !self.pre_neg.iter().any(|&f| s.contains(f))
    }

    /// The successor state (`(s \ del) ∪ add`); does not check applicability.
    pub fn apply(&self, s: &State) -> State {
        let mut t = s.clone();
        for &f in &self.del {
            t.remove(f);
        }
        for &f in &self.add {
            t.insert(f);
        }
        t
    }
}

#[cfg(test)]
impl Operator {
    /// A unit-cost operator without negative preconditions, for unit tests.
    pub(crate) fn unit(name: &str, pre: &[FactId], add: &[FactId], del: &[FactId]) -> Self {
        Operator {
            name: name.into(),
            pre: pre.to_vec(),
            pre_neg: vec![],
            add: add.to_vec(),
            del: del.to_vec(),
            cost: 1,
        }
    }
}

/// A grounded planning task.
#[derive(Clone, Debug, Default)]
pub struct Task {
    /// Fluent fact names, `(on a b)`, indexed by [`FactId`].
    pub facts: Vec<String>,
    /// Grounded operators, in a deterministic order.
    pub operators: Vec<Operator>,
    /// The initial state (fluents only).
    pub init: State,
    /// The goal (fluents only; static parts were checked at grounding).
    pub goal: Goal,
    /// Static facts that hold in every state (folded out of `facts`), for printing and scene graphs.
    pub static_facts: Vec<String>,
    /// Whether the domain uses `:action-costs` (a metric `minimize (total-cost)`).
    pub uses_costs: bool,
    index: HashMap<String, FactId>,
}

impl Task {
    /// The summed cost of the operators `ops`.
    pub fn cost_of(&self, ops: &[usize]) -> u64 {
        ops.iter().map(|&o| u64::from(self.operators[o].cost)).sum()
    }

    /// Builds a task and its fact-name index.
    pub fn new(
        facts: Vec<String>,
        operators: Vec<Operator>,
        init: State,
        goal: Goal,
        static_facts: Vec<String>,
        uses_costs: bool,
    ) -> Self {
        let index = facts
            .iter()
            .enumerate()
            .map(|(i, f)| (f.clone(), i as FactId))
            .collect();
        Task {
            facts,
            operators,
            init,
            goal,
            static_facts,
            uses_costs,
            index,
        }
    }

    /// The id of a fluent fact by its printed name, `(on a b)`.
    pub fn fact_id(&self, name: &str) -> Option<FactId> {
        self.index.get(name).copied()
    }

    /// Appends a fluent fact no operator touches yet (false in [`Task::init`]) and returns its
    /// id; `name` must not name a fact of the task already.
    pub(crate) fn push_fact(&mut self, name: String) -> FactId {
        let f = self.facts.len() as FactId;
        self.index.insert(name.clone(), f);
        self.facts.push(name);
        self.init = self.init.widened(self.facts.len());
        f
    }

    /// An empty state sized for this task.
    pub fn empty_state(&self) -> State {
        State::empty(self.facts.len())
    }

    /// The state in which exactly the named fluent facts hold (e.g. from a scene graph).
    ///
    /// Names are case-insensitive and whitespace-tolerant: `( ON A  b )` is `(on a b)`. Static
    /// facts (those in [`Task::static_facts`]) are accepted and ignored; any other name is an
    /// error.
    pub fn state_from_names(&self, names: &[String]) -> Result<State, UnknownFact> {
        let mut s = self.empty_state();
        for n in names {
            let norm = normalize_fact_name(n);
            if let Some(f) = self.fact_id(&norm) {
                s.insert(f);
            } else if !self.static_facts.contains(&norm) {
                return Err(UnknownFact(n.clone()));
            }
        }
        Ok(s)
    }

    /// The names of the fluent facts that hold in `s`, in [`FactId`] order.
    pub fn state_names(&self, s: &State) -> Vec<String> {
        s.facts()
            .filter_map(|f| self.facts.get(f as usize).cloned())
            .collect()
    }
}

/// A fact name that is neither a fluent nor a static fact of the task.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown fact `{0}`: neither a fluent nor a static fact of this task")]
pub struct UnknownFact(pub String);

/// `( ON A  b )` → `(on a b)`.
fn normalize_fact_name(n: &str) -> String {
    let lower = n.to_lowercase();
    let inner = lower.trim();
    let inner = inner.strip_prefix('(').unwrap_or(inner);
    let inner = inner.strip_suffix(')').unwrap_or(inner);
    format!(
        "({})",
        inner.split_whitespace().collect::<Vec<_>>().join(" ")
    )
}

/// The predicate and arguments of a fact or action written as `(p a b …)`.
pub fn fact_args(fact: &str) -> (&str, Vec<&str>) {
    let inner = fact.trim().trim_start_matches('(').trim_end_matches(')');
    let mut it = inner.split_whitespace();
    let p = it.next().unwrap_or("");
    (p, it.collect())
}

/// Replays `ops` from `s`; returns the final state, or the index of the first inapplicable action.
pub fn replay(task: &Task, s: &State, ops: &[usize]) -> Result<State, usize> {
    let mut cur = s.clone();
    for (i, &o) in ops.iter().enumerate() {
        let op = &task.operators[o];
        if !op.applicable(&cur) {
            return Err(i);
        }
        cur = op.apply(&cur);
    }
    Ok(cur)
}

/// Keeps only what the task knows: facts `≥ n` never hold, so alternatives needing one are
/// dropped and negative literals on them are vacuous.
pub(crate) fn sanitize_goals(n: usize, goals: &[Goal]) -> Vec<Goal> {
    goals
        .iter()
        .map(|g| Goal {
            alternatives: g
                .alternatives
                .iter()
                .filter(|c| c.pos.iter().all(|&f| (f as usize) < n))
                .map(|c| Condition {
                    pos: c.pos.clone(),
                    neg: c
                        .neg
                        .iter()
                        .copied()
                        .filter(|&f| (f as usize) < n)
                        .collect(),
                })
                .collect(),
            terminal_cost: g.terminal_cost,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bitset_insert_remove_iterate() {
        let mut s = State::empty(130);
        for f in [0, 63, 64, 129] {
            s.insert(f);
        }
        assert_eq!(s.facts().collect::<Vec<_>>(), vec![0, 63, 64, 129]);
        s.remove(63);
        assert!(!s.contains(63) && s.contains(64));
        assert_eq!(s.len(), 3);
    }

    #[test]
    fn apply_deletes_before_adding() {
        let op = Operator {
            name: "(x)".into(),
            pre: vec![0],
            pre_neg: vec![2],
            add: vec![1],
            del: vec![0, 1],
            cost: 1,
        };
        let s = State::from_facts(3, [0]);
        assert!(op.applicable(&s));
        let t = op.apply(&s);
        assert_eq!(t.facts().collect::<Vec<_>>(), vec![1]);
        assert!(!op.applicable(&State::from_facts(3, [0, 2])));
    }
}
