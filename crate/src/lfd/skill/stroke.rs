//! A pull's stroke as a learned skill with via-points (paper §IV-D, Fig. 4: the hook passes the
//! corners of the cube it pulls).
//!
//! The demonstrated stroke runs from the hook's `descent` (above the block) down behind the
//! block (`contact`) and drags it to the end of the pull (`pulled`). It is learned in the
//! *stroke frame* G: origin at the TCP's pulled position, yaw along the pull (from the pulled
//! towards the contact position), so a stroke to a new goal is the same skill in another frame.
//! Its via-points (`demo.json`'s `via_points` of the pull: the TCP where the blade's bottom passed
//! the block's far top edge, and where it was down behind its far face) are kept relative to the
//! contact TCP in axes along the pull, `o = R_z(−ψ)(p_via − p_contact)` (with the demo's velocity
//! there, in the same axes); for a new stroke they
//! become `p = p_contact + R_z(ψ) o` and, in G, `G⁻¹ p`, at phase `(k_via − k_descent)/(T − 1)`,
//! and LQT-CP passes them with the goal's precision. A DMP has no via-points (the paper's point).
//! A drag longer than the executor's stroke speed allows in the demonstrated time is learned
//! afresh from the demonstration played slower (the same motion, stretched in time).

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

use crate::lfd::ExecParams;
use crate::lqt::{Basis, SkillParams, Trajectory};
use crate::sim::demo::DemoAction;

/// Basis functions of a stroke's controls: three times an approach's, as its via-points (position
/// and velocity, twice) bend the motion within a third of its duration, which ten functions
/// cannot do without swinging the hook aside after them.
const STROKE_BASIS: usize = 30;

/// The LQT-CP parameters of a stroke: the default ones with [`STROKE_BASIS`] RBFs overlapping as
/// the default's do (λ scaled with the square of their number).
pub(super) fn params() -> SkillParams {
    let d = SkillParams::default();
    let k = d.basis.n_fct().max(2) as f64;
    let lambda = match &d.basis {
        Basis::Rbf { lambda, .. } => *lambda,
        _ => DEFAULT_LAMBDA,
    };
    let scale = (STROKE_BASIS as f64 - 1.0) / (k - 1.0);
    SkillParams {
        basis: Basis::rbf_uniform(STROKE_BASIS, lambda * scale * scale),
        ..d
    }
}

/// A slowdown this close to 1 plays the demonstration as it is.
pub(super) const SLOWDOWN_TOLERANCE: f64 = 1e-3;

/// RBF width λ when the default basis is not RBF.
const DEFAULT_LAMBDA: f64 = 100.0;

/// A stroke's via-point as learned: when, and where relative to the hook's contact pose.
#[derive(Clone, Debug)]
pub(super) struct StrokeVia {
    pub(super) label: String,
    /// Normalised time in the stroke, [0, 1].
    pub(super) phase: f64,
    /// Offset from the contact TCP, in axes along the pull (x), across it (y) and up (m).
    pub(super) offset: Vector3<f64>,
    /// The demo's velocity there, in the same axes (m/s): a via-point fixes where the hook
    /// passes and in which direction, so the blade comes down behind the block instead of
    /// sweeping into it sideways.
    pub(super) velocity: Vector3<f64>,
}

/// A demonstrated stroke: its positions in the stroke frame and its via-points.
#[derive(Clone, Debug)]
pub(super) struct DemoStroke {
    pub(super) positions: Vec<Point3<f64>>,
    pub(super) vias: Vec<StrokeVia>,
    /// Sample period (s).
    pub(super) dt: f64,
    /// Samples of the drag (contact to pulled).
    pub(super) drag_steps: usize,
}

impl DemoStroke {
    /// How much slower than demonstrated a drag of `length` (m) runs: at most the executor's
    /// stroke speed ([`ExecParams::stroke_speed`]; the tracker lags a faster stroke that folds
    /// the arm towards its base, and the lagging hand lifts the blade over the block), never
    /// faster than demonstrated.
    pub(super) fn slowdown(&self, length: f64) -> f64 {
        let speed = ExecParams::default().stroke_speed();
        let time = self.drag_steps as f64 * self.dt;
        if time <= 0.0 {
            return 1.0;
        }
        (length / speed / time).max(1.0)
    }

    /// The demonstration played `slow` times slower (linear interpolation of its samples).
    pub(super) fn slowed(&self, slow: f64) -> Vec<Point3<f64>> {
        let n = self.positions.len();
        let m = (libm::round((n - 1) as f64 * slow) as usize).max(1) + 1;
        (0..m)
            .map(|j| {
                let s = j as f64 * (n - 1) as f64 / (m - 1) as f64;
                let i = (s as usize).min(n - 2);
                let f = s - i as f64;
                self.positions[i] + (self.positions[i + 1] - self.positions[i]) * f
            })
            .collect()
    }
}

/// A stroke's via-point in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct StrokeViaPoint {
    /// `top-edge` or `bottom-edge` (see `sim::demo::DemoViaPoint`).
    pub label: String,
    /// The step of the planned trajectory at which the TCP should be there.
    pub step: usize,
    /// Where the TCP should be (world, m).
    pub position: Point3<f64>,
}

/// A planned stroke: the trajectory, its frame and its via-points.
#[derive(Clone, Debug)]
pub struct StrokePlan {
    /// The planned TCP trajectory with its feedback policy.
    pub trajectory: Trajectory,
    /// The stroke frame G (pulled TCP position, yaw along the pull).
    pub frame: Isometry3<f64>,
    /// The via-points the stroke should pass (a DMP's plan ignores them).
    pub via_points: Vec<StrokeViaPoint>,
}

/// The stroke frame of a stroke from TCP position `contact` to `pulled`: origin at `pulled`, yaw
/// from `pulled` towards `contact`.
pub fn stroke_frame(contact: &Point3<f64>, pulled: &Point3<f64>) -> Isometry3<f64> {
    let d = contact - pulled;
    Isometry3::from_parts(
        Translation3::from(pulled.coords),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), libm::atan2(d.y, d.x)),
    )
}

/// The stroke of a demonstrated pull `a` sampled every `dt`, `None` without its `descent`, `contact` and `pulled`
/// key points in order.
pub(super) fn demo_stroke(a: &DemoAction, dt: f64) -> Option<DemoStroke> {
    let key = |label: &str| {
        a.key_points
            .iter()
            .find(|k| k.label == label)
            .map(|k| k.step)
    };
    let (descent, contact, pulled) = (key("descent")?, key("contact")?, key("pulled")?);
    if !(descent < contact && contact < pulled && pulled < a.samples.len()) {
        return None;
    }
    let anchor = a.anchor_pose.isometry();
    let world: Vec<Point3<f64>> = a
        .samples
        .iter()
        .map(|s| anchor * Point3::new(s[0], s[1], s[2]))
        .collect();
    let frame = stroke_frame(&world[contact], &world[pulled]);
    let positions: Vec<Point3<f64>> = world[descent..=pulled]
        .iter()
        .map(|p| frame.inverse_transform_point(p))
        .collect();
    let last = (positions.len() - 1) as f64;
    // Central differences of the demo's positions (one-sided at the stroke's ends).
    let velocity = |k: usize| {
        let (lo, hi) = (k.max(descent + 1) - 1, (k + 1).min(pulled));
        frame.inverse_transform_vector(&(world[hi] - world[lo])) / ((hi - lo) as f64 * dt)
    };
    let vias = a
        .via_points
        .iter()
        .filter(|v| v.step > descent && v.step <= pulled)
        .map(|v| {
            let mut offset = frame.inverse_transform_vector(
                &(anchor * Point3::from(Vector3::from(v.position)) - world[contact]),
            );
            // Never nearer the block (towards the base, −x) than at contact: the expert's descent
            // comes down a few mm inside, which a block turned across the stroke (its corner 1 mm
            // from the blade at contact) would catch on the blade.
            offset.x = offset.x.max(0.0);
            StrokeVia {
                label: v.label.clone(),
                phase: (v.step - descent) as f64 / last,
                offset,
                velocity: velocity(v.step),
            }
        })
        .collect();
    Some(DemoStroke {
        positions,
        vias,
        dt,
        drag_steps: pulled - contact,
    })
}
