//! Brute-force references: every reachable state, the cheapest goal cost by Dijkstra, the fewest
//! steps by breadth-first search.

use logic_lfd::plan::{Goal, Operator, State, Task};
use std::collections::{BinaryHeap, HashMap};

/// All states reachable from `start` (breadth-first), and the successor lists.
pub fn reachable(task: &Task, start: &State) -> (Vec<State>, Vec<Vec<(usize, u64)>>) {
    let mut index: HashMap<State, usize> = HashMap::from([(start.clone(), 0)]);
    let mut states = vec![start.clone()];
    let mut succ = Vec::new();
    let mut i = 0;
    while i < states.len() {
        let s = states[i].clone();
        let mut out = Vec::new();
        for op in &task.operators {
            if op.applicable(&s) {
                let t = op.apply(&s);
                let j = *index.entry(t.clone()).or_insert_with(|| {
                    states.push(t);
                    states.len() - 1
                });
                out.push((j, op.cost as u64));
            }
        }
        succ.push(out);
        i += 1;
    }
    (states, succ)
}

/// `min_k (cost of a cheapest path from s to a G_k state + c_k)` by Dijkstra, `None` if no goal
/// is reachable.
pub fn brute_force_cost(task: &Task, start: &State, goals: &[Goal]) -> Option<u64> {
    let (states, succ) = reachable(task, start);
    let mut dist = vec![u64::MAX; states.len()];
    let mut heap = BinaryHeap::from([std::cmp::Reverse((0u64, 0usize))]);
    dist[0] = 0;
    let mut best: Option<u64> = None;
    while let Some(std::cmp::Reverse((d, i))) = heap.pop() {
        if d > dist[i] {
            continue;
        }
        for g in goals {
            if g.holds(&states[i]) {
                let v = d + g.terminal_cost;
                best = Some(best.map_or(v, |b: u64| b.min(v)));
            }
        }
        for &(j, c) in &succ[i] {
            if d + c < dist[j] {
                dist[j] = d + c;
                heap.push(std::cmp::Reverse((d + c, j)));
            }
        }
    }
    best
}

/// Fewest steps from `start` to any goal state (breadth-first), `None` if unreachable.
pub fn brute_force_length(task: &Task, start: &State, goals: &[Goal]) -> Option<u64> {
    let unit: Vec<Operator> = task
        .operators
        .iter()
        .map(|o| Operator {
            cost: 1,
            ..o.clone()
        })
        .collect();
    let t = Task::new(
        task.facts.clone(),
        unit,
        task.init.clone(),
        task.goal.clone(),
        vec![],
        false,
    );
    let zero: Vec<Goal> = goals
        .iter()
        .map(|g| Goal {
            alternatives: g.alternatives.clone(),
            terminal_cost: 0,
        })
        .collect();
    brute_force_cost(&t, start, &zero)
}
