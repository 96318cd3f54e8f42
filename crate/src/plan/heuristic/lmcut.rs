//! LM-cut (Helmert & Domshlak, ICAPS 2009), written from the paper's definition.
//!
//! On Π⁺ with the artificial goal `G★` (see [`super::relaxed`]) and current costs `cost_i`:
//!
//! 1. compute `h_max(s, ·)` under `cost_i`; if `h_max(s, G★) = ∞` the state is a dead end, if
//!    it is 0 stop;
//! 2. precondition choice function: `pcf(o) ∈ argmax_{q ∈ pre(o)} h_max(s, q)`;
//! 3. justification graph: an edge `pcf(o) → e` labelled `o` for every `e ∈ add(o)`;
//! 4. goal zone `V*`: facts from which `G★` is reached through edges of cost-0 operators;
//! 5. `V⁰`: facts reached from `s ∪ {⊤}` without entering `V*`; the cut
//!    `L = { o : pcf(o) ∈ V⁰, add(o) ∩ V* ≠ ∅ }` is a disjunctive action landmark;
//! 6. `m = min_{o ∈ L} cost_i(o)`, `h += m`, `cost_{i+1}(o) = cost_i(o) − m` on `L`; repeat.
//!
//! The sum of the `m`'s is admissible (cost partitioning over landmarks) and dominates h_max.

use super::relaxed::{has, BucketQueue, RelaxedTask, INF};

/// Buffers for LM-cut.
#[derive(Clone, Debug, Default)]
pub(crate) struct LmCut {
    /// Current operator costs `cost_i`.
    cost: Vec<u64>,
    /// `h_max(s, p)` under `cost_i`.
    fact_cost: Vec<u64>,
    /// Whether the fact is in `s ∪ {⊤}`.
    init: Vec<bool>,
    /// Unsettled preconditions (0 = the operator is relaxed-reachable).
    unsat: Vec<u32>,
    /// `max_{q ∈ pre(o)} h_max(s, q)`.
    pre_max: Vec<u64>,
    /// `pcf(o)`.
    pcf: Vec<u32>,
    heap: BucketQueue,
    zone: Vec<bool>,
    reached: Vec<bool>,
    in_cut: Vec<bool>,
    stack: Vec<u32>,
    cut: Vec<u32>,
}

impl LmCut {
    /// Full h_max exploration from `s` under `self.cost`.
    fn hmax_full(&mut self, rt: &RelaxedTask, words: &[u64]) {
        let nf = rt.num_facts();
        self.fact_cost.clear();
        self.fact_cost.resize(nf, INF);
        self.init.clear();
        self.init.resize(nf, false);
        self.unsat.clear();
        self.unsat
            .extend(rt.pre_start.windows(2).map(|w| w[1] - w[0]));
        self.pre_max.clear();
        self.pre_max.resize(rt.num_ops(), 0);
        self.pcf.clear();
        self.pcf.resize(rt.num_ops(), u32::MAX);
        self.heap.clear();
        for f in 0..rt.n as u32 {
            if has(words, f) {
                self.fact_cost[f as usize] = 0;
                self.init[f as usize] = true;
                self.heap.push(0, f);
            }
        }
        let top = rt.top();
        self.fact_cost[top as usize] = 0;
        self.init[top as usize] = true;
        self.heap.push(0, top);
        while let Some((c, f)) = self.heap.pop() {
            if c > self.fact_cost[f as usize] {
                continue;
            }
            for &o in rt.pre_of(f) {
                let o = o as usize;
                self.unsat[o] -= 1;
                if self.unsat[o] == 0 {
                    // Settled in increasing cost: `f` maximises the precondition costs.
                    self.pre_max[o] = c;
                    self.pcf[o] = f;
                    let v = c.saturating_add(self.cost[o]);
                    for &e in rt.add(o) {
                        if v < self.fact_cost[e as usize] {
                            self.fact_cost[e as usize] = v;
                            self.heap.push(v, e);
                        }
                    }
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
            let v = self.pre_max[o].saturating_add(self.cost[o]);
            for &e in rt.add(o) {
                if v < self.fact_cost[e as usize] {
                    self.fact_cost[e as usize] = v;
                    self.heap.push(v, e);
                }
            }
        }
        while let Some((c, f)) = self.heap.pop() {
            if c > self.fact_cost[f as usize] {
                continue;
            }
            for &o in rt.pre_of(f) {
                let o = o as usize;
                if self.unsat[o] != 0 || self.pcf[o] != f {
                    continue;
                }
                let (mut best, mut arg) = (0u64, u32::MAX);
                for &q in rt.pre(o) {
                    let v = self.fact_cost[q as usize];
                    if arg == u32::MAX || v > best {
                        best = v;
                        arg = q;
                    }
                }
                self.pcf[o] = arg;
                if best < self.pre_max[o] {
                    self.pre_max[o] = best;
                    let v = best.saturating_add(self.cost[o]);
                    for &e in rt.add(o) {
                        if v < self.fact_cost[e as usize] {
                            self.fact_cost[e as usize] = v;
                            self.heap.push(v, e);
                        }
                    }
                }
            }
        }
    }

    /// LM-cut value of the packed state, `None` for a dead end (`h_max = ∞`).
    pub fn eval(&mut self, rt: &RelaxedTask, words: &[u64]) -> Option<u64> {
        self.cost.clear();
        self.cost.extend_from_slice(&rt.cost);
        let goal = rt.goal_fact() as usize;
        let nf = rt.num_facts();
        let mut h: u64 = 0;
        self.hmax_full(rt, words);
        if self.fact_cost[goal] == INF {
            return None;
        }
        loop {
            if self.fact_cost[goal] == 0 {
                return Some(h);
            }
            // Goal zone: backwards from G★ through zero-cost operators' pcf edges.
            self.zone.clear();
            self.zone.resize(nf, false);
            self.zone[goal] = true;
            self.stack.clear();
            self.stack.push(goal as u32);
            while let Some(e) = self.stack.pop() {
                for &o in rt.add_of(e) {
                    let o = o as usize;
                    if self.cost[o] == 0 && self.unsat[o] == 0 {
                        let p = self.pcf[o] as usize;
                        if !self.zone[p] {
                            self.zone[p] = true;
                            self.stack.push(p as u32);
                        }
                    }
                }
            }
            // Forward from s ∪ {⊤} without entering the zone; collect the cut.
            self.reached.clear();
            self.reached.resize(nf, false);
            self.in_cut.clear();
            self.in_cut.resize(rt.num_ops(), false);
            self.cut.clear();
            self.stack.clear();
            for f in 0..nf {
                if self.init[f] && !self.zone[f] {
                    self.reached[f] = true;
                    self.stack.push(f as u32);
                }
            }
            while let Some(f) = self.stack.pop() {
                for &o in rt.pre_of(f) {
                    let o = o as usize;
                    if self.unsat[o] != 0 || self.pcf[o] != f {
                        continue;
                    }
                    for &e in rt.add(o) {
                        let e = e as usize;
                        if self.zone[e] {
                            if !self.in_cut[o] {
                                self.in_cut[o] = true;
                                self.cut.push(o as u32);
                            }
                        } else if !self.reached[e] {
                            self.reached[e] = true;
                            self.stack.push(e as u32);
                        }
                    }
                }
            }
            let m = self
                .cut
                .iter()
                .map(|&o| self.cost[o as usize])
                .min()
                .unwrap_or(0);
            if m == 0 {
                // Cannot happen for h_max(G★) > 0; stop rather than loop.
                return Some(h);
            }
            h = h.saturating_add(m);
            for &o in &self.cut {
                self.cost[o as usize] -= m;
            }
            self.hmax_incremental(rt);
        }
    }
}
