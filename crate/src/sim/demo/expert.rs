//! The scripted expert: minimum-jerk way-point motions with seeded human-like variation,
//! executed in the simulator and recorded relative to each action's anchor frame.

use super::template::{template_steps, Script, TemplateAction};
use super::{anchor_sample, min_jerk, pull_hook_poses, FRAME_CONVENTION, PULL_TARGET_RADIUS};
use super::{fail, AnchorPose, DemoAction, DemoError, Demonstration, GripperEvent, KeyPoint};
use crate::sim::benchmark::Benchmark;
use crate::sim::geometry::{self, yaw_of};
use crate::sim::panda;
use crate::sim::scene_graph::{Fact, SceneGraph};
use crate::sim::world::{GripperCommand, World, WorldEvent};
use nalgebra::{Isometry3, Translation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

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
pub(super) enum Step {
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

/// Largest relative change of a segment's duration (at `variation` 1).
const DURATION_JITTER: f64 = 0.15;

/// Largest change of an approach height (m, at `variation` 1).
const HEIGHT_JITTER: f64 = 0.02;

/// Largest horizontal offset of a way-point above the object (m, at `variation` 1).
const WAYPOINT_JITTER: f64 = 0.006;

/// Largest horizontal offset of the grasp or place pose (m, at `variation` 1).
const CONTACT_JITTER: f64 = 0.0015;

/// Lowest approach height over a grasp or a placement (m).
const MIN_APPROACH_HEIGHT: f64 = 0.03;

/// Points along a straight segment checked for bodies in the way.
const TRANSIT_PROBES: usize = 24;

/// Gap kept between the hand's box and other bodies along a segment (m).
const TRANSIT_CLEARANCE: f64 = 0.01;

/// Height of a transit over the highest body in the way, above its top (m).
const TRANSIT_RISE: f64 = 0.05;

/// Speed of a transit's way-points (m/s).
const TRANSIT_SPEED: f64 = 0.25;

/// The empty hand as a box around the TCP: half width, reach below and above it (m).
const HAND_HALF: f64 = 0.045;
const HAND_BELOW: f64 = 0.01;
const HAND_ABOVE: f64 = 0.06;

/// A segment's end farther than this from the TCP is reached in joint space (m).
const RECOVER_ERROR: f64 = 0.005;

/// Most steps of a joint-space recovery (4 s).
const RECOVER_STEPS: usize = 400;

/// Steps on the pose after a joint-space recovery (0.2 s).
const RECOVER_HOLD_STEPS: usize = 20;

/// Turning speed of transfer segments (rad/s).
const TURN_SPEED: f64 = 1.2;

/// Shortest transfer segment (s).
const MIN_TRANSFER_TIME: f64 = 0.6;

/// A pull stroke takes this many times as long as a transfer of its length (the hook drags
/// the block).
const STROKE_SLOWDOWN: f64 = 1.5;

/// The expert opens the gripper with the body this far above its resting pose (m): it drops
/// onto its support instead of being pressed into it.
const RELEASE_HEIGHT: f64 = 0.002;

/// The scripted expert: its parameters and the random source of its variation.
struct Expert {
    rng: Pcg64Mcg,
    p: ExpertParams,
}

impl Expert {
    /// A uniform random amount in `±amount · variation` (0 without variation, no draw).
    fn jitter(&mut self, amount: f64) -> f64 {
        if self.p.variation == 0.0 {
            return 0.0;
        }
        self.rng.random_range(-1.0..1.0) * amount * self.p.variation
    }

    /// A random factor for a segment's duration.
    fn scale(&mut self) -> f64 {
        1.0 + self.jitter(DURATION_JITTER)
    }

    /// A random horizontal offset, each coordinate within `±amount · variation`.
    fn offset(&mut self, amount: f64) -> Vector3<f64> {
        Vector3::new(self.jitter(amount), self.jitter(amount), 0.0)
    }

    /// The duration of a transfer from `from` to `to` at the expert's speeds, varied.
    fn transfer_time(&mut self, from: &Isometry3<f64>, to: &Isometry3<f64>) -> f64 {
        let d = (to.translation.vector - from.translation.vector).norm();
        let ang = (to.rotation * from.rotation.inverse()).angle();
        (d / self.p.speed)
            .max(ang / TURN_SPEED)
            .max(MIN_TRANSFER_TIME)
            * self.scale()
    }

    /// `p` raised by `h` and offset at random horizontally (a way-point above it).
    fn lifted(&mut self, p: &Isometry3<f64>, h: f64) -> Isometry3<f64> {
        let mut q = *p;
        q.translation.vector += Vector3::new(0.0, 0.0, h) + self.offset(WAYPOINT_JITTER);
        q
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
    for (i, seg) in segs.iter().enumerate() {
        // The transfer (the first segment) goes over whatever stands in its straight way (a tall
        // tower): up, across, then on.
        let vias = if i == 0 {
            transit_vias(world, arm, &from, &seg.to)
        } else {
            vec![]
        };
        for via in vias {
            let dur = libm::fmax(
                (via.translation.vector - from.translation.vector).norm() / TRANSIT_SPEED,
                MIN_TRANSFER_TIME,
            );
            let n = ((dur / dt).round() as usize).max(1);
            for k in 1..=n {
                let s = min_jerk(k as f64 / n as f64);
                let p = from.translation.vector.lerp(&via.translation.vector, s);
                let r = from.rotation.slerp(&via.rotation, s);
                let cmd = Isometry3::from_parts(Translation3::from(p), r);
                step_checked(world, arm, cmd, grip, action, out.samples.len())?;
                let tcp = world
                    .tcp_pose(arm)
                    .ok_or_else(|| fail(action, "no such arm"))?;
                out.samples
                    .push(anchor_sample(&tcp, &anchor_inv, anchor_yaw));
            }
            from = via;
        }
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
            step_checked(world, arm, cmd, grip, action, out.samples.len())?;
            let tcp = world
                .tcp_pose(arm)
                .ok_or_else(|| fail(action, "no such arm"))?;
            out.samples
                .push(anchor_sample(&tcp, &anchor_inv, anchor_yaw));
        }
        // Before the gripper acts, the hand must be where the segment ends.
        if segs.get(i + 1).is_some_and(|next| next.gripper.is_some()) {
            recover(
                world,
                arm,
                &seg.to,
                grip,
                action,
                out,
                &anchor_inv,
                anchor_yaw,
            )?;
        }
        from = seg.to;
    }
    Ok(())
}

/// The approach height over `p`: `h`, or less where `p` raised by `h` is beyond the arm's reach
/// (the top of a tall tower), in centimetre steps down to [`MIN_APPROACH_HEIGHT`].
fn reachable_height(world: &World, arm: usize, p: &Isometry3<f64>, h: f64) -> f64 {
    let mut hh = h;
    while hh > MIN_APPROACH_HEIGHT {
        let mut q = *p;
        q.translation.vector.z += hh;
        if world.reachable(arm, &q).is_ok() {
            return hh;
        }
        hh -= 0.01;
    }
    MIN_APPROACH_HEIGHT
}

/// Way-points that take arm `arm`'s hand (and what it carries) over the bodies the straight line
/// from `from` to `to` would run into: straight up to a clear height, across, and (the segment
/// itself) down. Empty when the straight way is clear, as in every template task.
fn transit_vias(
    world: &World,
    arm: usize,
    from: &Isometry3<f64>,
    to: &Isometry3<f64>,
) -> Vec<Isometry3<f64>> {
    let held = world.held_by(arm).map(str::to_string);
    let Some(tcp) = world.tcp_pose(arm) else {
        return vec![];
    };
    // What moves with the hand, as a box relative to the TCP: the carried body, or the fingers.
    let (lo, hi) = match held.as_deref().and_then(|h| world.body_aabb(h)) {
        Some((lo, hi)) => (lo - tcp.translation.vector, hi - tcp.translation.vector),
        None => (
            Vector3::new(-HAND_HALF, -HAND_HALF, -HAND_BELOW),
            Vector3::new(HAND_HALF, HAND_HALF, HAND_ABOVE),
        ),
    };
    let others: Vec<(Vector3<f64>, Vector3<f64>)> = world
        .bodies
        .iter()
        .filter(|b| b.is_movable() && !b.lost && Some(&b.name) != held.as_ref())
        .filter_map(|b| world.body_aabb(&b.name))
        .collect();
    let (a, b) = (from.translation.vector, to.translation.vector);
    let mut top = f64::NEG_INFINITY;
    for k in 0..=TRANSIT_PROBES {
        let p = a.lerp(&b, k as f64 / TRANSIT_PROBES as f64);
        let (plo, phi) = (p + lo, p + hi);
        for (olo, ohi) in &others {
            let apart = (0..3).any(|i| {
                phi[i] < olo[i] - TRANSIT_CLEARANCE || plo[i] > ohi[i] + TRANSIT_CLEARANCE
            });
            if !apart {
                top = libm::fmax(top, ohi.z);
            }
        }
    }
    if !top.is_finite() {
        return vec![];
    }
    let z = top + TRANSIT_RISE - lo.z;
    let mut vias = vec![];
    if a.z < z {
        vias.push(Isometry3::from_parts(
            Translation3::new(a.x, a.y, z),
            from.rotation,
        ));
    }
    if b.z < z {
        vias.push(Isometry3::from_parts(
            Translation3::new(b.x, b.y, z),
            to.rotation,
        ));
    }
    vias
}

/// The end of a segment before a grasp or a release that the arm did not reach (Cartesian
/// tracking stuck in a poor posture, as by the top of a tall tower) is reached in joint space: the IK solution with
/// the most room to the joint limits, then a short hold on the pose. Nothing happens when the
/// TCP is within [`RECOVER_ERROR`] of `to`.
#[allow(clippy::too_many_arguments)]
fn recover(
    world: &mut World,
    arm: usize,
    to: &Isometry3<f64>,
    grip: GripperCommand,
    action: &str,
    out: &mut DemoAction,
    anchor_inv: &Isometry3<f64>,
    anchor_yaw: f64,
) -> Result<(), DemoError> {
    let off = |w: &World| {
        w.tcp_pose(arm).map_or(f64::INFINITY, |t| {
            (t.translation.vector - to.translation.vector).norm()
        })
    };
    if off(world) <= RECOVER_ERROR {
        return Ok(());
    }
    let joints = world
        .reachable_with_room(arm, to)
        .map_err(|e| {
            fail(
                action,
                format!(
                    "cannot reach a way-point ({:.1} mm away)",
                    e.position_error * 1e3
                ),
            )
        })?
        .joints;
    let record = |world: &World, out: &mut DemoAction| -> Result<(), DemoError> {
        let tcp = world
            .tcp_pose(arm)
            .ok_or_else(|| fail(action, "no such arm"))?;
        out.samples
            .push(anchor_sample(&tcp, anchor_inv, anchor_yaw));
        Ok(())
    };
    world
        .command_joints(arm, joints, grip)
        .map_err(|e| fail(action, e.to_string()))?;
    for _ in 0..RECOVER_STEPS {
        step_joints(world, action, out.samples.len())?;
        record(world, out)?;
        if world
            .joints(arm)
            .is_some_and(|q| q.iter().zip(&joints).all(|(a, b)| libm::fabs(a - b) < 1e-6))
        {
            break;
        }
    }
    for _ in 0..RECOVER_HOLD_STEPS {
        step_checked(world, arm, *to, grip, action, out.samples.len())?;
        record(world, out)?;
    }
    if off(world) > RECOVER_ERROR {
        return Err(fail(
            action,
            format!(
                "the arm stops {:.1} mm short of a way-point",
                off(world) * 1e3
            ),
        ));
    }
    Ok(())
}

/// Steps the world once under a joint-space command, with the checks of [`step_checked`].
fn step_joints(world: &mut World, action: &str, sample: usize) -> Result<(), DemoError> {
    let events = world.step();
    for e in &events {
        if matches!(
            e,
            WorldEvent::GraspedNothing { .. } | WorldEvent::Lost { .. }
        ) {
            return Err(fail(action, e.to_string()));
        }
    }
    world.check_invariants().map_err(|v| DemoError::Invariant {
        action: action.to_string(),
        step: sample,
        violations: v,
    })
}

/// Commands arm `arm` to `cmd` and steps the world once: an error if the gripper closed on
/// nothing, a body fell, or an invariant broke (at sample `sample`).
fn step_checked(
    world: &mut World,
    arm: usize,
    cmd: Isometry3<f64>,
    grip: GripperCommand,
    action: &str,
    sample: usize,
) -> Result<(), DemoError> {
    world
        .command_arm(arm, cmd, grip)
        .map_err(|e| fail(action, e.to_string()))?;
    let events = world.step();
    for e in &events {
        if matches!(
            e,
            WorldEvent::GraspedNothing { .. } | WorldEvent::Lost { .. }
        ) {
            return Err(fail(action, e.to_string()));
        }
    }
    if let Err(v) = world.check_invariants() {
        return Err(DemoError::Invariant {
            action: action.to_string(),
            step: sample,
            violations: v,
        });
    }
    Ok(())
}

/// Where an expert motion starts: the arm, its TCP pose, and the action (for errors).
struct MotionStart<'a> {
    arm: usize,
    tcp: Isometry3<f64>,
    action: &'a str,
}

/// The expert's motion for one action: its segments and the anchor frame they are recorded in.
struct Motion {
    segs: Vec<Seg>,
    anchor: Isometry3<f64>,
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
    let start = world
        .tcp_pose(arm)
        .ok_or_else(|| fail(action, "no such arm"))?;
    let from = MotionStart {
        arm,
        tcp: start,
        action,
    };
    let motion = match step {
        Step::Pick { x, .. } => expert.pick(world, &from, x)?,
        Step::Place {
            x, target, retreat, ..
        } => expert.place(world, &from, x, target, *retreat)?,
        Step::Pull { hook, x, .. } => expert.pull(world, &from, hook, x)?,
    };
    rec.anchor_pose = AnchorPose::from_pose(&motion.anchor);
    execute(world, arm, &motion.segs, &motion.anchor, action, &mut rec)?;
    Ok(rec)
}

impl Expert {
    /// Picking `x` from `from`: above it (gripper open), down to the grasp, close,
    /// lift; anchored at the body where it lies.
    fn pick(&mut self, world: &World, from: &MotionStart, x: &str) -> Result<Motion, DemoError> {
        let (arm, start, action) = (from.arm, &from.tcp, from.action);
        let (h, ct, hold) = (
            self.p.approach_height,
            self.p.contact_time,
            self.p.hold_time,
        );
        let body = world
            .body_pose(x)
            .ok_or_else(|| fail(action, format!("no body {x}")))?;
        let mut g = geometry::grasp_pose(world, arm, x)
            .ok_or_else(|| fail(action, format!("{x} cannot be grasped")))?;
        g.translation.vector += self.offset(CONTACT_JITTER);
        let hh = reachable_height(world, arm, &g, h + self.jitter(HEIGHT_JITTER));
        let above = self.lifted(&g, hh);
        let lift = self.lifted(&g, hh);
        let t0 = self.transfer_time(start, &above);
        let segs = vec![
            Seg {
                to: above,
                duration: t0,
                gripper: Some(GripperCommand::Open),
                key: None,
            },
            Seg {
                to: g,
                duration: ct * self.scale(),
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
                duration: ct * self.scale(),
                gripper: None,
                key: None,
            },
        ];
        Ok(Motion {
            segs,
            anchor: AnchorPose::from_pose(&body).isometry(),
        })
    }

    /// Putting the held `x` down at `target` from `from`: above the place, down,
    /// open, up, and home to the ready posture if `retreat`; anchored at `target`.
    fn place(
        &mut self,
        world: &World,
        from: &MotionStart,
        x: &str,
        target: &Isometry3<f64>,
        retreat: bool,
    ) -> Result<Motion, DemoError> {
        let (arm, start, action) = (from.arm, &from.tcp, from.action);
        let (h, ct, hold) = (
            self.p.approach_height,
            self.p.contact_time,
            self.p.hold_time,
        );
        if world.arm_command(arm).is_none() || world.held_by(arm) != Some(x) {
            return Err(fail(action, format!("the arm does not hold {x}")));
        }
        let mut t = *target;
        t.translation.vector.z += RELEASE_HEIGHT;
        let mut tcp = geometry::tcp_for_body_pose(world, arm, &t);
        tcp.translation.vector += self.offset(CONTACT_JITTER);
        let hh = reachable_height(world, arm, &tcp, h + self.jitter(HEIGHT_JITTER));
        let above = self.lifted(&tcp, hh);
        let up = self.lifted(&tcp, hh);
        let t0 = self.transfer_time(start, &above);
        let mut segs = vec![
            Seg {
                to: above,
                duration: t0,
                gripper: None,
                key: None,
            },
            Seg {
                to: tcp,
                duration: ct * self.scale(),
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
                duration: ct * self.scale(),
                gripper: None,
                key: None,
            },
        ];
        if retreat {
            let base = world
                .arm_base(arm)
                .ok_or_else(|| fail(action, "no such arm"))?;
            let home = panda::forward_kinematics(&base, &panda::READY);
            let tr = self.transfer_time(&up, &home);
            segs.push(Seg {
                to: home,
                duration: tr,
                gripper: None,
                key: None,
            });
        }
        Ok(Motion {
            segs,
            anchor: AnchorPose::from_pose(target).isometry(),
        })
    }

    /// Pulling `x` with the held `hook` from `from`: above the contact pose, down
    /// behind the block, the stroke towards the base, up; anchored at the block where it lies.
    fn pull(
        &mut self,
        world: &World,
        from: &MotionStart,
        hook: &str,
        x: &str,
    ) -> Result<Motion, DemoError> {
        let (arm, start, action) = (from.arm, &from.tcp, from.action);
        let (h, ct) = (self.p.approach_height, self.p.contact_time);
        if world.held_by(arm) != Some(hook) {
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
        let hh = h + self.jitter(HEIGHT_JITTER);
        let above = self.lifted(&tcp_contact, hh);
        let up = self.lifted(&tcp_pulled, hh);
        let t0 = self.transfer_time(start, &above);
        let tp = self.transfer_time(&tcp_contact, &tcp_pulled) * STROKE_SLOWDOWN;
        let segs = vec![
            Seg {
                to: above,
                duration: t0,
                gripper: None,
                key: None,
            },
            Seg {
                to: tcp_contact,
                duration: ct * self.scale(),
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
                duration: ct * self.scale(),
                gripper: None,
                key: Some("pulled"),
            },
        ];
        Ok(Motion {
            segs,
            anchor: AnchorPose::from_pose(&bp).isometry(),
        })
    }
}

/// Records the template task's demonstration of `b` with the scripted expert (seeded variation),
/// checking the world's invariants after every step and the goal at the end.
pub fn record(b: Benchmark, seed: u64, params: &ExpertParams) -> Result<Demonstration, DemoError> {
    let script: Script =
        serde_json::from_str(b.expert_json()).map_err(|e| fail("expert.json", e.to_string()))?;
    record_script(b.scene(), &script, &b.goal(), b.dir_name(), seed, params)
}

/// Records a demonstration of `script` from `world` (which carries its domain's motions) with
/// the scripted expert (seeded variation), checking the world's invariants after every step and
/// that every fact of `goal` holds at the end. `name` is the task's directory name.
pub fn record_script(
    mut world: World,
    script: &Script,
    goal: &[Fact],
    name: &str,
    seed: u64,
    params: &ExpertParams,
) -> Result<Demonstration, DemoError> {
    let mut expert = Expert {
        rng: Pcg64Mcg::seed_from_u64(seed),
        p: params.clone(),
    };
    let steps = template_steps(script, &world)?;
    let mut actions = Vec::new();
    for TemplateAction {
        action,
        mut step,
        onto_block,
    } in steps
    {
        // Stacking targets depend on where the lower block is now.
        if let (Step::Place { x, target, .. }, Some(y)) = (&mut step, &onto_block) {
            *target = geometry::rest_pose_on(&world, x, y, 0.0)
                .ok_or_else(|| fail(&action, format!("nothing to stack on ({y})")))?;
        }
        let rec = perform(&mut world, &mut expert, &step, &action)?;
        actions.push(rec);
    }
    let sg = SceneGraph::from_world(&world);
    for g in goal {
        if !sg.facts.contains(g) {
            return Err(fail(
                "goal",
                format!("{g} does not hold after the demonstration"),
            ));
        }
    }
    Ok(Demonstration {
        benchmark: name.to_string(),
        seed,
        dt: world.dt(),
        frame_convention: FRAME_CONVENTION.to_string(),
        actions,
    })
}
