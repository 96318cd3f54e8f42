//! What a grounded action does physically, as its domain declares it (`motions.json`: grasp,
//! release onto a block / a region / a table / a shelf, pull with a tool), and what the streams
//! bind for it.

use crate::plan::Operator;
use crate::sim::BodyKind;
use crate::sim::World;
use crate::sim::{MotionKind, Motions, Onto};

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

/// Classifies a grounded operator by its schema's declared motion (`motions.json`, see
/// [`crate::sim::Motions`]). `None` for an action without a physical effect or whose objects
/// the world does not have.
pub fn classify(op: &Operator, world: &World) -> Option<ActionKind> {
    let (m, args) = world.motions().action(&op.name)?;
    let arg = |i: Option<usize>| i.and_then(|i| args.get(i)).map(|s| s.to_string());
    let arm = match m.arm {
        Some(i) => world.arm_index(args.get(i)?)?,
        None if world.arm_names().len() == 1 => 0,
        None => return None,
    };
    let body = arg(m.object)?;
    match m.motion {
        MotionKind::Grasp => Some(ActionKind::Grasp { arm, body }),
        MotionKind::Release => {
            let placement = match m.onto? {
                Onto::Param(i) => {
                    let y = args.get(i)?;
                    (world.body_kind(y) == Some(BodyKind::Block))
                        .then(|| Placement::OnBlock(y.to_string()))
                }
                Onto::Table | Onto::Shelf => None,
            };
            Some(ActionKind::Release {
                arm,
                body,
                placement,
            })
        }
        MotionKind::Pull => Some(ActionKind::Pull {
            arm,
            hook: arg(m.tool)?,
            body,
            turn: 0.0,
        }),
        MotionKind::None => None,
    }
}

/// Where a release puts its body, as the domain declares it.
#[derive(Clone, Debug, PartialEq)]
pub enum ReleaseTarget {
    /// On top of this block.
    Block(String),
    /// Inside this table region.
    Region(String),
    /// On any body of this kind (a table, a shelf).
    Surface(BodyKind),
}

/// The declared target of a release action `op` (`None`: not a release).
pub fn release_target(op: &Operator, world: &World) -> Option<ReleaseTarget> {
    let (m, args) = world.motions().action(&op.name)?;
    if m.motion != MotionKind::Release {
        return None;
    }
    Some(match m.onto? {
        Onto::Table => ReleaseTarget::Surface(BodyKind::Table),
        Onto::Shelf => ReleaseTarget::Surface(BodyKind::Shelf),
        Onto::Param(i) => {
            let y = args.get(i)?.to_string();
            match world.body_kind(&y) {
                Some(BodyKind::Block) => ReleaseTarget::Block(y),
                _ => ReleaseTarget::Region(y),
            }
        }
    })
}

/// Whether operator `op` moves `body`: grasps it (a pick, an unstack, a hand-over) or pulls it
/// in, by the schema's declared motion. The same reading of the task as [`classify`].
pub fn moves_body(motions: &Motions, op: &Operator, body: &str) -> bool {
    let Some((m, args)) = motions.action(&op.name) else {
        return false;
    };
    matches!(m.motion, MotionKind::Grasp | MotionKind::Pull)
        && m.object.and_then(|i| args.get(i)) == Some(&body)
}
