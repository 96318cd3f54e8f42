//! The delete relaxation Π⁺ of a task with a set of DNF goals, and the cost exploration behind
//! h_max, h_add and h_FF.
//!
//! Π⁺ keeps each operator's positive preconditions and add effects and drops deletes and negative
//! preconditions (every relaxed plan of the original task still exists, so admissibility of
//! h_max and LM-cut is kept). Two artificial facts are added: `⊤` (true in every state, the
//! precondition of operators without one) and `G★`. For each goal `k` with terminal cost `c_k`
//! and each alternative `γ` of it, a goal operator `⟨pre = γ⁺, add = {G★}, cost = c_k⟩` is added,
//! so that for every cost function of the exploration
//!
//! ```text
//! h(s) = h(s, G★) = min_k ( h(s, γ_k) + c_k ) ,
//! ```
//!
//! the minimum over goals and alternatives that the multi-goal search needs.
//!
//! Exploration (generalised Dijkstra over facts): `h(s, p) = 0` for `p ∈ s ∪ {⊤}`;
//! `h(s, o) = cost(o) + ⊕_{q ∈ pre(o)} h(s, q)` with `⊕ = max` (h_max) or `⊕ = Σ` (h_add);
//! `h(s, p) = min_{o : p ∈ add(o)} h(s, o)`. Facts are settled in increasing cost; an operator
//! fires when its last precondition is settled, and that last precondition is a maximiser of the
//! precondition costs (the precondition choice function LM-cut needs).

use crate::plan::{Goal, Task};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// "Unreachable" cost.
pub(crate) const INF: u64 = u64::MAX;

/// Marker in [`RelaxedTask::op_real`] for an artificial goal operator.
pub(crate) const GOAL_OP: u32 = u32::MAX;

/// Whether bit `f` is set in a packed state.
#[inline]
pub(crate) fn has(words: &[u64], f: u32) -> bool {
    let f = f as usize;
    words[f / 64] >> (f % 64) & 1 == 1
}

/// Π⁺ in compressed-sparse-row form.
#[derive(Clone, Debug)]
pub(crate) struct RelaxedTask {
    /// Number of fluent facts of the task (ids `0..n`); `⊤ = n`, `G★ = n + 1`.
    pub n: usize,
    pub pre_start: Vec<u32>,
    pub pre: Vec<u32>,
    pub add_start: Vec<u32>,
    pub add: Vec<u32>,
    pub cost: Vec<u64>,
    /// Index of the task operator, or [`GOAL_OP`].
    pub op_real: Vec<u32>,
    /// Fact → operators having it as precondition.
    pub pre_of_start: Vec<u32>,
    pub pre_of: Vec<u32>,
    /// Fact → operators adding it.
    pub add_of_start: Vec<u32>,
    pub add_of: Vec<u32>,
    /// Smallest operator cost of the task (for the blind heuristic); `INF` without operators.
    pub min_op_cost: u64,
}

fn csr(lists: &[Vec<u32>]) -> (Vec<u32>, Vec<u32>) {
    let mut start = Vec::with_capacity(lists.len() + 1);
    let mut flat = Vec::new();
    start.push(0);
    for l in lists {
        flat.extend_from_slice(l);
        start.push(flat.len() as u32);
    }
    (start, flat)
}

fn invert(lists: &[Vec<u32>], num_facts: usize) -> (Vec<u32>, Vec<u32>) {
    let mut inv = vec![Vec::new(); num_facts];
    for (o, l) in lists.iter().enumerate() {
        for &f in l {
            inv[f as usize].push(o as u32);
        }
    }
    csr(&inv)
}

impl RelaxedTask {
    /// Builds Π⁺ for `task` and `goals` (terminal costs included as given).
    pub fn new(task: &Task, goals: &[Goal]) -> Self {
        Self::with_operators(task, goals, None)
    }

    /// Builds Π⁺ over the operators with `keep[i]` (all operators without `keep`).
    pub fn with_operators(task: &Task, goals: &[Goal], keep: Option<&[bool]>) -> Self {
        let n = task.facts.len();
        let top = n as u32;
        let goal_fact = n as u32 + 1;
        let mut pres: Vec<Vec<u32>> = Vec::new();
        let mut adds: Vec<Vec<u32>> = Vec::new();
        let mut cost = Vec::new();
        let mut op_real = Vec::new();
        for (i, op) in task.operators.iter().enumerate() {
            if keep.is_some_and(|k| !k[i]) {
                continue;
            }
            let mut p: Vec<u32> = op.pre.clone();
            p.sort_unstable();
            p.dedup();
            let mut a: Vec<u32> = op.add.iter().copied().filter(|f| !p.contains(f)).collect();
            a.sort_unstable();
            a.dedup();
            if a.is_empty() {
                continue;
            }
            if p.is_empty() {
                p.push(top);
            }
            pres.push(p);
            adds.push(a);
            cost.push(op.cost as u64);
            op_real.push(i as u32);
        }
        for g in goals {
            for alt in &g.alternatives {
                if alt.pos.iter().any(|&f| f as usize >= n) {
                    continue; // a fact the task does not know never holds
                }
                let mut p = alt.pos.clone();
                p.sort_unstable();
                p.dedup();
                if p.is_empty() {
                    p.push(top);
                }
                pres.push(p);
                adds.push(vec![goal_fact]);
                cost.push(g.terminal_cost);
                op_real.push(GOAL_OP);
            }
        }
        let (pre_start, pre) = csr(&pres);
        let (add_start, add) = csr(&adds);
        let (pre_of_start, pre_of) = invert(&pres, n + 2);
        let (add_of_start, add_of) = invert(&adds, n + 2);
        let min_op_cost = task
            .operators
            .iter()
            .map(|o| o.cost as u64)
            .min()
            .unwrap_or(INF);
        RelaxedTask {
            n,
            pre_start,
            pre,
            add_start,
            add,
            cost,
            op_real,
            pre_of_start,
            pre_of,
            add_of_start,
            add_of,
            min_op_cost,
        }
    }

    #[inline]
    pub fn num_ops(&self) -> usize {
        self.cost.len()
    }
    #[inline]
    pub fn num_facts(&self) -> usize {
        self.n + 2
    }
    #[inline]
    pub fn top(&self) -> u32 {
        self.n as u32
    }
    #[inline]
    pub fn goal_fact(&self) -> u32 {
        self.n as u32 + 1
    }
    #[inline]
    pub fn pre(&self, o: usize) -> &[u32] {
        &self.pre[self.pre_start[o] as usize..self.pre_start[o + 1] as usize]
    }
    #[inline]
    pub fn add(&self, o: usize) -> &[u32] {
        &self.add[self.add_start[o] as usize..self.add_start[o + 1] as usize]
    }
    #[inline]
    pub fn pre_of(&self, f: u32) -> &[u32] {
        let f = f as usize;
        &self.pre_of[self.pre_of_start[f] as usize..self.pre_of_start[f + 1] as usize]
    }
    #[inline]
    pub fn add_of(&self, f: u32) -> &[u32] {
        let f = f as usize;
        &self.add_of[self.add_of_start[f] as usize..self.add_of_start[f + 1] as usize]
    }
}

/// How precondition costs combine.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Combine {
    Max,
    Sum,
}

/// Reusable buffers of one exploration.
#[derive(Clone, Debug, Default)]
pub(crate) struct Exploration {
    /// Cost of each fact.
    pub fact_cost: Vec<u64>,
    /// Operator that achieved the fact's cost (`u32::MAX` for facts of the state).
    pub supporter: Vec<u32>,
    /// Unsettled preconditions per operator.
    pub unsat: Vec<u32>,
    /// ⊕ of settled precondition costs per operator.
    pub acc: Vec<u64>,
    /// Last settled precondition (a maximiser: the precondition choice function).
    pub last_pre: Vec<u32>,
    heap: BucketQueue,
}

impl Exploration {
    /// Runs the exploration from the packed state `words` with operator costs `cost`.
    /// With `stop_at_goal`, stops once `G★` is settled (facts cheaper than it are final).
    pub fn run(
        &mut self,
        rt: &RelaxedTask,
        cost: &[u64],
        words: &[u64],
        combine: Combine,
        stop_at_goal: bool,
    ) {
        let nf = rt.num_facts();
        self.fact_cost.clear();
        self.fact_cost.resize(nf, INF);
        self.supporter.clear();
        self.supporter.resize(nf, u32::MAX);
        self.unsat.clear();
        self.unsat
            .extend(rt.pre_start.windows(2).map(|w| w[1] - w[0]));
        self.acc.clear();
        self.acc.resize(rt.num_ops(), 0);
        self.last_pre.clear();
        self.last_pre.resize(rt.num_ops(), u32::MAX);
        self.heap.clear();
        for (i, &w) in words.iter().enumerate() {
            let mut w = w;
            while w != 0 {
                let f = (i * 64) as u32 + w.trailing_zeros();
                w &= w - 1;
                if (f as usize) < rt.n {
                    self.fact_cost[f as usize] = 0;
                    self.heap.push(0, f);
                }
            }
        }
        self.fact_cost[rt.top() as usize] = 0;
        self.heap.push(0, rt.top());
        let goal = rt.goal_fact();
        while let Some((c, f)) = self.heap.pop() {
            if c > self.fact_cost[f as usize] {
                continue;
            }
            if f == goal {
                if stop_at_goal {
                    break;
                }
                continue;
            }
            for &o in rt.pre_of(f) {
                let o = o as usize;
                let a = &mut self.acc[o];
                *a = match combine {
                    Combine::Max => (*a).max(c),
                    Combine::Sum => a.saturating_add(c),
                };
                self.unsat[o] -= 1;
                if self.unsat[o] == 0 {
                    self.last_pre[o] = f;
                    let v = self.acc[o].saturating_add(cost[o]);
                    for &e in rt.add(o) {
                        if v < self.fact_cost[e as usize] {
                            self.fact_cost[e as usize] = v;
                            self.supporter[e as usize] = o as u32;
                            self.heap.push(v, e);
                        }
                    }
                }
            }
        }
    }
}

/// Priority queue of `(cost, fact)` for monotone (Dijkstra-like) use: a bucket per cost below
/// [`BucketQueue::LIMIT`], a binary heap above. Pops never return a cost below the last popped.
#[derive(Clone, Debug, Default)]
pub(crate) struct BucketQueue {
    buckets: Vec<Vec<u32>>,
    cur: usize,
    in_buckets: usize,
    overflow: BinaryHeap<Reverse<(u64, u32)>>,
}

impl BucketQueue {
    const LIMIT: u64 = 1 << 16;

    pub fn clear(&mut self) {
        if self.in_buckets > 0 {
            for b in &mut self.buckets[self.cur..] {
                b.clear();
            }
        }
        self.cur = 0;
        self.in_buckets = 0;
        self.overflow.clear();
    }

    #[inline]
    pub fn push(&mut self, c: u64, f: u32) {
        if c < Self::LIMIT {
            let c = c as usize;
            if c >= self.buckets.len() {
                self.buckets.resize_with(c + 1, Vec::new);
            }
            self.buckets[c].push(f);
            if c < self.cur {
                self.cur = c;
            }
            self.in_buckets += 1;
        } else {
            self.overflow.push(Reverse((c, f)));
        }
    }

    #[inline]
    pub fn pop(&mut self) -> Option<(u64, u32)> {
        if self.in_buckets > 0 {
            while self.buckets[self.cur].is_empty() {
                self.cur += 1;
            }
            self.in_buckets -= 1;
            let f = self.buckets[self.cur].pop().expect("non-empty bucket");
            return Some((self.cur as u64, f));
        }
        self.overflow.pop().map(|Reverse(x)| x)
    }
}
