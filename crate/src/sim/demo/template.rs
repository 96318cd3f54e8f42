//! The expert's script of a template task (`domains/*/expert.json`): the grounded actions in
//! order and, for each release onto a surface or a region, where the body goes. What each action
//! does (grasp, release, pull) comes from the world's declared motions, so a script names only
//! the domain's own actions.
//!
//! ```json
//! { "steps": [
//!   { "action": "(pick left b left-table)" },
//!   { "action": "(place left b handover)", "to": [0.38, 0.0, 0.03], "yaw": 0.0, "home": true }
//! ] }
//! ```
//!
//! `to` is the body's resting centre (world frame, m) and `yaw` its yaw (rad, default 0); a
//! release onto a block needs neither (the body is centred on it, with its yaw). `home`: back to
//! the ready posture afterwards (so two arms keep apart).

use serde::{Deserialize, Serialize};

use super::data::{fail, DemoError};
use super::segment::Step;
use crate::sim::world::World;
use crate::sim::BodyKind;
use crate::sim::{MotionKind, Onto};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// One step of an expert script.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScriptStep {
    /// The grounded action, e.g. `(pick panda c)`.
    pub action: String,
    /// Where a release onto a surface or a region puts the body's centre (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to: Option<[f64; 3]>,
    /// The released body's yaw (rad).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub yaw: f64,
    /// Back to the ready posture after the action.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub home: bool,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// An expert script (`expert.json`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Script {
    /// The steps in order.
    pub steps: Vec<ScriptStep>,
}

/// One action of a template task: the grounded PDDL action and what the expert does for it.
pub(super) struct TemplateAction {
    /// The grounded action, e.g. `(pick panda c)`.
    pub(super) action: String,
    /// What the expert does.
    pub(super) step: Step,
    /// The block a release stacks onto (its target is taken when the action starts).
    pub(super) onto_block: Option<String>,
}

/// The expert's actions for a script, read through `world`'s declared motions.
pub(super) fn template_steps(
    script: &Script,
    world: &World,
) -> Result<Vec<TemplateAction>, DemoError> {
    script
        .steps
        .iter()
        .map(|s| template_action(s, world))
        .collect()
}

fn template_action(s: &ScriptStep, world: &World) -> Result<TemplateAction, DemoError> {
    let (m, args) = world
        .motions()
        .action(&s.action)
        .ok_or_else(|| fail(&s.action, "the domain declares no motion for this action"))?;
    let arg = |i: Option<usize>, what: &str| {
        i.and_then(|i| args.get(i))
            .map(|v| v.to_string())
            .ok_or_else(|| fail(&s.action, format!("no {what} argument")))
    };
    let arm = match m.arm {
        Some(i) => {
            let name = arg(Some(i), "arm")?;
            world
                .arm_index(&name)
                .ok_or_else(|| fail(&s.action, format!("no arm {name}")))?
        }
        None => 0,
    };
    let x = arg(m.object, "object")?;
    let step = match m.motion {
        MotionKind::Grasp => Step::Pick { arm, x },
        MotionKind::Pull => Step::Pull {
            arm,
            hook: arg(m.tool, "tool")?,
            x,
        },
        MotionKind::Release => {
            let onto_block = match m.onto {
                Some(Onto::Param(i)) => args
                    .get(i)
                    .filter(|y| world.body_kind(y) == Some(BodyKind::Block))
                    .map(|y| y.to_string()),
                _ => None,
            };
            let target = match (&onto_block, s.to) {
                (Some(_), _) => Isometry3::identity(),
                (None, Some(p)) => Isometry3::from_parts(
                    Translation3::new(p[0], p[1], p[2]),
                    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), s.yaw),
                ),
                (None, None) => {
                    return Err(fail(
                        &s.action,
                        "a release onto a surface needs `to` in the script",
                    ))
                }
            };
            return Ok(TemplateAction {
                action: s.action.clone(),
                step: Step::Place {
                    arm,
                    x,
                    target,
                    retreat: s.home,
                },
                onto_block,
            });
        }
        MotionKind::None => return Err(fail(&s.action, "an action without a motion")),
    };
    Ok(TemplateAction {
        action: s.action.clone(),
        step,
        onto_block: None,
    })
}
