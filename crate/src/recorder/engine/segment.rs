//! Segmenting the recorded motion into the demonstration's actions: each action's sample range
//! (the boundaries of the module docs of [`crate::recorder`]), its samples in its anchor's
//! frame, its gripper events and key points, and the finished demonstration.

use super::{gripper_yaw, ActionRec, Cause, Recorder};
use crate::plan::State;
use crate::recorder::{RecorderError, Segment, Taught, TaughtDemo};
use crate::sim::demo::{AnchorPose, DemoAction, Demonstration, GripperChange, KeyPoint};
use crate::sim::geometry::wrap;
use crate::sim::WorldEvent;
use nalgebra::{Isometry3, Point3};

/// Resolution of the demonstration's sample positions (m).
const POSITION_QUANTUM: f64 = 1e-4;
/// Resolution of the demonstration's sample yaws (rad).
const YAW_QUANTUM: f64 = 1e-3;

/// `v` rounded to a multiple of `q`.
fn round_to(v: f64, q: f64) -> f64 {
    (v / q).round() * q
}

impl Recorder {
    /// The recognised actions so far, with their sample ranges (the last one's end is provisional).
    pub fn segments(&self) -> Vec<Segment> {
        (0..self.actions.len()).map(|i| self.segment(i)).collect()
    }

    /// Action `i` as the page lists it.
    pub(super) fn segment(&self, i: usize) -> Segment {
        let (start, end) = self.range(i);
        let a = &self.actions[i];
        let t_at = |k: usize| self.log_t.get(k).copied().unwrap_or(0.0);
        Segment {
            index: i,
            action: self.task.operators[a.op].name.clone(),
            arm: self.world.arm_names()[a.arm].to_string(),
            t_start: t_at(start),
            t_event: t_at(a.step),
            t_end: t_at(end),
            added: a.added.clone(),
            removed: a.removed.clone(),
        }
    }

    /// The demonstration states L_0..L_N so far (fluents, sorted).
    pub fn demo_states(&self) -> Vec<Vec<String>> {
        let mut s = self.init_state.clone();
        let mut out = vec![self.names(&s)];
        for a in &self.actions {
            s = self.task.operators[a.op].apply(&s);
            out.push(self.names(&s));
        }
        out
    }

    /// The fact names of `s`, sorted.
    fn names(&self, s: &State) -> Vec<String> {
        let mut v = self.task.state_names(s);
        v.sort();
        v
    }

    /// Log index range `[start, end]` of action `i`.
    fn range(&self, i: usize) -> (usize, usize) {
        let start = if i == 0 { 0 } else { self.boundary(i - 1) + 1 };
        let end = if i + 1 == self.actions.len() {
            self.log_t.len().saturating_sub(1)
        } else {
            self.boundary(i)
        };
        (start.min(end), end)
    }

    /// The last log index of action `i` (i < N − 1): see the module docs.
    pub(super) fn boundary(&self, i: usize) -> usize {
        let a = &self.actions[i];
        let b = &self.actions[i + 1];
        let (e, e2) = (a.step, b.step);
        if e2 <= e + 1 {
            return e;
        }
        let pos = |k: usize, arm: usize| self.log_tcp[k][arm].translation.vector;
        let moved = |k: usize, arm: usize| {
            k > 0 && (pos(k, arm) - pos(k - 1, arm)).norm() > self.params.still_per_step
        };
        if a.arm != b.arm {
            let last_move = (e + 1..e2).rev().find(|&k| moved(k, a.arm)).unwrap_or(e);
            let first_other = (e + 1..e2).find(|&k| moved(k, b.arm));
            let mut bnd = last_move;
            if let Some(f) = first_other {
                bnd = bnd.min(f.saturating_sub(1));
            }
            return bnd.max(e);
        }
        let z0 = pos(e, a.arm).z;
        let speed = |k: usize| {
            if k == 0 {
                0.0
            } else {
                (pos(k, a.arm) - pos(k - 1, a.arm)).norm()
            }
        };
        if let Some(k) = (e + 1..e2).find(|&k| pos(k, a.arm).z >= z0 + self.params.lift_height) {
            // The end of the lift: the first local minimum of the speed once the speed has come
            // down from its peak (the lift height is often reached while still accelerating; a
            // cut there leaves both neighbours starting or ending at full speed).
            let mut peak = (e + 1..=k).map(speed).fold(0.0, f64::max);
            for k2 in k..e2 - 1 {
                let v = speed(k2);
                if v < peak && v <= speed(k2 + 1) {
                    return k2;
                }
                peak = peak.max(v);
            }
            return e2 - 1;
        }
        (e + 1..e2)
            .max_by(|&x, &y| pos(x, a.arm).z.total_cmp(&pos(y, a.arm).z))
            .unwrap_or(e)
    }

    fn body_pose_at(&self, name: &str, k: usize) -> Option<Isometry3<f64>> {
        let j = self.body_names.iter().position(|b| b == name)?;
        self.log_bodies.get(k).map(|v| v[j])
    }

    /// Action `i` as the demonstration stores it (see [`crate::sim::demo`]).
    fn demo_action(&self, i: usize) -> Result<DemoAction, RecorderError> {
        let a = &self.actions[i];
        let op_name = self.task.operators[a.op].name.clone();
        let words: Vec<String> = op_name
            .trim_matches(|c| c == '(' || c == ')')
            .split_whitespace()
            .map(String::from)
            .collect();
        let (start, end) = self.range(i);
        let (anchor, anchor_pose) = self.anchor(a, &op_name, &words, start, end)?;
        let anchor_pose = AnchorPose::from_pose(
            &anchor_pose
                .ok_or_else(|| RecorderError::Model(format!("{op_name}: no pose of {anchor}")))?,
        );
        let samples = self.anchor_samples(a.arm, &anchor_pose, start, end);
        let gripper = self.gripper_events(a.arm, start, end);
        let key_points = self.key_points(a, &anchor, start, end);
        Ok(DemoAction {
            action: op_name,
            name: words.first().cloned().unwrap_or_default(),
            args: words.iter().skip(1).cloned().collect(),
            arm: self.world.arm_names()[a.arm].to_string(),
            anchor,
            anchor_pose,
            samples,
            gripper,
            key_points,
            via_points: Vec::new(),
        })
    }

    /// The anchor of an action and its pose: the grasped body at the action's start, the released
    /// one at its end, else the first argument naming a body that is not held (the block a hook
    /// pulls) at the start.
    fn anchor(
        &self,
        a: &ActionRec,
        op_name: &str,
        words: &[String],
        start: usize,
        end: usize,
    ) -> Result<(String, Option<Isometry3<f64>>), RecorderError> {
        Ok(match &a.cause {
            Cause::Grasp(b) => (b.clone(), self.body_pose_at(b, start)),
            Cause::Release(b) => (b.clone(), self.body_pose_at(b, end)),
            Cause::Other => {
                let held: Vec<&str> = (0..self.world.arm_names().len())
                    .filter_map(|r| self.world.held_by(r))
                    .collect();
                let name = words
                    .iter()
                    .skip(1)
                    .find(|w| self.body_names.contains(w) && !held.contains(&w.as_str()))
                    .or_else(|| words.iter().skip(1).find(|w| self.body_names.contains(w)))
                    .cloned()
                    .ok_or_else(|| {
                        RecorderError::Model(format!("{op_name} names no block or hook"))
                    })?;
                let p = self.body_pose_at(&name, start);
                (name, p)
            }
        })
    }

    /// The TCP samples `start..=end` of `arm` as `[x, y, z, yaw]` in the anchor's frame, rounded
    /// to [`POSITION_QUANTUM`] and [`YAW_QUANTUM`].
    fn anchor_samples(
        &self,
        arm: usize,
        anchor_pose: &AnchorPose,
        start: usize,
        end: usize,
    ) -> Vec<[f64; 4]> {
        let frame = anchor_pose.isometry();
        let inv = frame.inverse();
        (start..=end)
            .map(|k| {
                let tcp = self.log_tcp[k][arm];
                let lp = inv * Point3::from(tcp.translation.vector);
                let yaw = wrap(gripper_yaw(&tcp.rotation) - anchor_pose.yaw);
                [
                    round_to(lp.x, POSITION_QUANTUM),
                    round_to(lp.y, POSITION_QUANTUM),
                    round_to(lp.z, POSITION_QUANTUM),
                    round_to(yaw, YAW_QUANTUM),
                ]
            })
            .collect()
    }

    /// `arm`'s gripper command at `start` and every change up to `end` (steps from `start`).
    fn gripper_events(&self, arm: usize, start: usize, end: usize) -> Vec<GripperChange> {
        let mut gripper = vec![GripperChange {
            step: 0,
            command: self.log_grip[start][arm],
        }];
        for k in start + 1..=end {
            let g = self.log_grip[k][arm];
            if g != self.log_grip[k - 1][arm] {
                gripper.push(GripperChange {
                    step: k - start,
                    command: g,
                });
            }
        }
        gripper
    }

    /// The action's key points: its grasp or release, or (a pull) the hook's first contact with
    /// the anchor and the moment the block is pulled.
    fn key_points(&self, a: &ActionRec, anchor: &str, start: usize, end: usize) -> Vec<KeyPoint> {
        let mut key_points = vec![];
        match &a.cause {
            Cause::Grasp(_) => key_points.push(KeyPoint {
                step: a.step - start,
                label: "grasp".into(),
            }),
            Cause::Release(_) => key_points.push(KeyPoint {
                step: a.step - start,
                label: "release".into(),
            }),
            Cause::Other => {
                if let Some((k, _)) = self.log_events.iter().find(|(k, e)| {
                    *k >= start
                        && *k <= end
                        && matches!(e, WorldEvent::Pushed { body, .. } if *body == anchor)
                }) {
                    key_points.push(KeyPoint {
                        step: k - start,
                        label: "contact".into(),
                    });
                }
                key_points.push(KeyPoint {
                    step: a.step - start,
                    label: "pulled".into(),
                });
            }
        }
        key_points
    }

    /// Ends the recording: the demonstration (`demo.json`), its states and the skill fits. Refused
    /// when nothing was demonstrated, when an arm still holds something, or when the goal does not
    /// hold in L_N.
    pub fn finish(&self) -> Result<Taught, RecorderError> {
        if self.actions.is_empty() {
            return Err(RecorderError::Refused(
                "nothing was demonstrated: no fact of the scene changed".into(),
            ));
        }
        for (r, name) in self.world.arm_names().iter().enumerate() {
            if let Some(b) = self.world.held_by(r) {
                return Err(RecorderError::Refused(format!(
                    "the recording ends while {name} holds {b}: put it down first"
                )));
            }
        }
        let states = self.demo_states();
        let last = states.last().cloned().unwrap_or_default();
        let goal = match &self.goal {
            Some(g) => {
                for f in g {
                    if !last.contains(f) && !self.task.static_facts.contains(f) {
                        return Err(RecorderError::Refused(format!(
                            "the goal fact {f} does not hold at the end of the demonstration"
                        )));
                    }
                }
                g.clone()
            }
            None => last.clone(),
        };
        let actions = (0..self.actions.len())
            .map(|i| self.demo_action(i))
            .collect::<Result<Vec<_>, _>>()?;
        let dt = self.world.dt();
        let demo = Demonstration {
            benchmark: self.initial.name.clone(),
            seed: self.seed,
            dt,
            frame_convention: FRAME_CONVENTION.to_string(),
            actions,
        };
        let skills = if self.params.learn_skills {
            crate::recorder::taught::skill_fits(&demo)?
        } else {
            vec![]
        };
        Ok(Taught {
            demo: TaughtDemo {
                demo,
                domain: self.domain_name.clone(),
                initial_facts: states[0].clone(),
                goal,
                scene: self.initial.clone(),
            },
            states,
            skills,
        })
    }
}

/// The `frame_convention` text of a taught demonstration.
const FRAME_CONVENTION: &str =
    "samples are [x, y, z, yaw] of the gripper tool centre point in the \
anchor frame (anchor centre + its yaw about world z; pick/unstack/pull: the object at the action's \
start; place/place-on-shelf/stack: the carried object's resting pose at the action's end), every \
10 ms; gripper pointing straight down; yaw relative to the anchor's yaw";
