//! h² reachability: the operators that can ever apply from a start state, by pairs of facts.
//!
//! The delete relaxation forgets that two facts may never hold together (a crate both `clear`
//! and `lifting`), so it keeps operators no reachable state can apply, and LM-cut pays for them
//! with weaker cuts. Fast Downward drops such operators while translating to SAS+ (preconditions
//! that are mutex under its invariants); here the pairs come from h² (Haslum & Geffner 2000):
//!
//! * `R` starts as every pair of facts of the start state (`(p, p)` means `p` is reachable);
//! * an operator *fires* when every pair of its preconditions is in `R`; then every pair of its
//!   add effects joins `R`, and so does `(a, q)` for each add `a` and each fact `q` the operator
//!   does not delete with `(q, r) ∈ R` for every precondition `r`;
//! * repeat to the fixpoint.
//!
//! `R` over-approximates the pairs of every state reachable from the start, so an operator that
//! never fires applies in no such state and dropping it keeps every heuristic admissible there.
//! Negative preconditions are ignored (the approximation only grows). Rows are bitsets, so one
//! pass costs `O(|O| · (|pre| + |add|) · |F| / 64)`; tasks with more than [`MAX_FACTS`] facts
//! skip the analysis (its matrix would take `|F|²/8` bytes).

use crate::plan::{State, Task};

/// Largest number of facts the analysis runs on (an 8 MiB pair matrix).
pub(crate) const MAX_FACTS: usize = 8192;

/// The pair matrix: row `p` holds the facts `q` with `(p, q)` possibly true together.
struct Pairs {
    words: usize,
    bits: Vec<u64>,
}

impl Pairs {
    #[inline]
    fn row(&self, p: u32) -> &[u64] {
        let s = p as usize * self.words;
        &self.bits[s..s + self.words]
    }
    #[inline]
    fn get(&self, p: u32, q: u32) -> bool {
        self.bits[p as usize * self.words + q as usize / 64] >> (q % 64) & 1 == 1
    }
    #[inline]
    fn set(&mut self, p: u32, q: u32) {
        self.bits[p as usize * self.words + q as usize / 64] |= 1 << (q % 64);
    }
}

/// For each operator of `task`, whether it may apply in a state reachable from `start`;
/// `None` when the task has more than [`MAX_FACTS`] facts (nothing is known then).
pub(crate) fn reachable_operators(task: &Task, start: &State) -> Option<Vec<bool>> {
    let n = task.facts.len();
    if n > MAX_FACTS {
        return None;
    }
    let words = n.div_ceil(64).max(1);
    let mut r = Pairs {
        words,
        bits: vec![0; n * words],
    };
    let init: Vec<u32> = start.facts().filter(|&f| (f as usize) < n).collect();
    for &p in &init {
        for &q in &init {
            r.set(p, q);
        }
    }
    let mut fired = vec![false; task.operators.len()];
    let mut q_set = vec![0u64; words];
    let mut fresh = vec![0u64; words];
    let mut changed = true;
    while changed {
        changed = false;
        for (i, op) in task.operators.iter().enumerate() {
            if !fired[i] {
                if !op.pre.iter().all(|&p| op.pre.iter().all(|&q| r.get(p, q))) {
                    continue;
                }
                fired[i] = true;
                changed = true;
            }
            // Q: facts that may hold with every precondition and survive the operator.
            match op.pre.first() {
                Some(&p0) => q_set.copy_from_slice(r.row(p0)),
                None => {
                    q_set.iter_mut().for_each(|w| *w = 0);
                    for q in (0..n as u32).filter(|&q| r.get(q, q)) {
                        q_set[q as usize / 64] |= 1 << (q % 64);
                    }
                }
            }
            for &p in op.pre.iter().skip(1) {
                for (w, x) in q_set.iter_mut().zip(r.row(p)) {
                    *w &= x;
                }
            }
            for &d in &op.del {
                if !op.add.contains(&d) {
                    q_set[d as usize / 64] &= !(1 << (d % 64));
                }
            }
            for &a in &op.add {
                q_set[a as usize / 64] |= 1 << (a % 64);
            }
            for &a in &op.add {
                let base = a as usize * words;
                let mut any = false;
                for (k, f) in fresh.iter_mut().enumerate() {
                    *f = q_set[k] & !r.bits[base + k];
                    any |= *f != 0;
                }
                if !any {
                    continue;
                }
                changed = true;
                for (k, &f) in fresh.iter().enumerate() {
                    r.bits[base + k] |= f;
                    let mut w = f;
                    while w != 0 {
                        let q = (k * 64) as u32 + w.trailing_zeros();
                        w &= w - 1;
                        r.set(q, a);
                    }
                }
            }
        }
    }
    Some(fired)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{Condition, Goal, Operator};

    /// One gripper, one block: `holding` and `clear` never hold together, so "stack the block
    /// on itself" (needs both) never fires, while the relaxation would apply it.
    #[test]
    fn mutex_preconditions_never_fire() {
        // 0 = ontable, 1 = clear, 2 = holding, 3 = handempty, 4 = on-itself
        let facts = ["ontable", "clear", "holding", "handempty", "on-itself"];
        let ops = vec![
            Operator::unit("pick", &[0, 1, 3], &[2], &[0, 1, 3]),
            Operator::unit("put", &[2], &[0, 1, 3], &[2]),
            Operator::unit("stack-self", &[2, 1], &[4, 3], &[2, 1]),
            Operator::unit("unstack-self", &[4, 3], &[2, 1], &[4, 3]),
        ];
        let task = Task::new(
            facts.iter().map(|s| s.to_string()).collect(),
            ops,
            State::from_facts(5, [0, 1, 3]),
            Goal {
                alternatives: vec![Condition {
                    pos: vec![4],
                    neg: vec![],
                }],
                terminal_cost: 0,
            },
            vec![],
            false,
        );
        let fired = reachable_operators(&task, &task.init).unwrap();
        assert_eq!(fired, vec![true, true, false, false]);
        // From a state where the block is held and clear (not reachable from the table), both
        // fire: the analysis is relative to its start state.
        let odd = State::from_facts(5, [1, 2]);
        assert_eq!(
            reachable_operators(&task, &odd).unwrap(),
            vec![true, true, true, true]
        );
    }
}
