//! The task level of the reactive loop (paper Algorithm 1) and of its baselines.
//!
//! Every decision point (start, end of an action, a task-level deviation seen mid-action) the
//! controller gets the scene graph's facts S_C and the world's objects:
//!
//! ```text
//!   S_C ← SceneGraph(env)                      (re-ground the task if S_C names a new object)
//!   if G ⊆ S_C: done
//!   if S_C = Ŝ (the state the current plan predicts) and pre(a_next) ⊆ S_C: execute a_next
//!   else, by method:
//!     logic-lfd: 𝒫 ← LogicIn(S_C, 𝒢) ? a_{k+1..N} : MultiGoalSearch(S_C, 𝒢) ⧺ a_{k+1..N}
//!                (when no skeleton binds: TAMP from scratch if `tamp_fallback`, logged as one)
//!     rlds:      𝒫 ← a_{k+1..N} for the latest k whose suffix applies in S_C and reaches G
//!                (G regressed through it holds in S_C), else fail; never a new action
//!     tamp:      𝒫 ← TAMP(S_C, G) from scratch
//!     linear:    never replans: a_1..a_N in order, whatever S_C is
//!   then bind the continuous parameters (tamp streams) and execute 𝒫[0]
//! ```
//!
//! Every replan is logged with its reason, planning time (caller's clock), matched k and plan.

use std::collections::BTreeSet;

use crate::pddl::ObjectDecl;
use crate::plan::{replay, Algorithm, BannedTask, Clock, HeuristicKind, Operator, State, Task};
use crate::tamp::{Binder, Binding, BoundPlan, TimedBinder};

use super::catalogue::{Method, Mode};
use super::demo::DemoTrace;
use super::symbolic::LogicLfd;
use super::LfdError;
use reason::{predicate, reground_reason};

mod baselines;
mod reason;
#[cfg(test)]
mod tests;
mod types;

pub use types::{ControlParams, Decision, FailReason, Replan};

/// Builds the grounded task for the current world: objects (name, PDDL type) and facts S_C.
pub trait TaskBuilder {
    /// A task whose initial state is `facts` and whose goal is the benchmark's goal.
    fn build(&self, objects: &[ObjectDecl], facts: &[String]) -> Result<Task, LfdError>;
}

/// A new plan: its operators, the demonstration state it joins, how many of its leading actions
/// are new, and what the streams bound for each action (empty when nothing was bound).
struct Planned {
    ops: Vec<usize>,
    k: Option<usize>,
    new_actions: usize,
    bindings: Vec<Binding>,
    /// States the searches expanded.
    expanded: u64,
    /// Planned from scratch after Logic-LfD's skeletons failed.
    fallback: bool,
    /// Logic-LfD's candidates L_k with their costs (empty for the other methods).
    alternatives: Vec<crate::lfd::Alternative>,
}

/// The task-level controller of one episode.
pub struct Controller {
    method: Method,
    mode: Mode,
    params: ControlParams,
    /// The task level: the current grounding, the demonstration and its specification.
    lfd: LogicLfd,
    objects: Vec<ObjectDecl>,
    plan: Vec<usize>,
    plan_names: Vec<String>,
    /// What the streams bound for each action of the plan (empty when the method binds
    /// nothing itself: linear, rlds).
    bindings: Vec<Binding>,
    /// States predicted by the plan: `predicted[i]` before `plan[i]`.
    predicted: Vec<State>,
    cursor: usize,
    plan_k: Option<usize>,
    replans: Vec<Replan>,
    started: bool,
    /// Why the next decision replans although the state is as predicted (an action failed:
    /// its parameters are bound anew).
    replan_because: Option<String>,
}

/// A task-level observation: S_C as a state of the current task.
fn observe(task: &Task, facts: &[String]) -> Option<State> {
    let statics: BTreeSet<&str> = task.static_facts.iter().map(String::as_str).collect();
    let mut s = task.empty_state();
    for f in facts {
        match task.fact_id(f) {
            Some(id) => s.insert(id),
            None if statics.contains(f.as_str()) => {}
            None => return None,
        }
    }
    // A static fact of a predicate the scene graph reports must still hold.
    let preds: BTreeSet<&str> = facts.iter().map(|f| predicate(f)).collect();
    let present: BTreeSet<&str> = facts.iter().map(String::as_str).collect();
    for f in &task.static_facts {
        if preds.contains(predicate(f)) && !present.contains(f.as_str()) {
            return None;
        }
    }
    Some(s)
}

impl Controller {
    /// A controller for `method` from the demonstration `trace` (derived on the template task).
    pub fn new(
        method: Method,
        mode: Mode,
        params: ControlParams,
        trace: DemoTrace,
        task: Task,
        objects: Vec<ObjectDecl>,
    ) -> Self {
        Controller {
            method,
            mode,
            params,
            lfd: LogicLfd::from_task(task, trace),
            objects,
            plan: vec![],
            plan_names: vec![],
            bindings: vec![],
            predicted: vec![],
            cursor: 0,
            plan_k: None,
            replans: vec![],
            started: false,
            replan_because: None,
        }
    }

    /// The method.
    pub fn method(&self) -> Method {
        self.method
    }

    /// The current grounded task.
    pub fn task(&self) -> &Task {
        self.lfd.task()
    }

    /// The demonstration trace.
    pub fn trace(&self) -> &DemoTrace {
        self.lfd.trace()
    }

    /// The current plan as action names.
    pub fn plan_names(&self) -> &[String] {
        &self.plan_names
    }

    /// The current plan as operator indices of [`Controller::task`].
    pub fn plan_ops(&self) -> &[usize] {
        &self.plan
    }

    /// What the streams bound for each action of the current plan, as the replan that made it
    /// bound them (empty for linear and rlds, which bind nothing themselves).
    pub fn bindings(&self) -> &[Binding] {
        &self.bindings
    }

    /// Index of the next action to execute in the plan.
    pub fn cursor(&self) -> usize {
        self.cursor
    }

    /// The demonstration state the current plan joins.
    pub fn matched_k(&self) -> Option<usize> {
        self.plan_k
    }

    /// Every replan so far.
    pub fn replans(&self) -> &[Replan] {
        &self.replans
    }

    /// Drops the current plan; the next decision replans (`cancel` on the page).
    pub fn cancel(&mut self) {
        self.plan.clear();
        self.plan_names.clear();
        self.bindings.clear();
        self.predicted.clear();
        self.cursor = 0;
        self.plan_k = None;
    }

    /// Makes the next decision replan, with `reason`, even if the state is as predicted: the
    /// action at the cursor failed, and retrying it with the same bound parameters (an occupied
    /// placement, a blocked stroke) would fail the same way.
    pub fn replan_after_failure(&mut self, reason: String) {
        self.replan_because = Some(reason);
    }

    /// Marks the action at the cursor as executed.
    pub fn advance(&mut self) {
        self.cursor += 1;
    }

    /// The fluents the plan predicts now (before the action at the cursor), if there is a plan.
    fn expected(&self) -> Option<&State> {
        self.predicted.get(self.cursor)
    }

    /// Whether S_C is consistent with executing the action at the cursor: every fact that the
    /// action does not touch is as predicted. `None` if S_C cannot be expressed in the task.
    pub fn consistent_during_action(&self, facts: &[String]) -> bool {
        let Some(s) = observe(self.task(), facts) else {
            return false;
        };
        let (Some(before), Some(&op)) = (self.expected(), self.plan.get(self.cursor)) else {
            return true;
        };
        let o = &self.task().operators[op];
        let touched: BTreeSet<u32> = o
            .pre
            .iter()
            .chain(&o.pre_neg)
            .chain(&o.add)
            .chain(&o.del)
            .copied()
            .collect();
        (0..self.task().facts.len() as u32)
            .filter(|f| !touched.contains(f))
            .all(|f| s.contains(f) == before.contains(f))
    }

    /// Whether the fact set, seen after the action at the cursor ended, is what the plan predicted.
    pub fn action_had_its_effect(&self, facts: &[String]) -> bool {
        match (
            observe(self.task(), facts),
            self.predicted.get(self.cursor + 1),
        ) {
            (Some(s), Some(p)) => &s == p,
            _ => false,
        }
    }

    /// The decision at a decision point (start, after an action, after a deviation).
    pub fn decide(
        &mut self,
        facts: &[String],
        objects: &[ObjectDecl],
        builder: &dyn TaskBuilder,
        binder: &mut dyn Binder,
        clock: &dyn Clock,
        tick: u64,
    ) -> Decision {
        let t0 = clock.now_secs();
        let mut regrounded = None;
        let s = match observe(self.task(), facts) {
            Some(s) if objects == self.objects.as_slice() => s,
            _ => {
                // New objects or facts outside the task: re-ground from the scene.
                let why = reground_reason(self.task(), &self.objects, objects, facts);
                match builder.build(objects, facts) {
                    Ok(task) => {
                        self.lfd = LogicLfd::from_task(task, self.lfd.trace().clone());
                        self.objects = objects.to_vec();
                        regrounded = Some(why);
                        // Re-express the plan in the new task's operator indices.
                        let ops: Option<Vec<usize>> = self
                            .plan_names
                            .iter()
                            .map(|n| super::demo::operator_index(self.task(), n))
                            .collect();
                        match ops {
                            Some(ops) => self.plan = ops,
                            None => self.cancel(),
                        }
                        self.predicted.clear();
                        match observe(self.task(), facts) {
                            Some(s) => s,
                            None => {
                                return Decision::Failed(FailReason::NoPlan {
                                    message: "the scene has facts the domain cannot express".into(),
                                })
                            }
                        }
                    }
                    Err(e) => {
                        return Decision::Failed(FailReason::NoPlan {
                            message: e.to_string(),
                        })
                    }
                }
            }
        };
        if self.task().goal.holds(&s) {
            return Decision::Done;
        }
        if self.method == Method::Linear {
            return self.decide_linear(&s, clock, t0, tick);
        }
        // Is the current plan still good?
        let reason = if !self.started {
            "start".to_string()
        } else if let Some(r) = self.replan_because.take() {
            r
        } else if let Some(why) = regrounded.clone() {
            why
        } else if self.plan.is_empty() {
            "no plan (cancelled)".to_string()
        } else if self.cursor >= self.plan.len() {
            "the plan ended but the goal does not hold".to_string()
        } else {
            let expected = if regrounded.is_some() {
                None
            } else {
                self.expected().cloned()
            };
            let op = &self.task().operators[self.plan[self.cursor]];
            match expected {
                Some(e) if e == s && op.applicable(&s) => {
                    return Decision::Execute {
                        index: self.cursor,
                        action: self.plan_names[self.cursor].clone(),
                    };
                }
                Some(e) if e != s => self.describe_change(&e, &s),
                Some(_) => format!(
                    "a precondition of {} does not hold: {}",
                    op.name,
                    op.pre
                        .iter()
                        .filter(|&&f| !s.contains(f))
                        .map(|&f| self.task().facts[f as usize].clone())
                        .collect::<Vec<_>>()
                        .join(" ")
                ),
                None => "unknown state".to_string(),
            }
        };
        self.started = true;
        if self.replans.len() >= self.params.max_replans {
            return Decision::Failed(FailReason::Budget {
                what: "replan budget".into(),
            });
        }
        let mut timed = TimedBinder::new(binder, clock);
        let planned = match self.method {
            Method::LogicLfd => self.plan_with_logic_lfd(&s, &mut timed, clock),
            Method::Rlds => self.plan_with_rlds(&s),
            Method::Tamp => self.plan_with_tamp(&s, &mut timed, clock),
            Method::Linear => unreachable_linear(),
        };
        let bind_ms = timed.secs * 1e3;
        let time_ms = (clock.now_secs() - t0) * 1e3;
        match planned {
            Ok(Planned {
                ops,
                k,
                new_actions,
                bindings,
                expanded,
                fallback,
                alternatives,
            }) => {
                self.install(&s, ops, k);
                self.bindings = bindings;
                self.replans.push(Replan {
                    reason,
                    time_ms,
                    k,
                    plan: self.plan_names.clone(),
                    tick,
                    new_actions,
                    bind_ms,
                    expanded,
                    fallback,
                    alternatives,
                });
                if self.plan.is_empty() {
                    return Decision::Done;
                }
                Decision::Execute {
                    index: 0,
                    action: self.plan_names[0].clone(),
                }
            }
            Err(reason) => Decision::Failed(reason),
        }
    }

    fn install(&mut self, s: &State, ops: Vec<usize>, k: Option<usize>) {
        let mut predicted = vec![s.clone()];
        let mut cur = s.clone();
        for &o in &ops {
            cur = self.task().operators[o].apply(&cur);
            predicted.push(cur.clone());
        }
        self.plan_names = ops
            .iter()
            .map(|&o| self.task().operators[o].name.clone())
            .collect();
        self.plan = ops;
        self.predicted = predicted;
        self.cursor = 0;
        self.plan_k = k;
    }

    fn describe_change(&self, expected: &State, s: &State) -> String {
        let gone: Vec<&str> = expected
            .facts()
            .filter(|&f| !s.contains(f))
            .map(|f| self.task().facts[f as usize].as_str())
            .collect();
        let new: Vec<&str> = s
            .facts()
            .filter(|&f| !expected.contains(f))
            .map(|f| self.task().facts[f as usize].as_str())
            .collect();
        match (gone.is_empty(), new.is_empty()) {
            (false, _) => format!("{} no longer holds", gone.join(" ")),
            (true, false) => format!("{} appeared", new.join(" ")),
            _ => "the scene changed".into(),
        }
    }

    fn plan_with_logic_lfd(
        &self,
        s: &State,
        binder: &mut dyn Binder,
        clock: &dyn Clock,
    ) -> Result<Planned, FailReason> {
        let mut banned = BannedTask::new(self.task());
        let mut first_k = 0;
        let mut expanded = 0;
        let mut why = format!(
            "no skeleton joining the demonstration binds in {} tries",
            self.params.max_skeletons.max(1)
        );
        // A prioritised skeleton that does not bind gives way to the paper search's: the retries
        // need a plan that binds, and proving each retry's plan cheapest made crowded 12-block
        // scenes spend seconds on skeletons that did not bind either.
        let mut mode = self.mode;
        let mut search = self.params.search;
        let mut tries = 0;
        while tries < self.params.max_skeletons.max(1) {
            let p = match self.lfd.replan_avoiding(
                s,
                mode,
                &search,
                clock,
                (!banned.is_empty()).then_some(&banned),
                first_k,
            ) {
                Ok(p) => p,
                // An optimal search out of budget (two arms and many blocks make wide plateaus)
                // gives way to the satisficing one: a plan now beats the cheapest plan never.
                Err(LfdError::Budget(_)) if search.algorithm != Algorithm::LazyGbfs => {
                    search.algorithm = Algorithm::LazyGbfs;
                    search.heuristic = HeuristicKind::HFf;
                    continue;
                }
                Err(e) => {
                    why = e.to_string();
                    break;
                }
            };
            tries += 1;
            expanded += p.stats.expanded;
            match binder.bind(self.task(), &p.ops, p.prefix_len) {
                Ok(bindings) => {
                    return Ok(Planned {
                        ops: p.ops,
                        k: p.k,
                        new_actions: p.prefix_len,
                        bindings,
                        expanded,
                        fallback: false,
                        alternatives: p.alternatives,
                    })
                }
                Err(failure) if failure.action < p.prefix_len => {
                    mode = Mode::Paper;
                    let i = failure.action;
                    // A new action could not be bound where the plan puts it: ban it there (or,
                    // when movable bodies were in its way, until one of them has moved), and
                    // sample more.
                    if let Ok(at) = replay(self.task(), s, &p.ops[..i]) {
                        let moves = |_: &Task, o: &Operator, b: &str| binder.moves_body(o, b);
                        banned.ban_failed(p.ops[i], &at, &p.ops[..i], &failure.blockers, &moves);
                    }
                    binder.widen();
                }
                // An action of the demonstration's suffix, a_{k+1+(i−prefix)}: join the
                // demonstration after it (the search plans that step itself, with certified
                // actions), and sample more.
                Err(failure) => {
                    mode = Mode::Paper;
                    let i = failure.action;
                    let k = p.k.unwrap_or(self.lfd.spec().len());
                    first_k = first_k.max(k + 1 + (i - p.prefix_len));
                    binder.widen();
                }
            }
        }
        // No demonstration state can be joined with bindable actions: plan to G from scratch
        // (the TAMP solver Logic-LfD wraps), so the loop still finishes the task.
        if !self.params.tamp_fallback {
            return Err(FailReason::NoPlan { message: why });
        }
        self.plan_with_tamp(s, binder, clock).map(|mut p| {
            p.expanded += expanded;
            p.fallback = true;
            p
        })
    }

    fn plan_with_tamp(
        &self,
        s: &State,
        binder: &mut dyn Binder,
        clock: &dyn Clock,
    ) -> Result<Planned, FailReason> {
        let BoundPlan {
            ops,
            bindings,
            expanded,
        } = crate::tamp::plan_from_scratch(
            self.task(),
            s,
            binder,
            &self.params.search,
            self.params.max_skeletons,
            clock,
        )
        .map_err(|e| FailReason::NoPlan {
            message: e.to_string(),
        })?;
        Ok(Planned {
            new_actions: ops.len(),
            ops,
            k: None,
            bindings,
            expanded,
            fallback: false,
            alternatives: vec![],
        })
    }
}

fn unreachable_linear() -> Result<Planned, FailReason> {
    Err(FailReason::NoPlan {
        message: "linear never replans".into(),
    })
}
