//! The hook's pull strokes: where the hook lies at contact behind a block and after pulling
//! it towards an arm, shared by the expert, the disturbances, the executor and the streams.

use crate::sim::BLOCK_SIZE;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// Distance from the arm's base axis (m) to which the expert pulls a block with the hook: inside
/// the reach annulus, and far enough out that the hand holding the hook (31 cm behind the block)
/// stays clear of the base: nearer it, the folded arm tilts the hook into the table and the
/// stroke stops at contact.
pub const PULL_TARGET_RADIUS: f64 = 0.64;

/// Height above a stroke's contact and pulled poses from which the hook comes down and to which
/// it rises again (m). On its way there the blade passes over the block it is to pull; at far
/// reach the tracker's orientation lag tilts the 40 cm hook by 2–3 cm at the blade, so it crosses
/// 6 cm above the block's top (much lower, the tilted blade catches the block and the arm stops).
pub const PULL_LIFT: f64 = 0.11;

/// Turns of the hook's pull strokes (rad, from the line through the arm's base, see
/// [`pull_hook_poses_turned`]) in the order a planner tries them: radial first, then ±15°,
/// ±30°, ±45°, ±60° (a block right behind the shelf comes into reach only along it).
pub const PULL_TURNS: [f64; 9] = [0.0, 0.26, -0.26, 0.52, -0.52, 0.79, -0.79, 1.05, -1.05];

/// Gap between the hook's blade and the block's far face at the contact pose (m): the stroke
/// moves the hook this much farther than the block.
const PULL_GAP: f64 = 0.01;

/// Where a stroke from hook pose `contact` to `pulled` leaves the block lying at `block`: moved
/// along with the hook, less the gap the blade closes first.
pub fn pulled_block_position(
    block: &Isometry3<f64>,
    contact: &Isometry3<f64>,
    pulled: &Isometry3<f64>,
) -> Vector3<f64> {
    let stroke = pulled.translation.vector - contact.translation.vector;
    let n = stroke.norm();
    if n <= PULL_GAP {
        return block.translation.vector;
    }
    block.translation.vector + stroke * ((n - PULL_GAP) / n)
}

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
/// and a blade that scrapes the table is stopped at contact (a few mm of clearance are not
/// enough). The blade (z 12–32 mm) still meets a 6 cm block below its middle.
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
    let local = Vector3::new(0.18 - PULL_GAP - 0.5 * BLOCK_SIZE, 0.08, 0.0);
    let mut origin = b - rot * local;
    origin.z = PULL_HOOK_Z;
    // |w − v·s| = reach along the stroke: s = w·v − √(reach² − |w|² + (w·v)²).
    let along = w.dot(&v);
    let disc = reach * reach - w.norm_squared() + along * along;
    if disc < 0.0 {
        return None;
    }
    let dist = (along - libm::sqrt(disc)).max(0.0) + PULL_GAP;
    let contact = Isometry3::from_parts(Translation3::from(origin), rot);
    let pulled = Isometry3::from_parts(Translation3::from(origin - v * dist), rot);
    Some((contact, pulled))
}
