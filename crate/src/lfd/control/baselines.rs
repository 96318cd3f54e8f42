//! The baselines' task level: Linear replays the demonstration blindly, RLDS moves along it to
//! the latest step whose remaining actions reach the goal from S_C; neither plans a new action.

use crate::plan::{reaches_goal, Clock, State};

use super::{Controller, Decision, FailReason, Planned, Replan};

impl Controller {
    pub(super) fn decide_linear(
        &mut self,
        s: &State,
        clock: &dyn Clock,
        t0: f64,
        tick: u64,
    ) -> Decision {
        if !self.started {
            self.started = true;
            let ops: Vec<usize> = self.lfd.spec().actions.iter().flatten().copied().collect();
            self.install(s, ops, Some(0));
            self.bindings.clear();
            self.replans.push(Replan {
                reason: "start".into(),
                time_ms: (clock.now_secs() - t0) * 1e3,
                k: Some(0),
                plan: self.plan_names.clone(),
                tick,
                new_actions: 0,
                bind_ms: 0.0,
                expanded: 0,
                fallback: false,
                alternatives: vec![],
            });
        }
        if self.cursor < self.plan.len() {
            return Decision::Execute {
                index: self.cursor,
                action: self.plan_names[self.cursor].clone(),
            };
        }
        let missing = self.missing_goal_facts(s);
        Decision::Failed(FailReason::GoalNotReached { missing })
    }

    fn missing_goal_facts(&self, s: &State) -> Vec<String> {
        self.task()
            .goal
            .alternatives
            .first()
            .map(|c| {
                c.pos
                    .iter()
                    .filter(|&&f| !s.contains(f))
                    .map(|&f| self.task().facts[f as usize].clone())
                    .collect()
            })
            .unwrap_or_default()
    }

    pub(super) fn plan_with_rlds(&self, s: &State) -> Result<Planned, FailReason> {
        // RLDS moves backward or forward along the demonstration to the latest step whose
        // remaining actions apply in S_C and reach G (the goal regressed through the suffix
        // holds); it never plans a new action.
        let spec = self.lfd.spec();
        for k in (0..=spec.len()).rev() {
            let Some(ops) = spec.suffix(k) else {
                continue;
            };
            if reaches_goal(self.task(), s, &ops) {
                return Ok(Planned {
                    ops,
                    k: Some(k),
                    new_actions: 0,
                    bindings: vec![],
                    expanded: 0,
                    fallback: false,
                    alternatives: vec![],
                });
            }
        }
        Err(FailReason::NoDemoStateMatches {
            facts: crate::lfd::state_names(self.task(), s),
        })
    }
}
