//! One tick of the loop (paper Algorithm 1, with the executor of [`crate::lfd::exec`]): decide
//! and start the next action when none runs, else advance the running skill by one tick and
//! check the scene; `step` and `run_to_end` repeat it.

use crate::lfd::Method;
use crate::lfd::{ActionExec, ExecStatus};
use crate::lfd::{Controller, Decision, FailReason};
use crate::plan::Clock;
use crate::sim::World;
use crate::tamp::{classify, ActionKind, Binder, Binding, Placement};
use crate::tamp::{StreamBinder, StreamParams};

use super::options::PlacementHints;
use super::{facts_of, mix_seed, objects_of, ActionRecord, Frame, Session};

/// Added to `dt_secs / dt` before it is floored to whole ticks, so a `dt` that is a whole number
/// of ticks up to rounding runs that number.
const TICK_ROUNDING: f64 = 1e-9;

impl Session {
    /// Advances whole 10 ms ticks covering `dt_secs` (fractions carry over); replans inside.
    pub fn step(&mut self, dt_secs: f64, clock: &dyn Clock) -> Frame {
        let dt = self.world.dt();
        let want = self.carry + dt_secs.max(0.0);
        let n = (want / dt + TICK_ROUNDING).floor() as u64;
        self.carry = want - n as f64 * dt;
        for _ in 0..n {
            if self.outcome.is_some() {
                break;
            }
            self.tick_once(clock);
        }
        let facts = facts_of(&self.world);
        self.frame_added = facts
            .iter()
            .filter(|f| !self.prev_facts.contains(f))
            .cloned()
            .collect();
        self.frame_removed = self
            .prev_facts
            .iter()
            .filter(|f| !facts.contains(f))
            .cloned()
            .collect();
        self.prev_facts = facts;
        self.frame()
    }

    /// Runs until the episode ends or `max_ticks` more ticks have passed.
    pub fn run_to_end(&mut self, max_ticks: u64, clock: &dyn Clock) {
        for _ in 0..max_ticks {
            if self.outcome.is_some() {
                break;
            }
            self.tick_once(clock);
        }
    }

    /// One 10 ms tick of the loop.
    pub fn tick_once(&mut self, clock: &dyn Clock) {
        if self.outcome.is_some() {
            return;
        }
        if self.world.time() > self.params.max_time {
            self.outcome = Some(Err(FailReason::Budget {
                what: "simulated time".into(),
            }));
            return;
        }
        if self.exec.is_none() && !self.start_next_action(clock) {
            return;
        }
        let Some(exec) = self.exec.as_mut() else {
            return;
        };
        let status = exec.tick(&mut self.world, &self.skills, &self.params.exec);
        self.tick += 1;
        let linear = self.options.method == Method::Linear;
        match status {
            ExecStatus::Running => {
                if !linear {
                    let facts = facts_of(&self.world);
                    if !self.controller.consistent_during_action(&facts) {
                        self.end_action("interrupted: the scene changed".into());
                    }
                }
            }
            ExecStatus::Done => {
                let facts = facts_of(&self.world);
                if linear || self.controller.action_had_its_effect(&facts) {
                    self.controller.advance();
                    self.actions_done += 1;
                    self.failures_in_a_row = 0;
                    self.end_action("done".into());
                } else {
                    self.failures_in_a_row += 1;
                    self.end_action("no effect".into());
                    self.check_failures();
                }
            }
            ExecStatus::Failed(why) => {
                let action = self
                    .exec
                    .as_ref()
                    .map(|e| e.action.clone())
                    .unwrap_or_default();
                self.end_action(format!("failed: {why}"));
                if linear {
                    self.outcome = Some(Err(FailReason::ActionFailed { action, why }));
                } else {
                    self.controller
                        .replan_after_failure(format!("{action} failed: {why}"));
                    self.failures_in_a_row += 1;
                    self.check_failures();
                }
            }
        }
    }

    fn check_failures(&mut self) {
        if self.failures_in_a_row >= self.params.max_action_failures {
            let action = self
                .actions
                .last()
                .map(|a| a.action.clone())
                .unwrap_or_default();
            // The record says "failed: why"; the reason says "(action) failed: why" once.
            let why = self
                .actions
                .last()
                .map(|a| {
                    let o = a.outcome.as_str();
                    o.strip_prefix("failed: ").unwrap_or(o).to_string()
                })
                .unwrap_or_default();
            self.outcome = Some(Err(FailReason::ActionFailed { action, why }));
        }
    }

    pub(super) fn end_action(&mut self, outcome: String) {
        self.exec = None;
        if let Some(a) = self.actions.last_mut() {
            if a.end_tick.is_none() {
                a.end_tick = Some(self.tick);
                a.outcome = outcome;
            }
        }
    }

    /// Asks the controller what to do; starts the action. `false` if nothing to execute.
    fn start_next_action(&mut self, clock: &dyn Clock) -> bool {
        let facts = facts_of(&self.world);
        let objects = objects_of(&self.world);
        let before = self.controller.replans().len();
        // The streams certify the executor's motions: the same heights.
        let streams = StreamParams {
            motion: self.params.exec.motion,
            ..self.params.streams
        };
        let mut binder = StreamBinder::new(
            &self.world,
            mix_seed(self.options.seed, before as u64 + 1),
            streams,
        )
        .with_hints(&self.hints);
        let decision =
            self.controller
                .decide(&facts, &objects, &self.model, &mut binder, clock, self.tick);
        let replanned = self.controller.replans().len() > before;
        if replanned {
            self.bindings = plan_bindings(
                self.options.method,
                &self.controller,
                &self.world,
                &self.hints,
                &mut binder,
            );
        }
        drop(binder);
        match decision {
            Decision::Done => {
                self.outcome = Some(Ok(()));
                false
            }
            Decision::Failed(r) => {
                self.outcome = Some(Err(r));
                false
            }
            Decision::Execute { index, action } => self.start_action(index, action),
        }
    }

    /// Starts executing step `index` of the plan, `action`, with its bound placement. `false`
    /// (and the episode fails) when the executor cannot run it.
    fn start_action(&mut self, index: usize, action: String) -> bool {
        let task = self.controller.task();
        let op = &task.operators[self.controller.plan_ops()[index]];
        let Some(mut kind) = classify(op, &self.world) else {
            self.outcome = Some(Err(FailReason::ActionFailed {
                action,
                why: "the executor does not know this kind of action".into(),
            }));
            return false;
        };
        let binding = self.bindings.get(index).cloned().unwrap_or_default();
        if let ActionKind::Pull { turn, .. } = &mut kind {
            if let Some(Placement::Stroke(t)) = binding.placement {
                *turn = t;
            }
        }
        if let ActionKind::Release { placement, .. } = &mut kind {
            if placement.is_none() {
                placement.clone_from(&binding.placement);
            }
            if placement.is_none() {
                self.outcome = Some(Err(FailReason::ActionFailed {
                    action,
                    why: "no placement could be bound".into(),
                }));
                return false;
            }
        }
        let exec = ActionExec::new(&action, kind, &self.world, &self.skills, &self.params.exec)
            .with_hand_yaw(binding.hand_yaw);
        self.exec = Some(match binding.transit {
            Some(z) => exec.with_transit(z),
            None => exec,
        });
        self.actions.push(ActionRecord {
            action,
            start_tick: self.tick,
            end_tick: None,
            outcome: "running".into(),
        });
        true
    }
}

/// The bindings of a new plan. Logic-LfD and TAMP keep what the streams bound while planning;
/// the baselines sample nothing: Linear keeps the demonstration's placements as demonstrated,
/// RLDS re-targets only surface placements.
fn plan_bindings(
    method: Method,
    controller: &Controller,
    world: &World,
    hints: &PlacementHints,
    binder: &mut StreamBinder<'_>,
) -> Vec<Binding> {
    match method {
        Method::Linear => {
            // No task-level feedback, nothing re-sampled; blocks are re-targeted by the skills.
            let task = controller.task();
            controller
                .plan_ops()
                .iter()
                .map(|&o| {
                    let op = &task.operators[o];
                    match classify(op, world) {
                        Some(ActionKind::Release {
                            placement: Some(p), ..
                        }) => Some(p),
                        Some(ActionKind::Release { .. }) => {
                            hints.get(&op.name).map(|h| Placement::At {
                                x: h.x,
                                y: h.y,
                                yaw: h.yaw,
                            })
                        }
                        _ => None,
                    }
                    .into()
                })
                .collect()
        }
        Method::Rlds => {
            // No new actions: only surface placements are re-targeted.
            let ops = controller.plan_ops().to_vec();
            let task = controller.task().clone();
            binder
                .bind(&task, &ops, 0)
                .unwrap_or_else(|_| vec![Binding::default(); ops.len()])
        }
        Method::LogicLfd | Method::Tamp => controller.bindings().to_vec(),
    }
}
