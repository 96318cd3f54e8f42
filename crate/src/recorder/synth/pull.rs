//! The quick-mode hook pull: pick the hook with an arm that can reach behind the block with it,
//! then — with the grasp the hook actually got — drag the block into reach and put the hook back.

use super::motion::{
    at_height, highest_top, motion_start, reaches, resolve_arms, PUT_DOWN_CLEARANCE,
};
use super::params::{refused, SynthParams};
use crate::recorder::{ArmRef, RawSample};
use crate::recorder::{Recorder, RecorderError};
use crate::sim::demo::{pull_hook_poses, PULL_TARGET_RADIUS};
use crate::sim::geometry;
use crate::sim::BodyKind;
use crate::sim::{GripperCommand, World};
use nalgebra::{Isometry3, Vector3};

/// Shortest horizontal pull stroke (m) that still gives the blade a direction to back off along.
const MIN_BACK_OFF_DIRECTION: f64 = 1e-9;

/// The arm that picked the hook and the hook's pose before the pick.
pub type HookGrip = (usize, Isometry3<f64>);

/// Samples of a hook pull (see [`Edit::Pull`](super::Edit::Pull)), in two phases: with
/// `holding = None`, picking the hook and lifting it (returns the arm used); with
/// `holding = Some((arm, home))` (the arm now holds the hook, using its actual grasp), putting
/// the blade behind `body`, dragging it into reach, lifting, and putting the hook back at
/// `home`, where it was picked.
pub fn pull_samples(
    rec: &Recorder,
    body: &str,
    hook: Option<&str>,
    arm: &Option<ArmRef>,
    holding: Option<HookGrip>,
    p: &SynthParams,
) -> Result<(Vec<RawSample>, HookGrip), RecorderError> {
    let world = rec.world();
    let cannot = |why: String| refused(format!("cannot pull {body}: {why}"));
    if world.body_kind(body) != Some(BodyKind::Block) {
        return Err(cannot("there is no such block".into()));
    }
    let hook_name = match hook {
        Some(h) => h.to_string(),
        None => SceneHook::first(world).ok_or_else(|| cannot("the scene has no hook".into()))?,
    };
    if world.body_kind(&hook_name) != Some(BodyKind::Hook) {
        return Err(cannot(format!("{hook_name} is not a hook")));
    }
    let hp = world
        .body_pose(&hook_name)
        .ok_or_else(|| cannot("no hook pose".into()))?;
    let bp = world
        .body_pose(body)
        .ok_or_else(|| cannot("no pose".into()))?;
    let safe = highest_top(world) + 0.05 + p.approach_height;
    match holding {
        Some(grip) => pull_stroke(rec, &hook_name, grip, &bp, safe, p, &cannot),
        None => pick_hook(rec, body, &hook_name, &hp, &bp, safe, arm, p, &cannot),
    }
}

/// The first phase of a pull: the first arm (of `arm`, or any) that can grasp the hook and
/// reach behind `body` with it picks the hook and lifts it to the height `safe`.
#[allow(clippy::too_many_arguments)]
fn pick_hook(
    rec: &Recorder,
    body: &str,
    hook_name: &str,
    hp: &Isometry3<f64>,
    bp: &Isometry3<f64>,
    safe: f64,
    arm: &Option<ArmRef>,
    p: &SynthParams,
    cannot: &dyn Fn(String) -> RecorderError,
) -> Result<(Vec<RawSample>, HookGrip), RecorderError> {
    let world = rec.world();
    let arms = resolve_arms(world, arm)?;
    let mut why = vec![];
    for &r in &arms {
        let name = world.arm_names()[r].to_string();
        if let Some(h) = world.held_by(r) {
            why.push(format!("{name} holds {h}"));
            continue;
        }
        let Some(g) = geometry::grasp_pose(world, r, hook_name) else {
            return Err(cannot("the hook cannot be grasped".into()));
        };
        let grasp_inv = (g.inverse() * hp).inverse();
        let base = world
            .arm_base(r)
            .ok_or_else(|| cannot("no arm base".into()))?;
        let (contact, pulled) = pull_hook_poses(&base, bp, PULL_TARGET_RADIUS);
        if !reaches(world, r, &[g, contact * grasp_inv, pulled * grasp_inv]) {
            why.push(format!(
                "{name} cannot reach behind {body} with {hook_name}"
            ));
            continue;
        }
        let mut m = motion_start(rec, r)?;
        let safe = g.translation.z.max(safe);
        m.transfer(at_height(&g, safe), p.speed);
        m.to(g, p.contact_time, Some(GripperCommand::Open));
        m.to(g, p.hold_time, Some(GripperCommand::Close));
        m.to(at_height(&g, safe), p.contact_time, None);
        return Ok((m.out, (r, *hp)));
    }
    Err(cannot(why.join("; ")))
}

/// The second phase of a pull, with the grasp the hook actually got: the blade goes behind the
/// block (`bp`), drags it into reach, backs off and lifts; the hook goes back to `home`.
fn pull_stroke(
    rec: &Recorder,
    hook_name: &str,
    (r, home): HookGrip,
    bp: &Isometry3<f64>,
    safe: f64,
    p: &SynthParams,
    cannot: &dyn Fn(String) -> RecorderError,
) -> Result<(Vec<RawSample>, HookGrip), RecorderError> {
    let world = rec.world();
    let grasp = world
        .grasp_transform(r)
        .filter(|_| world.held_by(r) == Some(hook_name))
        .ok_or_else(|| cannot(format!("the arm does not hold {hook_name}")))?;
    let grasp_inv = grasp.inverse();
    let base = world
        .arm_base(r)
        .ok_or_else(|| cannot("no arm base".into()))?;
    let (contact, pulled) = pull_hook_poses(&base, bp, PULL_TARGET_RADIUS);
    let tc = contact * grasp_inv;
    let tp = pulled * grasp_inv;
    let mut m = motion_start(rec, r)?;
    m.grip = GripperCommand::Close;
    m.transfer(at_height(&tc, safe), p.speed);
    m.to(tc, p.contact_time, None);
    let d = (tp.translation.vector - tc.translation.vector).norm();
    m.to(tp, (d / p.pull_speed).max(0.6), None);
    // Back the blade off the block before lifting, so the lift cannot scrape it.
    let mut off = tp;
    let back = tc.translation.vector - tp.translation.vector;
    let back = Vector3::new(back.x, back.y, 0.0);
    if back.norm() > MIN_BACK_OFF_DIRECTION {
        off.translation.vector += back.normalize() * 0.015;
    }
    m.to(off, p.hold_time, None);
    m.to(at_height(&off, safe), p.contact_time, None);
    // Put the hook back where it was before the pick (kept in the first phase's log).
    let mut put = home;
    put.translation.vector += Vector3::new(0.0, 0.0, PUT_DOWN_CLEARANCE);
    let place = put * grasp_inv;
    m.transfer(at_height(&place, safe), p.speed);
    m.to(place, p.contact_time, None);
    m.to(place, p.hold_time, Some(GripperCommand::Open));
    m.to(at_height(&place, safe), p.contact_time, None);
    Ok((m.out, (r, home)))
}

struct SceneHook;

impl SceneHook {
    fn first(world: &World) -> Option<String> {
        let s = world.snapshot();
        s.bodies
            .iter()
            .find(|b| b.kind == BodyKind::Hook && !b.lost)
            .map(|b| b.name.clone())
    }
}
