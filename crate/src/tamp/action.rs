//! What a grounded action does physically, read from its effects (not its name), and what the
//! streams bind for it.
//!
//! ```text
//!   add ∋ (holding r x)                          → grasp x with arm r     (pick, unstack)
//!   del ∋ (holding r x), add ∋ (on x y)          → release x on block y   (stack)
//!   del ∋ (holding r x), add ∋ (ontable|onshelf|at x …) → release x at a placement (place)
//!   r holds the hook, add ∋ (inreach r x)        → pull x with the hook   (pull)
//! ```

use crate::plan::{fact_args, Operator, Task};
use crate::sim::snapshot::BodyKind;
use crate::sim::World;

/// What the streams bound for one action of a plan.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Binding {
    /// Where a released body goes, or how a pull strokes (`None`: nothing to bind).
    pub placement: Option<Placement>,
    /// TCP height of a transit before the action's first approach, when the straight approach
    /// is blocked (the executor's `ActionExec::with_transit`).
    pub transit: Option<f64>,
    /// The yaw of the TCP's x axis with which a release was certified
    /// (the executor's `ActionExec::with_hand_yaw`); `None` for an uncertified one.
    pub hand_yaw: Option<f64>,
}

impl From<Option<Placement>> for Binding {
    fn from(placement: Option<Placement>) -> Self {
        Binding {
            placement,
            transit: None,
            hand_yaw: None,
        }
    }
}

/// Where a body rests on a surface: its centre's `(x, y)` and its yaw, the height left to
/// whatever is below (a demonstration's placement, a candidate spot).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PlanarPose {
    /// x (m).
    pub x: f64,
    /// y (m).
    pub y: f64,
    /// Yaw (rad).
    pub yaw: f64,
}

/// Where a stream puts an action's body: where a released body goes, or how a pull strokes.
#[derive(Clone, Debug, PartialEq)]
pub enum Placement {
    /// A pull stroke turned by this angle (rad) from the line through the arm's base.
    Stroke(f64),
    /// Centred on top of this block.
    OnBlock(String),
    /// Resting with its centre above `(x, y)` with yaw `yaw` (rad) on whatever is below.
    At {
        /// x (m).
        x: f64,
        /// y (m).
        y: f64,
        /// Yaw (rad).
        yaw: f64,
    },
}

/// What an action does physically.
#[derive(Clone, Debug, PartialEq)]
pub enum ActionKind {
    /// Grasp `body` with `arm` (pick / unstack).
    Grasp {
        /// Arm index.
        arm: usize,
        /// The body.
        body: String,
    },
    /// Release the held `body` at a placement (place / stack).
    Release {
        /// Arm index.
        arm: usize,
        /// The body.
        body: String,
        /// Where; `None` until the placement is bound by a stream.
        placement: Option<Placement>,
    },
    /// Pull `body` towards the arm with the held hook.
    Pull {
        /// Arm index.
        arm: usize,
        /// The hook.
        hook: String,
        /// The body pulled.
        body: String,
        /// The stroke's turn from the line through the arm's base (rad; 0 until bound by a
        /// stream, see `sim::demo::pull_hook_poses_turned`).
        turn: f64,
    },
}

impl ActionKind {
    /// The body the action grasps, releases or pulls.
    pub fn body(&self) -> &str {
        match self {
            ActionKind::Grasp { body, .. }
            | ActionKind::Release { body, .. }
            | ActionKind::Pull { body, .. } => body.as_str(),
        }
    }
}

/// Classifies a grounded operator (see the module documentation). `None` for an action without
/// a physical effect the executor knows.
pub fn classify(task: &Task, op: &Operator, world: &World) -> Option<ActionKind> {
    let names =
        |v: &[u32]| -> Vec<String> { v.iter().map(|&f| task.facts[f as usize].clone()).collect() };
    let add = names(&op.add);
    let del = names(&op.del);
    let pre = names(&op.pre);
    for f in &add {
        let (p, a) = fact_args(f);
        if p == "holding" && a.len() == 2 {
            return Some(ActionKind::Grasp {
                arm: world.arm_index(a[0])?,
                body: a[1].to_string(),
            });
        }
    }
    for f in &del {
        let (p, a) = fact_args(f);
        if p == "holding" && a.len() == 2 {
            let arm = world.arm_index(a[0])?;
            let body = a[1].to_string();
            let on = add.iter().find_map(|g| {
                let (q, b) = fact_args(g);
                (q == "on" && b.len() == 2 && b[0] == body).then(|| b[1].to_string())
            });
            return Some(ActionKind::Release {
                arm,
                placement: on.map(Placement::OnBlock),
                body,
            });
        }
    }
    // Pull: the arm holds the hook (precondition) and the block comes into reach.
    let hook = pre.iter().find_map(|f| {
        let (p, a) = fact_args(f);
        (p == "holding" && a.len() == 2 && world.body_kind(a[1]) == Some(HOOK))
            .then(|| (a[0].to_string(), a[1].to_string()))
    });
    if let Some((arm, hook)) = hook {
        let body = add.iter().find_map(|f| {
            let (p, a) = fact_args(f);
            (p == "inreach" && a.len() == 2 && a[0] == arm).then(|| a[1].to_string())
        })?;
        return Some(ActionKind::Pull {
            arm: world.arm_index(&arm)?,
            hook,
            body,
            turn: 0.0,
        });
    }
    None
}

/// Whether operator `op` of `task` moves `body`: grasps it (adds `(holding ?arm body)`, which
/// a pick, an unstack and a hand-over do), or pulls it in (adds `(inreach ?arm body)` while the
/// arm holds another body: the hook). The same reading of the task as [`classify`], without a
/// world.
pub fn moves_body(task: &Task, op: &Operator, body: &str) -> bool {
    let fact = |f: &u32| fact_args(task.facts.get(*f as usize).map_or("", String::as_str));
    op.add.iter().map(fact).any(|(p, a)| {
        (p == "holding" && a.len() == 2 && a[1] == body)
            || (p == "inreach"
                && a.len() == 2
                && a[1] == body
                && op
                    .pre
                    .iter()
                    .map(fact)
                    .any(|(q, h)| q == "holding" && h.len() == 2 && h[0] == a[0] && h[1] != body))
    })
}

const HOOK: BodyKind = BodyKind::Hook;
