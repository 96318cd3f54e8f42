//! The scripted expert: minimum-jerk way-point motions with seeded human-like variation,
//! executed in the simulator and recorded relative to each action's anchor frame.

use super::data::{
    fail, AnchorPose, DemoAction, DemoError, DemoViaPoint, Demonstration, FRAME_CONVENTION,
};
use super::flight::{execute, reachable_height};
use super::pull::{pull_hook_poses, PULL_TARGET_RADIUS};
use super::segment::{Seg, Step, MIN_TRANSFER_TIME};
use super::template::{template_steps, Script, TemplateAction};
use crate::sim::geometry;
use crate::sim::world::{GripperCommand, World};
use crate::sim::Benchmark;
use crate::sim::{Fact, SceneGraph};
use nalgebra::{Isometry3, Vector3};
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

/// Largest relative change of a segment's duration (at `variation` 1).
const DURATION_JITTER: f64 = 0.15;

/// Largest change of an approach height (m, at `variation` 1).
const HEIGHT_JITTER: f64 = 0.02;

/// Largest horizontal offset of a way-point above the object (m, at `variation` 1).
const WAYPOINT_JITTER: f64 = 0.006;

/// Largest horizontal offset of the grasp or place pose (m, at `variation` 1).
const CONTACT_JITTER: f64 = 0.0015;

/// Turning speed of transfer segments (rad/s).
const TURN_SPEED: f64 = 1.2;

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
        via_points: Vec::new(),
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
    // The pulled block's top in the anchor frame, before the stroke moves it.
    let top = world
        .body_aabb(&anchor_name)
        .map(|(_, hi)| hi.z - motion.anchor.translation.z);
    execute(world, arm, &motion.segs, &motion.anchor, action, &mut rec)?;
    if let (Step::Pull { hook, .. }, Some(top)) = (step, top) {
        rec.via_points = pull_via_points(world, arm, hook, top, &rec);
    }
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
            let home = world
                .ready_tcp(arm)
                .ok_or_else(|| fail(action, "no such arm"))?;
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
                key: Some("descent"),
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

/// The via-points of a recorded pull `rec` (module docs of [`super::DemoViaPoint`]): the first
/// sample of the descent at which the held `hook`'s lowest point is down to the block's top
/// (`top`, anchor frame), and the contact. Empty without `descent` and `contact` key points.
fn pull_via_points(
    world: &World,
    arm: usize,
    hook: &str,
    top: f64,
    rec: &DemoAction,
) -> Vec<DemoViaPoint> {
    let key = |label: &str| {
        rec.key_points
            .iter()
            .find(|k| k.label == label)
            .map(|k| k.step)
    };
    let (Some(descent), Some(contact)) = (key("descent"), key("contact")) else {
        return vec![];
    };
    // The hook is held rigidly: its lowest point stays this far below the TCP (m).
    let (Some(tcp), Some((lo, _))) = (world.tcp_pose(arm), world.body_aabb(hook)) else {
        return vec![];
    };
    let below = tcp.translation.z - lo.z;
    let at = |step: usize, label: &str| {
        rec.samples.get(step).map(|s| DemoViaPoint {
            step,
            label: label.to_string(),
            position: [s[0], s[1], s[2]],
        })
    };
    let edge = (descent..=contact)
        .find(|&k| rec.samples.get(k).is_some_and(|s| s[2] - below <= top))
        .unwrap_or(contact);
    [at(edge, "top-edge"), at(contact, "bottom-edge")]
        .into_iter()
        .flatten()
        .collect()
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
