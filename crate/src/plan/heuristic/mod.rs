//! Heuristics for forward search over a set of DNF goals with terminal costs.
//!
//! All heuristics estimate `h*(s) = min_k ( cost of a cheapest plan from s to goal k + c_k )`:
//!
//! * `blind`: `min_k (c_k + [s ∉ G_k] · min_o cost(o))` (admissible);
//! * `hmax`: `h_max(s, G★)` of the delete relaxation (admissible, consistent);
//! * `hadd`: `h_add(s, G★)` (not admissible; informative);
//! * `hff`: cost of the relaxed plan extracted from `h_add` best supporters (not admissible); its
//!   operators applicable in `s` are the *preferred operators*;
//! * `lmcut`: LM-cut (admissible, `h_max ≤ LM-cut ≤ h*`).
//!
//! `G★` is the artificial goal fact of [`relaxed`], reached by one operator per goal alternative
//! with cost `c_k`. Negative preconditions and negative goal literals are ignored by the
//! relaxation. `None` means a proved dead end (no goal reachable even in the relaxation).

mod h2;
mod lmcut;
pub(crate) mod relaxed;

use crate::plan::{Goal, State, Task};
use lmcut::LmCut;
use relaxed::{has, Combine, Exploration, RelaxedTask, GOAL_OP, INF};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// The heuristic of a search configuration (JSON: its command-line name).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify))]
#[serde(rename_all = "lowercase")]
pub enum HeuristicKind {
    /// 0 on goal states, the cheapest operator cost elsewhere.
    Blind,
    /// h_max of the delete relaxation (admissible).
    HMax,
    /// h_add of the delete relaxation.
    HAdd,
    /// h_FF: relaxed plan cost, with preferred operators.
    HFf,
    /// LM-cut (admissible).
    LmCut,
}

impl HeuristicKind {
    /// All heuristics, in the order of their names.
    pub const ALL: [HeuristicKind; 5] = [
        HeuristicKind::Blind,
        HeuristicKind::HMax,
        HeuristicKind::HAdd,
        HeuristicKind::HFf,
        HeuristicKind::LmCut,
    ];

    /// The command-line name: `blind|hmax|hadd|hff|lmcut`.
    pub fn name(self) -> &'static str {
        match self {
            HeuristicKind::Blind => "blind",
            HeuristicKind::HMax => "hmax",
            HeuristicKind::HAdd => "hadd",
            HeuristicKind::HFf => "hff",
            HeuristicKind::LmCut => "lmcut",
        }
    }

    /// Whether the heuristic never overestimates `h*` (so A* with it is optimal).
    pub fn is_admissible(self) -> bool {
        matches!(
            self,
            HeuristicKind::Blind | HeuristicKind::HMax | HeuristicKind::LmCut
        )
    }
}

impl fmt::Display for HeuristicKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown heuristic or algorithm name.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown {what} `{name}` (expected one of: {expected})")]
pub struct UnknownName {
    /// What was being named (`heuristic`, `search algorithm`).
    pub what: &'static str,
    /// The name given.
    pub name: String,
    /// The accepted names, separated by `|`.
    pub expected: &'static str,
}

impl FromStr for HeuristicKind {
    type Err = UnknownName;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        HeuristicKind::ALL
            .into_iter()
            .find(|h| h.name() == s)
            .ok_or_else(|| UnknownName {
                what: "heuristic",
                name: s.to_string(),
                expected: "blind|hmax|hadd|hff|lmcut",
            })
    }
}

/// A heuristic bound to a task and a goal set, with reusable buffers.
///
/// ```
/// use logic_lfd::plan::{Condition, Goal, HeuristicEvaluator, HeuristicKind, Operator, State, Task};
/// // One fact, one operator making it true; goal: the fact.
/// let op = Operator { name: "(go)".into(), pre: vec![], pre_neg: vec![], add: vec![0], del: vec![], cost: 1 };
/// let goal = Goal { alternatives: vec![Condition { pos: vec![0], neg: vec![] }], terminal_cost: 0 };
/// let task = Task::new(vec!["(at)".into()], vec![op], State::empty(1), goal.clone(), vec![], false);
/// let mut h = HeuristicEvaluator::new(&task, &[goal], HeuristicKind::LmCut);
/// assert_eq!(h.value(&task.init), Some(1));
/// ```
#[derive(Clone, Debug)]
pub struct HeuristicEvaluator {
    kind: HeuristicKind,
    rt: RelaxedTask,
    ex: Exploration,
    lmcut: LmCut,
    goals: Vec<Goal>,
    marked: Vec<bool>,
    stack: Vec<u32>,
    plan_ops: Vec<u32>,
}

impl HeuristicEvaluator {
    /// Binds heuristic `kind` to `task` with the goals `goals` (terminal costs `c_k` included).
    pub fn new(task: &Task, goals: &[Goal], kind: HeuristicKind) -> Self {
        Self::with_relaxed(RelaxedTask::new(task, goals), goals, kind)
    }

    /// Binds heuristic `kind` for a search from `start`: values hold for states reachable
    /// from `start`.
    ///
    /// LM-cut leaves out the operators no such state can apply (their preconditions are never
    /// true together, by h² reachability from `start`; see `h2`), which only raises its values;
    /// the other heuristics are those of [`HeuristicEvaluator::new`].
    pub fn for_search(task: &Task, goals: &[Goal], kind: HeuristicKind, start: &State) -> Self {
        let keep = match kind {
            HeuristicKind::LmCut => h2::reachable_operators(task, start),
            _ => None,
        };
        let rt = RelaxedTask::with_operators(task, goals, keep.as_deref());
        Self::with_relaxed(rt, goals, kind)
    }

    fn with_relaxed(rt: RelaxedTask, goals: &[Goal], kind: HeuristicKind) -> Self {
        let lmcut = if kind == HeuristicKind::LmCut {
            LmCut::new(&rt)
        } else {
            LmCut::default()
        };
        HeuristicEvaluator {
            kind,
            marked: vec![false; rt.num_ops()],
            rt,
            ex: Exploration::default(),
            lmcut,
            goals: goals.to_vec(),
            stack: Vec::new(),
            plan_ops: Vec::new(),
        }
    }

    /// The heuristic this evaluator computes.
    pub fn kind(&self) -> HeuristicKind {
        self.kind
    }

    /// `h(s)`, or `None` when no goal is reachable from `s` even in the relaxation.
    /// Facts beyond the task's facts are ignored.
    pub fn value(&mut self, s: &State) -> Option<u64> {
        let n = self.rt.n;
        if s.words().len() == n.div_ceil(64) {
            self.eval(s.words(), None)
        } else {
            let fixed = State::from_facts(n, s.facts().filter(|&f| (f as usize) < n));
            self.eval(fixed.words(), None)
        }
    }

    /// `h(s)` of a packed state; with `preferred`, also fills in the preferred operators (task
    /// operator indices, only for `hff` and `hadd`, relaxed-plan operators applicable in `s`).
    pub(crate) fn eval(&mut self, words: &[u64], preferred: Option<&mut Vec<u32>>) -> Option<u64> {
        let rt = &self.rt;
        match self.kind {
            HeuristicKind::Blind => {
                let mut best = INF;
                for g in &self.goals {
                    if g.alternatives.is_empty() {
                        continue;
                    }
                    let holds = g.alternatives.iter().any(|c| {
                        c.pos.iter().all(|&f| in_words(words, f))
                            && !c.neg.iter().any(|&f| in_words(words, f))
                    });
                    let v = if holds {
                        g.terminal_cost
                    } else if rt.min_op_cost == INF {
                        continue;
                    } else {
                        g.terminal_cost.saturating_add(rt.min_op_cost)
                    };
                    best = best.min(v);
                }
                (best != INF).then_some(best)
            }
            HeuristicKind::HMax => {
                self.ex.run(rt, &rt.cost, words, Combine::Max, true);
                let v = self.ex.fact_cost[rt.goal_fact() as usize];
                (v != INF).then_some(v)
            }
            HeuristicKind::HAdd | HeuristicKind::HFf => {
                self.ex.run(rt, &rt.cost, words, Combine::Sum, true);
                let v = self.ex.fact_cost[rt.goal_fact() as usize];
                if v == INF {
                    return None;
                }
                if self.kind == HeuristicKind::HAdd && preferred.is_none() {
                    return Some(v);
                }
                let ff = relaxed_plan(
                    rt,
                    &self.ex,
                    &mut self.marked,
                    &mut self.plan_ops,
                    &mut self.stack,
                    words,
                );
                if let Some(pref) = preferred {
                    pref.clear();
                    for &o in &self.plan_ops {
                        let o = o as usize;
                        let real = rt.op_real[o];
                        if real != GOAL_OP
                            && rt.pre(o).iter().all(|&f| {
                                self.ex.fact_cost[f as usize] == 0
                                    && self.ex.supporter[f as usize] == u32::MAX
                            })
                        {
                            pref.push(real);
                        }
                    }
                }
                Some(if self.kind == HeuristicKind::HFf {
                    ff
                } else {
                    v
                })
            }
            HeuristicKind::LmCut => self.lmcut.eval(rt, words),
        }
    }
}

/// Marks the relaxed plan from the best supporters of the last exploration; returns its cost.
fn relaxed_plan(
    rt: &RelaxedTask,
    ex: &Exploration,
    marked: &mut [bool],
    plan_ops: &mut Vec<u32>,
    stack: &mut Vec<u32>,
    words: &[u64],
) -> u64 {
    for &o in plan_ops.iter() {
        marked[o as usize] = false;
    }
    plan_ops.clear();
    stack.clear();
    stack.push(rt.goal_fact());
    let mut total: u64 = 0;
    while let Some(f) = stack.pop() {
        let o = ex.supporter[f as usize];
        if o == u32::MAX {
            continue; // in the state, or ⊤
        }
        debug_assert!(!((f as usize) < rt.n && has(words, f)));
        let ou = o as usize;
        if marked[ou] {
            continue;
        }
        marked[ou] = true;
        plan_ops.push(o);
        total = total.saturating_add(rt.cost[ou]);
        stack.extend_from_slice(rt.pre(ou));
    }
    total
}

#[inline]
fn in_words(words: &[u64], f: u32) -> bool {
    (f as usize) < words.len() * 64 && has(words, f)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{Condition, Operator};

    /// Two independent facts, each reached by its own operator of cost 2 and 3; plus a
    /// combined operator of cost 4 adding both. h* = 4, h_max = 3, h_add = h_FF = 5, LM-cut = 4.
    fn task() -> (Task, Goal) {
        let op = |name: &str, add: Vec<u32>, cost| Operator {
            name: name.into(),
            pre: vec![],
            pre_neg: vec![],
            add,
            del: vec![],
            cost,
        };
        let goal = Goal {
            alternatives: vec![Condition {
                pos: vec![0, 1],
                neg: vec![],
            }],
            terminal_cost: 0,
        };
        let t = Task::new(
            vec!["(a)".into(), "(b)".into()],
            vec![
                op("(x)", vec![0], 2),
                op("(y)", vec![1], 3),
                op("(z)", vec![0, 1], 4),
            ],
            State::empty(2),
            goal.clone(),
            vec![],
            false,
        );
        (t, goal)
    }

    #[test]
    fn textbook_values() {
        let (t, g) = task();
        let goals = [g];
        let v = |k| HeuristicEvaluator::new(&t, &goals, k).value(&t.init);
        assert_eq!(v(HeuristicKind::HMax), Some(3));
        assert_eq!(v(HeuristicKind::HAdd), Some(5));
        assert_eq!(v(HeuristicKind::HFf), Some(5)); // h_add supporters x and y
        assert_eq!(v(HeuristicKind::LmCut), Some(4));
        assert_eq!(v(HeuristicKind::Blind), Some(2));
    }

    /// The cut follows only operators without an effect in the goal zone (the `V⁰` of the
    /// module header): `o1 = ⟨∅ → {a, y}, 2⟩`, `o2 = ⟨{y} → {a, d}, 1⟩`, `o4 = ⟨∅ → {d}, 1⟩`,
    /// goal `{a, d}`. Round 1: `V* = {G★, a}`, `L = {o1}` (`y` is not reached through `o1`,
    /// so `o2 ∉ L`), `m = 2`; round 2: `V* = {G★, d}`, `L = {o2, o4}`, `m = 1`. LM-cut = 3 = h*
    /// (following `o1` to `y` would put `o2` in the first cut and give 2).
    #[test]
    fn cut_does_not_pass_through_cut_operators() {
        let op = |name: &str, pre: Vec<u32>, add: Vec<u32>, cost| Operator {
            name: name.into(),
            pre,
            pre_neg: vec![],
            add,
            del: vec![],
            cost,
        };
        let goal = Goal {
            alternatives: vec![Condition {
                pos: vec![0, 1],
                neg: vec![],
            }],
            terminal_cost: 0,
        };
        let t = Task::new(
            vec!["(a)".into(), "(d)".into(), "(y)".into()],
            vec![
                op("(o1)", vec![], vec![0, 2], 2),
                op("(o2)", vec![2], vec![0, 1], 1),
                op("(o4)", vec![], vec![1], 1),
            ],
            State::empty(3),
            goal.clone(),
            vec![],
            false,
        );
        let goals = [goal];
        let v = |k| HeuristicEvaluator::new(&t, &goals, k).value(&t.init);
        assert_eq!(v(HeuristicKind::HMax), Some(2));
        assert_eq!(v(HeuristicKind::LmCut), Some(3));
        // Repeated evaluations reuse the buffers (epoch marks) and agree.
        let mut h = HeuristicEvaluator::new(&t, &goals, HeuristicKind::LmCut);
        for _ in 0..3 {
            assert_eq!(h.value(&t.init), Some(3));
            assert_eq!(h.value(&State::from_facts(3, [2])), Some(1));
            assert_eq!(h.value(&State::from_facts(3, [0, 1])), Some(0));
        }
    }

    #[test]
    fn terminal_costs_and_alternatives_take_the_minimum() {
        let (t, g) = task();
        let cheap_a = Goal {
            alternatives: vec![Condition {
                pos: vec![0],
                neg: vec![],
            }],
            terminal_cost: 5,
        };
        // min(4 + 0, 2 + 5) = 4; with c = 1 instead: min(4, 3) = 3.
        let mut goals = vec![g, cheap_a];
        let v = |goals: &[Goal]| {
            HeuristicEvaluator::new(&t, goals, HeuristicKind::LmCut).value(&t.init)
        };
        assert_eq!(v(&goals), Some(4));
        goals[1].terminal_cost = 1;
        assert_eq!(v(&goals), Some(3));
        // A state sized for another task does not panic: unknown facts are ignored.
        let mut h = HeuristicEvaluator::new(&t, &goals, HeuristicKind::HMax);
        assert_eq!(h.value(&State::from_facts(200, [0, 1, 150])), Some(0));
    }
}
