//! Franka-Panda-like 7-DoF arm: forward kinematics, geometric Jacobian, damped-least-squares IK.
//!
//! **Forward kinematics** uses the published modified (Craig) Denavit–Hartenberg parameters of the
//! Panda, one homogeneous transform per joint
//!
//! ```text
//! ⁱ⁻¹Tᵢ = Rot_x(αᵢ₋₁) · Trans_x(aᵢ₋₁) · Rot_z(qᵢ) · Trans_z(dᵢ)
//! ⁰T_tcp = ⁰T₁ ⋯ ⁶T₇ · T_flange(d = 0.107) · Rot_z(−π/4) · Trans_z(0.1034)
//! ```
//!
//! with the tool centre point (TCP) between the fingertips, its `z` axis pointing out of the hand
//! and its `y` axis joining the fingers.
//!
//! **Jacobian** (geometric, world frame) from the FK frames: for revolute joint i with axis zᵢ
//! through oᵢ, `Jᵢ = [zᵢ × (p_tcp − oᵢ); zᵢ]`.
//!
//! **IK** (damped least squares with a null-space posture term): with the task error
//! `e = [p* − p; log(R* Rᵀ)]` (position in metres, rotation vector in radians),
//!
//! ```text
//! Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e  +  (I − J⁺J) k_ns (q_mid − q),    q ← clamp(q + Δq, q_min, q_max)
//! ```
//!
//! iterated from a warm start (the arm's current joints); if that does not converge, restarts from
//! seeded random configurations. Failure returns the best residual found, so "unreachable" is a
//! clear answer and not a silent approximation.

use nalgebra::{
    Isometry3, Matrix3, Matrix6, Matrix6x1, SMatrix, Translation3, UnitQuaternion, Vector3, Vector6,
};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::sync::OnceLock;

use super::fast_math::{norm3, quaternion_of, sincos_table, Cholesky};

/// Number of joints.
pub const DOF: usize = 7;

/// Modified DH `(a_{i-1}, d_i, alpha_{i-1})` of joints 1..7 (Franka documentation), metres / radians.
const DH: [(f64, f64, f64); DOF] = [
    (0.0, 0.333, 0.0),
    (0.0, 0.0, -std::f64::consts::FRAC_PI_2),
    (0.0, 0.316, std::f64::consts::FRAC_PI_2),
    (0.0825, 0.0, std::f64::consts::FRAC_PI_2),
    (-0.0825, 0.384, -std::f64::consts::FRAC_PI_2),
    (0.0, 0.0, std::f64::consts::FRAC_PI_2),
    (0.088, 0.0, std::f64::consts::FRAC_PI_2),
];
/// Distance from joint 7's frame to the flange (m).
const FLANGE_D: f64 = 0.107;
/// Distance from the flange to the tool centre point between the fingertips (m).
pub const TCP_OFFSET: f64 = 0.1034;

/// Lower joint limits (rad), Franka documentation.
pub const JOINT_LOWER: [f64; DOF] = [
    -2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973,
];
/// Upper joint limits (rad), Franka documentation.
pub const JOINT_UPPER: [f64; DOF] = [2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973];
/// Joint velocity limits (rad/s), Franka documentation.
pub const JOINT_VELOCITY: [f64; DOF] = [2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61];
/// The "ready" configuration: gripper pointing down in front of the base.
pub const READY: [f64; DOF] = [
    0.0,
    -std::f64::consts::FRAC_PI_4,
    0.0,
    -3.0 * std::f64::consts::FRAC_PI_4,
    0.0,
    std::f64::consts::FRAC_PI_2,
    std::f64::consts::FRAC_PI_4,
];
/// Largest finger opening (m).
pub const GRIPPER_MAX_OPENING: f64 = 0.08;

/// A rigid frame as rotation matrix + translation (cheaper to chain than quaternions).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub r: Matrix3<f64>,
    pub p: Vector3<f64>,
}

impl Frame {
    fn identity() -> Self {
        Frame {
            r: Matrix3::identity(),
            p: Vector3::zeros(),
        }
    }
    fn from_iso(iso: &Isometry3<f64>) -> Self {
        Frame {
            r: *iso.rotation.to_rotation_matrix().matrix(),
            p: iso.translation.vector,
        }
    }
    fn mul(&self, o: &Frame) -> Frame {
        Frame {
            r: self.r * o.r,
            p: self.r * o.p + self.p,
        }
    }
    pub(crate) fn to_iso(self) -> Isometry3<f64> {
        Isometry3::from_parts(Translation3::from(self.p), quaternion_of(&self.r))
    }
}

/// Modified DH transform `Rot_x(α) Trans_x(a) Rot_z(θ) Trans_z(d)` from `(sin α, cos α)` and
/// `(sin θ, cos θ)`.
fn dh((a, d): (f64, f64), (sa, ca): (f64, f64), (st, ct): (f64, f64)) -> Frame {
    Frame {
        r: Matrix3::new(ct, -st, 0.0, st * ca, ct * ca, -sa, st * sa, ct * sa, ca),
        p: Vector3::new(a, -sa * d, ca * d),
    }
}

/// `libm::sincos` of the constant angles of the chain: the twists α of joints 1..7, then 0 (the
/// flange and TCP offsets) and −π/4 (the hand).
fn chain_trig() -> &'static [(f64, f64); DOF + 2] {
    static CELL: OnceLock<[(f64, f64); DOF + 2]> = OnceLock::new();
    let mut angles = [0.0; DOF + 2];
    for i in 0..DOF {
        angles[i] = DH[i].2;
    }
    angles[DOF + 1] = -std::f64::consts::FRAC_PI_4;
    sincos_table(&CELL, &angles)
}

/// All frames of one arm configuration, world coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ArmFrames {
    /// Base, joint frames 1..7, flange (index 8), hand (index 9: rotated −π/4, at the flange).
    pub frames: [Frame; 10],
    /// Tool centre point.
    pub tcp: Frame,
}

/// Forward kinematics of every frame.
pub(crate) fn forward_frames(base: &Isometry3<f64>, q: &[f64; DOF]) -> ArmFrames {
    let trig = chain_trig();
    let zero = trig[DOF];
    let mut frames = [Frame::identity(); 10];
    frames[0] = Frame::from_iso(base);
    for i in 0..DOF {
        let (a, d, _) = DH[i];
        frames[i + 1] = frames[i].mul(&dh((a, d), trig[i], libm::sincos(q[i])));
    }
    frames[8] = frames[7].mul(&dh((0.0, FLANGE_D), zero, zero));
    frames[9] = frames[8].mul(&dh((0.0, 0.0), zero, trig[DOF + 1]));
    let tcp = frames[9].mul(&dh((0.0, TCP_OFFSET), zero, zero));
    ArmFrames { frames, tcp }
}

/// Forward kinematics: the TCP pose in the world for joint angles `q` of an arm based at `base`.
pub fn forward_kinematics(base: &Isometry3<f64>, q: &[f64; DOF]) -> Isometry3<f64> {
    forward_frames(base, q).tcp.to_iso()
}

/// The geometric Jacobian (6×7, rows = linear then angular velocity, world frame) at `f`.
pub(crate) fn jacobian(f: &ArmFrames) -> SMatrix<f64, 6, DOF> {
    let mut j = SMatrix::<f64, 6, DOF>::zeros();
    for i in 0..DOF {
        let fr = &f.frames[i + 1];
        let z = fr.r.column(2).into_owned();
        let lin = z.cross(&(f.tcp.p - fr.p));
        j.fixed_view_mut::<3, 1>(0, i).copy_from(&lin);
        j.fixed_view_mut::<3, 1>(3, i).copy_from(&z);
    }
    j
}

/// Below this `sin θ` a rotation's axis is numerically undefined: the log map takes θ ≈ 0 or,
/// when `cos θ` is negative, θ ≈ π.
const SMALL_ROTATION: f64 = 1e-9;

/// Rotation vector of `R_target R_currentᵀ` (radians, world frame).
fn rotation_error(target: &Matrix3<f64>, current: &Matrix3<f64>) -> Vector3<f64> {
    let m = target * current.transpose();
    // log map: sin θ · axis = vee(M − Mᵀ)/2, cos θ = (tr M − 1)/2, θ = atan2(|v|, cos θ).
    let v = Vector3::new(
        m[(2, 1)] - m[(1, 2)],
        m[(0, 2)] - m[(2, 0)],
        m[(1, 0)] - m[(0, 1)],
    ) * 0.5;
    let s = norm3(&v);
    let c = 0.5 * (m.trace() - 1.0);
    if s < SMALL_ROTATION {
        if c > 0.0 {
            return v;
        }
        // θ ≈ π: fall back to the eigen-axis from nalgebra.
        return nalgebra::Rotation3::from_matrix_unchecked(m).scaled_axis();
    }
    v * (libm::atan2(s, c) / s)
}

/// Tunables of the IK solver.
#[derive(Clone, Debug, PartialEq)]
pub struct IkParams {
    /// Iterations per attempt (warm start and each restart).
    pub max_iterations: usize,
    /// Random restarts after the warm start fails.
    pub restarts: usize,
    /// Damping λ of the least-squares step (m / rad).
    pub damping: f64,
    /// Converged when the position error is below this (m).
    pub position_tolerance: f64,
    /// Converged when the orientation error is below this (rad).
    pub orientation_tolerance: f64,
    /// Gain of the null-space pull towards the middle of the joint ranges (1/iteration).
    pub null_space_gain: f64,
    /// Largest Cartesian correction per iteration (m, and rad for rotation).
    pub max_step: f64,
    /// Seed of the restart configurations.
    pub seed: u64,
}

impl Default for IkParams {
    fn default() -> Self {
        IkParams {
            max_iterations: 40,
            restarts: 6,
            damping: 0.005,
            position_tolerance: 5e-4,
            orientation_tolerance: 5e-3,
            null_space_gain: 0.05,
            max_step: 0.2,
            seed: 7,
        }
    }
}

/// A converged IK solution.
#[derive(Clone, Debug, PartialEq)]
pub struct IkSolution {
    /// Joint angles within the limits.
    pub joints: [f64; DOF],
    /// Remaining position error (m).
    pub position_error: f64,
    /// Remaining orientation error (rad).
    pub orientation_error: f64,
    /// Iterations used (over all attempts).
    pub iterations: usize,
}

/// IK did not reach the pose: the best configuration found and its residual.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("unreachable pose: best residual {position_error:.4} m, {orientation_error:.4} rad")]
pub struct Unreachable {
    /// Best joint angles found (within limits).
    pub best_joints: [f64; DOF],
    /// Position error of the best configuration (m).
    pub position_error: f64,
    /// Orientation error of the best configuration (rad).
    pub orientation_error: f64,
}

fn mid_joints() -> [f64; DOF] {
    let mut m = [0.0; DOF];
    for i in 0..DOF {
        m[i] = 0.5 * (JOINT_LOWER[i] + JOINT_UPPER[i]);
    }
    m
}

/// Clamps joint angles to the limits.
pub fn clamp_joints(q: &mut [f64; DOF]) {
    for i in 0..DOF {
        q[i] = q[i].clamp(JOINT_LOWER[i], JOINT_UPPER[i]);
    }
}

/// Weight of the orientation error against the position error when IK attempts are compared
/// (m per rad): the best attempt minimises `position error + weight · orientation error`.
const ORIENTATION_WEIGHT: f64 = 0.1;

/// One DLS attempt from `q`; returns (q, position error, orientation error, iterations).
/// `hold_limits`: a joint at a limit that a step drives further out is held there and left out
/// of that step's Jacobian, so the other joints take up its share (otherwise the step is
/// clamped afterwards, which leaves the TCP short of where it aimed, step after step).
fn dls_attempt(
    base: &Isometry3<f64>,
    target: &Frame,
    mut q: [f64; DOF],
    params: &IkParams,
    max_iterations: usize,
    hold_limits: bool,
) -> ([f64; DOF], f64, f64, usize) {
    let mid = mid_joints();
    let lambda2 = params.damping * params.damping;
    let mut best = (q, f64::INFINITY, f64::INFINITY);
    let mut best_score = f64::INFINITY;
    for it in 0..max_iterations {
        let f = forward_frames(base, &q);
        let ep = target.p - f.tcp.p;
        let er = rotation_error(&target.r, &f.tcp.r);
        let (np, nr) = (norm3(&ep), norm3(&er));
        let score = np + ORIENTATION_WEIGHT * nr;
        if score < best_score {
            best_score = score;
            best = (q, np, nr);
        }
        if np < params.position_tolerance && nr < params.orientation_tolerance {
            return (q, np, nr, it);
        }
        let mut e = Vector6::zeros();
        e.fixed_rows_mut::<3>(0)
            .copy_from(&(ep * (params.max_step / np.max(params.max_step))));
        e.fixed_rows_mut::<3>(3)
            .copy_from(&(er * (params.max_step / nr.max(params.max_step))));
        let full = jacobian(&f);
        let mut held = [false; DOF];
        let dq = loop {
            let mut j = full;
            for i in (0..DOF).filter(|&i| held[i]) {
                j.column_mut(i).fill(0.0);
            }
            let jjt: Matrix6<f64> = j * j.transpose() + Matrix6::identity() * lambda2;
            let Some(chol) = Cholesky::new(jjt) else {
                break None;
            };
            let y: Matrix6x1<f64> = chol.solve(&e);
            let mut dq = j.transpose() * y;
            // Null-space posture term: (I - J⁺J) k (q_mid - q), J⁺ = Jᵀ (JJᵀ + λ²I)⁻¹.
            let mut z = SMatrix::<f64, DOF, 1>::zeros();
            for i in (0..DOF).filter(|&i| !held[i]) {
                z[i] = params.null_space_gain * (mid[i] - q[i]);
            }
            let jz = j * z;
            let proj = j.transpose() * chol.solve(&jz);
            dq += z - proj;
            let mut newly_held = false;
            for i in (0..DOF).filter(|_| hold_limits) {
                let out = (q[i] >= JOINT_UPPER[i] && dq[i] > 0.0)
                    || (q[i] <= JOINT_LOWER[i] && dq[i] < 0.0);
                if out && !held[i] {
                    held[i] = true;
                    newly_held = true;
                }
            }
            if !newly_held {
                break Some(dq);
            }
        };
        let Some(dq) = dq else {
            break;
        };
        for i in 0..DOF {
            q[i] = (q[i] + dq[i]).clamp(JOINT_LOWER[i], JOINT_UPPER[i]);
        }
    }
    let f = forward_frames(base, &q);
    let np = norm3(&(target.p - f.tcp.p));
    let nr = norm3(&rotation_error(&target.r, &f.tcp.r));
    if np + ORIENTATION_WEIGHT * nr < best_score {
        best = (q, np, nr);
    }
    (best.0, best.1, best.2, max_iterations)
}

/// Inverse kinematics for a TCP pose, warm-started at `seed_joints`, with seeded random restarts.
pub fn inverse_kinematics(
    base: &Isometry3<f64>,
    target: &Isometry3<f64>,
    seed_joints: &[f64; DOF],
    params: &IkParams,
) -> Result<IkSolution, Unreachable> {
    let target = Frame::from_iso(target);
    let mut q0 = *seed_joints;
    clamp_joints(&mut q0);
    let mut total = 0;
    let (q, np, nr, it) = dls_attempt(base, &target, q0, params, params.max_iterations, false);
    total += it;
    let mut best = (q, np, nr);
    let ok = |np: f64, nr: f64| np < params.position_tolerance && nr < params.orientation_tolerance;
    if ok(np, nr) {
        return Ok(IkSolution {
            joints: q,
            position_error: np,
            orientation_error: nr,
            iterations: total,
        });
    }
    let mut rng = Pcg64Mcg::seed_from_u64(params.seed);
    for _ in 0..params.restarts {
        let mut qr = [0.0; DOF];
        for i in 0..DOF {
            // Sample the inner 80 % of each range, biased towards the ready posture.
            let (lo, hi) = (JOINT_LOWER[i], JOINT_UPPER[i]);
            let u: f64 = rng.random_range(0.1..0.9);
            qr[i] = 0.5 * (lo + u * (hi - lo)) + 0.5 * READY[i].clamp(lo, hi);
        }
        let (q, np, nr, it) =
            dls_attempt(base, &target, qr, params, params.max_iterations * 2, false);
        total += it;
        if ok(np, nr) {
            return Ok(IkSolution {
                joints: q,
                position_error: np,
                orientation_error: nr,
                iterations: total,
            });
        }
        if np + ORIENTATION_WEIGHT * nr < best.1 + ORIENTATION_WEIGHT * best.2 {
            best = (q, np, nr);
        }
    }
    Err(Unreachable {
        best_joints: best.0,
        position_error: best.1,
        orientation_error: best.2,
    })
}

/// Inverse kinematics for a TCP pose from `seed_joints` alone (no restarts), holding a joint
/// at a limit where a step would drive it further out: the solution nearest the seed where
/// [`inverse_kinematics`]' warm start stalls against a limit.
pub fn inverse_kinematics_near(
    base: &Isometry3<f64>,
    target: &Isometry3<f64>,
    seed_joints: &[f64; DOF],
    params: &IkParams,
) -> Result<IkSolution, Unreachable> {
    let mut q0 = *seed_joints;
    clamp_joints(&mut q0);
    let target = Frame::from_iso(target);
    let (q, np, nr, it) = dls_attempt(base, &target, q0, params, params.max_iterations, true);
    if np < params.position_tolerance && nr < params.orientation_tolerance {
        Ok(IkSolution {
            joints: q,
            position_error: np,
            orientation_error: nr,
            iterations: it,
        })
    } else {
        Err(Unreachable {
            best_joints: q,
            position_error: np,
            orientation_error: nr,
        })
    }
}

/// How far joints `q` are from their nearest limit, as a fraction of that joint's range (0 at a
/// limit, 0.5 in the middle of every range).
pub fn limit_margin(q: &[f64; DOF]) -> f64 {
    (0..DOF)
        .map(|i| {
            let range = JOINT_UPPER[i] - JOINT_LOWER[i];
            ((q[i] - JOINT_LOWER[i]).min(JOINT_UPPER[i] - q[i]) / range).max(0.0)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Largest joint step between the samples of a straight joint-space move checked for collisions
/// (rad): the executor's recovery and the streams' certification of it sample alike.
pub(crate) const JOINT_PATH_STEP: f64 = 0.05;

/// The samples of the straight joint-space move from `from` to `to`, at most
/// [`JOINT_PATH_STEP`] apart in every joint, `from` excluded and `to` included.
pub(crate) fn joint_line(from: &[f64; DOF], to: &[f64; DOF]) -> impl Iterator<Item = [f64; DOF]> {
    let (from, to) = (*from, *to);
    let span = from
        .iter()
        .zip(&to)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let n = ((span / JOINT_PATH_STEP).ceil() as usize).max(1);
    (1..=n).map(move |k| {
        let s = k as f64 / n as f64;
        let mut q = from;
        for (j, v) in q.iter_mut().enumerate() {
            *v += s * (to[j] - from[j]);
        }
        q
    })
}

/// One solution has more room to the limits than another only by more than this (a fraction
/// of a joint range): equal solutions keep the warm start's.
const MARGIN_EPSILON: f64 = 1e-9;

/// [`inverse_kinematics`] warm-started at `from` and again at [`READY`] (each with its restarts);
/// of the solutions found, the one farthest from the joint limits ([`limit_margin`]). For moves
/// in joint space that must leave the tracker room to follow on: a wrist recovered to its limit
/// stalls again. The executor's recovery and the streams' check of it both call this.
pub fn inverse_kinematics_with_room(
    base: &Isometry3<f64>,
    target: &Isometry3<f64>,
    from: &[f64; DOF],
    params: &IkParams,
) -> Result<IkSolution, Unreachable> {
    let mut best: Option<IkSolution> = None;
    let mut failure = None;
    for seed in [from, &READY] {
        match inverse_kinematics(base, target, seed, params) {
            Ok(sol) => {
                if best.as_ref().is_none_or(|b| {
                    limit_margin(&sol.joints) > limit_margin(&b.joints) + MARGIN_EPSILON
                }) {
                    best = Some(sol);
                }
            }
            Err(e) => failure = failure.or(Some(e)),
        }
    }
    if best.is_none() {
        // Near the edges of the workspace (a target just outside the minimum reach, the arm
        // folded) few random restarts converge: more of them, from other seeds, before giving up.
        let wide = IkParams {
            restarts: ROOMY_EXTRA_RESTARTS,
            seed: params.seed.wrapping_add(1),
            ..params.clone()
        };
        best = inverse_kinematics(base, target, &READY, &wide).ok();
    }
    best.ok_or_else(|| {
        failure.unwrap_or(Unreachable {
            best_joints: READY,
            position_error: f64::INFINITY,
            orientation_error: f64::INFINITY,
        })
    })
}

/// Random restarts of [`inverse_kinematics_with_room`]'s last try, when the warm start and the
/// ready posture (with their restarts) found nothing.
const ROOMY_EXTRA_RESTARTS: usize = 24;

/// A gripper orientation pointing straight down (`z` to −z world) with the fingers joined along the
/// world direction at angle `yaw` from +y.
pub fn down_orientation(yaw: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ready_pose_points_down_in_front() {
        let tcp = forward_kinematics(&Isometry3::identity(), &READY);
        let p = tcp.translation.vector;
        assert!((p.x - 0.307).abs() < 0.002, "{p}");
        assert!(p.y.abs() < 1e-9);
        assert!((p.z - (0.5903 - TCP_OFFSET)).abs() < 0.003, "{p}");
        let z = tcp.rotation * Vector3::z();
        assert!((z + Vector3::z()).norm() < 1e-9, "{z}");
    }

    #[test]
    fn ik_with_room_keeps_away_from_the_limits_the_warm_start_sticks_to() {
        // A wrist at its limit: the warm start keeps it there; the ready seed finds the same
        // pose with room on every joint.
        let base = Isometry3::identity();
        let mut wound = READY;
        wound[6] = JOINT_UPPER[6] - 0.01;
        wound[0] = 0.4;
        let target = forward_kinematics(&base, &wound);
        let p = IkParams::default();
        let warm = inverse_kinematics(&base, &target, &wound, &p).unwrap();
        assert!(limit_margin(&warm.joints) < 0.01);
        let roomy = inverse_kinematics_with_room(&base, &target, &wound, &p).unwrap();
        let reached = forward_kinematics(&base, &roomy.joints);
        assert!((reached.translation.vector - target.translation.vector).norm() < 1e-3);
        assert!((reached.rotation.inverse() * target.rotation).angle() < 1e-2);
        assert!(
            limit_margin(&roomy.joints) > 0.05,
            "{:?} has margin {}",
            roomy.joints,
            limit_margin(&roomy.joints)
        );
    }

    #[test]
    fn holding_a_joint_at_its_limit_leaves_the_others_to_reach_the_target() {
        // Targets reachable with one joint at a limit, from warm starts beside them with that
        // joint at the limit too. Where a step drives it further out, the other joints must
        // make up its share.
        let base = Isometry3::identity();
        let p = IkParams {
            restarts: 0,
            max_iterations: 100,
            ..IkParams::default()
        };
        let mut rng = Pcg64Mcg::seed_from_u64(7);
        let (mut warm, mut near) = (0, 0);
        let cases = 300;
        for _ in 0..cases {
            let mut q = [0.0; DOF];
            for i in 0..DOF {
                q[i] = rng.random_range(JOINT_LOWER[i] + 0.3..JOINT_UPPER[i] - 0.3);
            }
            let k = rng.random_range(0..DOF);
            q[k] = if rng.random_bool(0.5) {
                JOINT_LOWER[k]
            } else {
                JOINT_UPPER[k]
            };
            let target = forward_kinematics(&base, &q);
            let mut seed = q;
            for i in (0..DOF).filter(|&i| i != k) {
                seed[i] += rng.random_range(-0.15..0.15);
            }
            warm += inverse_kinematics(&base, &target, &seed, &p).is_ok() as usize;
            if let Ok(sol) = inverse_kinematics_near(&base, &target, &seed, &p) {
                let reached = forward_kinematics(&base, &sol.joints);
                assert!((reached.translation.vector - target.translation.vector).norm() < 1e-3);
                near += 1;
            }
        }
        assert_eq!(near, cases, "warm start {warm} of {cases}");
        // The plain warm start stalls on some of them: the cases test the hold.
        assert!(warm < cases);
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let q = [0.3, -0.2, 0.4, -1.9, 0.2, 1.7, 0.5];
        let f = forward_frames(&Isometry3::identity(), &q);
        let j = jacobian(&f);
        let h = 1e-7;
        for i in 0..DOF {
            let mut qh = q;
            qh[i] += h;
            let fh = forward_frames(&Isometry3::identity(), &qh);
            let dp = (fh.tcp.p - f.tcp.p) / h;
            assert!((dp - j.fixed_view::<3, 1>(0, i)).norm() < 1e-5, "joint {i}");
            let dr = rotation_error(&fh.tcp.r, &f.tcp.r) / h;
            assert!((dr - j.fixed_view::<3, 1>(3, i)).norm() < 1e-5, "joint {i}");
        }
    }
}
