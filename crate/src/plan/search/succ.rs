//! Successor generator: each operator is indexed under one of its preconditions, the one shared
//! by the fewest operators; a state's applicable operators are found by walking its true facts
//! and testing only the operators indexed under them (plus those without preconditions).

use crate::plan::heuristic::relaxed::has;
use crate::plan::Task;

/// Operators indexed by a key precondition.
#[derive(Clone, Debug)]
pub(crate) struct SuccessorGenerator {
    start: Vec<u32>,
    ops: Vec<u32>,
    always: Vec<u32>,
    pre_start: Vec<u32>,
    pre: Vec<u32>,
    neg_start: Vec<u32>,
    neg: Vec<u32>,
}

impl SuccessorGenerator {
    pub fn new(task: &Task) -> Self {
        let n = task.facts.len();
        let mut count = vec![0u32; n];
        for op in &task.operators {
            for &f in &op.pre {
                count[f as usize] += 1;
            }
        }
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); n];
        let mut always = Vec::new();
        let (mut pre_start, mut pre, mut neg_start, mut neg) = (vec![0], vec![], vec![0], vec![]);
        for (i, op) in task.operators.iter().enumerate() {
            match op.pre.iter().min_by_key(|&&f| (count[f as usize], f)) {
                Some(&k) => lists[k as usize].push(i as u32),
                None => always.push(i as u32),
            }
            pre.extend_from_slice(&op.pre);
            pre_start.push(pre.len() as u32);
            neg.extend_from_slice(&op.pre_neg);
            neg_start.push(neg.len() as u32);
        }
        let mut start = vec![0];
        let mut ops = Vec::new();
        for l in lists {
            ops.extend(l);
            start.push(ops.len() as u32);
        }
        SuccessorGenerator {
            start,
            ops,
            always,
            pre_start,
            pre,
            neg_start,
            neg,
        }
    }

    #[inline]
    fn applicable(&self, o: usize, words: &[u64]) -> bool {
        let p = &self.pre[self.pre_start[o] as usize..self.pre_start[o + 1] as usize];
        let q = &self.neg[self.neg_start[o] as usize..self.neg_start[o + 1] as usize];
        p.iter().all(|&f| has(words, f)) && !q.iter().any(|&f| has(words, f))
    }

    /// The operators applicable in `words`, in increasing operator index, into `out`.
    pub fn applicable_ops(&self, words: &[u64], out: &mut Vec<u32>) {
        out.clear();
        for &o in &self.always {
            if self.applicable(o as usize, words) {
                out.push(o);
            }
        }
        let n = self.start.len() - 1;
        for (i, &w) in words.iter().enumerate() {
            let mut w = w;
            while w != 0 {
                let f = i * 64 + w.trailing_zeros() as usize;
                w &= w - 1;
                if f >= n {
                    break;
                }
                for &o in &self.ops[self.start[f] as usize..self.start[f + 1] as usize] {
                    if self.applicable(o as usize, words) {
                        out.push(o);
                    }
                }
            }
        }
        out.sort_unstable();
    }
}
