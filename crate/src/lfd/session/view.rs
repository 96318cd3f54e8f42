//! How a session's [`Frame`] is read off it.

use super::frame::{EePoint, Frame, Status, StatusKind};
use super::{facts_of, Session};

/// For this many ticks after a replan (other than the first plan) the status line says
/// "replanning because …".
const REPLAN_NOTICE_TICKS: u64 = 50;

impl Session {
    /// The current frame without stepping.
    pub fn frame(&self) -> Frame {
        let facts = facts_of(&self.world);
        let plan = self.controller.plan_names().to_vec();
        let executing = self.exec.as_ref().map(|_| self.controller.cursor());
        let replans = self.controller.replans();
        let status = self.status(&plan, executing);
        let ee = (0..self.world.arm_names().len())
            .filter_map(|a| {
                let tcp = self.world.tcp_pose(a)?.translation.vector;
                let target = self
                    .exec
                    .as_ref()
                    .filter(|e| e.arm() == a)
                    .and_then(|e| e.target())
                    .unwrap_or(tcp);
                Some(EePoint {
                    arm: a,
                    pos: [tcp.x, tcp.y, tcp.z],
                    target: [target.x, target.y, target.z],
                })
            })
            .collect();
        Frame {
            t: self.world.time(),
            tick: self.tick,
            world: self.world.snapshot(),
            status,
            plan,
            executing,
            demo: self.trace.actions.clone(),
            demo_states: self
                .trace
                .states
                .iter()
                .map(|s| s.iter().cloned().collect())
                .collect(),
            matched_k: self.controller.matched_k(),
            facts,
            facts_added: self.frame_added.clone(),
            facts_removed: self.frame_removed.clone(),
            last_replan: replans.last().cloned(),
            replans: replans.len(),
            ee,
        }
    }

    fn status(&self, plan: &[String], executing: Option<usize>) -> Status {
        let st = |kind, message: String, step: Option<usize>, of: Option<usize>| Status {
            kind,
            message,
            step,
            of,
        };
        match &self.outcome {
            Some(Ok(())) => return st(StatusKind::Done, "done: the goal holds".into(), None, None),
            Some(Err(r)) => {
                return st(
                    StatusKind::Failed,
                    format!("failed because {r}"),
                    None,
                    None,
                )
            }
            None => {}
        }
        match executing {
            Some(i) => {
                let replan = self.controller.replans().last();
                let fresh = replan.is_some_and(|r| {
                    r.tick + REPLAN_NOTICE_TICKS > self.tick && r.reason != "start"
                });
                let kind = if fresh {
                    StatusKind::Replanning
                } else {
                    StatusKind::Executing
                };
                let msg = match (fresh, replan) {
                    (true, Some(r)) => format!(
                        "replanned because {}; executing step {} of {}: {}",
                        r.reason,
                        i + 1,
                        plan.len(),
                        plan.get(i).cloned().unwrap_or_default()
                    ),
                    _ => format!(
                        "executing step {} of {}: {}",
                        i + 1,
                        plan.len(),
                        plan.get(i).cloned().unwrap_or_default()
                    ),
                };
                st(kind, msg, Some(i + 1), Some(plan.len()))
            }
            None if self.tick == 0 => st(StatusKind::Idle, "ready".into(), None, None),
            None => st(StatusKind::Planning, "planning".into(), None, None),
        }
    }
}
