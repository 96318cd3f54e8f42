//! Whether an arm can work a block where it lies: grasp it from above, or pull it in with a
//! hook's stroke. Geometry queries (IK, parry intersection tests) on a [`World`], used by the
//! disturbance injectors (a block they move stays workable) and by the soak (a user drag that put
//! a block beyond every arm is not a planner failure).

use super::demo::{pull_hook_poses_turned, PULL_LIFT, PULL_TARGET_RADIUS, PULL_TURNS};
use super::geometry;
use super::snapshot::BodyKind;
use super::World;
use crate::sim::collide;
use nalgebra::{Isometry3, Translation3};
use parry3d_f64::shape::Cuboid;

/// Height above a top grasp that the hand must reach too, to come down onto the block (m).
const APPROACH_RISE: f64 = 0.12;

/// Shrinkage of every shape in the hook's checks (m), so resting contacts do not count.
const SLACK: f64 = 0.002;

/// Gap between the hook's blade and the block's far face at a stroke's contact pose (m), as
/// [`pull_hook_poses_turned`] places it.
const BLADE_GAP: f64 = 0.01;

/// Spacing of the samples along a stroke at which the swept hook and the dragged block are
/// tested (m).
const SWEEP_STEP: f64 = 0.01;

/// Whether some arm can work block `x` where it is, whatever the benchmark: grasp it from above
/// (inside the arm's reach annulus, IK of the top grasp and of the approach 12 cm above it), or,
/// where the scene has a hook and the block lies beyond the annulus, pull it in
/// ([`hook_can_pull`]). `Err` says why not. Disturbances keep every block they move workable,
/// and the soak uses this to tell a user drag that put a block beyond every arm from a planner
/// failure.
pub fn handleable(w: &World, x: &str) -> Result<(), String> {
    let arms = w.arm_names().len();
    let snap = w.snapshot();
    let Some(c) = w.body_pose(x).map(|p| p.translation.vector) else {
        return Err(format!("there is no body {x}"));
    };
    // Distance of the block from arm `arm`'s base in the plane, and its reach annulus (the
    // scene graph's `inreach`).
    let radius = |arm: usize| {
        snap.arms.get(arm).map(|a| {
            let b = a.base.position;
            (
                libm::hypot(c.x - b[0], c.y - b[1]),
                a.reach.min_radius,
                a.reach.max_radius,
            )
        })
    };
    for arm in 0..arms {
        let Some(g) = geometry::grasp_pose(w, arm, x) else {
            return Err(format!("{x} is not a block or hook"));
        };
        if radius(arm).is_none_or(|(d, lo, hi)| d < lo || d > hi) {
            continue;
        }
        let mut above = g;
        above.translation.vector.z += APPROACH_RISE;
        if w.reachable(arm, &g).is_ok() && w.reachable(arm, &above).is_ok() {
            return Ok(());
        }
    }
    let hooks: Vec<String> = snap
        .bodies
        .iter()
        .filter(|b| b.kind == BodyKind::Hook && !b.lost)
        .map(|b| b.name.clone())
        .collect();
    for hook in &hooks {
        for arm in 0..arms {
            // The hook pulls a block from beyond the annulus towards the base.
            if radius(arm).is_none_or(|(d, _, hi)| d <= hi) {
                continue;
            }
            if hook_can_pull(w, arm, hook, x) {
                return Ok(());
            }
        }
    }
    Err(if hooks.is_empty() {
        format!("no arm can grasp {x} where it is (IK)")
    } else {
        format!("no arm can grasp {x} where it is, nor pull it in with a clear stroke of the hook")
    })
}

/// Whether arm `arm`, holding `hook` as it holds it now or would grasp it where it rests, can
/// pull block `x` towards its base with one of the hook's strokes ([`PULL_TURNS`],
/// [`pull_hook_poses_turned`]): the arm reaches the stroke's contact and pulled poses and the
/// poses [`PULL_LIFT`] above them (IK) with its hand clear of everything but the tables there,
/// the hook sweeps from contact to pulled through nothing but the tables and `x`, and `x`
/// slides along the stroke into nothing but the tables and the hook (every shape shrunk by 2 mm,
/// so resting contacts do not count, but a shelf only as far as the simulator lets a carried or
/// pushed body press into it). The arm's path is not checked: a stroke that fails here
/// cannot be executed, whatever the planner.
pub fn hook_can_pull(w: &World, arm: usize, hook: &str, x: &str) -> bool {
    let (Some(base), Some(bp), Some(hp), Some(gp)) = (
        w.arm_base(arm),
        w.body_pose(x),
        w.body_pose(hook),
        geometry::grasp_pose(w, arm, hook),
    ) else {
        return false;
    };
    // The hook's pose in the hand: as the hand holds it now, or as a grasp of it where it
    // rests would hold it (not the resting grasp of a hook the hand tilts while it carries it).
    let grasp = match w.grasp_transform(arm) {
        Some(g) if w.held_by(arm) == Some(hook) => g,
        _ => gp.inverse() * hp,
    };
    let shrink = |c: &Cuboid| geometry::shrunk(c, SLACK);
    let hits = |parts: &[(Isometry3<f64>, Cuboid)], others: &[(Isometry3<f64>, Cuboid)]| {
        parts.iter().any(|(iso, c)| {
            others
                .iter()
                .any(|(oi, oc)| collide::intersects(iso, c, oi, oc))
        })
    };
    // Everything but the tables, the hook and x, shrunk by SLACK, a shelf by `shelf_slack`.
    let around = |shelf_slack: f64| -> Vec<(Isometry3<f64>, Cuboid)> {
        w.bodies
            .iter()
            .filter(|b| !b.lost && b.kind != BodyKind::Table && b.name != hook && b.name != x)
            .flat_map(|b| {
                let slack = if b.kind == BodyKind::Shelf {
                    shelf_slack
                } else {
                    SLACK
                };
                b.world_parts()
                    .map(move |(iso, c)| (iso, geometry::shrunk(c, slack)))
            })
            .collect()
    };
    let others = around(SLACK);
    // For the hook and x (shrunk by SLACK): a shelf only as far as the simulator lets a carried
    // or pushed body press into it.
    let pressed = around(w.params().carried_stop_depth() - SLACK);
    let hook_parts = w.body_shapes(hook);
    let block_parts = w.body_shapes(x);
    PULL_TURNS.iter().any(|&turn| {
        let Some((contact, pulled)) = pull_hook_poses_turned(&base, &bp, PULL_TARGET_RADIUS, turn)
        else {
            return false;
        };
        let lifted = |h: &Isometry3<f64>| geometry::raised(h, PULL_LIFT);
        if [contact, pulled, lifted(&contact), lifted(&pulled)]
            .iter()
            .map(|h| h * grasp.inverse())
            .any(|tcp| w.reachable(arm, &tcp).is_err() || geometry::hand_hits(&tcp, &others))
        {
            return false;
        }
        let at_contact: Vec<_> = hook_parts
            .iter()
            .map(|(iso, c)| (contact * hp.inverse() * iso, shrink(c)))
            .collect();
        if hits(&at_contact, &pressed) {
            return false;
        }
        // The hook sweeps from contact to pulled; its blade meets the block after its 1 cm
        // gap, then drags it the rest of the way.
        let d = pulled.translation.vector - contact.translation.vector;
        let slide = d * (1.0 - BLADE_GAP / d.norm().max(BLADE_GAP));
        let steps = (d.norm() / SWEEP_STEP).ceil().max(1.0) as usize;
        (0..=steps).all(|k| {
            let s = k as f64 / steps as f64;
            let hook_shift = Translation3::from(d * s);
            let swept: Vec<_> = at_contact
                .iter()
                .map(|(iso, c)| (hook_shift * iso, *c))
                .collect();
            let shift = Translation3::from(slide * s);
            let moved: Vec<_> = block_parts
                .iter()
                .map(|(iso, c)| (shift * iso, shrink(c)))
                .collect();
            !hits(&swept, &pressed) && !hits(&moved, &pressed)
        })
    })
}
