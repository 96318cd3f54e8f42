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

use super::relaxed::{Combine, Exploration, RelaxedTask, INF};

/// Buffers for LM-cut.
#[derive(Clone, Debug, Default)]
pub(crate) struct LmCut {
    cost: Vec<u64>,
    ex: Exploration,
    zone: Vec<bool>,
    reached: Vec<bool>,
    in_cut: Vec<bool>,
    stack: Vec<u32>,
    cut: Vec<u32>,
}

impl LmCut {
    /// LM-cut value of the packed state, `None` for a dead end (`h_max = ∞`).
    pub fn eval(&mut self, rt: &RelaxedTask, words: &[u64]) -> Option<u64> {
        self.cost.clear();
        self.cost.extend_from_slice(&rt.cost);
        let goal = rt.goal_fact() as usize;
        let nf = rt.num_facts();
        let mut h: u64 = 0;
        let mut first = true;
        loop {
            self.ex.run(rt, &self.cost, words, Combine::Max, false);
            let hg = self.ex.fact_cost[goal];
            if hg == INF {
                return if first { None } else { Some(h) };
            }
            first = false;
            if hg == 0 {
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
                    if self.cost[o] == 0 && self.ex.unsat[o] == 0 {
                        let p = self.ex.last_pre[o] as usize;
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
                if self.ex.fact_cost[f] == 0 && !self.zone[f] && self.ex.supporter[f] == u32::MAX {
                    self.reached[f] = true;
                    self.stack.push(f as u32);
                }
            }
            while let Some(f) = self.stack.pop() {
                for &o in rt.pre_of(f) {
                    let o = o as usize;
                    if self.ex.unsat[o] != 0 || self.ex.last_pre[o] != f {
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
        }
    }
}
