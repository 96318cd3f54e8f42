//! LM-cut (Helmert & Domshlak, ICAPS 2009), written from the paper's definition.
//!
//! On Π⁺ with the artificial goal `G★` (see [`super::relaxed`]) and current costs `cost_i`:
//!
//! 1. compute `h_max(s, ·)` under `cost_i`; if `h_max(s, G★) = ∞` the state is a dead end, if
//!    it is 0 stop;
//! 2. precondition choice function: `pcf(o) ∈ argmax_{q ∈ pre(o)} h_max(s, q)`;
//! 3. justification graph: an edge `pcf(o) → e` labelled `o` for every `e ∈ add(o)`;
//! 4. goal zone `V*`: facts from which `G★` is reached through edges of cost-0 operators (while
//!    marking it, a cost-0 operator's pcf is re-chosen among tied maximisers in favour of the
//!    zone's border or the zone itself, as Fast Downward does);
//! 5. `V⁰`: facts reached from `s ∪ {⊤}` through edges of operators with no effect in `V*`;
//!    the cut `L = { o : pcf(o) ∈ V⁰, add(o) ∩ V* ≠ ∅ }` is a disjunctive action landmark
//!    (every relaxed plan's first operator adding a fact of `V*` is in `L`);
//! 6. `m = min_{o ∈ L} cost_i(o)`, `h += m`, `cost_{i+1}(o) = cost_i(o) − m` on `L`; repeat.
//!
//! The sum of the `m`'s is admissible (cost partitioning over landmarks) and dominates h_max.
//!
//! Cost per round: after step 6 only costs on `L` decreased, so `h_max` is repaired
//! incrementally (values only decrease; an operator's `pcf` is recomputed only when the value of
//! its current `pcf` decreased). Fact marks (`V*`, `V⁰`) are epoch stamps, so no round clears an
//! array of all facts; marking `V*` meets every achiever of a zone fact, so it also stamps the
//! operators with an effect in `V*` and step 5 tests one stamp instead of scanning add lists;
//! each operator is met at most once per round in step 5 (through its unique `pcf`), so `L`
//! needs no duplicate check. A fact's count of zero-cost achievers is kept up to date as costs
//! reach 0, so the border test of step 4 needs no scan either.

use super::relaxed::{BucketQueue, RelaxedTask, INF};

/// Per-operator state of one evaluation, kept together so that the hot loops load one record.
#[derive(Clone, Copy, Debug)]
struct OpState {
    /// Current cost `cost_i(o)`.
    cost: u64,
    /// `max_{q ∈ pre(o)} h_max(s, q)`.
    pre_max: u64,
    /// `pcf(o)`; `u32::MAX` while `o` is not relaxed-reachable.
    pcf: u32,
    /// Unsettled preconditions (0 = the operator is relaxed-reachable).
    unsat: u32,
    /// `== epoch` ⇔ some effect of `o` lies in `V*` in the current round.
    zone: u32,
}

/// Per-fact marks of one round.
#[derive(Clone, Copy, Debug, Default)]
struct FactMarks {
    /// `== epoch` ⇔ `p ∈ V*`.
    zone: u32,
    /// `== epoch` ⇔ `p ∈ V⁰`.
    reached: u32,
}

/// Buffers for LM-cut.
#[derive(Clone, Debug, Default)]
pub(crate) struct LmCut {
    /// Operator states at the start of an evaluation (costs of the task, nothing reached).
    ops_start: Vec<OpState>,
    /// Number of zero-cost achievers of each fact under the costs of the task.
    zero_start: Vec<u32>,
    ops: Vec<OpState>,
    /// Number of zero-cost achievers of each fact under `cost_i` (0 ⇔ a border fact of `V*`).
    zero_achievers: Vec<u32>,
    /// `h_max(s, p)` under `cost_i`.
    fact_cost: Vec<u64>,
    marks: Vec<FactMarks>,
    /// The facts of `s ∪ {⊤}`.
    init: Vec<u32>,
    heap: BucketQueue,
    epoch: u32,
    stack: Vec<u32>,
    /// Depth-first marking of `V*`: (fact, next index into its achievers).
    dfs: Vec<(u32, u32)>,
    cut: Vec<u32>,
}

impl LmCut {
    /// Buffers for evaluations on `rt`, with its per-task templates (the evaluator keeps one task
    /// for its lifetime).
    pub(crate) fn new(rt: &RelaxedTask) -> LmCut {
        let ops_start = (0..rt.num_ops())
            .map(|o| OpState {
                cost: rt.cost[o],
                pre_max: 0,
                pcf: u32::MAX,
                unsat: rt.pre_start[o + 1] - rt.pre_start[o],
                zone: 0,
            })
            .collect();
        let zero_start = (0..rt.num_facts() as u32)
            .map(|f| {
                rt.add_of(f)
                    .iter()
                    .filter(|&&a| rt.cost[a as usize] == 0)
                    .count() as u32
            })
            .collect();
        LmCut {
            ops_start,
            zero_start,
            marks: vec![FactMarks::default(); rt.num_facts()],
            ..LmCut::default()
        }
    }

    /// Relaxes the add effects of operator `o` to `v`.
    #[inline]
    fn relax_adds(
        fact_cost: &mut [u64],
        heap: &mut BucketQueue,
        rt: &RelaxedTask,
        o: usize,
        v: u64,
    ) {
        for &e in rt.add(o) {
            let fc = &mut fact_cost[e as usize];
            if v < *fc {
                *fc = v;
                heap.push(v, e);
            }
        }
    }

    /// Full h_max exploration from `s` under the costs of the task.
    fn hmax_full(&mut self, rt: &RelaxedTask, words: &[u64]) {
        self.fact_cost.clear();
        self.fact_cost.resize(rt.num_facts(), INF);
        self.ops.clone_from(&self.ops_start);
        self.zero_achievers.clone_from(&self.zero_start);
        self.heap.clear();
        self.init.clear();
        for (i, &w) in words.iter().enumerate() {
            let mut w = w;
            while w != 0 {
                let f = (i * 64) as u32 + w.trailing_zeros();
                w &= w - 1;
                if (f as usize) < rt.n {
                    self.init.push(f);
                }
            }
        }
        self.init.push(rt.top());
        for &f in &self.init {
            self.fact_cost[f as usize] = 0;
            self.heap.push(0, f);
        }
        while let Some((c, f)) = self.heap.pop() {
            if c > self.fact_cost[f as usize] {
                continue;
            }
            for &o in rt.pre_of(f) {
                let o = o as usize;
                let op = &mut self.ops[o];
                op.unsat -= 1;
                if op.unsat == 0 {
                    // Settled in increasing cost: `f` maximises the precondition costs.
                    op.pre_max = c;
                    op.pcf = f;
                    let v = c.saturating_add(op.cost);
                    Self::relax_adds(&mut self.fact_cost, &mut self.heap, rt, o, v);
                }
            }
        }
    }

    /// Updates h_max after the costs of the cut operators decreased (values only decrease;
    /// an operator's `pcf` is recomputed when its current `pcf` decreases).
    fn hmax_incremental(&mut self, rt: &RelaxedTask) {
        self.heap.clear();
        for &o in &self.cut {
            let o = o as usize;
            let op = &self.ops[o];
            let v = op.pre_max.saturating_add(op.cost);
            Self::relax_adds(&mut self.fact_cost, &mut self.heap, rt, o, v);
        }
        while let Some((c, f)) = self.heap.pop() {
            if c > self.fact_cost[f as usize] {
                continue;
            }
            for &o in rt.pre_of(f) {
                let o = o as usize;
                let op = &mut self.ops[o];
                // Unreached operators (pcf = MAX) stay unreached; others only change through
                // their pcf.
                if op.pcf != f || op.pre_max <= c {
                    continue;
                }
                let (mut best, mut arg) = (c, f);
                for &q in rt.pre(o) {
                    let v = self.fact_cost[q as usize];
                    if v > best {
                        best = v;
                        arg = q;
                    }
                }
                op.pcf = arg;
                if best < op.pre_max {
                    op.pre_max = best;
                    let v = best.saturating_add(op.cost);
                    Self::relax_adds(&mut self.fact_cost, &mut self.heap, rt, o, v);
                }
            }
        }
    }

    /// Starts a new round of marks (`V*`, `V⁰`), resetting the stamps on wrap-around.
    fn next_epoch(&mut self) {
        if self.epoch == u32::MAX {
            self.marks.fill(FactMarks::default());
            for op in &mut self.ops {
                op.zone = 0;
            }
            self.epoch = 0;
        }
        self.epoch += 1;
    }

    /// Marks the goal zone `V*` (facts from which `G★` is reached through zero-cost operators'
    /// pcf edges), depth first from `goal` in `add_of` order, and every operator with an
    /// effect in it (all achievers of each zone fact are met).
    ///
    /// On the way each zero-cost operator's pcf is re-chosen among its tied maximisers: first a
    /// precondition with no zero-cost achiever (the zone's border) or one already in the zone
    /// (Fickert, HSDIP 2020; Fast Downward's default). Either keeps the zone small, so the cut
    /// lies closer to the goal and later rounds find more landmarks. Any tied maximiser is a
    /// valid pcf, so the value stays admissible.
    fn mark_goal_zone(&mut self, rt: &RelaxedTask, goal: u32, ep: u32) {
        self.marks[goal as usize].zone = ep;
        self.dfs.clear();
        self.dfs.push((goal, 0));
        while let Some(top) = self.dfs.last_mut() {
            let (e, i) = *top;
            let Some(&o) = rt.add_of(e).get(i as usize) else {
                self.dfs.pop();
                continue;
            };
            top.1 += 1;
            let o = o as usize;
            let op = &mut self.ops[o];
            op.zone = ep;
            if op.cost != 0 || op.unsat != 0 {
                continue;
            }
            let p = self.break_pcf_tie(rt, o, ep);
            let m = &mut self.marks[p as usize];
            if m.zone != ep {
                m.zone = ep;
                self.dfs.push((p, 0));
            }
        }
    }

    /// Re-chooses `pcf(o)` among the preconditions of maximal h_max (see `mark_goal_zone`);
    /// returns the pcf.
    fn break_pcf_tie(&mut self, rt: &RelaxedTask, o: usize, ep: u32) -> u32 {
        let op = &mut self.ops[o];
        for &q in rt.pre(o) {
            let q_ = q as usize;
            if self.fact_cost[q_] != op.pre_max {
                continue;
            }
            if self.zero_achievers[q_] == 0 || self.marks[q_].zone == ep {
                op.pcf = q;
                return q;
            }
        }
        op.pcf
    }

    /// `V⁰`: forward from `s ∪ {⊤}` along pcf edges; an operator with an effect in `V*` joins
    /// the cut and is not followed. h_max(G★) > 0 keeps every fact of `s ∪ {⊤}` outside `V*`.
    fn find_cut(&mut self, rt: &RelaxedTask, ep: u32) {
        self.cut.clear();
        self.stack.clear();
        for &f in &self.init {
            self.marks[f as usize].reached = ep;
            self.stack.push(f);
        }
        while let Some(f) = self.stack.pop() {
            for &o in rt.pre_of(f) {
                let op = &self.ops[o as usize];
                // An unreached operator has pcf = MAX.
                if op.pcf != f {
                    continue;
                }
                if op.zone == ep {
                    self.cut.push(o);
                    continue;
                }
                for &e in rt.add(o as usize) {
                    let m = &mut self.marks[e as usize];
                    if m.reached != ep {
                        m.reached = ep;
                        self.stack.push(e);
                    }
                }
            }
        }
    }

    /// LM-cut value of the packed state, `None` for a dead end (`h_max = ∞`).
    pub fn eval(&mut self, rt: &RelaxedTask, words: &[u64]) -> Option<u64> {
        debug_assert_eq!(self.ops_start.len(), rt.num_ops(), "built for another task");
        let goal = rt.goal_fact();
        let mut h: u64 = 0;
        self.hmax_full(rt, words);
        if self.fact_cost[goal as usize] == INF {
            return None;
        }
        while self.fact_cost[goal as usize] != 0 {
            self.next_epoch();
            let ep = self.epoch;
            self.mark_goal_zone(rt, goal, ep);
            self.find_cut(rt, ep);
            let m = self
                .cut
                .iter()
                .map(|&o| self.ops[o as usize].cost)
                .min()
                .unwrap_or(0);
            if m == 0 {
                // Cannot happen for h_max(G★) > 0; stop rather than loop.
                return Some(h);
            }
            h = h.saturating_add(m);
            for &o in &self.cut {
                let op = &mut self.ops[o as usize];
                op.cost -= m;
                if op.cost == 0 {
                    for &e in rt.add(o as usize) {
                        self.zero_achievers[e as usize] += 1;
                    }
                }
            }
            self.hmax_incremental(rt);
        }
        Some(h)
    }
}
