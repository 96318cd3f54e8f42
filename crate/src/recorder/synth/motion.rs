//! The motion builder of the synthesiser: minimum-jerk segments between way-points, sampled
//! every simulator step, and the pick-and-place it chains them into.

use super::params::{refused, SynthParams};
use crate::recorder::engine::gripper_sample;
use crate::recorder::{ArmRef, RawSample};
use crate::recorder::{Recorder, RecorderError};
use crate::sim::demo::min_jerk;
use crate::sim::geometry;
use crate::sim::{GripperCommand, World};
use nalgebra::Isometry3;

/// Height above its resting pose at which a carried body is released (m).
pub(super) const PUT_DOWN_CLEARANCE: f64 = 0.002;

/// `p` moved to the height `z` (orientation and x, y kept). Unlike `sim::geometry::raised`,
/// which moves a pose up by an offset, this sets the height itself.
pub(super) fn at_height(p: &Isometry3<f64>, z: f64) -> Isometry3<f64> {
    let mut q = *p;
    q.translation.vector.z = z;
    q
}

/// Builds samples segment by segment.
pub(super) struct Motion {
    pub(super) arm: usize,
    pub(super) dt: f64,
    pub(super) t: f64,
    pub(super) at: Isometry3<f64>,
    pub(super) grip: GripperCommand,
    pub(super) out: Vec<RawSample>,
}

impl Motion {
    /// Moves to `target` along a minimum-jerk segment of `duration` s (at least one step),
    /// switching the gripper to `grip` first if given.
    pub(super) fn to(
        &mut self,
        target: Isometry3<f64>,
        duration: f64,
        grip: Option<GripperCommand>,
    ) {
        if let Some(g) = grip {
            self.grip = g;
        }
        let n = ((duration / self.dt).round() as usize).max(1);
        let from = self.at;
        for k in 1..=n {
            let s = min_jerk(k as f64 / n as f64);
            let p = from.translation.vector.lerp(&target.translation.vector, s);
            let r = from.rotation.slerp(&target.rotation, s);
            let pose = Isometry3::from_parts(p.into(), r);
            self.out
                .push(gripper_sample(self.t, self.arm, &pose, self.grip));
            self.t += self.dt;
        }
        self.at = target;
    }

    /// Moves to `target` at `speed` (m/s; turns at most 1.2 rad/s, at least 0.5 s).
    pub(super) fn transfer(&mut self, target: Isometry3<f64>, speed: f64) {
        let d = (target.translation.vector - self.at.translation.vector).norm();
        let a = (target.rotation * self.at.rotation.inverse()).angle();
        self.to(target, (d / speed).max(a / 1.2).max(0.5), None);
    }
}

/// The arms an edit may use: the one it names, or every arm in order.
pub(super) fn resolve_arms(
    world: &World,
    arm: &Option<ArmRef>,
) -> Result<Vec<usize>, RecorderError> {
    match arm {
        Some(a) => a
            .resolve(world)
            .map(|i| vec![i])
            .ok_or_else(|| refused(format!("no such arm {a:?}"))),
        None => Ok((0..world.arm_names().len()).collect()),
    }
}

/// A motion of `arm` starting where its TCP is now, at the recorder's time, gripper open.
pub(super) fn motion_start(rec: &Recorder, arm: usize) -> Result<Motion, RecorderError> {
    let w = rec.world();
    let at = w.tcp_pose(arm).ok_or_else(|| refused("no such arm"))?;
    Ok(Motion {
        arm,
        dt: w.dt(),
        t: rec.time(),
        at,
        grip: GripperCommand::Open,
        out: vec![],
    })
}

/// The highest top face of any block or the hook (m), for safe transfers.
pub(super) fn highest_top(world: &World) -> f64 {
    world
        .block_names()
        .iter()
        .filter(|b| !world.is_lost(b))
        .filter_map(|b| world.body_aabb(b).map(|(_, hi)| hi.z))
        .fold(0.0, f64::max)
}

/// Pick `body` with `m.arm`, carry it to `rest` (its resting pose), release, lift.
pub(super) fn pick_and_place(
    world: &World,
    m: &mut Motion,
    body: &str,
    rest: &Isometry3<f64>,
    p: &SynthParams,
) -> Result<(), RecorderError> {
    let bp = world
        .body_pose(body)
        .ok_or_else(|| refused(format!("no body {body}")))?;
    let g = geometry::grasp_pose(world, m.arm, body)
        .ok_or_else(|| refused(format!("{body} cannot be grasped")))?;
    let grasp = g.inverse() * bp; // the body in the TCP frame
    let mut put = *rest;
    put.translation.vector.z += PUT_DOWN_CLEARANCE;
    let place = put * grasp.inverse();
    let safe = g
        .translation
        .z
        .max(place.translation.z)
        .max(highest_top(world) + 0.05)
        + p.approach_height;
    m.transfer(at_height(&g, safe), p.speed);
    m.grip = GripperCommand::Open;
    m.to(g, p.contact_time, Some(GripperCommand::Open));
    m.to(g, p.hold_time, Some(GripperCommand::Close));
    m.to(at_height(&g, safe), p.contact_time, None);
    m.transfer(at_height(&place, safe), p.speed);
    m.to(place, p.contact_time, None);
    m.to(place, p.hold_time, Some(GripperCommand::Open));
    m.to(
        at_height(&place, place.translation.z + p.approach_height),
        p.contact_time,
        None,
    );
    Ok(())
}

/// Whether `arm` reaches every pose (IK).
pub(super) fn reaches(world: &World, arm: usize, poses: &[Isometry3<f64>]) -> bool {
    poses.iter().all(|q| world.reachable(arm, q).is_ok())
}

/// With more than one arm, back to the ready pose (out of the hand-over region).
pub(super) fn go_home(world: &World, m: &mut Motion, p: &SynthParams) {
    if world.arm_names().len() > 1 {
        if let Some(home) = world.ready_tcp(m.arm) {
            m.transfer(home, p.speed);
        }
    }
}
