//! The checks of a scene's layout: every block and hook within some arm's reach, and room
//! around each block for a grasp from above (the hand and the arm's links at the grasp and on
//! the way down clear of every other body).

use nalgebra::Isometry3;
use parry3d_f64::shape::Cuboid;

use super::finding::Finding;
use crate::sim::geometry::{grasp_poses_at, raised, shrunk};
use crate::sim::{collide, handleable, BodyKind, World, WorldSnapshot};

/// Heights above a grasp the hand passes on its way down to it (m): the approach starts 12 cm up.
const APPROACH_HEIGHTS: [f64; 3] = [0.0, 0.06, 0.12];

/// Bodies are shrunk by this before the grasp check (m), so resting contacts do not count.
const TOUCH_SLACK: f64 = 0.002;

/// Every block and hook some arm can work where it lies ([`handleable`]: a grasp from above,
/// or a pull with the hook).
pub(super) fn check_reach(world: &World, snap: &WorldSnapshot, scene_file: &str) -> Vec<Finding> {
    let mut out = Vec::new();
    for (i, b) in snap.bodies.iter().enumerate() {
        if b.lost || !matches!(b.kind, BodyKind::Block | BodyKind::Hook) {
            continue;
        }
        let Err(why) = handleable(world, &b.name) else {
            continue;
        };
        let p = b.pose.position;
        let arms: Vec<String> = snap
            .arms
            .iter()
            .map(|a| {
                let c = a.base.position;
                format!(
                    "{} reaches {:.2}–{:.2} m from its base, `{}` is {:.2} m from it",
                    a.name,
                    a.reach.min_radius,
                    a.reach.max_radius,
                    b.name,
                    libm::hypot(p[0] - c[0], p[1] - c[1])
                )
            })
            .collect();
        out.push(Finding::new(
            scene_file,
            format!("bodies[{i}].pose.position"),
            format!(
                "no arm can work `{}` at ({:.3}, {:.3}): {why} ({})",
                b.name,
                p[0],
                p[1],
                arms.join("; ")
            ),
        ));
    }
    out
}

/// What a grasp from above of one block hits: the body, and the part of the arm (`hand`,
/// `link k`).
struct Hit {
    body: String,
    part: String,
}

/// Blocks too close to another body for a grasp from above: at every grasp yaw of every arm
/// that reaches the block, the hand or a link of the arm, at the grasp or on the way down to
/// it, overlaps the other body. Each pair is named once, with the gap between the two bodies.
pub(super) fn check_grasp_room(
    world: &World,
    snap: &WorldSnapshot,
    scene_file: &str,
) -> Vec<Finding> {
    let mut out = Vec::new();
    let mut pairs: Vec<(String, String)> = Vec::new();
    for (i, b) in snap.bodies.iter().enumerate() {
        if b.lost || b.kind != BodyKind::Block || !world.resting_on(&b.name).is_empty() {
            continue;
        }
        let Some(hit) = grasp_hit(world, &b.name) else {
            continue;
        };
        let pair = if b.name < hit.body {
            (b.name.clone(), hit.body.clone())
        } else {
            (hit.body.clone(), b.name.clone())
        };
        if pairs.contains(&pair) {
            continue;
        }
        pairs.push(pair);
        let gap = gap_mm(world, &b.name, &hit.body);
        out.push(Finding::new(
            scene_file,
            format!("bodies[{i}].pose.position"),
            format!(
                "a grasp of `{}` from above hits `{}` ({}) at every grasp angle: they stand \
                 {gap:.0} mm apart; keep one horizontal axis of `{}` free of other bodies for at \
                 least {MIN_GAP_MM} mm on both sides (the hand spans 23 cm along the axis its \
                 fingers close on)",
                b.name, hit.body, hit.part, b.name
            ),
        ));
    }
    out
}

/// The room a grasp from above needs on both sides of a 6 cm block along one horizontal axis
/// (mm): the gap `docs/formats.md` advises, the smallest at which this check finds a block with
/// neighbours on both axes clear in B1's workcell.
pub const MIN_GAP_MM: u32 = 75;

/// What every grasp of `x` from above hits, for the arms that reach it (`None`: some grasp is
/// clear, or no arm reaches `x` at all, which the reach check reports).
fn grasp_hit(world: &World, x: &str) -> Option<Hit> {
    let pose = world.body_pose(x)?;
    let others: Vec<(String, Isometry3<f64>, Cuboid)> = world
        .block_names()
        .into_iter()
        .map(str::to_string)
        .chain(world.hook_names())
        .filter(|n| n != x)
        .flat_map(|n| {
            world
                .body_shapes(&n)
                .into_iter()
                .map(move |(iso, c)| (n.clone(), iso, shrunk(&c, TOUCH_SLACK)))
        })
        .collect();
    let mut first: Option<Hit> = None;
    for arm in 0..world.arm_names().len() {
        for g in grasp_poses_at(world, arm, x, &pose) {
            let mut hit = None;
            let mut reached = true;
            for dz in APPROACH_HEIGHTS {
                let Ok(ik) = world.reachable(arm, &raised(&g, dz)) else {
                    reached = false;
                    break;
                };
                hit = hit.or_else(|| links_hit(world, arm, &ik.joints, &others));
            }
            if !reached {
                continue;
            }
            match hit {
                None => return None,
                Some(h) => {
                    first.get_or_insert(h);
                }
            }
        }
    }
    first
}

/// The first body of `others` a solid of arm `arm` at joints `q` overlaps (the base's
/// excepted; the last is the hand).
fn links_hit(
    world: &World,
    arm: usize,
    q: &[f64; crate::sim::panda::DOF],
    others: &[(String, Isometry3<f64>, Cuboid)],
) -> Option<Hit> {
    let (parts, base) = world.arm_parts(arm, q);
    let last = parts.len().saturating_sub(1);
    parts.iter().enumerate().skip(base).find_map(|(k, part)| {
        others
            .iter()
            .find(|(_, iso, c)| collide::intersects(&part.iso, &part.shape, iso, c))
            .map(|(name, _, _)| Hit {
                body: name.clone(),
                part: if k == last {
                    "the hand".into()
                } else {
                    format!("link {k} of the arm")
                },
            })
    })
}

/// The horizontal gap between the bounding boxes of bodies `a` and `b` (mm; 0 if they overlap
/// in the plane).
fn gap_mm(world: &World, a: &str, b: &str) -> f64 {
    let (Some((alo, ahi)), Some((blo, bhi))) = (world.body_aabb(a), world.body_aabb(b)) else {
        return 0.0;
    };
    let gx = (blo.x - ahi.x).max(alo.x - bhi.x).max(0.0);
    let gy = (blo.y - ahi.y).max(alo.y - bhi.y).max(0.0);
    1000.0 * libm::hypot(gx, gy)
}
