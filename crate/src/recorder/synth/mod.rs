//! Edits of the page, and the quicker teaching mode: the user drags a block from one support to
//! another (or asks for a hook pull) and the arm motion is synthesised as gripper samples, which
//! are then segmented exactly like a hand-made recording.
//!
//! A synthesised motion is a chain of minimum-jerk segments between way-points,
//!
//! ```text
//!   p(τ) = p₀ + (p₁ − p₀)(10τ³ − 15τ⁴ + 6τ⁵),   q(τ) = slerp(q₀, q₁, 10τ³ − 15τ⁴ + 6τ⁵),   τ ∈ [0, 1]
//! ```
//!
//! sampled every simulator step `dt`: approach above the body at a safe height, descend to the top
//! grasp ([`geometry::grasp_pose`]), close and hold, lift, transfer at the safe height, descend to
//! the pose that puts the body at rest 2 mm above its new support, open and hold, lift; with more
//! than one arm, the arm then returns to its ready pose (so it leaves the hand-over region free).
//! A hook pull picks the hook, puts its blade behind the block
//! ([`pull_hook_poses`](crate::sim::demo::pull_hook_poses)), drags it towards the arm, lifts,
//! and puts the hook back where it was.
//!
//! This file holds the edits, the gripper mode and the drag; `motion.rs` the motion builder and
//! the pick-and-place, `pull.rs` the hook pull.

mod motion;
mod params;
mod pull;

use params::refused;
pub use params::SynthParams;
pub use pull::{pull_samples, HookGrip};

use crate::sim::demo::min_jerk;
use motion::{go_home, motion_start, pick_and_place, reaches, resolve_arms};

use super::engine::gripper_sample;
use super::recording::{
    ArmRef, GripperPose, GripperState, HandMove, RawRecording, RawSample, RecordingScene,
};
use super::{Recorder, RecorderError, RecorderEvent};
use crate::sim::demo::{self, Demonstration};
use crate::sim::geometry;
use crate::sim::Benchmark;
use crate::sim::BodyKind;
use crate::sim::World;
use serde::{Deserialize, Serialize};

/// One edit of the page or of a script (JSON: `{"edit": "drag", …}`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(
    feature = "wasm-core",
    derive(tsify::Tsify),
    tsify(missing_as_null, rename = "TeachEdit")
)]
#[serde(tag = "edit", rename_all = "snake_case")]
pub enum Edit {
    /// A raw gripper sample (or hand move) as in a recording file.
    Sample {
        /// The sample.
        sample: RawSample,
    },
    /// Gripper mode without time stamps: move `arm`'s gripper from where it is to
    /// `position`/`yaw` along a minimum-jerk path lasting `duration` seconds (at least one step),
    /// with the gripper `gripper` throughout.
    Gripper {
        /// The arm.
        arm: ArmRef,
        /// TCP position (m, world).
        position: [f64; 3],
        /// Gripper yaw (rad).
        yaw: f64,
        /// `open` or `closed`.
        gripper: GripperState,
        /// How long the command holds (s; 0 = one step).
        #[serde(default)]
        duration: f64,
    },
    /// Quick mode: move `body` onto the block `onto`, or to `position` `[x, y]` on whatever is
    /// there (table, shelf, block); the arm motion is synthesised.
    Drag {
        /// The block to move.
        body: String,
        /// A block to stack it on (its centre and yaw are used).
        #[serde(default)]
        onto: Option<String>,
        /// Where to put it instead: `[x, y]` (m, world).
        #[serde(default)]
        position: Option<[f64; 2]>,
        /// Its new yaw (rad; default: kept, or the yaw of `onto`).
        #[serde(default)]
        yaw: Option<f64>,
        /// The arm to use (default: the first that reaches both places).
        #[serde(default)]
        arm: Option<ArmRef>,
    },
    /// Quick mode: pull an out-of-reach block in with the hook (B2).
    Pull {
        /// The block.
        body: String,
        /// The hook (default: the scene's first hook).
        #[serde(default)]
        hook: Option<String>,
        /// The arm (default: the first that reaches the hook).
        #[serde(default)]
        arm: Option<ArmRef>,
    },
    /// The user moves a block by hand (allowed only if no fact changes).
    Move {
        /// The block.
        body: String,
        /// Its new centre before settling (m).
        position: [f64; 3],
    },
}

impl Recorder {
    /// Applies one edit (atomically: on error nothing changes) and says what happened.
    pub fn push(&mut self, edit: &Edit) -> Result<RecorderEvent, RecorderError> {
        self.push_with(edit, &SynthParams::default())
    }

    /// [`Recorder::push`] with explicit synthesis tunables.
    pub fn push_with(
        &mut self,
        edit: &Edit,
        p: &SynthParams,
    ) -> Result<RecorderEvent, RecorderError> {
        match edit {
            Edit::Sample { sample } => self.push_sample(sample),
            Edit::Gripper {
                arm,
                position,
                yaw,
                gripper,
                duration,
            } => {
                let samples = self.gripper_path(arm, *position, *yaw, *gripper, *duration);
                self.push_samples(&samples)
            }
            Edit::Drag {
                body,
                onto,
                position,
                yaw,
                arm,
            } => {
                let s = drag_samples(self, body, onto.as_deref(), *position, *yaw, arm, p)?;
                self.push_samples(&s)
            }
            Edit::Pull { body, hook, arm } => {
                // Two phases: pick the hook, then pull with the grasp it actually got.
                let c = self.checkpoint();
                let edits_len = c.edits_len;
                let result = pull_samples(self, body, hook.as_deref(), arm, None, p)
                    .and_then(|(s, r)| self.push_samples(&s).map(|_| r))
                    .and_then(|r| pull_samples(self, body, hook.as_deref(), arm, Some(r), p))
                    .and_then(|(s, _)| self.push_samples(&s));
                match result {
                    Ok(_) => Ok(self.event_since(&c)),
                    Err(e) => {
                        self.rollback(c, edits_len);
                        Err(e)
                    }
                }
            }
            Edit::Move { body, position } => {
                let s = RawSample::Move {
                    t: self.time(),
                    hand: HandMove {
                        body: body.clone(),
                        position: *position,
                    },
                };
                self.push_sample(&s)
            }
        }
    }

    /// Gripper mode: samples from where `arm`'s gripper is now to `position`/`yaw` along a
    /// minimum-jerk path lasting `duration` seconds (at least one step).
    fn gripper_path(
        &self,
        arm: &ArmRef,
        position: [f64; 3],
        yaw: f64,
        gripper: GripperState,
        duration: f64,
    ) -> Vec<RawSample> {
        let t0 = self.time();
        let dt = self.world().dt();
        let n = ((duration / dt).round().max(1.0)) as usize;
        // From where the gripper is now to the commanded pose along a minimum-jerk path
        // (the handle gives where to go; a jump would make the arm move at its joint
        // speed limits, a motion no skill reproduces well).
        let from = arm
            .resolve(self.world())
            .and_then(|a| self.world().tcp_pose(a))
            .map(|p| {
                let v = p.translation.vector;
                ([v.x, v.y, v.z], super::engine::gripper_yaw(&p.rotation))
            });
        (0..n)
            .map(|k| {
                let (p, y) = match from {
                    Some((p0, y0)) => {
                        let s = min_jerk((k + 1) as f64 / n as f64);
                        (
                            [
                                p0[0] + (position[0] - p0[0]) * s,
                                p0[1] + (position[1] - p0[1]) * s,
                                p0[2] + (position[2] - p0[2]) * s,
                            ],
                            y0 + geometry::wrap(yaw - y0) * s,
                        )
                    }
                    None => (position, yaw),
                };
                RawSample::Gripper {
                    t: t0 + k as f64 * dt,
                    arm: arm.clone(),
                    pose: GripperPose {
                        position: p,
                        yaw: y,
                    },
                    gripper,
                }
            })
            .collect()
    }
}

/// Where a drag puts a body: its new centre `x`, `y` (m, world) and yaw (rad).
struct DragTarget {
    x: f64,
    y: f64,
    yaw: f64,
}

/// The target of a drag of `body` (now at yaw `cur_yaw`) onto `onto` or to `position`: onto a
/// block, its centre and yaw; onto another support, `position` or the support's centre; `Err`
/// says why there is none.
fn drag_target(
    world: &World,
    body: &str,
    onto: Option<&str>,
    position: Option<[f64; 2]>,
    yaw: Option<f64>,
    cur_yaw: f64,
) -> Result<DragTarget, String> {
    let (x, y, yaw) = match (onto, position) {
        (Some(s), _) => {
            if s == body {
                return Err("not onto itself".into());
            }
            let sp = world
                .body_pose(s)
                .ok_or_else(|| format!("there is no body {s}"))?;
            match (world.body_kind(s), position) {
                (Some(BodyKind::Block), _) => (
                    sp.translation.x,
                    sp.translation.y,
                    yaw.unwrap_or_else(|| crate::sim::yaw_of(&sp.rotation)),
                ),
                (_, Some([x, y])) => (x, y, yaw.unwrap_or(cur_yaw)),
                (_, None) => {
                    let (lo, hi) = world.body_aabb(s).ok_or_else(|| "no box".to_string())?;
                    let c = 0.5 * (lo + hi);
                    (c.x, c.y, yaw.unwrap_or(cur_yaw))
                }
            }
        }
        (None, Some([x, y])) => (x, y, yaw.unwrap_or(cur_yaw)),
        (None, None) => return Err("say where: \"onto\" a block or a \"position\"".into()),
    };
    Ok(DragTarget { x, y, yaw })
}

/// Samples that move `body` onto `onto` or to `position` (see [`Edit::Drag`]).
pub fn drag_samples(
    rec: &Recorder,
    body: &str,
    onto: Option<&str>,
    position: Option<[f64; 2]>,
    yaw: Option<f64>,
    arm: &Option<ArmRef>,
    p: &SynthParams,
) -> Result<Vec<RawSample>, RecorderError> {
    let world = rec.world();
    let cannot = |why: String| refused(format!("cannot move {body}: {why}"));
    match world.body_kind(body) {
        Some(BodyKind::Block | BodyKind::Hook) => {}
        Some(_) => return Err(cannot("it is fixed".into())),
        None => return Err(cannot("there is no such block".into())),
    }
    if world.is_lost(body) {
        return Err(cannot("it is lost".into()));
    }
    let arms = resolve_arms(world, arm)?;
    if (0..world.arm_names().len()).any(|r| world.held_by(r) == Some(body)) {
        return Err(cannot("it is held".into()));
    }
    let bp = world
        .body_pose(body)
        .ok_or_else(|| cannot("no pose".into()))?;
    let cur_yaw = crate::sim::yaw_of(&bp.rotation);
    let DragTarget { x, y, yaw } =
        drag_target(world, body, onto, position, yaw, cur_yaw).map_err(cannot)?;
    if !(x.is_finite() && y.is_finite() && yaw.is_finite()) {
        return Err(cannot("the target is not finite".into()));
    }
    // Rest pose with the body itself out of the way.
    let rest = geometry::rest_pose(world, body, x, y, yaw)
        .ok_or_else(|| cannot(format!("nothing is under ({x:.3}, {y:.3})")))?;
    let mut why = vec![];
    for &r in &arms {
        let name = world.arm_names()[r].to_string();
        if let Some(h) = world.held_by(r) {
            why.push(format!("{name} holds {h}"));
            continue;
        }
        let Some(g) = geometry::grasp_pose(world, r, body) else {
            return Err(cannot("it cannot be grasped".into()));
        };
        let place = rest * (g.inverse() * bp).inverse();
        if !reaches(world, r, &[g, place]) {
            why.push(format!("{name} does not reach both places"));
            continue;
        }
        let mut m = motion_start(rec, r)?;
        pick_and_place(world, &mut m, body, &rest, p)?;
        go_home(world, &mut m, p);
        return Ok(m.out);
    }
    Err(cannot(why.join("; ")))
}

/// A raw recording of a demonstration: `demo` is replayed from the benchmark's template scene
/// ([`demo::replay`]) and every commanded gripper pose and state becomes a sample (one per step).
/// Segmenting it must give back the demonstration's actions.
pub fn recording_from_demo(
    b: Benchmark,
    demonstration: &Demonstration,
) -> Result<RawRecording, RecorderError> {
    let mut world = b.scene();
    let dt = world.dt();
    let mut samples = vec![];
    demo::replay(&mut world, demonstration, |w, a, _k| {
        if let Some(arm) = w.arm_index(&a.arm) {
            if let Some((Some(target), grip)) = w.arm_command(arm) {
                samples.push(gripper_sample(
                    samples.len() as f64 * dt,
                    arm,
                    &target,
                    grip,
                ));
            }
        }
        Ok(())
    })
    .map_err(|e| refused(format!("replaying the demonstration failed: {e}")))?;
    Ok(RawRecording {
        scene: RecordingScene::Benchmark(b),
        dt,
        samples,
        goal: None,
        seed: demonstration.seed,
    })
}
