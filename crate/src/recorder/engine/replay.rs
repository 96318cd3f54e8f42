//! Replaying one sample in the simulator with every check (time order, finite poses, a release
//! in mid-air, a body falling, the world's invariants), and explaining each fact change by the
//! one operator of the grounded task that makes it.

use super::{model_err, sorted_facts, ActionRec, Cause, Recorder};
use crate::plan::State;
use crate::recorder::RecorderError;
use crate::recorder::{ArmRef, GripperPose, GripperState, HandMove, RawSample};
use crate::sim::panda;
use crate::sim::{GripperCommand, WorldEvent};
use nalgebra::{Isometry3, Translation3, Vector3};

/// Round-off allowed when a sample's time is compared with the current time (s): a sample stamped
/// at the current time is not "back in time".
const TIME_SLACK: f64 = 1e-9;

impl Recorder {
    /// Applies one sample at its time (catching up with the previous commands first).
    pub(super) fn apply_sample(&mut self, sample: &RawSample) -> Result<(), RecorderError> {
        let t = sample.t();
        if !t.is_finite() {
            return Err(RecorderError::Input {
                path: "t".into(),
                message: "expected a finite number".into(),
            });
        }
        let dt = self.world.dt();
        let cur = *self.cur_t.get_or_insert(t);
        if t + 0.5 * dt < cur - TIME_SLACK && self.log_t.last().is_some_and(|&l| t + 0.5 * dt < l) {
            return Err(RecorderError::Input {
                path: "t".into(),
                message: format!(
                    "goes back in time ({t} s after {} s)",
                    self.log_t.last().copied().unwrap_or(cur)
                ),
            });
        }
        let same_time = t + 0.5 * dt < cur;
        if !same_time {
            // Catch up: the world keeps following the previous commands until t.
            while self.time() + 0.5 * dt < t {
                self.step_once()?;
            }
        }
        match sample {
            RawSample::Gripper {
                arm, pose, gripper, ..
            } => self.command_gripper(arm, pose, *gripper)?,
            RawSample::Move { hand, .. } => {
                let HandMove { body, position } = hand;
                self.world
                    .move_block(body, Vector3::from(*position))
                    .map_err(|e| RecorderError::Physics {
                        t: self.time(),
                        message: e.to_string(),
                    })?;
            }
        }
        if !same_time || matches!(sample, RawSample::Move { .. }) {
            self.step_once()?;
        }
        Ok(())
    }

    /// Commands `arm`'s gripper to `pose` (checked: a known arm, finite numbers).
    fn command_gripper(
        &mut self,
        arm: &ArmRef,
        pose: &GripperPose,
        gripper: GripperState,
    ) -> Result<(), RecorderError> {
        let ai = arm
            .resolve(&self.world)
            .ok_or_else(|| RecorderError::Input {
                path: "arm".into(),
                message: format!(
                    "no such arm {} (arms: {})",
                    match arm {
                        ArmRef::Index(i) => i.to_string(),
                        ArmRef::Name(n) => format!("{n:?}"),
                    },
                    self.world.arm_names().join(", ")
                ),
            })?;
        if !(pose.position.iter().all(|v| v.is_finite()) && pose.yaw.is_finite()) {
            return Err(RecorderError::Input {
                path: "pose".into(),
                message: "expected finite numbers".into(),
            });
        }
        let target = Isometry3::from_parts(
            Translation3::from(Vector3::from(pose.position)),
            panda::down_orientation(pose.yaw),
        );
        self.world
            .command_arm(ai, target, gripper.command())
            .map_err(model_err)
    }

    /// One simulator step with every check; logs it.
    fn step_once(&mut self) -> Result<(), RecorderError> {
        if self.log_t.len() >= self.params.max_steps {
            return Err(RecorderError::Refused(format!(
                "the recording is longer than {} simulator steps",
                self.params.max_steps
            )));
        }
        let t = self.time();
        let events = self.world.step();
        let step = self.log_t.len();
        let cause = self.step_cause(t, &events)?;
        let facts = sorted_facts(&self.world);
        if facts != self.facts {
            self.explain_change(t, step, &facts, cause)?;
            self.facts = facts;
        }
        if let Err(v) = self.world.check_invariants() {
            let text: Vec<String> = v.iter().map(|x| x.to_string()).collect();
            return Err(RecorderError::Physics {
                t,
                message: text.join("; "),
            });
        }
        self.log_step(t, step, events);
        Ok(())
    }

    /// What caused the step's fact change, if any (a grasp or a release), or the physical
    /// implausibility that refuses the step (a body lost, a release in mid-air).
    fn step_cause(&self, t: f64, events: &[WorldEvent]) -> Result<Cause, RecorderError> {
        let mut cause = Cause::Other;
        for e in events {
            match e {
                WorldEvent::Lost { body, reason } => {
                    return Err(RecorderError::Physics {
                        t,
                        message: format!("{body} fell: {reason}"),
                    })
                }
                WorldEvent::Released {
                    arm,
                    body,
                    support,
                    drop,
                } => {
                    if *drop > self.params.max_release_drop {
                        return Err(RecorderError::Physics {
                            t,
                            message: format!(
                                "{arm} released {body} in mid-air, {:.0} mm above {support} \
                                 (at most {:.0} mm counts as putting it down)",
                                drop * 1000.0,
                                self.params.max_release_drop * 1000.0
                            ),
                        });
                    }
                    cause = Cause::Release(body.clone());
                }
                WorldEvent::Grasped { body, .. } => cause = Cause::Grasp(body.clone()),
                _ => {}
            }
        }
        Ok(cause)
    }

    /// Logs step `step` at time `t`: every arm's TCP and gripper, every body's pose, the events.
    fn log_step(&mut self, t: f64, step: usize, events: Vec<WorldEvent>) {
        let n = self.world.arm_names().len();
        self.log_t.push(t);
        self.log_tcp.push(
            (0..n)
                .map(|a| self.world.tcp_pose(a).unwrap_or_else(Isometry3::identity))
                .collect(),
        );
        self.log_grip.push(
            (0..n)
                .map(|a| {
                    self.world
                        .arm_command(a)
                        .map(|c| c.1)
                        .unwrap_or(GripperCommand::Open)
                })
                .collect(),
        );
        self.log_bodies.push(
            self.body_names
                .iter()
                .map(|b| self.world.body_pose(b).unwrap_or_else(Isometry3::identity))
                .collect(),
        );
        self.log_events
            .extend(events.into_iter().map(|e| (step, e)));
        self.cur_t = Some(t + self.world.dt());
    }

    /// Finds the operator that explains `S → facts`, records it, or errors.
    fn explain_change(
        &mut self,
        t: f64,
        step: usize,
        facts: &[String],
        cause: Cause,
    ) -> Result<(), RecorderError> {
        let old: std::collections::BTreeSet<&String> = self.facts.iter().collect();
        let new: std::collections::BTreeSet<&String> = facts.iter().collect();
        let added: Vec<String> = new.difference(&old).map(|s| s.to_string()).collect();
        let removed: Vec<String> = old.difference(&new).map(|s| s.to_string()).collect();
        let next = match self.task.state_from_names(facts) {
            Ok(s) => s,
            Err(e) => {
                return Err(RecorderError::Unexplained {
                    t,
                    added,
                    removed,
                    hint: format!("; {e}"),
                })
            }
        };
        let found = self
            .task
            .operators
            .iter()
            .position(|o| o.applicable(&self.state) && o.apply(&self.state) == next);
        let Some(op) = found else {
            let hint = self.closest_hint(&next);
            return Err(RecorderError::Unexplained {
                t,
                added,
                removed,
                hint,
            });
        };
        let name = &self.task.operators[op].name;
        let arm = name
            .trim_matches(|c| c == '(' || c == ')')
            .split_whitespace()
            .skip(1)
            .find_map(|w| self.world.arm_index(w))
            .ok_or_else(|| {
                RecorderError::Model(format!(
                    "at t = {t:.2} s: the action {name} explains the change but names no arm of the scene"
                ))
            })?;
        self.actions.push(ActionRec {
            op,
            arm,
            step,
            cause,
            added,
            removed,
        });
        self.state = next;
        Ok(())
    }

    /// "; the closest action … needs … / would …" for an unexplained change.
    fn closest_hint(&self, next: &State) -> String {
        let s = &self.state;
        let mut best: Option<(usize, usize)> = None;
        for (i, o) in self.task.operators.iter().enumerate() {
            let unmet = o.pre.iter().filter(|&&f| !s.contains(f)).count()
                + o.pre_neg.iter().filter(|&&f| s.contains(f)).count();
            let after = o.apply(s);
            let diff = (0..self.task.facts.len() as u32)
                .filter(|&f| after.contains(f) != next.contains(f))
                .count();
            let score = unmet + diff;
            if best.is_none_or(|(b, _)| score < b) {
                best = Some((score, i));
            }
        }
        let Some((_, i)) = best else {
            return String::new();
        };
        let o = &self.task.operators[i];
        let name = |f: &u32| self.task.facts[*f as usize].clone();
        let mut parts = vec![];
        let missing: Vec<String> = o
            .pre
            .iter()
            .filter(|&&f| !s.contains(f))
            .map(name)
            .collect();
        if !missing.is_empty() {
            parts.push(format!("needs {}", missing.join(" ")));
        }
        let forbidden: Vec<String> = o
            .pre_neg
            .iter()
            .filter(|&&f| s.contains(f))
            .map(name)
            .collect();
        if !forbidden.is_empty() {
            parts.push(format!("needs not {}", forbidden.join(" ")));
        }
        let after = o.apply(s);
        let too_much: Vec<u32> = (0..self.task.facts.len() as u32)
            .filter(|&f| after.contains(f) != next.contains(f))
            .collect();
        if !too_much.is_empty() {
            let want_add: Vec<String> = too_much
                .iter()
                .filter(|&&f| next.contains(f) && !after.contains(f))
                .map(name)
                .collect();
            let want_del: Vec<String> = too_much
                .iter()
                .filter(|&&f| !next.contains(f) && after.contains(f))
                .map(name)
                .collect();
            let mut d = vec![];
            if !want_add.is_empty() {
                d.push(format!("does not make {} true", want_add.join(" ")));
            }
            if !want_del.is_empty() {
                d.push(format!("does not make {} false", want_del.join(" ")));
            }
            parts.push(d.join(" and "));
        }
        format!("; the closest action {} {}", o.name, parts.join("; "))
    }
}
