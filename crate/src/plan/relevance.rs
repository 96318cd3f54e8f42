//! Backward relevance: the part of a grounded [`Task`] that can matter for its goal.
//!
//! A fact is *relevant* if it is in the goal (positive or negative), or in a precondition
//! (positive or negative) of a relevant operator; an operator is relevant if it adds or deletes a
//! relevant fact. The least fixpoint `R` is computed from the goal backwards. The relevant part
//! keeps the facts of `R` and the relevant operators with their add and delete lists cut down to
//! `R`. This is the fact-level counterpart of the variables Fast Downward's translator keeps
//! (those the goal depends on in the causal graph).
//!
//! # Why plans carry over
//! Only relevant operators change relevant facts, and every precondition of a relevant operator
//! is relevant. So along any plan of the task the relevant facts evolve exactly as along the same
//! plan with the irrelevant operators removed, and the goal reads only relevant facts:
//! * a plan of the task minus its irrelevant operators is a plan of the relevant part, no dearer;
//! * a plan of the relevant part (mapped back through [`Relevance::operators`]) is a plan of the
//!   task from the same start, of the same cost.
//!
//! Optimal costs are therefore equal, and a search over the relevant part never tells apart two
//! states that differ only in irrelevant facts (which is where it saves expansions). The
//! relaxation heuristics h_max, h_add and h_FF take the same value on a state and its projection,
//! since the relaxed achievers of relevant facts are relevant operators; LM-cut stays admissible
//! but may differ where its ties are broken by the order facts are met.

use super::task::{sanitize_goals, Condition, FactId, Goal, Operator, State, Task};

/// The relevant part of a task and the way back to the task's own facts and operators.
#[derive(Clone, Debug)]
pub struct Relevance {
    /// The relevant part: facts of `R`, relevant operators (add/delete cut to `R`), projected
    /// initial state and goal.
    pub task: Task,
    /// Per fact of [`Relevance::task`], its id in the original task (increasing).
    pub facts: Vec<FactId>,
    /// Per operator of [`Relevance::task`], its index in the original task (increasing, so the
    /// successor order and hence tie-breaking are the original's).
    pub operators: Vec<usize>,
    /// Per fact of the original task, its id in [`Relevance::task`] (`None`: irrelevant).
    renumber: Vec<Option<FactId>>,
}

impl Relevance {
    /// The state of the relevant part that `s` (a state of the original task) projects to.
    pub fn project(&self, s: &State) -> State {
        let n = self.task.facts.len();
        State::from_facts(
            n,
            s.facts()
                .filter_map(|f| self.renumber.get(f as usize).copied().flatten()),
        )
    }

    /// The id in the relevant part of fact `f` of the original task (`None`: irrelevant).
    pub fn project_fact(&self, f: FactId) -> Option<FactId> {
        self.renumber.get(f as usize).copied().flatten()
    }

    /// The original operator indices of `ops`, a plan of the relevant part.
    pub fn lift(&self, ops: &[usize]) -> Vec<usize> {
        ops.iter().map(|&o| self.operators[o]).collect()
    }
}

/// The relevant part of `task`, or `None` when every fact and operator is relevant.
///
/// Goal literals on facts the task does not have are read as the search reads them: a positive
/// one makes its alternative unreachable, a negative one holds vacuously.
pub fn relevant_part(task: &Task) -> Option<Relevance> {
    let n = task.facts.len();
    let goal = sanitize_goals(n, std::slice::from_ref(&task.goal)).remove(0);

    // Operators by the facts they change, to walk from a fact to its achievers and deleters.
    let mut changers: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (i, op) in task.operators.iter().enumerate() {
        for &f in op.add.iter().chain(&op.del) {
            let list = &mut changers[f as usize];
            if list.last() != Some(&(i as u32)) {
                list.push(i as u32);
            }
        }
    }

    let mut fact_rel = vec![false; n];
    let mut op_rel = vec![false; task.operators.len()];
    let mut stack: Vec<FactId> = Vec::new();
    fn mark(f: FactId, fact_rel: &mut [bool], stack: &mut Vec<FactId>) {
        if !fact_rel[f as usize] {
            fact_rel[f as usize] = true;
            stack.push(f);
        }
    }
    for c in &goal.alternatives {
        for &f in c.pos.iter().chain(&c.neg) {
            mark(f, &mut fact_rel, &mut stack);
        }
    }
    while let Some(f) = stack.pop() {
        for &o in &changers[f as usize] {
            if std::mem::replace(&mut op_rel[o as usize], true) {
                continue;
            }
            let op = &task.operators[o as usize];
            for &p in op.pre.iter().chain(&op.pre_neg) {
                mark(p, &mut fact_rel, &mut stack);
            }
        }
    }

    if fact_rel.iter().all(|&r| r) && op_rel.iter().all(|&r| r) {
        return None;
    }

    let mut renumber = vec![None; n];
    let mut facts = Vec::new();
    for f in (0..n).filter(|&f| fact_rel[f]) {
        renumber[f] = Some(facts.len() as FactId);
        facts.push(f as FactId);
    }
    let map = |fs: &[FactId]| -> Vec<FactId> {
        fs.iter()
            .filter_map(|&f| renumber.get(f as usize).copied().flatten())
            .collect()
    };
    let operators: Vec<usize> = (0..task.operators.len()).filter(|&o| op_rel[o]).collect();
    let ops = operators
        .iter()
        .map(|&o| {
            let op = &task.operators[o];
            Operator {
                name: op.name.clone(),
                pre: map(&op.pre),
                pre_neg: map(&op.pre_neg),
                add: map(&op.add),
                del: map(&op.del),
                cost: op.cost,
            }
        })
        .collect();
    let goal = Goal {
        alternatives: goal
            .alternatives
            .iter()
            .map(|c| Condition {
                pos: map(&c.pos),
                neg: map(&c.neg),
            })
            .collect(),
        terminal_cost: task.goal.terminal_cost,
    };
    let names = facts
        .iter()
        .map(|&f| task.facts[f as usize].clone())
        .collect();
    let mut rel = Relevance {
        task: Task::new(
            names,
            ops,
            State::empty(0),
            goal,
            task.static_facts.clone(),
            task.uses_costs,
        ),
        facts,
        operators,
        renumber,
    };
    rel.task.init = rel.project(&task.init);
    Some(rel)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Facts: 0 (at a), 1 (at b), 2 (light on), 3 (light off), 4 (key), 5 (door open).
    fn task() -> Task {
        let facts = [
            "(at a)",
            "(at b)",
            "(light on)",
            "(light off)",
            "(key)",
            "(door open)",
        ];
        let ops = vec![
            Operator::unit("(go a b)", &[0, 5], &[1], &[0]),
            Operator::unit("(switch on)", &[3], &[2], &[3]),
            Operator::unit("(switch off)", &[2], &[3], &[2]),
            Operator::unit("(open)", &[4], &[5], &[]),
            Operator::unit("(go b a)", &[1], &[0], &[1]),
        ];
        let goal = Goal {
            alternatives: vec![Condition {
                pos: vec![1],
                neg: vec![],
            }],
            terminal_cost: 0,
        };
        Task::new(
            facts.iter().map(|s| s.to_string()).collect(),
            ops,
            State::from_facts(6, [0, 3, 4]),
            goal,
            vec![],
            false,
        )
    }

    #[test]
    fn drops_facts_and_operators_the_goal_never_needs() {
        let t = task();
        let r = relevant_part(&t).expect("the light is irrelevant");
        assert_eq!(r.facts, vec![0, 1, 4, 5]);
        // `(go b a)` deletes the goal fact (at b), so it stays; the switches go.
        assert_eq!(r.operators, vec![0, 3, 4]);
        assert_eq!(
            r.task.state_names(&r.task.init),
            ["(at a)", "(key)"].map(String::from)
        );
        let lit = State::from_facts(6, [1, 2]);
        assert_eq!(r.project(&lit), State::from_facts(4, [1]));
        assert_eq!(r.lift(&[1, 0]), vec![3, 0]);
    }

    #[test]
    fn negative_preconditions_and_goals_are_relevant() {
        let mut t = task();
        // Going needs the light not on; the goal also asks for no key.
        t.operators[0].pre_neg = vec![2];
        t.goal.alternatives[0].neg = vec![4];
        // The switches now change a relevant fact, so their preconditions join: all is relevant.
        assert!(relevant_part(&t).is_none());
    }

    #[test]
    fn a_fully_relevant_task_is_left_alone() {
        let mut t = task();
        t.operators.drain(1..3);
        // (light on)/(light off) are in no operator any more but are still facts of the task.
        assert!(relevant_part(&t).is_some());
        t.goal.alternatives[0].pos.push(2);
        t.goal.alternatives[0].neg.push(3);
        assert!(relevant_part(&t).is_none());
    }

    #[test]
    fn unknown_goal_facts_follow_the_search_reading() {
        let mut t = task();
        t.goal.alternatives.push(Condition {
            pos: vec![99],
            neg: vec![],
        });
        t.goal.alternatives[0].neg.push(99);
        let r = relevant_part(&t).unwrap();
        assert_eq!(r.task.goal.alternatives.len(), 1);
        assert_eq!(r.task.goal.alternatives[0].neg, Vec::<FactId>::new());
    }
}
