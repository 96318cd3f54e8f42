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
//! array of all facts; each operator is met at most once per round in step 5 (through its unique
//! `pcf`), so `L` needs no duplicate check.

use super::relaxed::{BucketQueue, RelaxedTask, INF};

/// Buffers for LM-cut.
#[derive(Clone, Debug, Default)]
pub(crate) struct LmCut {
    /// Current operator costs `cost_i`.
    cost: Vec<u64>,
    /// `h_max(s, p)` under `cost_i`.
    fact_cost: Vec<u64>,
    /// The facts of `s ∪ {⊤}`.
    init: Vec<u32>,
    /// Unsettled preconditions (0 = the operator is relaxed-reachable).
    unsat: Vec<u32>,
    /// `max_{q ∈ pre(o)} h_max(s, q)`.
    pre_max: Vec<u64>,
    /// `pcf(o)`.
    pcf: Vec<u32>,
    heap: BucketQueue,
    /// `zone[p] == epoch` ⇔ `p ∈ V*` in the current round.
    zone: Vec<u32>,
    /// `reached[p] == epoch` ⇔ `p ∈ V⁰` in the current round.
    reached: Vec<u32>,
    epoch: u32,
    stack: Vec<u32>,
    /// Depth-first marking of `V*`: (fact, next index into its achievers).
    dfs: Vec<(u32, usize)>,
    cut: Vec<u32>,
}

impl LmCut {
    /// Full h_max exploration from `s` under `self.cost`.
    fn hmax_full(&mut self, rt: &RelaxedTask, words: &[u64]) {
        let nf = rt.num_facts();
        self.fact_cost.clear();
        self.fact_cost.resize(nf, INF);
        self.unsat.clear();
        self.unsat
            .extend(rt.pre_start.windows(2).map(|w| w[1] - w[0]));
        self.pre_max.clear();
        self.pre_max.resize(rt.num_ops(), 0);
        self.pcf.clear();
        self.pcf.resize(rt.num_ops(), u32::MAX);
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
                // Unreached operators stay unreached; others only change through their pcf.
                if self.pcf[o] != f || self.pre_max[o] <= c || self.unsat[o] != 0 {
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

    /// Starts a new round of marks (`V*`, `V⁰`), resetting the stamps on wrap-around.
    fn next_epoch(&mut self, nf: usize) {
        if self.zone.len() != nf || self.epoch == u32::MAX {
            self.zone.clear();
            self.zone.resize(nf, 0);
            self.reached.clear();
            self.reached.resize(nf, 0);
            self.epoch = 0;
        }
        self.epoch += 1;
    }

    /// Marks the goal zone `V*` (facts from which `G★` is reached through zero-cost operators'
    /// pcf edges), depth first from `goal` in `add_of` order.
    ///
    /// On the way each zero-cost operator's pcf is re-chosen among its tied maximisers: first a
    /// precondition with no zero-cost achiever (the zone's border) or one already in the zone
    /// (Fickert, HSDIP 2020; Fast Downward's default). Either keeps the zone small, so the cut
    /// lies closer to the goal and later rounds find more landmarks. Any tied maximiser is a
    /// valid pcf, so the value stays admissible.
    fn mark_goal_zone(&mut self, rt: &RelaxedTask, goal: u32, ep: u32) {
        self.zone[goal as usize] = ep;
        self.dfs.clear();
        self.dfs.push((goal, 0));
        while let Some(top) = self.dfs.last_mut() {
            let (e, i) = *top;
            let achievers = rt.add_of(e);
            let Some(&o) = achievers.get(i) else {
                self.dfs.pop();
                continue;
            };
            top.1 += 1;
            let o = o as usize;
            if self.cost[o] != 0 || self.unsat[o] != 0 {
                continue;
            }
            self.break_pcf_tie(rt, o, ep);
            let p = self.pcf[o];
            if self.zone[p as usize] != ep {
                self.zone[p as usize] = ep;
                self.dfs.push((p, 0));
            }
        }
    }

    /// Re-chooses `pcf(o)` among the preconditions of maximal h_max (see `mark_goal_zone`).
    fn break_pcf_tie(&mut self, rt: &RelaxedTask, o: usize, ep: u32) {
        for &q in rt.pre(o) {
            if self.fact_cost[q as usize] != self.pre_max[o] {
                continue;
            }
            let border = rt.add_of(q).iter().all(|&a| self.cost[a as usize] != 0);
            if border || self.zone[q as usize] == ep {
                self.pcf[o] = q;
                return;
            }
        }
    }

    /// LM-cut value of the packed state, `None` for a dead end (`h_max = ∞`).
    pub fn eval(&mut self, rt: &RelaxedTask, words: &[u64]) -> Option<u64> {
        self.cost.clear();
        self.cost.extend_from_slice(&rt.cost);
        let goal = rt.goal_fact();
        let nf = rt.num_facts();
        let mut h: u64 = 0;
        self.hmax_full(rt, words);
        if self.fact_cost[goal as usize] == INF {
            return None;
        }
        while self.fact_cost[goal as usize] != 0 {
            self.next_epoch(nf);
            let ep = self.epoch;
            self.mark_goal_zone(rt, goal, ep);
            // V⁰: forward from s ∪ {⊤}; an operator with an effect in V* joins the cut and
            // is not followed. h_max(G★) > 0 keeps every fact of s ∪ {⊤} outside V*.
            self.cut.clear();
            self.stack.clear();
            for &f in &self.init {
                self.reached[f as usize] = ep;
                self.stack.push(f);
            }
            while let Some(f) = self.stack.pop() {
                for &o in rt.pre_of(f) {
                    let o = o as usize;
                    if self.pcf[o] != f || self.unsat[o] != 0 {
                        continue;
                    }
                    let adds = rt.add(o);
                    if adds.iter().any(|&e| self.zone[e as usize] == ep) {
                        self.cut.push(o as u32);
                        continue;
                    }
                    for &e in adds {
                        if self.reached[e as usize] != ep {
                            self.reached[e as usize] = ep;
                            self.stack.push(e);
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
        Some(h)
    }
}
