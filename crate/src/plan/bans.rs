//! Task rewrites for the retries of one replan: operators banned at the states where their
//! continuous parameters could not be bound, or until a body in their way has moved.

use std::collections::BTreeMap;

use super::{fact_args, Operator, State, Task};

/// Whether an operator of a task moves a body (grasps it or pulls it in): the physical reading
/// of the task, given by the layer that knows what actions do (`tamp::moves_body`).
pub type MovesBody<'a> = dyn Fn(&Task, &Operator, &str) -> bool + 'a;

/// Makes operator `o` inapplicable everywhere.
pub(crate) fn forbid(task: &mut Task, o: usize) {
    let op = &mut task.operators[o];
    if let Some(&f) = op.pre.first() {
        if !op.pre_neg.contains(&f) {
            op.pre_neg.push(f);
        }
    } else {
        op.pre_neg.extend(0..task.facts.len() as u32);
    }
}

/// A task in which some operators are banned at some states — where their continuous parameters
/// could not be bound — for the searches of one replan (the retries of PDDLStream's loop).
///
/// Banning operator `o` at state `s` keeps `o` everywhere else: every copy of `o` that applies
/// at `s` is replaced by copies, each with one more precondition that tells a state from `s` (a
/// fact of `s` that `o` does not require must be false, or a fact outside `s` must be true), so
/// `o` applies exactly where `pre(o)` holds and the state is none of the banned ones. After
/// [`STATE_BANS`] bans of the same operator, the next one bans it everywhere.
///
/// An action that movable bodies blocked is banned until one of them has moved instead
/// ([`BannedTask::ban_failed`]). Facts cannot say that: taking a block off the blocker changes
/// the blocker's facts without moving it, and a blocker taken away and put back where the goal
/// wants it (centred this time) has its old facts again. So each such blocker `b` gets a fact
/// of its own, `(*moved* b)`, false at the replan's state and made true by every operator that
/// moves `b` (grasps it or pulls it in), and the banned action's copies require one of them.
/// Plans found on [`BannedTask::task`] map back to the original operators with
/// [`BannedTask::original`]; a state of the original task is one of the banned task's with
/// [`BannedTask::lift`].
#[derive(Clone, Debug)]
pub struct BannedTask {
    /// The task with the bans.
    pub task: Task,
    /// Original operator of every operator of `task`.
    origin: Vec<usize>,
    /// Operators of `task` made inapplicable (split into copies, or banned everywhere).
    dead: Vec<bool>,
    /// Bans so far per original operator.
    bans: BTreeMap<usize, usize>,
    /// Facts of the original task; the `(*moved* b)` facts come after them.
    base_facts: usize,
    /// The `(*moved* b)` fact of every body a ban waits on.
    moved: BTreeMap<String, u32>,
}

/// Bans of one operator at single states before the next bans it everywhere (an action that
/// could not be bound at two states, e.g. a pull stroke blocked in two arrangements, may still
/// bind in a third: the block in the way moved elsewhere first).
pub const STATE_BANS: usize = 2;

impl BannedTask {
    /// No bans yet.
    pub fn new(task: &Task) -> Self {
        BannedTask {
            origin: (0..task.operators.len()).collect(),
            dead: vec![false; task.operators.len()],
            task: task.clone(),
            bans: BTreeMap::new(),
            base_facts: task.facts.len(),
            moved: BTreeMap::new(),
        }
    }

    /// Whether nothing is banned.
    pub fn is_empty(&self) -> bool {
        !self.dead.contains(&true)
    }

    /// State `s` of the original task as a state of the banned task (no body has moved yet).
    pub fn lift(&self, s: &State) -> State {
        s.widened(self.task.facts.len())
    }

    /// Bans original operator `o` at state `s` (see the type's documentation).
    pub fn ban(&mut self, o: usize, s: &State) {
        let at = self.lift(s);
        self.ban_at(o, s, &at);
    }

    /// [`BannedTask::ban`] at `s`, which is `at` in the banned task (with its `(*moved* b)`
    /// facts).
    fn ban_at(&mut self, o: usize, s: &State, at: &State) {
        if o >= self.task.operators.len() || self.origin.get(o) != Some(&o) {
            return;
        }
        let count = self.bans.entry(o).or_insert(0);
        *count += 1;
        let everywhere = *count > STATE_BANS;
        let base: Vec<u32> = (0..self.base_facts as u32).collect();
        for i in self.live_copies(o) {
            if everywhere {
                forbid(&mut self.task, i);
                self.dead[i] = true;
            } else if self.task.operators[i].applicable(at) {
                self.split_on(i, s, &base);
            }
        }
    }

    /// Bans original operator `o`, which could not be bound at state `s` (reached from the
    /// replan's state by the original operators `prefix`) with `blockers` (movable bodies) in
    /// its way. The blockers that are not the action's own arguments count. Until one of those
    /// that `prefix` left where they were has moved (see the type's documentation); when
    /// `prefix` moved them all, at every state where none of them has moved from where `s` has
    /// it by its facts (moving a block out of a pull's way, say, lifts the ban). Either way the
    /// ban is lifted too once the body the action itself moves has been moved elsewhere first,
    /// if `prefix` had not moved it (the conflict is between two poses). With no such blocker,
    /// a ban at `s` only ([`BannedTask::ban`]). A ban until something moves does not count
    /// towards [`STATE_BANS`].
    pub fn ban_failed(
        &mut self,
        o: usize,
        s: &State,
        prefix: &[usize],
        blockers: &[String],
        moves_body: &MovesBody<'_>,
    ) {
        if o >= self.task.operators.len() || self.origin.get(o) != Some(&o) {
            return;
        }
        let (_, args) = fact_args(&self.task.operators[o].name);
        let movers: Vec<&str> = blockers
            .iter()
            .map(String::as_str)
            .filter(|b| !args.contains(b))
            .collect();
        let moved_by_prefix = |task: &Task, b: &str| {
            prefix
                .iter()
                .any(|&p| p < task.operators.len() && moves_body(task, &task.operators[p], b))
        };
        // `s` in the banned task: the flags of the bodies `prefix` moved are set.
        let mut at = self.lift(s);
        for (b, &f) in &self.moved {
            if moved_by_prefix(&self.task, b) {
                at.insert(f);
            }
        }
        if movers.is_empty() {
            return self.ban_at(o, s, &at);
        }
        let own: Vec<String> = args
            .iter()
            .filter(|b| {
                moves_body(&self.task, &self.task.operators[o], b)
                    && !moved_by_prefix(&self.task, b)
            })
            .map(|b| b.to_string())
            .collect();
        let still: Vec<&str> = movers
            .iter()
            .copied()
            .filter(|b| !moved_by_prefix(&self.task, b))
            .collect();
        let mut lifts: Vec<u32> = if still.is_empty() {
            (0..self.base_facts as u32)
                .filter(|&f| {
                    let (_, named) = fact_args(&self.task.facts[f as usize]);
                    movers.iter().any(|m| named.contains(m))
                })
                .collect()
        } else {
            still
                .iter()
                .map(|b| self.moved_flag(b, moves_body))
                .collect()
        };
        lifts.extend(own.iter().map(|b| self.moved_flag(b, moves_body)));
        // Sized again: `moved_flag` may have added facts (false at `s`).
        let at = self.lift(&at);
        for i in self.live_copies(o) {
            if self.task.operators[i].applicable(&at) {
                self.split_on(i, &at, &lifts);
            }
        }
    }

    /// The `(*moved* body)` fact, made when first asked for: every operator that moves `body`
    /// (copies included) adds it.
    fn moved_flag(&mut self, body: &str, moves_body: &MovesBody<'_>) -> u32 {
        if let Some(&f) = self.moved.get(body) {
            return f;
        }
        let f = self.task.push_fact(format!("(*moved* {body})"));
        for i in 0..self.task.operators.len() {
            if moves_body(&self.task, &self.task.operators[i], body) {
                self.task.operators[i].add.push(f);
            }
        }
        self.moved.insert(body.to_string(), f);
        f
    }

    /// The operators of the banned task that stand for original operator `o` and are not dead.
    fn live_copies(&self, o: usize) -> Vec<usize> {
        (0..self.task.operators.len())
            .filter(|&i| self.origin[i] == o && !self.dead[i])
            .collect()
    }

    /// Replaces operator `i` by copies that apply only where one of `facts` differs from `s`.
    fn split_on(&mut self, i: usize, s: &State, facts: &[u32]) {
        let op = self.task.operators[i].clone();
        let o = self.origin[i];
        forbid(&mut self.task, i);
        self.dead[i] = true;
        for &f in facts {
            let mut copy = op.clone();
            if op.pre.contains(&f) || op.pre_neg.contains(&f) {
                continue;
            }
            if s.contains(f) {
                copy.pre_neg.push(f);
            } else {
                copy.pre.push(f);
            }
            self.task.operators.push(copy);
            self.origin.push(o);
            self.dead.push(false);
        }
    }

    /// The original operators of a plan found on [`BannedTask::task`].
    pub fn original(&self, ops: &[usize]) -> Vec<usize> {
        ops.iter()
            .map(|&o| self.origin.get(o).copied().unwrap_or(o))
            .collect()
    }
}
