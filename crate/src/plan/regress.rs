//! Goal regression through a fixed action sequence: the weakest condition on a state under which
//! the sequence is applicable and ends where a condition holds.
//!
//! For an operator a with preconditions pre⁺/pre⁻, adds A and deletes D (applied `(s \ D) ∪ A`),
//! a condition (P, N) regresses to
//!
//! ```text
//!   P' = (P \ A) ∪ pre⁺        N' = (N \ (D \ A)) ∪ pre⁻
//! ```
//!
//! and to nothing when a destroys what the condition needs (a fact of P in D \ A, or of N in A)
//! or when P' and N' contradict each other. RLDS (Paxton et al.) checks a demonstration's
//! remaining steps this way.

use std::collections::BTreeSet;

use super::{Condition, FactId, State, Task};

/// The condition a state must meet for `ops` (operator indices of `task`) to apply in order and
/// end where `goal` holds; `None` when no state can.
pub fn regress(task: &Task, goal: &Condition, ops: &[usize]) -> Option<Condition> {
    let mut pos: BTreeSet<FactId> = goal.pos.iter().copied().collect();
    let mut neg: BTreeSet<FactId> = goal.neg.iter().copied().collect();
    if pos.intersection(&neg).next().is_some() {
        return None;
    }
    for &o in ops.iter().rev() {
        let op = &task.operators[o];
        let adds: BTreeSet<FactId> = op.add.iter().copied().collect();
        let deletes = op.del.iter().filter(|f| !adds.contains(f));
        let mut destroyed = BTreeSet::new();
        for &f in deletes {
            if pos.contains(&f) {
                return None;
            }
            destroyed.insert(f);
        }
        if neg.iter().any(|f| adds.contains(f)) {
            return None;
        }
        pos.retain(|f| !adds.contains(f));
        neg.retain(|f| !destroyed.contains(f));
        pos.extend(op.pre.iter().copied());
        neg.extend(op.pre_neg.iter().copied());
        if pos.intersection(&neg).next().is_some() {
            return None;
        }
    }
    Some(Condition {
        pos: pos.into_iter().collect(),
        neg: neg.into_iter().collect(),
    })
}

/// Whether `ops` applies in `s` and reaches `task`'s goal, decided by regressing each goal
/// alternative (the same answer as replaying the sequence, without applying it).
pub fn reaches_goal(task: &Task, s: &State, ops: &[usize]) -> bool {
    task.goal
        .alternatives
        .iter()
        .filter_map(|c| regress(task, c, ops))
        .any(|c| c.holds(s))
}
