//! The template tasks the expert demonstrates: per benchmark, the grounded actions in order
//! with what the expert does for each.

use super::expert::Step;
use super::{fail, DemoError};
use crate::sim::benchmark::{Benchmark, BLOCK_SIZE};
use crate::sim::geometry::yaw_of;
use crate::sim::world::World;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// One action of a template task: the grounded PDDL action and what the expert does for it.
pub(super) struct TemplateAction {
    /// The grounded action, e.g. `(pick panda c)`.
    pub(super) action: String,
    /// What the expert does.
    pub(super) step: Step,
}

/// Picking `x` with arm `arm`.
fn pick(action: String, arm: usize, x: &str) -> TemplateAction {
    TemplateAction {
        action,
        step: Step::Pick { arm, x: x.into() },
    }
}

/// Putting `x`, held by arm `arm`, down at `target` (then home to the ready posture if
/// `retreat`).
fn place(
    action: String,
    arm: usize,
    x: &str,
    target: Isometry3<f64>,
    retreat: bool,
) -> TemplateAction {
    TemplateAction {
        action,
        step: Step::Place {
            arm,
            x: x.into(),
            target,
            retreat,
        },
    }
}

/// The expert's action list for a benchmark's template task.
pub(super) fn template_steps(
    b: Benchmark,
    world: &World,
) -> Result<Vec<TemplateAction>, DemoError> {
    let idx = |n: &str| world.arm_index(n).ok_or_else(|| fail(n, "no such arm"));
    match b {
        Benchmark::B1 => Ok(tower_steps(idx("panda")?)),
        Benchmark::B2 => workspace_reach_steps(world, idx("panda")?),
        Benchmark::B3 => {
            let (l, r) = (idx("left")?, idx("right")?);
            Ok(dual_arm_steps(l, r))
        }
    }
}

/// B1: c on d, b on c, a on b with arm `p`.
fn tower_steps(p: usize) -> Vec<TemplateAction> {
    let mut out = Vec::new();
    for (x, y) in [("c", "d"), ("b", "c"), ("a", "b")] {
        out.push(pick(format!("(pick panda {x})"), p, x));
        // Target: centred on y, y's yaw (computed when the action starts).
        out.push(place(
            format!("(stack panda {x} {y})"),
            p,
            x,
            Isometry3::identity(),
            false,
        ));
    }
    out
}

/// B2: arm `p` pulls b in with the hook, puts the hook back, then puts a and b on the shelf.
fn workspace_reach_steps(world: &World, p: usize) -> Result<Vec<TemplateAction>, DemoError> {
    let yaw_of_body = |n: &str| {
        world
            .body_pose(n)
            .map(|p| yaw_of(&p.rotation))
            .unwrap_or(0.0)
    };
    let mut out = Vec::new();
    let hook = world
        .body_pose("hook")
        .ok_or_else(|| fail("hook", "no hook"))?;
    out.push(pick("(pick panda hook)".into(), p, "hook"));
    out.push(TemplateAction {
        action: "(pull panda hook b)".into(),
        step: Step::Pull {
            arm: p,
            hook: "hook".into(),
            x: "b".into(),
        },
    });
    out.push(place("(place panda hook)".into(), p, "hook", hook, false));
    for (x, sx) in [("a", 0.28), ("b", 0.42)] {
        out.push(pick(format!("(pick panda {x})"), p, x));
        let t = Isometry3::from_parts(
            Translation3::new(sx, -0.50, 0.10 + 0.5 * BLOCK_SIZE),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw_of_body(x)),
        );
        out.push(place(format!("(place-on-shelf panda {x})"), p, x, t, false));
    }
    Ok(out)
}

/// B3: arm `l` hands b and then a over; arm `r` puts b on the right table and stacks a on it.
fn dual_arm_steps(l: usize, r: usize) -> Vec<TemplateAction> {
    let h = 0.5 * BLOCK_SIZE;
    let at = |x: f64, y: f64| {
        Isometry3::from_parts(Translation3::new(x, y, h), UnitQuaternion::identity())
    };
    vec![
        pick("(pick left b left-table)".into(), l, "b"),
        place(
            "(place left b handover)".into(),
            l,
            "b",
            at(0.38, 0.0),
            true,
        ),
        pick("(pick right b handover)".into(), r, "b"),
        place(
            "(place right b right-table)".into(),
            r,
            "b",
            at(0.42, -0.62),
            false,
        ),
        pick("(pick left a left-table)".into(), l, "a"),
        place(
            "(place left a handover)".into(),
            l,
            "a",
            at(0.38, 0.0),
            true,
        ),
        pick("(pick right a handover)".into(), r, "a"),
        place(
            "(stack right a b right-table)".into(),
            r,
            "a",
            Isometry3::identity(),
            true,
        ),
    ]
}
