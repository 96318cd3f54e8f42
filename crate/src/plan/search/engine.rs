//! The search loops behind [`super::search`] and [`crate::plan::search_multi_goal`].
//! See the module documentation of [`super`] for the algorithms and tie-breaking.

use super::space::StateSpace;
use super::succ::SuccessorGenerator;
use super::{Algorithm, Budget, Plan, SearchConfig, SearchOutcome, SearchStats};
use crate::plan::clock::{Clock, PROGRESS_EVERY};
use crate::plan::heuristic::relaxed::has;
use crate::plan::heuristic::HeuristicEvaluator;
use crate::plan::task::sanitize_goals;
use crate::plan::{Goal, State, Task};
use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};

/// Result of one run: outcome, statistics and, for a compiled multi-goal task, what each goal's
/// operator met.
pub(crate) struct RunResult {
    pub outcome: SearchOutcome,
    pub stats: SearchStats,
    /// Per goal of [`Parts::goal_of_op`], the cheapest `g` of an expanded state in which its goal
    /// operator applies (`None`: never); empty without goal operators.
    pub reached: Vec<Option<u64>>,
}

const NONE: u32 = u32::MAX;

/// Whether `goal` holds in the packed state `words` (one of its alternatives does).
fn goal_holds(goal: &Goal, words: &[u64]) -> bool {
    goal.alternatives
        .iter()
        .any(|c| c.pos.iter().all(|&f| has(words, f)) && !c.neg.iter().any(|&f| has(words, f)))
}
const OPEN: u8 = 0;
const CLOSED: u8 = 1;
const DEAD: u8 = 2;

/// An open-list entry: ordered by `(k1, k2, seq)`, smallest first.
#[derive(PartialEq, Eq, PartialOrd, Ord, Clone, Copy, Debug)]
struct Entry {
    k1: u64,
    k2: u64,
    seq: u64,
    node: u32,
    g: u64,
}

/// What a search runs on, built once and reused by every search of the same task.
pub(crate) struct Parts<'a> {
    /// The task; its goal is the goal (terminal cost ignored).
    pub task: &'a Task,
    /// Its successor generator.
    pub succ: &'a SuccessorGenerator,
    /// The heuristic bound to `task` and its goal.
    pub heur: &'a mut HeuristicEvaluator,
    /// Per operator, the goal whose goal operator it is (`u32::MAX`: an ordinary operator);
    /// empty for a task without goal operators.
    pub goal_of_op: &'a [u32],
    /// Number of goals behind the goal operators.
    pub num_goals: usize,
    /// With `bfs`, `gbfs` and `lazy-gbfs`: a state in which one of these operators applies is a
    /// goal state too (the search stops where a goal holds, not one step later).
    pub goal_ops: &'a [u32],
    /// With `ucs` and A*: only plans cheaper than this are wanted (one of this cost is known);
    /// states whose `f` reaches it are dropped and the search ends unsolved when none is left.
    pub cost_below: Option<u64>,
}

/// Runs `config` from `start` on `task` alone: builds the successor generator and the heuristic
/// (LM-cut pruned by h² reachability from `start`) for this one search.
pub(crate) fn run(
    task: &Task,
    start: &State,
    config: &SearchConfig,
    clock: &dyn Clock,
) -> RunResult {
    let n = task.facts.len();
    let start = State::from_facts(n, start.facts().filter(|&f| (f as usize) < n));
    let mut goal = sanitize_goals(n, std::slice::from_ref(&task.goal));
    goal[0].terminal_cost = 0;
    let succ = SuccessorGenerator::new(task);
    let mut heur = HeuristicEvaluator::for_search(task, &goal, search_heuristic(config), &start);
    let parts = Parts {
        task,
        succ: &succ,
        heur: &mut heur,
        goal_of_op: &[],
        num_goals: 0,
        goal_ops: &[],
        cost_below: None,
    };
    run_on(parts, &start, config, clock)
}

/// The heuristic a configuration evaluates (`bfs` and `ucs` use none).
pub(crate) fn search_heuristic(config: &SearchConfig) -> crate::plan::HeuristicKind {
    if config.algorithm.uses_heuristic() {
        config.heuristic
    } else {
        crate::plan::HeuristicKind::Blind
    }
}

/// Runs `config` from `start` (a state of `parts.task`) until a state satisfying the task's goal
/// is reached.
pub(crate) fn run_on(
    parts: Parts<'_>,
    start: &State,
    config: &SearchConfig,
    clock: &dyn Clock,
) -> RunResult {
    let task = parts.task;
    let n = task.facts.len();
    let start = State::from_facts(n, start.facts().filter(|&f| (f as usize) < n));
    let goal = sanitize_goals(n, std::slice::from_ref(&task.goal)).remove(0);
    let t0 = clock.now_secs();
    let mut e = Engine {
        task,
        goal: &goal,
        config,
        clock,
        t0,
        space: StateSpace::new(start.words().len()),
        parent: Vec::new(),
        op: Vec::new(),
        g: Vec::new(),
        h: Vec::new(),
        status: Vec::new(),
        succ: parts.succ,
        heur: parts.heur,
        stats: SearchStats::default(),
        ops_buf: Vec::new(),
        words_buf: Vec::new(),
        child_buf: Vec::new(),
        goal_of_op: parts.goal_of_op,
        reached: vec![u64::MAX; parts.num_goals],
        goal_ops: match config.algorithm {
            Algorithm::Bfs | Algorithm::Gbfs | Algorithm::LazyGbfs => parts.goal_ops,
            Algorithm::Ucs | Algorithm::Astar => &[],
        },
        cost_below: match config.algorithm {
            Algorithm::Ucs | Algorithm::Astar => parts.cost_below,
            _ => None,
        },
    };
    let outcome = match config.algorithm {
        Algorithm::Bfs => e.bfs(start.words()),
        Algorithm::Ucs | Algorithm::Astar | Algorithm::Gbfs => {
            e.best_first(start.words(), config.algorithm)
        }
        Algorithm::LazyGbfs => e.lazy_gbfs(start.words()),
    };
    e.stats.time_secs = (clock.now_secs() - t0).max(0.0);
    e.stats.states = e.space.len() as u64;
    if let SearchOutcome::Plan(p) = &outcome {
        e.stats.plan_cost = Some(p.cost);
        e.stats.plan_length = Some(p.len());
    }
    RunResult {
        outcome,
        stats: e.stats,
        reached: e
            .reached
            .iter()
            .map(|&g| (g != u64::MAX).then_some(g))
            .collect(),
    }
}

struct Engine<'a> {
    task: &'a Task,
    goal: &'a Goal,
    config: &'a SearchConfig,
    clock: &'a dyn Clock,
    t0: f64,
    space: StateSpace,
    parent: Vec<u32>,
    op: Vec<u32>,
    g: Vec<u64>,
    h: Vec<u64>,
    status: Vec<u8>,
    succ: &'a SuccessorGenerator,
    heur: &'a mut HeuristicEvaluator,
    stats: SearchStats,
    ops_buf: Vec<u32>,
    words_buf: Vec<u64>,
    child_buf: Vec<u64>,
    goal_of_op: &'a [u32],
    /// Per goal, the cheapest `g` of an expanded state its goal operator applies in
    /// (`u64::MAX`: never); empty without goal operators.
    reached: Vec<u64>,
    /// Operators whose applicability makes a goal state (see [`Parts::goal_ops`]).
    goal_ops: &'a [u32],
    /// See [`Parts::cost_below`].
    cost_below: Option<u64>,
}

impl Engine<'_> {
    /// Notes, for goal operators among `ops` (applicable in a state of cost `g`), that their
    /// goal was met at `g`.
    fn note_reached(&mut self, ops: &[u32], g: u64) {
        if self.goal_of_op.is_empty() {
            return;
        }
        for &o in ops {
            let k = self.goal_of_op[o as usize];
            if k != NONE && g < self.reached[k as usize] {
                self.reached[k as usize] = g;
            }
        }
    }

    /// Registers a state (if new, with its parent link and `g`).
    fn register(&mut self, words: &[u64], parent: u32, op: u32, g: u64) -> (u32, bool) {
        let (id, new) = self.space.insert(words);
        if new {
            self.parent.push(parent);
            self.op.push(op);
            self.g.push(g);
            self.h.push(0);
            self.status.push(OPEN);
        }
        (id, new)
    }

    fn budget(&self) -> Option<Budget> {
        if self.stats.expanded % PROGRESS_EVERY == 0 && self.stats.expanded > 0 {
            self.clock.progress(self.stats.expanded);
        }
        if let Some(m) = self.config.max_nodes {
            if self.stats.expanded >= m {
                return Some(Budget::Nodes);
            }
        }
        if let Some(t) = self.config.time_limit_secs {
            if self.clock.now_secs() - self.t0 > t {
                return Some(Budget::Time);
            }
        }
        None
    }

    /// `h` of a packed state for the best-first searches, `None` for a proven dead end; 0 where
    /// the goal holds (`goal`), whatever the heuristic estimates (a heuristic to a goal implied
    /// by the task's, see [`crate::plan::MultiGoalSearch::with_lower_bound`], is not 0 there).
    fn h_of(&mut self, words: &[u64], goal: bool) -> Option<u64> {
        if goal {
            return Some(0);
        }
        self.heur.eval(words, None)
    }

    /// Whether the goal holds in `words`, or one of the goal operators applies.
    fn is_goal(&self, words: &[u64]) -> bool {
        goal_holds(self.goal, words)
            || self.goal_ops.iter().any(|&o| {
                let op = &self.task.operators[o as usize];
                op.pre.iter().all(|&f| has(words, f)) && !op.pre_neg.iter().any(|&f| has(words, f))
            })
    }

    /// Writes the successor of `self.words_buf` by operator `o` into `self.child_buf`.
    fn apply_into_child(&mut self, o: u32) {
        let op = &self.task.operators[o as usize];
        self.child_buf.clear();
        self.child_buf.extend_from_slice(&self.words_buf);
        for &f in &op.del {
            self.child_buf[f as usize / 64] &= !(1u64 << (f % 64));
        }
        for &f in &op.add {
            self.child_buf[f as usize / 64] |= 1u64 << (f % 64);
        }
    }

    fn load(&mut self, id: u32) {
        self.words_buf.clear();
        self.words_buf.extend_from_slice(self.space.get(id));
    }

    fn plan_to(&mut self, id: u32) -> SearchOutcome {
        let mut ops = Vec::new();
        let mut cur = id;
        while self.parent[cur as usize] != NONE {
            ops.push(self.op[cur as usize] as usize);
            cur = self.parent[cur as usize];
        }
        ops.reverse();
        let cost = self.task.cost_of(&ops);
        SearchOutcome::Plan(Plan {
            operators: ops,
            cost,
        })
    }

    fn bfs(&mut self, start: &[u64]) -> SearchOutcome {
        let (s, _) = self.register(start, NONE, NONE, 0);
        if self.is_goal(start) {
            return self.plan_to(s);
        }
        let mut queue = VecDeque::from([s]);
        let mut ops = std::mem::take(&mut self.ops_buf);
        while let Some(id) = queue.pop_front() {
            if let Some(b) = self.budget() {
                return SearchOutcome::BudgetExhausted { which: b };
            }
            self.stats.expanded += 1;
            self.load(id);
            self.succ.applicable_ops(&self.words_buf, &mut ops);
            let g = self.g[id as usize];
            self.note_reached(&ops, g);
            for &o in &ops {
                self.apply_into_child(o);
                self.stats.generated += 1;
                let cost = self.task.operators[o as usize].cost as u64;
                let child = std::mem::take(&mut self.child_buf);
                let (t, new) = self.register(&child, id, o, g + cost);
                let goal = new && self.is_goal(&child);
                self.child_buf = child;
                if new {
                    if goal {
                        return self.plan_to(t);
                    }
                    queue.push_back(t);
                }
            }
        }
        SearchOutcome::Unsolvable
    }

    fn best_first(&mut self, start: &[u64], alg: Algorithm) -> SearchOutcome {
        // Among equal `f` (A*) or `g` (UCS), goal states first, then smaller `h`; then the newest
        // entry, except among goal states, where the oldest (often the shortest path) wins.
        let key = |g: u64, h: u64, goal: bool| {
            let rank = 2 * h + u64::from(!goal);
            match alg {
                Algorithm::Ucs => (g, rank),
                Algorithm::Astar => (g.saturating_add(h), rank),
                _ => (h, 0),
            }
        };
        let greedy = alg == Algorithm::Gbfs;
        let below = self.cost_below.unwrap_or(u64::MAX);
        let (s, _) = self.register(start, NONE, NONE, 0);
        self.stats.evaluated += 1;
        let start_goal = goal_holds(self.goal, start);
        let Some(h0) = self.h_of(start, start_goal) else {
            return SearchOutcome::Unsolvable;
        };
        self.h[s as usize] = h0;
        if greedy && self.is_goal(start) {
            return self.plan_to(s);
        }
        let mut open = BinaryHeap::new();
        let mut seq = 0u64;
        let (k1, k2) = key(0, h0, start_goal);
        if k1 < below {
            open.push(Reverse(Entry {
                k1,
                k2,
                seq,
                node: s,
                g: 0,
            }));
        }
        let mut ops = std::mem::take(&mut self.ops_buf);
        while let Some(Reverse(e)) = open.pop() {
            let id = e.node;
            if self.status[id as usize] != OPEN || e.g != self.g[id as usize] {
                continue;
            }
            if let Some(b) = self.budget() {
                return SearchOutcome::BudgetExhausted { which: b };
            }
            self.load(id);
            let g = e.g;
            if !greedy && self.is_goal(&self.words_buf) {
                return self.plan_to(id);
            }
            self.status[id as usize] = CLOSED;
            self.stats.expanded += 1;
            self.succ.applicable_ops(&self.words_buf, &mut ops);
            self.note_reached(&ops, g);
            for &o in &ops {
                self.apply_into_child(o);
                self.stats.generated += 1;
                let ng = g + self.task.operators[o as usize].cost as u64;
                let child = std::mem::take(&mut self.child_buf);
                let (t, new) = self.register(&child, id, o, ng);
                let tu = t as usize;
                let mut push = false;
                let mut goal = false;
                if new {
                    goal = goal_holds(self.goal, &child);
                    self.stats.evaluated += 1;
                    match self.h_of(&child, goal) {
                        None => self.status[tu] = DEAD,
                        Some(h) => {
                            self.h[tu] = h;
                            if greedy && self.is_goal(&child) {
                                self.child_buf = child;
                                return self.plan_to(t);
                            }
                            push = true;
                        }
                    }
                } else if !greedy && self.status[tu] != DEAD && ng < self.g[tu] {
                    self.g[tu] = ng;
                    self.parent[tu] = id;
                    self.op[tu] = o;
                    if self.status[tu] == CLOSED {
                        self.status[tu] = OPEN;
                        self.stats.reopened += 1;
                    }
                    goal = goal_holds(self.goal, &child);
                    push = true;
                }
                self.child_buf = child;
                if !push {
                    continue;
                }
                let (k1, k2) = key(self.g[tu], self.h[tu], goal);
                if k1 < below {
                    seq += 1;
                    // Greedy search returned at a goal child: only A* and UCS push one.
                    open.push(Reverse(Entry {
                        k1,
                        k2,
                        seq: if goal { seq } else { u64::MAX - seq },
                        node: t,
                        g: self.g[tu],
                    }));
                }
            }
        }
        SearchOutcome::Unsolvable
    }

    fn lazy_gbfs(&mut self, start: &[u64]) -> SearchOutcome {
        // Entries: (parent's h, seq, parent, operator).
        type Lazy = Reverse<(u64, u64, u32, u32)>;
        const BOOST: i64 = 1000;
        let use_pref = matches!(
            self.heur.kind(),
            crate::plan::HeuristicKind::HFf | crate::plan::HeuristicKind::HAdd
        );
        let mut queues: [BinaryHeap<Lazy>; 2] = [BinaryHeap::new(), BinaryHeap::new()];
        let mut priority: [i64; 2] = [0, 0];
        let mut seq = 0u64;
        let mut best_h = u64::MAX;
        let mut ops = std::mem::take(&mut self.ops_buf);
        let mut pref: Vec<u32> = Vec::new();
        let (s, _) = self.register(start, NONE, NONE, 0);
        let mut current = Some(s);
        loop {
            if let Some(id) = current.take() {
                // Evaluate and expand `id` (already registered, parent set).
                self.load(id);
                if self.is_goal(&self.words_buf) {
                    return self.plan_to(id);
                }
                if let Some(b) = self.budget() {
                    return SearchOutcome::BudgetExhausted { which: b };
                }
                self.stats.evaluated += 1;
                let h = self
                    .heur
                    .eval(&self.words_buf, use_pref.then_some(&mut pref));
                match h {
                    None => self.status[id as usize] = DEAD,
                    Some(h) => {
                        self.h[id as usize] = h;
                        self.status[id as usize] = CLOSED;
                        self.stats.expanded += 1;
                        if h < best_h {
                            best_h = h;
                            if use_pref {
                                priority[1] -= BOOST;
                            }
                        }
                        self.succ.applicable_ops(&self.words_buf, &mut ops);
                        self.note_reached(&ops, self.g[id as usize]);
                        if use_pref {
                            pref.sort_unstable();
                            pref.dedup();
                        }
                        for &o in &ops {
                            seq += 1;
                            queues[0].push(Reverse((h, seq, id, o)));
                            if use_pref && pref.binary_search(&o).is_ok() {
                                queues[1].push(Reverse((h, seq, id, o)));
                            }
                        }
                    }
                }
            }
            // Pick the next entry.
            let q = match (queues[0].is_empty(), queues[1].is_empty()) {
                (true, true) => return SearchOutcome::Unsolvable,
                (false, true) => 0,
                (true, false) => 1,
                (false, false) => usize::from(priority[1] < priority[0]),
            };
            priority[q] += 1;
            let Some(Reverse((_, _, parent, o))) = queues[q].pop() else {
                continue;
            };
            self.load(parent);
            self.apply_into_child(o);
            self.stats.generated += 1;
            let ng = self.g[parent as usize] + self.task.operators[o as usize].cost as u64;
            let child = std::mem::take(&mut self.child_buf);
            let (t, new) = self.register(&child, parent, o, ng);
            self.child_buf = child;
            if new {
                current = Some(t);
            }
        }
    }
}
