//! Demonstration → multi-goal specification (paper §III-C, Algorithm 1 line 4).
//!
//! A demonstration is the action sequence a_1..a_N shown once. Applying it to the initial state
//! gives the logical state sequence
//!
//! ```text
//!   L_0 = S_init,   L_k = succ(L_{k-1}, a_k)   (k = 1..N),   G ⊆ L_N
//! ```
//!
//! over *fluents only* (the grounded [`Task`] has already folded static facts away, which is the
//! paper's `MultiGoalsSpecification` filter). The multi-goal specification 𝒢 = {L_0..L_N, G} is
//! what the multi-goal search plans to; goal `k` carries the terminal cost
//!
//! ```text
//!   c_k = Σ_{j>k} cost(a_j)        (= (N − k) × unit cost for unit-cost domains),   c_G = 0
//! ```
//!
//! so that the prioritised search minimises "cost to reach L_k + cost of the demo left after k".
//! A search goal "L_k" is met by any superset of L_k — which is enough for the suffix a_{k+1}..a_N
//! in STRIPS, but not when an action of the suffix needs a fact *false*. Goal k therefore also
//! requires false the facts the suffix needs false (its negative preconditions and negative goal
//! literals, regressed through the suffix); LogicIn uses the same conditions. Without negative
//! preconditions this is exactly the paper's `L_k ⊆ S_C`.
//! The specification is compiled against a particular task: when the world gains an object (L4),
//! the task is re-grounded and the specification recompiled from the fact *names*.

use std::collections::BTreeSet;

use crate::plan::{Condition, Goal, State, Task};

use super::LfdError;

/// Normalises an action written as `(stack a b)`, `stack a b` or `(STACK  A B)` to the grounded
/// operator spelling `(stack a b)`.
pub fn normalize_action(text: &str) -> String {
    let t = text.trim();
    let t = t.strip_prefix('(').unwrap_or(t);
    let t = t.strip_suffix(')').unwrap_or(t);
    let words: Vec<String> = t.split_whitespace().map(|w| w.to_lowercase()).collect();
    format!("({})", words.join(" "))
}

/// The index of the operator named `name` (any spelling accepted by [`normalize_action`]).
pub fn operator_index(task: &Task, name: &str) -> Option<usize> {
    let n = normalize_action(name);
    task.operators.iter().position(|o| o.name == n)
}

/// The fluent names that hold in `s`, sorted.
pub fn state_names(task: &Task, s: &State) -> Vec<String> {
    let mut v: Vec<String> = s.facts().map(|f| task.facts[f as usize].clone()).collect();
    v.sort();
    v
}

/// The demonstration at the logical level: its actions and the states they pass through, by name
/// (independent of any particular grounding).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DemoTrace {
    /// a_1..a_N, as grounded operator names `(stack a b)`.
    pub actions: Vec<String>,
    /// L_0..L_N: the fluents that hold before a_1, after a_1, …, after a_N.
    pub states: Vec<BTreeSet<String>>,
    /// The task's static facts (true throughout, left out of every L_k): what a scene's facts
    /// drop before they are compared with an L_k.
    pub static_facts: BTreeSet<String>,
}

impl DemoTrace {
    /// Applies the demonstrated actions from the task's initial state, checking each is applicable.
    pub fn derive(task: &Task, actions: &[String]) -> Result<Self, LfdError> {
        let mut s = task.init.clone();
        let mut states = vec![names_of(task, &s)];
        let mut names = Vec::with_capacity(actions.len());
        for (i, a) in actions.iter().enumerate() {
            let idx = operator_index(task, a).ok_or_else(|| LfdError::UnknownAction {
                index: i,
                action: a.clone(),
            })?;
            let op = &task.operators[idx];
            if !op.applicable(&s) {
                return Err(LfdError::DemoNotApplicable {
                    index: i,
                    action: op.name.clone(),
                    false_literals: op
                        .pre
                        .iter()
                        .filter(|&&f| !s.contains(f))
                        .map(|&f| task.facts[f as usize].clone())
                        .chain(
                            op.pre_neg
                                .iter()
                                .filter(|&&f| s.contains(f))
                                .map(|&f| format!("(not {})", task.facts[f as usize])),
                        )
                        .collect(),
                    location: None,
                });
            }
            s = op.apply(&s);
            names.push(op.name.clone());
            states.push(names_of(task, &s));
        }
        if !task.goal.holds(&s) {
            return Err(LfdError::DemoMissesGoal {
                false_literals: vec![],
            });
        }
        Ok(DemoTrace {
            actions: names,
            states,
            static_facts: task.static_facts.iter().cloned().collect(),
        })
    }

    /// N, the number of demonstrated actions.
    pub fn len(&self) -> usize {
        self.actions.len()
    }

    /// Whether the demonstration has no action.
    pub fn is_empty(&self) -> bool {
        self.actions.is_empty()
    }
}

fn names_of(task: &Task, s: &State) -> BTreeSet<String> {
    s.facts().map(|f| task.facts[f as usize].clone()).collect()
}

/// Per demonstration state k, the facts the rest of the demonstration needs *false* when it is
/// run from a superset of L_k: the negative literals of the goal regressed through a_N … a_{k+1}
/// (`¬f` is dropped by an action deleting f and added by one with `¬f` in its precondition).
/// Without negative preconditions or goals every set is empty.
fn needed_false(
    task: &Task,
    states: &[Option<Condition>],
    actions: &[Option<usize>],
) -> Vec<BTreeSet<crate::plan::FactId>> {
    let n = actions.len();
    let last = states
        .get(n)
        .and_then(Option::as_ref)
        .map(|c| crate::plan::State::from_facts(task.facts.len(), c.pos.iter().copied()));
    let mut need: BTreeSet<crate::plan::FactId> = task
        .goal
        .alternatives
        .iter()
        .find(|a| last.as_ref().is_some_and(|l| a.holds(l)))
        .map(|a| a.neg.iter().copied().collect())
        .unwrap_or_default();
    let mut out = vec![BTreeSet::new(); n + 1];
    for k in (0..n).rev() {
        out[k + 1] = need.clone();
        if let Some(o) = actions[k] {
            let op = &task.operators[o];
            need.retain(|f| !op.del.contains(f));
            need.extend(op.pre_neg.iter().copied());
        }
    }
    out[0] = need;
    out
}

/// The multi-goal specification 𝒢 compiled against one grounded task.
#[derive(Clone, Debug)]
pub struct MultiGoalSpec {
    /// L_0..L_N as conditions over the task's fluents (`None`: L_k mentions a fact this task can
    /// never make true, so it cannot be reached). Positive part: L_k. Negative part: the facts
    /// false in L_k that the rest of the demonstration needs false (negative preconditions and
    /// goals, regressed), so a state satisfying the condition is one from which a_{k+1} … a_N
    /// apply and reach G — exactly the supersets of L_k the suffix works from.
    pub states: Vec<Option<Condition>>,
    /// Operator index of each demonstrated action a_1..a_N in this task (`None`: not grounded).
    pub actions: Vec<Option<usize>>,
    /// The demonstrated action names a_1..a_N.
    pub action_names: Vec<String>,
    /// Search goals: index k ≤ N is L_k with c_k = cost of the demo after k; index N+1 is G (c = 0).
    pub goals: Vec<Goal>,
}

impl MultiGoalSpec {
    /// Compiles the trace against `task`. Facts of L_k that are static in `task` and true are
    /// dropped; facts the task does not know make L_k unreachable.
    pub fn new(task: &Task, demo: &DemoTrace) -> Self {
        let statics: BTreeSet<&str> = task.static_facts.iter().map(String::as_str).collect();
        let states: Vec<Option<Condition>> = demo
            .states
            .iter()
            .map(|l| {
                let mut pos = Vec::with_capacity(l.len());
                for f in l {
                    match task.fact_id(f) {
                        Some(id) => pos.push(id),
                        None if statics.contains(f.as_str()) => {}
                        None => return None,
                    }
                }
                pos.sort_unstable();
                Some(Condition { pos, neg: vec![] })
            })
            .collect();
        let actions: Vec<Option<usize>> = demo
            .actions
            .iter()
            .map(|a| operator_index(task, a))
            .collect();
        let n = actions.len();
        let needed_false = needed_false(task, &states, &actions);
        let states: Vec<Option<Condition>> = states
            .into_iter()
            .zip(needed_false)
            .map(|(c, neg)| {
                c.map(|mut c| {
                    c.neg = neg.into_iter().filter(|f| !c.pos.contains(f)).collect();
                    c
                })
            })
            .collect();
        // c_k = Σ_{j>k} cost(a_j); an ungrounded action makes the suffix unusable (c = ∞ → drop).
        let mut suffix_cost = vec![Some(0u64); n + 1];
        for k in (0..n).rev() {
            suffix_cost[k] = match (suffix_cost[k + 1], actions[k]) {
                (Some(c), Some(i)) => Some(c + u64::from(task.operators[i].cost)),
                _ => None,
            };
        }
        let mut goals: Vec<Goal> = states
            .iter()
            .zip(&suffix_cost)
            .map(|(c, cost)| match (c, cost) {
                (Some(c), Some(cost)) => Goal {
                    alternatives: vec![c.clone()],
                    terminal_cost: *cost,
                },
                _ => Goal {
                    alternatives: vec![],
                    terminal_cost: 0,
                },
            })
            .collect();
        goals.push(Goal {
            alternatives: task.goal.alternatives.clone(),
            terminal_cost: 0,
        });
        MultiGoalSpec {
            states,
            actions,
            action_names: demo.actions.clone(),
            goals,
        }
    }

    /// N, the number of demonstrated actions.
    pub fn len(&self) -> usize {
        self.actions.len()
    }

    /// Whether the demonstration is empty.
    pub fn is_empty(&self) -> bool {
        self.actions.is_empty()
    }

    /// Index of the goal G in [`MultiGoalSpec::goals`] (N + 1).
    pub fn goal_index(&self) -> usize {
        self.actions.len() + 1
    }

    /// The operator indices of a_{k+1}..a_N (the suffix after L_k), or `None` if one of them is
    /// not grounded in this task. For `k = N + 1` (the goal G) the suffix is empty.
    pub fn suffix(&self, k: usize) -> Option<Vec<usize>> {
        if k >= self.actions.len() {
            return Some(vec![]);
        }
        self.actions[k..].iter().copied().collect()
    }
}
