//! Flying the scripted expert's segments: minimum-jerk moves recorded in the action's anchor
//! frame, a transit over whatever stands in a transfer's straight way (a tall tower), a
//! joint-space recovery of a grasp or release pose Cartesian tracking cannot reach, and the
//! approach height that still fits under the top of the workspace.

use super::data::{anchor_sample, fail, min_jerk, DemoAction, DemoError, GripperChange, KeyPoint};
use super::segment::{Seg, MIN_TRANSFER_TIME};
use crate::sim::geometry::yaw_of;
use crate::sim::world::{GripperCommand, World, WorldEvent};
use nalgebra::{Isometry3, Translation3, Vector3};

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

/// One action being recorded: its arm, its name (for errors) and the anchor frame its samples
/// are expressed in.
struct Track<'a> {
    arm: usize,
    action: &'a str,
    anchor_inv: Isometry3<f64>,
    anchor_yaw: f64,
}

impl Track<'_> {
    /// Records the TCP's pose now as the next sample.
    fn sample(&self, world: &World, out: &mut DemoAction) -> Result<(), DemoError> {
        let tcp = world
            .tcp_pose(self.arm)
            .ok_or_else(|| fail(self.action, "no such arm"))?;
        out.samples
            .push(anchor_sample(&tcp, &self.anchor_inv, self.anchor_yaw));
        Ok(())
    }

    /// Moves the TCP from `from` to `to` along a minimum-jerk profile in `n` steps, recording
    /// every step.
    fn fly(
        &self,
        world: &mut World,
        from: &Isometry3<f64>,
        to: &Isometry3<f64>,
        n: usize,
        grip: GripperCommand,
        out: &mut DemoAction,
    ) -> Result<(), DemoError> {
        for k in 1..=n {
            let s = min_jerk(k as f64 / n as f64);
            let p = from.translation.vector.lerp(&to.translation.vector, s);
            let r = from.rotation.slerp(&to.rotation, s);
            let cmd = Isometry3::from_parts(Translation3::from(p), r);
            step_checked(world, self.arm, cmd, grip, self.action, out.samples.len())?;
            self.sample(world, out)?;
        }
        Ok(())
    }
}

/// Executes segments on `world` for `arm`, recording samples relative to `anchor`.
pub(super) fn execute(
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
    let track = Track {
        arm,
        action,
        anchor_inv: anchor.inverse(),
        anchor_yaw: yaw_of(&anchor.rotation),
    };
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
            track.fly(world, &from, &via, n, grip, out)?;
            from = via;
        }
        let n = ((seg.duration / dt).round() as usize).max(1);
        if let Some(g) = seg.gripper {
            grip = g;
            out.gripper.push(GripperChange {
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
        track.fly(world, &from, &seg.to, n, grip, out)?;
        // Before the gripper acts, the hand must be where the segment ends.
        if segs.get(i + 1).is_some_and(|next| next.gripper.is_some()) {
            recover(world, &track, &seg.to, grip, out)?;
        }
        from = seg.to;
    }
    Ok(())
}

/// The approach height over `p`: `h`, or less where `p` raised by `h` is beyond the arm's reach
/// (the top of a tall tower), in centimetre steps down to [`MIN_APPROACH_HEIGHT`].
pub(super) fn reachable_height(world: &World, arm: usize, p: &Isometry3<f64>, h: f64) -> f64 {
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
/// tracking stuck in a poor posture, as by the top of a tall tower) is reached in joint space:
/// the IK solution with the most room to the joint limits, then a short hold on the pose.
/// Nothing happens when the TCP is within [`RECOVER_ERROR`] of `to`.
fn recover(
    world: &mut World,
    track: &Track<'_>,
    to: &Isometry3<f64>,
    grip: GripperCommand,
    out: &mut DemoAction,
) -> Result<(), DemoError> {
    let (arm, action) = (track.arm, track.action);
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
    world
        .command_joints(arm, joints, grip)
        .map_err(|e| fail(action, e.to_string()))?;
    for _ in 0..RECOVER_STEPS {
        step_joints(world, action, out.samples.len())?;
        track.sample(world, out)?;
        if world
            .joints(arm)
            .is_some_and(|q| q.iter().zip(&joints).all(|(a, b)| libm::fabs(a - b) < 1e-6))
        {
            break;
        }
    }
    for _ in 0..RECOVER_HOLD_STEPS {
        step_checked(world, arm, *to, grip, action, out.samples.len())?;
        track.sample(world, out)?;
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
pub(super) fn step_checked(
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
