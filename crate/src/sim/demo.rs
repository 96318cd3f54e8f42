//! Demonstrations (`domains/*/demo.json`): the template task's action sequence and, per action,
//! the end-effector trajectory expressed relative to the object it acts on; recorded by a
//! scripted expert in the simulator, replayable in it.
//!
//! **Frame convention.** Each action has an *anchor* object and an anchor frame `F` = the anchor's
//! centre with its yaw about world `z` (no tilt):
//! * `pick`, `unstack`, `pull`: the picked / pulled block (or the hook) at the start of the action;
//! * `place`, `place-on-shelf`, `stack`: the carried object at the pose where it is put down
//!   (its resting pose at the end of the action).
//!
//! A sample `[x, y, z, yaw]` is the gripper's tool centre point in `F` (metres) and the gripper's
//! yaw about `z` relative to `F`'s yaw (radians); the gripper always points straight down
//! (`panda::down_orientation`). Samples are taken every `dt` = 10 ms after each simulator step,
//! rounded to 0.1 mm / 1 mrad. A gripper event at sample `k` was commanded at the step that
//! produced sample `k`. `key_points` name the samples that matter to a motion skill (grasp,
//! release, hook contact) — the via-points of LQT-CP.
//!
//! **Expert.** Each motion is a chain of minimum-jerk segments `p(τ) = p₀ + (p₁ − p₀)(10τ³ −
//! 15τ⁴ + 6τ⁵)` between way-points (approach above the object, the grasp / place pose, a lift),
//! with seeded human-like variation of segment durations (±15 %), approach heights (±2 cm) and
//! way-point offsets (±6 mm above, ±1.5 mm at contact).

use super::benchmark::{Benchmark, BLOCK_SIZE};
use super::geometry::{self, wrap};
use super::panda;
use super::scene_graph::SceneGraph;
use super::world::{yaw_of, GripperCommand, Violation, World};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};

/// World pose of an anchor frame: position and yaw.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AnchorPose {
    /// Anchor centre, world frame (m).
    pub position: [f64; 3],
    /// Yaw about world `z` (rad).
    pub yaw: f64,
}

impl AnchorPose {
    /// As an isometry (translation + yaw).
    pub fn isometry(&self) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::from(Vector3::from(self.position)),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), self.yaw),
        )
    }

    /// The anchor frame of a world pose (tilt dropped).
    pub fn from_pose(p: &Isometry3<f64>) -> AnchorPose {
        AnchorPose {
            position: p.translation.vector.into(),
            yaw: yaw_of(&p.rotation),
        }
    }
}

/// A gripper command at a sample index.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GripperEvent {
    /// Sample index (0-based, within the action).
    pub step: usize,
    /// The command from that step on.
    pub command: GripperCommand,
}

/// A named sample of an action's trajectory (a via-point for the motion skill).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct KeyPoint {
    /// Sample index (0-based, within the action).
    pub step: usize,
    /// What happens there: `grasp`, `release`, `contact` (hook behind the block), `pulled`.
    pub label: String,
}

/// One demonstrated action with its motion.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DemoAction {
    /// The grounded PDDL action, e.g. `(pick panda c)`.
    pub action: String,
    /// Action name (`pick`, `place`, `stack`, `unstack`, `place-on-shelf`, `pull`).
    pub name: String,
    /// Arguments in PDDL order.
    pub args: Vec<String>,
    /// The arm executing it.
    pub arm: String,
    /// The object whose frame the samples are expressed in (see the module docs).
    pub anchor: String,
    /// The anchor frame in the world during the demonstration.
    pub anchor_pose: AnchorPose,
    /// `[x, y, z, yaw]` of the TCP in the anchor frame, one per 10 ms step (see the module docs).
    pub samples: Vec<[f64; 4]>,
    /// Gripper commands and the samples they start at.
    pub gripper: Vec<GripperEvent>,
    /// Named samples (via-points).
    pub key_points: Vec<KeyPoint>,
}

/// A demonstration of a benchmark's template task.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Demonstration {
    /// Benchmark directory name (`b1-tower`, …).
    pub benchmark: String,
    /// Seed of the expert's variation.
    pub seed: u64,
    /// Sample period (s).
    pub dt: f64,
    /// The frame convention in words.
    pub frame_convention: String,
    /// The actions in order (the demo's states L0..LN are derived by applying them).
    pub actions: Vec<DemoAction>,
}

impl Demonstration {
    /// The grounded action strings in order.
    pub fn plan(&self) -> Vec<&str> {
        self.actions.iter().map(|a| a.action.as_str()).collect()
    }
}

/// Why recording or replaying a demonstration failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DemoError {
    /// The world broke an invariant.
    #[error("action {action} step {step}: invariant broken: {violations:?}")]
    Invariant {
        /// The action.
        action: String,
        /// Sample index.
        step: usize,
        /// What broke.
        violations: Vec<Violation>,
    },
    /// The motion did not have the intended effect or refers to unknown things.
    #[error("action {action}: {message}")]
    Failed {
        /// The action.
        action: String,
        /// What went wrong.
        message: String,
    },
    /// Malformed demo JSON.
    #[error("demo JSON: {0}")]
    Json(String),
}

const FRAME_CONVENTION: &str =
    "samples are [x, y, z, yaw] of the gripper tool centre point in the \
anchor frame (anchor centre + its yaw about world z; pick/unstack/pull: the object at the action's \
start; place/place-on-shelf/stack: the carried object's resting pose at the action's end), every \
10 ms; gripper pointing straight down; yaw relative to the anchor's yaw";

/// Tunables of the scripted expert.
#[derive(Clone, Debug, PartialEq)]
pub struct ExpertParams {
    /// Mean Cartesian speed of transfer segments (m/s).
    pub speed: f64,
    /// Height of approach way-points above the grasp / place pose (m).
    pub approach_height: f64,
    /// Time the gripper is held still while closing or opening (s).
    pub hold_time: f64,
    /// Duration of the final approach and of the lift (s).
    pub contact_time: f64,
    /// Scale of the random variation (0: none, 1: the amounts in the module docs).
    pub variation: f64,
}

impl Default for ExpertParams {
    fn default() -> Self {
        ExpertParams {
            speed: 0.35,
            approach_height: 0.12,
            hold_time: 0.3,
            contact_time: 0.6,
            variation: 1.0,
        }
    }
}

/// One way-point segment of an expert motion.
struct Seg {
    to: Isometry3<f64>,
    duration: f64,
    gripper: Option<GripperCommand>,
    key: Option<&'static str>,
}

/// What the expert does for one action.
enum Step {
    Pick {
        arm: usize,
        x: String,
    },
    Place {
        arm: usize,
        x: String,
        /// Where the carried body should rest.
        target: Isometry3<f64>,
        /// Go back to the home pose afterwards (B3 hand-over, so the arms keep apart).
        retreat: bool,
    },
    Pull {
        arm: usize,
        hook: String,
        x: String,
    },
}

fn min_jerk(t: f64) -> f64 {
    t * t * t * (10.0 + t * (-15.0 + 6.0 * t))
}

fn round_to(v: f64, q: f64) -> f64 {
    (v / q).round() * q
}

struct Expert {
    rng: Pcg64Mcg,
    p: ExpertParams,
}

impl Expert {
    fn jitter(&mut self, amount: f64) -> f64 {
        if self.p.variation == 0.0 {
            return 0.0;
        }
        self.rng.random_range(-1.0..1.0) * amount * self.p.variation
    }

    fn scale(&mut self) -> f64 {
        1.0 + self.jitter(0.15)
    }

    fn offset(&mut self, amount: f64) -> Vector3<f64> {
        Vector3::new(self.jitter(amount), self.jitter(amount), 0.0)
    }

    fn transfer_time(&mut self, from: &Isometry3<f64>, to: &Isometry3<f64>) -> f64 {
        let d = (to.translation.vector - from.translation.vector).norm();
        let ang = (to.rotation * from.rotation.inverse()).angle();
        (d / self.p.speed).max(ang / 1.2).max(0.6) * self.scale()
    }

    fn lifted(&mut self, p: &Isometry3<f64>, h: f64) -> Isometry3<f64> {
        let mut q = *p;
        q.translation.vector += Vector3::new(0.0, 0.0, h) + self.offset(0.006);
        q
    }
}

fn fail(action: &str, message: impl Into<String>) -> DemoError {
    DemoError::Failed {
        action: action.to_string(),
        message: message.into(),
    }
}

/// Executes segments on `world` for `arm`, recording samples relative to `anchor`.
fn execute(
    world: &mut World,
    arm: usize,
    segs: &[Seg],
    anchor: &Isometry3<f64>,
    action: &str,
    out: &mut DemoAction,
) -> Result<(), DemoError> {
    let dt = world.dt();
    let mut from = world
        .tcp_pose(arm)
        .ok_or_else(|| fail(action, "no such arm"))?;
    let (_, mut grip) = world
        .arm_command(arm)
        .ok_or_else(|| fail(action, "no such arm"))?;
    let anchor_inv = anchor.inverse();
    let anchor_yaw = yaw_of(&anchor.rotation);
    for seg in segs {
        let n = ((seg.duration / dt).round() as usize).max(1);
        if let Some(g) = seg.gripper {
            grip = g;
            out.gripper.push(GripperEvent {
                step: out.samples.len(),
                command: g,
            });
        }
        if let Some(k) = seg.key {
            out.key_points.push(KeyPoint {
                step: out.samples.len(),
                label: k.to_string(),
            });
        }
        for k in 1..=n {
            let s = min_jerk(k as f64 / n as f64);
            let p = from.translation.vector.lerp(&seg.to.translation.vector, s);
            let r = from.rotation.slerp(&seg.to.rotation, s);
            let cmd = Isometry3::from_parts(Translation3::from(p), r);
            world
                .command_arm(arm, cmd, grip)
                .map_err(|e| fail(action, e.to_string()))?;
            let events = world.step();
            for e in &events {
                if matches!(
                    e,
                    super::WorldEvent::GraspedNothing { .. } | super::WorldEvent::Lost { .. }
                ) {
                    return Err(fail(action, e.to_string()));
                }
            }
            if let Err(v) = world.check_invariants() {
                return Err(DemoError::Invariant {
                    action: action.to_string(),
                    step: out.samples.len(),
                    violations: v,
                });
            }
            let tcp = world
                .tcp_pose(arm)
                .ok_or_else(|| fail(action, "no such arm"))?;
            let lp = anchor_inv * nalgebra::Point3::from(tcp.translation.vector);
            let yaw = wrap(
                yaw_of(
                    &(tcp.rotation
                        * UnitQuaternion::from_axis_angle(
                            &Vector3::x_axis(),
                            std::f64::consts::PI,
                        )),
                ) - anchor_yaw,
            );
            out.samples.push([
                round_to(lp.x, 1e-4),
                round_to(lp.y, 1e-4),
                round_to(lp.z, 1e-4),
                round_to(yaw, 1e-3),
            ]);
        }
        from = seg.to;
    }
    Ok(())
}

/// Performs one expert step and records it.
fn perform(
    world: &mut World,
    expert: &mut Expert,
    step: &Step,
    action: &str,
) -> Result<DemoAction, DemoError> {
    let words: Vec<String> = action
        .trim_matches(|c| c == '(' || c == ')')
        .split_whitespace()
        .map(String::from)
        .collect();
    let (arm, anchor_name) = match step {
        Step::Pick { arm, x } | Step::Place { arm, x, .. } | Step::Pull { arm, x, .. } => {
            (*arm, x.clone())
        }
    };
    let mut rec = DemoAction {
        action: action.to_string(),
        name: words.first().cloned().unwrap_or_default(),
        args: words.iter().skip(1).cloned().collect(),
        arm: world
            .arm_names()
            .get(arm)
            .map(|s| s.to_string())
            .unwrap_or_default(),
        anchor: anchor_name.clone(),
        anchor_pose: AnchorPose {
            position: [0.0; 3],
            yaw: 0.0,
        },
        samples: Vec::new(),
        gripper: Vec::new(),
        key_points: Vec::new(),
    };
    let h = expert.p.approach_height;
    let ct = expert.p.contact_time;
    let hold = expert.p.hold_time;
    let start = world
        .tcp_pose(arm)
        .ok_or_else(|| fail(action, "no such arm"))?;
    let (segs, anchor) = match step {
        Step::Pick { x, .. } => {
            let body = world
                .body_pose(x)
                .ok_or_else(|| fail(action, format!("no body {x}")))?;
            let mut g = geometry::grasp_pose(world, arm, x)
                .ok_or_else(|| fail(action, format!("{x} cannot be grasped")))?;
            g.translation.vector += expert.offset(0.0015);
            let hh = h + expert.jitter(0.02);
            let above = expert.lifted(&g, hh);
            let lift = expert.lifted(&g, hh);
            let t0 = expert.transfer_time(&start, &above);
            let segs = vec![
                Seg {
                    to: above,
                    duration: t0,
                    gripper: Some(GripperCommand::Open),
                    key: None,
                },
                Seg {
                    to: g,
                    duration: ct * expert.scale(),
                    gripper: None,
                    key: None,
                },
                Seg {
                    to: g,
                    duration: hold,
                    gripper: Some(GripperCommand::Close),
                    key: Some("grasp"),
                },
                Seg {
                    to: lift,
                    duration: ct * expert.scale(),
                    gripper: None,
                    key: None,
                },
            ];
            (segs, AnchorPose::from_pose(&body).isometry())
        }
        Step::Place {
            x, target, retreat, ..
        } => {
            if world.arm_command(arm).is_none() || world.held_by(arm) != Some(x.as_str()) {
                return Err(fail(action, format!("the arm does not hold {x}")));
            }
            let mut t = *target;
            t.translation.vector.z += 0.002;
            let mut tcp = geometry::tcp_for_body_pose(world, arm, &t);
            tcp.translation.vector += expert.offset(0.0015);
            let hh = h + expert.jitter(0.02);
            let above = expert.lifted(&tcp, hh);
            let up = expert.lifted(&tcp, hh);
            let t0 = expert.transfer_time(&start, &above);
            let mut segs = vec![
                Seg {
                    to: above,
                    duration: t0,
                    gripper: None,
                    key: None,
                },
                Seg {
                    to: tcp,
                    duration: ct * expert.scale(),
                    gripper: None,
                    key: None,
                },
                Seg {
                    to: tcp,
                    duration: hold,
                    gripper: Some(GripperCommand::Open),
                    key: Some("release"),
                },
                Seg {
                    to: up,
                    duration: ct * expert.scale(),
                    gripper: None,
                    key: None,
                },
            ];
            if *retreat {
                let base = world
                    .arm_base(arm)
                    .ok_or_else(|| fail(action, "no such arm"))?;
                let home = panda::forward_kinematics(&base, &panda::READY);
                let tr = expert.transfer_time(&up, &home);
                segs.push(Seg {
                    to: home,
                    duration: tr,
                    gripper: None,
                    key: None,
                });
            }
            (segs, AnchorPose::from_pose(target).isometry())
        }
        Step::Pull { hook, x, .. } => {
            if world.held_by(arm) != Some(hook.as_str()) {
                return Err(fail(action, format!("the arm does not hold {hook}")));
            }
            let bp = world
                .body_pose(x)
                .ok_or_else(|| fail(action, format!("no body {x}")))?;
            let base = world
                .arm_base(arm)
                .ok_or_else(|| fail(action, "no such arm"))?;
            let reach = PULL_TARGET_RADIUS;
            let (contact, pulled) = pull_hook_poses(&base, &bp, reach);
            let tcp_contact = geometry::tcp_for_body_pose(world, arm, &contact);
            let tcp_pulled = geometry::tcp_for_body_pose(world, arm, &pulled);
            let hh = h + expert.jitter(0.02);
            let above = expert.lifted(&tcp_contact, hh);
            let up = expert.lifted(&tcp_pulled, hh);
            let t0 = expert.transfer_time(&start, &above);
            let tp = expert.transfer_time(&tcp_contact, &tcp_pulled) * 1.5;
            let segs = vec![
                Seg {
                    to: above,
                    duration: t0,
                    gripper: None,
                    key: None,
                },
                Seg {
                    to: tcp_contact,
                    duration: ct * expert.scale(),
                    gripper: None,
                    key: None,
                },
                Seg {
                    to: tcp_pulled,
                    duration: tp,
                    gripper: None,
                    key: Some("contact"),
                },
                Seg {
                    to: up,
                    duration: ct * expert.scale(),
                    gripper: None,
                    key: Some("pulled"),
                },
            ];
            (segs, AnchorPose::from_pose(&bp).isometry())
        }
    };
    rec.anchor_pose = AnchorPose::from_pose(&anchor);
    execute(world, arm, &segs, &anchor, action, &mut rec)?;
    Ok(rec)
}

/// Distance from the arm's base axis (m) to which the expert pulls a block with the hook: inside
/// the reach annulus, and far enough out that the hand holding the hook (31 cm behind the block)
/// stays clear of the base, where the folded arm tilts the hook into the table (0.60: stopped
/// strokes).
pub const PULL_TARGET_RADIUS: f64 = 0.64;

/// Height above a stroke's contact and pulled poses from which the hook comes down and to which
/// it rises again (m). On its way there the blade passes over the block it is to pull; at far
/// reach the tracker's orientation lag tilts the 40 cm hook by 2–3 cm at the blade, so it crosses
/// 6 cm above the block's top (8 cm left 3 cm: the soak's "stopped by a" pulls).
pub const PULL_LIFT: f64 = 0.11;

/// Turns of the hook's pull strokes (rad, from the line through the arm's base, see
/// [`pull_hook_poses_turned`]) in the order a planner tries them: radial first, then ±15°,
/// ±30°, ±45°, ±60° (a block right behind the shelf comes into reach only along it).
pub const PULL_TURNS: [f64; 9] = [0.0, 0.26, -0.26, 0.52, -0.52, 0.79, -0.79, 1.05, -1.05];

/// Hook poses for pulling the block at `block` towards the arm based at `base` until its centre
/// is `reach` metres from the base axis: `(contact, pulled)`. At `contact` the hook lies 12 mm above
/// the table with its blade 1 cm behind the block's far face and the block in the middle of the
/// blade; `pulled` is `contact` moved straight towards the base.
pub fn pull_hook_poses(
    base: &Isometry3<f64>,
    block: &Isometry3<f64>,
    reach: f64,
) -> (Isometry3<f64>, Isometry3<f64>) {
    // At turn 0 the stroke's line passes through the base: it always reaches the annulus.
    pull_hook_poses_turned(base, block, reach, 0.0).unwrap_or((*block, *block))
}

/// Height of the hook's frame during a pull stroke (m): 12 mm of clearance, as the arm's
/// tracking tilts the long hook by a few mm at the blade (more with the hand close to the base),
/// and a blade that scrapes the table is stopped at contact (3 and 6 mm: stopped strokes). The
/// blade (z 12–32 mm) still meets a 6 cm block below its middle.
const PULL_HOOK_Z: f64 = 0.022;

/// A pull stroke turned by `turn` (rad, about `z`) from the line through the base: the hook is
/// yawed along v = R_z(turn)·u (u: from the base to the block) and drags the block along −v
/// until its centre is `reach` from the base (+1 cm), the contact pose as in
/// [`pull_hook_poses`]; a block already within `reach` gets a 1 cm stroke. `None` when no
/// point of that line is within `reach` of the base.
pub fn pull_hook_poses_turned(
    base: &Isometry3<f64>,
    block: &Isometry3<f64>,
    reach: f64,
    turn: f64,
) -> Option<(Isometry3<f64>, Isometry3<f64>)> {
    let b = block.translation.vector;
    let o = base.translation.vector;
    let w = Vector3::new(b.x - o.x, b.y - o.y, 0.0);
    let yaw = libm::atan2(w.y, w.x) + turn;
    let rot = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw);
    let v = rot * Vector3::x(); // away from the base, turned
                                // Block centre in the hook frame: 1 cm gap to the blade's inner face (x = 0.18), mid-blade.
    let local = Vector3::new(0.18 - 0.01 - 0.5 * BLOCK_SIZE, 0.08, 0.0);
    let mut origin = b - rot * local;
    origin.z = PULL_HOOK_Z;
    // |w − v·s| = reach along the stroke: s = w·v − √(reach² − |w|² + (w·v)²).
    let along = w.dot(&v);
    let disc = reach * reach - w.norm_squared() + along * along;
    if disc < 0.0 {
        return None;
    }
    let dist = (along - libm::sqrt(disc)).max(0.0) + 0.01;
    let contact = Isometry3::from_parts(Translation3::from(origin), rot);
    let pulled = Isometry3::from_parts(Translation3::from(origin - v * dist), rot);
    Some((contact, pulled))
}

/// The expert's action list for a benchmark's template task.
fn template_steps(b: Benchmark, world: &World) -> Result<Vec<(String, Step)>, DemoError> {
    let idx = |n: &str| world.arm_index(n).ok_or_else(|| fail(n, "no such arm"));
    let yaw_of_body = |n: &str| {
        world
            .body_pose(n)
            .map(|p| yaw_of(&p.rotation))
            .unwrap_or(0.0)
    };
    let mut out = Vec::new();
    match b {
        Benchmark::B1 => {
            let p = idx("panda")?;
            for (x, y) in [("c", "d"), ("b", "c"), ("a", "b")] {
                out.push((
                    format!("(pick panda {x})"),
                    Step::Pick {
                        arm: p,
                        x: x.into(),
                    },
                ));
                // Target: centred on y, y's yaw (computed when the action starts).
                out.push((
                    format!("(stack panda {x} {y})"),
                    Step::Place {
                        arm: p,
                        x: x.into(),
                        target: Isometry3::identity(),
                        retreat: false,
                    },
                ));
            }
        }
        Benchmark::B2 => {
            let p = idx("panda")?;
            let hook = world
                .body_pose("hook")
                .ok_or_else(|| fail("hook", "no hook"))?;
            out.push((
                "(pick panda hook)".into(),
                Step::Pick {
                    arm: p,
                    x: "hook".into(),
                },
            ));
            out.push((
                "(pull panda hook b)".into(),
                Step::Pull {
                    arm: p,
                    hook: "hook".into(),
                    x: "b".into(),
                },
            ));
            out.push((
                "(place panda hook)".into(),
                Step::Place {
                    arm: p,
                    x: "hook".into(),
                    target: hook,
                    retreat: false,
                },
            ));
            for (x, sx) in [("a", 0.28), ("b", 0.42)] {
                out.push((
                    format!("(pick panda {x})"),
                    Step::Pick {
                        arm: p,
                        x: x.into(),
                    },
                ));
                let t = Isometry3::from_parts(
                    Translation3::new(sx, -0.50, 0.10 + 0.5 * BLOCK_SIZE),
                    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw_of_body(x)),
                );
                out.push((
                    format!("(place-on-shelf panda {x})"),
                    Step::Place {
                        arm: p,
                        x: x.into(),
                        target: t,
                        retreat: false,
                    },
                ));
            }
        }
        Benchmark::B3 => {
            let (l, r) = (idx("left")?, idx("right")?);
            let h = 0.5 * BLOCK_SIZE;
            let at = |x: f64, y: f64| {
                Isometry3::from_parts(Translation3::new(x, y, h), UnitQuaternion::identity())
            };
            out.push((
                "(pick left b left-table)".into(),
                Step::Pick {
                    arm: l,
                    x: "b".into(),
                },
            ));
            out.push((
                "(place left b handover)".into(),
                Step::Place {
                    arm: l,
                    x: "b".into(),
                    target: at(0.38, 0.0),
                    retreat: true,
                },
            ));
            out.push((
                "(pick right b handover)".into(),
                Step::Pick {
                    arm: r,
                    x: "b".into(),
                },
            ));
            out.push((
                "(place right b right-table)".into(),
                Step::Place {
                    arm: r,
                    x: "b".into(),
                    target: at(0.42, -0.62),
                    retreat: false,
                },
            ));
            out.push((
                "(pick left a left-table)".into(),
                Step::Pick {
                    arm: l,
                    x: "a".into(),
                },
            ));
            out.push((
                "(place left a handover)".into(),
                Step::Place {
                    arm: l,
                    x: "a".into(),
                    target: at(0.38, 0.0),
                    retreat: true,
                },
            ));
            out.push((
                "(pick right a handover)".into(),
                Step::Pick {
                    arm: r,
                    x: "a".into(),
                },
            ));
            out.push((
                "(stack right a b right-table)".into(),
                Step::Place {
                    arm: r,
                    x: "a".into(),
                    target: Isometry3::identity(),
                    retreat: true,
                },
            ));
        }
    }
    Ok(out)
}

/// Records the template task's demonstration of `b` with the scripted expert (seeded variation),
/// checking the world's invariants after every step and the goal at the end.
pub fn record(b: Benchmark, seed: u64, params: &ExpertParams) -> Result<Demonstration, DemoError> {
    let mut world = b.scene();
    let mut expert = Expert {
        rng: Pcg64Mcg::seed_from_u64(seed),
        p: params.clone(),
    };
    let steps = template_steps(b, &world)?;
    let mut actions = Vec::new();
    for (action, mut step) in steps {
        // Stacking targets depend on where the lower block is now.
        if let Step::Place { x, target, .. } = &mut step {
            if action.starts_with("(stack") {
                let words: Vec<&str> = action
                    .trim_matches(|c| c == '(' || c == ')')
                    .split_whitespace()
                    .collect();
                let y = words[3];
                *target = geometry::rest_pose_on(&world, x, y, 0.0)
                    .ok_or_else(|| fail(&action, format!("nothing to stack on ({y})")))?;
            }
        }
        let rec = perform(&mut world, &mut expert, &step, &action)?;
        actions.push(rec);
    }
    let sg = SceneGraph::from_world(&world);
    for g in b.goal() {
        if !sg.facts.contains(&g) {
            return Err(fail(
                "goal",
                format!("{g} does not hold after the demonstration"),
            ));
        }
    }
    Ok(Demonstration {
        benchmark: b.dir_name().to_string(),
        seed,
        dt: world.dt(),
        frame_convention: FRAME_CONVENTION.to_string(),
        actions,
    })
}

/// Replays a demonstration in `world` (which should be the template scene): each action's
/// samples are mapped through its anchor frame — the anchor object's current pose for
/// pick/unstack/pull, the recorded `anchor_pose` for placing actions — and commanded step by
/// step with the recorded gripper events. `after_step` is called after every simulator step
/// (tests check invariants there).
pub fn replay(
    world: &mut World,
    demo: &Demonstration,
    mut after_step: impl FnMut(&World, &DemoAction, usize) -> Result<(), DemoError>,
) -> Result<(), DemoError> {
    for a in &demo.actions {
        let arm = world
            .arm_index(&a.arm)
            .ok_or_else(|| fail(&a.action, format!("unknown arm {}", a.arm)))?;
        let anchor = match a.name.as_str() {
            "pick" | "unstack" | "pull" => {
                let p = world
                    .body_pose(&a.anchor)
                    .ok_or_else(|| fail(&a.action, format!("unknown body {}", a.anchor)))?;
                AnchorPose::from_pose(&p).isometry()
            }
            _ => a.anchor_pose.isometry(),
        };
        let ayaw = yaw_of(&anchor.rotation);
        let (_, mut grip) = world
            .arm_command(arm)
            .ok_or_else(|| fail(&a.action, "no arm"))?;
        let mut ev = a.gripper.iter().peekable();
        for (k, s) in a.samples.iter().enumerate() {
            while let Some(e) = ev.peek() {
                if e.step <= k {
                    grip = e.command;
                    ev.next();
                } else {
                    break;
                }
            }
            let p = anchor * nalgebra::Point3::new(s[0], s[1], s[2]);
            let cmd = Isometry3::from_parts(
                Translation3::from(p.coords),
                panda::down_orientation(ayaw + s[3]),
            );
            world
                .command_arm(arm, cmd, grip)
                .map_err(|e| fail(&a.action, e.to_string()))?;
            world.step();
            after_step(world, a, k)?;
        }
    }
    Ok(())
}

/// Parses a demo JSON text.
pub fn from_json(text: &str) -> Result<Demonstration, DemoError> {
    serde_json::from_str(text)
        .map_err(|e| DemoError::Json(format!("line {} column {}: {e}", e.line(), e.column())))
}

/// The committed demonstration of a benchmark (`domains/<dir>/demo.json`).
pub fn committed(b: Benchmark) -> Result<Demonstration, DemoError> {
    from_json(match b {
        Benchmark::B1 => include_str!("../../../domains/b1-tower/demo.json"),
        Benchmark::B2 => include_str!("../../../domains/b2-workspace-reach/demo.json"),
        Benchmark::B3 => include_str!("../../../domains/b3-dual-arm/demo.json"),
    })
}

/// The demonstration's states `L0..LN` as the scene graph sees them: the facts of the template
/// world and after each action of the committed demo, replayed in the simulator. (They equal the
/// PDDL states derived by applying the actions, plus the static facts the scene graph reports —
/// the integration tests check this.)
pub fn demo_states(b: Benchmark) -> Result<Vec<std::collections::BTreeSet<String>>, DemoError> {
    let d = committed(b)?;
    let mut w = b.scene();
    let facts = |w: &World| -> std::collections::BTreeSet<String> {
        SceneGraph::from_world(w).to_strings().into_iter().collect()
    };
    let mut out = vec![facts(&w)];
    replay(&mut w, &d, |w, a, k| {
        if k + 1 == a.samples.len() {
            out.push(facts(w));
        }
        Ok(())
    })?;
    Ok(out)
}
