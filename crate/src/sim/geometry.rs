//! Per-action geometry helpers: grasp poses, resting poses, the TCP pose that puts a held body at
//! a pose, and the arm's drawing/collision capsules.
//!
//! Grasp convention: the gripper points straight down (TCP `z` = −world `z`), its tool centre
//! point is at the block's centre (fingertips around the block's middle), its fingers close along
//! one of the block's horizontal face normals — the one whose yaw is closest to the direction from
//! the arm's base to the block (what joint 1 gives naturally). The hook is grasped on its handle
//! at [`HOOK_GRASP_POINT`] (hook frame), fingers across the handle, the hand turned as the hook.

use super::panda::{self, hand_capsule, HAND_HALF_SPAN, HAND_RADIUS};
use super::snapshot::BodyKind;
use super::world::{Arm, World};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::shape::{Capsule, Cuboid};
use std::f64::consts::{FRAC_PI_2, PI};

/// Where the hook is grasped, in the hook's own frame (near the end of the handle) (m).
pub const HOOK_GRASP_POINT: [f64; 3] = [-0.17, 0.0, 0.0];

/// Link capsules `(a, b, radius)` and finger boxes `(pose, half extents)` in the world frame.
pub(crate) type ArmDrawing = (
    Vec<(Vector3<f64>, Vector3<f64>, f64)>,
    Vec<(Isometry3<f64>, Vector3<f64>)>,
);

/// Capsules of the links (base to hand) and the two finger boxes of an arm, world frame.
pub(crate) fn arm_drawing(a: &Arm) -> ArmDrawing {
    let links = a.model.link_capsules(&a.base, &a.joints);
    let tcp = a.tcp();
    let half = Vector3::new(0.01, 0.006, 0.0225);
    let fingers = [-1.0, 1.0]
        .iter()
        .map(|s| {
            let off = Vector3::new(0.0, s * (0.5 * a.gripper_opening + half.y), -0.018);
            (
                tcp * Isometry3::from_parts(Translation3::from(off), UnitQuaternion::identity()),
                half,
            )
        })
        .collect();
    (links, fingers)
}

/// The hand at `tcp` as a capsule ([`hand_capsule`]), its radius grown by `margin`.
pub(crate) fn hand_shape(tcp: &Isometry3<f64>, margin: f64) -> Capsule {
    let (a, b, r) = hand_capsule(tcp);
    Capsule::new(Point3::from(a), Point3::from(b), r + margin)
}

/// Whether the hand at `tcp` overlaps one of `boxes` (world poses and half extents).
pub fn hand_hits(tcp: &Isometry3<f64>, boxes: &[(Isometry3<f64>, Cuboid)]) -> bool {
    hand_within(tcp, boxes, 0.0)
}

/// Whether the hand at `tcp`, grown by `margin`, overlaps one of `boxes`.
pub(crate) fn hand_within(
    tcp: &Isometry3<f64>,
    boxes: &[(Isometry3<f64>, Cuboid)],
    margin: f64,
) -> bool {
    let cap = hand_shape(tcp, margin);
    boxes
        .iter()
        .any(|(iso, c)| super::collide::intersects(&Isometry3::identity(), &cap, iso, c))
}

/// Clearance of a transit over the tops below it (m).
pub const TRANSIT_CLEARANCE: f64 = 0.03;

/// How far around its TCP an empty hand reaches horizontally (m): the hand's half span and
/// radius.
const HAND_REACH: f64 = HAND_HALF_SPAN + HAND_RADIUS;

/// The TCP height of a transit (straight up, across at this height, straight down) from TCP
/// position `a` to `b`. What the arm carries — the body with world AABB `load` (`None`: the
/// empty hand) — passes [`TRANSIT_CLEARANCE`] above every top that `top_in` (the highest top
/// meeting an x, y rectangle) finds within its reach around the TCP (the load's extent + 2 cm,
/// at least 8 cm; the hand's span) of the rectangle spanned by `a` and `b`; never below either
/// end. The executor (from the world) and the TAMP streams (from their predicted state) both use it.
pub fn transit_z(
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    load: Option<(Vector3<f64>, Vector3<f64>)>,
    top_in: impl Fn([f64; 2], [f64; 2]) -> f64,
) -> f64 {
    let (reach, below_tcp) = match load {
        Some((lo, hi)) => {
            let extent = [lo.x - a.x, hi.x - a.x, lo.y - a.y, hi.y - a.y]
                .iter()
                .fold(0.0f64, |m, d| m.max(d.abs()));
            ((extent + 0.02).max(0.08), (a.z - lo.z).max(0.0))
        }
        None => (HAND_REACH, 0.0),
    };
    let top = top_in(
        [a.x.min(b.x) - reach, a.y.min(b.y) - reach],
        [a.x.max(b.x) + reach, a.y.max(b.y) + reach],
    );
    (top + TRANSIT_CLEARANCE + below_tcp).max(a.z).max(b.z)
}

/// Where arm `arm` rises to before its next action when its empty hand is down among bodies
/// (an action interrupted right after a release, or before a grasp closed): its TCP moved
/// straight up by `dz`, if the hand, grown by 1 cm, overlaps a body other than a table. Both
/// the executor and the TAMP streams start from it, so they agree.
pub fn rise_first(world: &World, arm: usize, dz: f64) -> Option<Isometry3<f64>> {
    if world.held_by(arm).is_some() {
        return None;
    }
    let tcp = world.tcp_pose(arm)?;
    let around: Vec<(Isometry3<f64>, Cuboid)> = world
        .bodies
        .iter()
        .filter(|body| !body.lost && body.kind != BodyKind::Table)
        .flat_map(|body| body.world_parts().map(|(iso, c)| (iso, *c)))
        .collect();
    hand_within(&tcp, &around, RISE_MARGIN).then(|| raised(&tcp, dz))
}

/// The hand rises first when it, grown by this (m), overlaps a body ([`rise_first`]).
const RISE_MARGIN: f64 = 0.01;

/// The top grasps of block `body` at `pose` for arm `arm`, best first: the fingers close along
/// one of its horizontal face normals (yaw ∈ yaw_x + k·π/2) that the gripper can span, ordered
/// by closeness to the arm's heading (the first is [`grasp_pose_at`]'s). The hook has one.
pub fn grasp_poses_at(
    world: &World,
    arm: usize,
    body: &str,
    pose: &Isometry3<f64>,
) -> Vec<Isometry3<f64>> {
    let Some(first) = grasp_pose_at(world, arm, body, pose) else {
        return vec![];
    };
    if world.body_kind(body) != Some(BodyKind::Block) {
        return vec![first];
    }
    let heading = yaw_from_base(world, arm, &pose.translation.vector);
    let first_yaw = closest_yaw(yaw_of(&pose.rotation), FRAC_PI_2, heading);
    let mut yaws: Vec<f64> = (0..4)
        .map(|k| wrap(first_yaw + k as f64 * FRAC_PI_2))
        .collect();
    yaws.sort_by(|a, b| wrap(a - heading).abs().total_cmp(&wrap(b - heading).abs()));
    // The fingers must span the block across the closing axis (the TCP's y).
    let parts = world.body_shapes(body);
    let cur = world.body_pose(body).unwrap_or(*pose);
    yaws.into_iter()
        .map(|yaw| Isometry3::from_parts(pose.translation, panda::down_orientation(yaw)))
        .filter(|g| {
            parts.iter().all(|(iso, c)| {
                let local = g.inverse() * pose * cur.inverse() * iso;
                let m = local.rotation.to_rotation_matrix().matrix().abs();
                2.0 * (m * c.half_extents).y <= panda::GRIPPER_MAX_OPENING
            })
        })
        .collect()
}

/// The grasp of block `body` at `pose` whose hand keeps clear of `boxes` at the grasp and
/// halfway up its approach (`approach` m above): the first of [`grasp_poses_at`] that does,
/// else the first whose hand presses hardly deeper into them than the least deep one (a block
/// beside a shelf: the hand turned along the shelf's face grazes it, turned across it reaches
/// over it). Both the executor (boxes: the world now) and the TAMP streams (boxes: the predicted
/// world) choose with it, so they agree.
pub fn clear_grasp_at(
    world: &World,
    arm: usize,
    body: &str,
    pose: &Isometry3<f64>,
    boxes: &[(Isometry3<f64>, Cuboid)],
    approach: f64,
) -> Option<Isometry3<f64>> {
    let depth = |g: &Isometry3<f64>| {
        hand_depth(g, boxes).max(hand_depth(&raised(g, 0.5 * approach), boxes))
    };
    let all: Vec<(f64, Isometry3<f64>)> = grasp_poses_at(world, arm, body, pose)
        .into_iter()
        .map(|g| (depth(&g), g))
        .collect();
    let least = all.iter().map(|(d, _)| *d).fold(f64::INFINITY, f64::min);
    // A clear grasp, if there is one; else nearly the least deep.
    let slack = if least > 0.0 { GRASP_DEPTH_SLACK } else { 0.0 };
    all.into_iter()
        .find(|(d, _)| *d <= least + slack)
        .map(|(_, g)| g)
}

/// Grasps whose hands press at most this much deeper than the least deep one count as equal
/// (m): among them [`clear_grasp_at`] keeps the one nearest the arm's heading.
const GRASP_DEPTH_SLACK: f64 = 0.005;

/// How deep the hand at `tcp` presses into the deepest of `boxes` (m; 0 if it overlaps none).
fn hand_depth(tcp: &Isometry3<f64>, boxes: &[(Isometry3<f64>, Cuboid)]) -> f64 {
    let cap = hand_shape(tcp, 0.0);
    boxes
        .iter()
        .filter_map(|(iso, c)| {
            super::collide::contact(&Isometry3::identity(), &cap, iso, c, 0.0)
                .map(|k| (-k.dist).max(0.0))
        })
        .fold(0.0, f64::max)
}

/// The boxes of every body of `world` but `except` and the held ones (world frame).
pub fn boxes_except(world: &World, except: &[&str]) -> Vec<(Isometry3<f64>, Cuboid)> {
    let held: Vec<&str> = (0..world.arm_names().len())
        .filter_map(|a| world.held_by(a))
        .collect();
    world
        .bodies
        .iter()
        .filter(|b| {
            !b.lost && !except.contains(&b.name.as_str()) && !held.contains(&b.name.as_str())
        })
        .flat_map(|b| b.world_parts().map(|(iso, c)| (iso, *c)))
        .collect()
}

/// The smallest half extent [`shrunk`] leaves (m): a box never shrinks to nothing.
const MIN_HALF_EXTENT: f64 = 1e-4;

/// `c` with every half extent `slack` smaller (at least [`MIN_HALF_EXTENT`]), so that touching
/// faces and resting contacts do not count as overlaps.
pub(crate) fn shrunk(c: &Cuboid, slack: f64) -> Cuboid {
    Cuboid::new((c.half_extents - Vector3::repeat(slack)).map(|h| h.max(MIN_HALF_EXTENT)))
}

/// `iso` moved up by `dz` along world `z` (orientation kept).
pub(crate) fn raised(iso: &Isometry3<f64>, dz: f64) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::from(iso.translation.vector + Vector3::z() * dz),
        iso.rotation,
    )
}

/// The link capsules `(a, b, radius)` of arm `arm` at joint angles `q` (world frame, base link
/// first, hand last), without moving the arm: what a planner checks along a candidate motion.
/// Empty for an unknown arm.
pub fn link_capsules(
    world: &World,
    arm: usize,
    q: &[f64; panda::DOF],
) -> Vec<(Vector3<f64>, Vector3<f64>, f64)> {
    match (world.arm_base(arm), world.arm_model(arm)) {
        (Some(base), Some(model)) => model.link_capsules(&base, q),
        _ => vec![],
    }
}

/// Yaw (rotation about world `z`) of a pose's rotation: the heading of its `x` axis.
pub(crate) fn yaw_of(rot: &UnitQuaternion<f64>) -> f64 {
    let x = rot * Vector3::x();
    libm::atan2(x.y, x.x)
}

/// The gripper yaw of a TCP orientation: the yaw [`panda::down_orientation`] was given (its
/// inverse for a gripper pointing down).
pub(crate) fn gripper_yaw(rot: &UnitQuaternion<f64>) -> f64 {
    yaw_of(&(rot * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), PI)))
}

/// Wraps an angle to (−π, π].
pub(crate) fn wrap(a: f64) -> f64 {
    let mut x = (a + PI).rem_euclid(2.0 * PI) - PI;
    if x <= -PI {
        x += 2.0 * PI;
    }
    x
}

/// Among `yaw + k·step` (k integer) the one closest to `preferred`.
fn closest_yaw(yaw: f64, step: f64, preferred: f64) -> f64 {
    let k = ((preferred - yaw) / step).round();
    wrap(yaw + k * step)
}

/// A point closer than this to an arm's base axis (m) has no direction from the base; the
/// base's own yaw stands in for it.
const ON_BASE_AXIS: f64 = 1e-6;

/// Yaw of the direction from arm `arm`'s base to the point `p`, in the world.
fn yaw_from_base(world: &World, arm: usize, p: &Vector3<f64>) -> f64 {
    let base = world.arm_base(arm).unwrap_or_else(Isometry3::identity);
    let d = p - base.translation.vector;
    if libm::hypot(d.x, d.y) < ON_BASE_AXIS {
        yaw_of(&base.rotation)
    } else {
        libm::atan2(d.y, d.x)
    }
}

/// The TCP pose with which arm `arm` grasps the block or hook called `body` from above (see the
/// module docs), or `None` for an unknown body or a fixed one.
pub fn grasp_pose(world: &World, arm: usize, body: &str) -> Option<Isometry3<f64>> {
    grasp_pose_at(world, arm, body, &world.body_pose(body)?)
}

/// The TCP pose with which arm `arm` would grasp `body` from above if the body were at `pose`
/// (the convention of [`grasp_pose`]); `None` for an unknown or fixed body.
pub fn grasp_pose_at(
    world: &World,
    arm: usize,
    body: &str,
    pose: &Isometry3<f64>,
) -> Option<Isometry3<f64>> {
    let pose = *pose;
    match world.body_kind(body)? {
        BodyKind::Block => {
            let p = pose.translation.vector;
            let yaw = closest_yaw(
                yaw_of(&pose.rotation),
                FRAC_PI_2,
                yaw_from_base(world, arm, &p),
            );
            Some(Isometry3::from_parts(
                Translation3::from(p),
                panda::down_orientation(yaw),
            ))
        }
        BodyKind::Hook => {
            // The hand turned as the hook, never half a turn from it: strokes drag the hook
            // along its own axis (`sim::demo::pull_hook_poses`), where this grasp keeps the
            // wrist near the middle of its range; the other would drive joint 7 into its limit.
            let p = (pose * Point3::from(Vector3::from(HOOK_GRASP_POINT))).coords;
            let yaw = yaw_of(&pose.rotation);
            Some(Isometry3::from_parts(
                Translation3::from(p),
                panda::down_orientation(yaw),
            ))
        }
        BodyKind::Table | BodyKind::Shelf => None,
    }
}

/// The pose at which body `body` (a block or the hook) rests with its centre above `(x, y)` and
/// yaw `yaw`: on the highest top face under `(x, y)` among the other bodies that are not held (a
/// table, the shelf or a block). `None` for an unknown body or when nothing is under `(x, y)`.
pub fn rest_pose(world: &World, body: &str, x: f64, y: f64, yaw: f64) -> Option<Isometry3<f64>> {
    let bi = world.body_index(body)?;
    let b = &world.bodies[bi];
    let rot = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw);
    let probe = Isometry3::from_parts(Translation3::new(x, y, 0.0), rot);
    let (lo, _) = b.aabb_at(&probe);
    let held: Vec<usize> = (0..world.arms.len())
        .filter_map(|a| world.arms[a].holding.map(|(i, _)| i))
        .collect();
    let top = world
        .bodies
        .iter()
        .enumerate()
        .filter(|(j, o)| *j != bi && !o.lost && !held.contains(j))
        .filter_map(|(_, o)| o.top_under(x, y, 0.0))
        .fold(None, |acc: Option<f64>, t| {
            Some(acc.map_or(t, |a| a.max(t)))
        })?;
    Some(Isometry3::from_parts(
        Translation3::new(x, y, top - lo.z),
        rot,
    ))
}

/// The pose at which `body` rests centred on top of `support` (a block, table or shelf), with
/// the yaw of `support` for a block and `yaw` otherwise.
pub fn rest_pose_on(world: &World, body: &str, support: &str, yaw: f64) -> Option<Isometry3<f64>> {
    let sp = world.body_pose(support)?;
    let yaw = if world.body_kind(support)? == BodyKind::Block {
        yaw_of(&sp.rotation)
    } else {
        yaw
    };
    let (lo, hi) = world.body_aabb(support)?;
    let c = if world.body_kind(support)? == BodyKind::Block {
        sp.translation.vector
    } else {
        0.5 * (lo + hi)
    };
    rest_pose(world, body, c.x, c.y, yaw)
}

/// `body_pose` turned about the vertical by the quarter turn (0, ±π/2, π) that makes the TCP of
/// arm `arm`, holding `body` with its actual grasp, point its fingers closest to the yaw
/// `toward` (of the TCP's x axis; `None`: the direction from the base, the orientation the
/// placement streams sample with IK). The streams pass the hand yaw they certified the release
/// with: the actual grasp may differ from the predicted one by a quarter turn, and the hand must
/// end where it was certified. A block with a square footprint looks the same after a quarter
/// turn, so its facts and footprint do not change; any other body, or an arm that holds
/// nothing, gets `body_pose` back.
///
/// Why the turn: placed with the placement's yaw as sampled, a block held with another
/// quarter-turn grasp puts the wrist up to 180° away from the certified orientation, where the
/// arm may not reach the place via-point. Why towards the certified yaw and not the base's
/// heading: a hand certified lengthwise beside a tower would otherwise come down across it,
/// its palm in the tower.
pub fn quarter_turn_for_arm(
    world: &World,
    arm: usize,
    body: &str,
    body_pose: &Isometry3<f64>,
    toward: Option<f64>,
) -> Isometry3<f64> {
    match world.grasp_transform(arm) {
        Some(g) => quarter_turns(world, arm, body, body_pose, &g, toward)[0],
        None => *body_pose,
    }
}

/// A box whose two horizontal half extents differ by less than this (m) has a square footprint.
const SQUARE_TOLERANCE: f64 = 1e-9;

/// Quarter turns are ordered by their yaw offsets in whole nanoradians, so that offsets equal
/// but for rounding keep the lesser turn first.
const NANORADIANS_PER_RADIAN: f64 = 1e9;

/// `body_pose` turned by each quarter turn, ordered by how close the yaw of the TCP holding
/// `body` with grasp `g` (its pose in the TCP frame) comes to `toward` (`None`: the heading
/// from arm `arm`'s base); just `body_pose` for a body without a square footprint. The first
/// is [`quarter_turn_for_arm`]'s; the streams certify a release with the first one or two.
pub(crate) fn quarter_turns(
    world: &World,
    arm: usize,
    body: &str,
    body_pose: &Isometry3<f64>,
    g: &Isometry3<f64>,
    toward: Option<f64>,
) -> Vec<Isometry3<f64>> {
    let square = world.body_index(body).is_some_and(|bi| {
        let b = &world.bodies[bi];
        b.kind == BodyKind::Block
            && b.parts.len() == 1
            && (b.parts[0].1.half_extents.x - b.parts[0].1.half_extents.y).abs() < SQUARE_TOLERANCE
    });
    if !square {
        return vec![*body_pose];
    }
    let toward = toward.unwrap_or_else(|| yaw_from_base(world, arm, &body_pose.translation.vector));
    let mut turned: Vec<(f64, Isometry3<f64>)> = (0..4)
        .map(|k| {
            let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), k as f64 * FRAC_PI_2);
            let pose = Isometry3::from_parts(body_pose.translation, turn * body_pose.rotation);
            // The TCP's fingers close along its y axis; its yaw is that of its x axis.
            (
                wrap(yaw_of(&(pose * g.inverse()).rotation) - toward).abs(),
                pose,
            )
        })
        .collect();
    // Of two turns equally close (to a nanoradian), the lesser turn first (a stable sort).
    turned.sort_by_key(|(off, _)| (off * NANORADIANS_PER_RADIAN).round() as i64);
    turned.into_iter().map(|(_, p)| p).collect()
}

/// The TCP pose that puts the body held by arm `arm` at `body_pose` (using the actual grasp), or,
/// when the arm holds nothing, the standard top grasp of a block at `body_pose`.
pub fn tcp_for_body_pose(world: &World, arm: usize, body_pose: &Isometry3<f64>) -> Isometry3<f64> {
    match world.grasp_transform(arm) {
        Some(g) => body_pose * g.inverse(),
        None => {
            let p = body_pose.translation.vector;
            let yaw = closest_yaw(
                yaw_of(&body_pose.rotation),
                FRAC_PI_2,
                yaw_from_base(world, arm, &p),
            );
            Isometry3::from_parts(Translation3::from(p), panda::down_orientation(yaw))
        }
    }
}
