//! Damped-least-squares inverse kinematics of an [`ArmModel`], with a null-space pull towards
//! the middle of the joint ranges.
//!
//! With the task error `e = [p* − p; log(R* Rᵀ)]` (position in metres, rotation vector in
//! radians),
//!
//! ```text
//! Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e  +  (I − J⁺J) k_ns (q_mid − q),    q ← clamp(q + Δq, q_min, q_max)
//! ```
//!
//! iterated from a warm start (the arm's current joints); if that does not converge, restarts from
//! seeded random configurations. Failure returns the best residual found, so "unreachable" is a
//! clear answer and not a silent approximation. The unused entries of a 6-joint arm's joint
//! vector have a zero Jacobian column and the range `[0, 0]`: they stay 0.

use nalgebra::{Isometry3, Matrix3, Matrix6, Matrix6x1, SMatrix, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::arm::ArmModel;
use crate::sim::fast_math::{norm3, Cholesky};
use crate::sim::panda::Frame;
use crate::sim::panda::DOF;

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

impl IkSolution {
    fn of(
        joints: [f64; DOF],
        position_error: f64,
        orientation_error: f64,
        iterations: usize,
    ) -> Self {
        IkSolution {
            joints,
            position_error,
            orientation_error,
            iterations,
        }
    }
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

/// Weight of the orientation error against the position error when IK attempts are compared
/// (m per rad): the best attempt minimises `position error + weight · orientation error`.
const ORIENTATION_WEIGHT: f64 = 0.1;

/// One DLS attempt from `q`; returns (q, position error, orientation error, iterations).
/// `hold_limits`: a joint at a limit that a step drives further out is held there and left out
/// of that step's Jacobian, so the other joints take up its share (otherwise the step is
/// clamped afterwards, which leaves the TCP short of where it aimed, step after step).
fn dls_attempt(
    arm: &ArmModel,
    base: &Isometry3<f64>,
    target: &Frame,
    mut q: [f64; DOF],
    params: &IkParams,
    max_iterations: usize,
    hold_limits: bool,
) -> ([f64; DOF], f64, f64, usize) {
    let mid = arm.mid();
    let lambda2 = params.damping * params.damping;
    let mut best = (q, f64::INFINITY, f64::INFINITY);
    let mut best_score = f64::INFINITY;
    for it in 0..max_iterations {
        let (tcp, full) = arm.tcp_and_jacobian(base, &q);
        let ep = target.p - tcp.p;
        let er = rotation_error(&target.r, &tcp.r);
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
                let out =
                    (q[i] >= arm.upper[i] && dq[i] > 0.0) || (q[i] <= arm.lower[i] && dq[i] < 0.0);
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
            q[i] = (q[i] + dq[i]).clamp(arm.lower[i], arm.upper[i]);
        }
    }
    let tcp = arm.tcp_frame(base, &q);
    let np = norm3(&(target.p - tcp.p));
    let nr = norm3(&rotation_error(&target.r, &tcp.r));
    if np + ORIENTATION_WEIGHT * nr < best_score {
        best = (q, np, nr);
    }
    (best.0, best.1, best.2, max_iterations)
}

impl ArmModel {
    /// Inverse kinematics for a TCP pose, warm-started at `seed_joints`, with seeded random restarts.
    pub fn inverse_kinematics(
        &self,
        base: &Isometry3<f64>,
        target: &Isometry3<f64>,
        seed_joints: &[f64; DOF],
        params: &IkParams,
    ) -> Result<IkSolution, Unreachable> {
        let target = Frame::from_iso(target);
        let mut q0 = *seed_joints;
        self.clamp(&mut q0);
        let mut total = 0;
        let (q, np, nr, it) = dls_attempt(
            self,
            base,
            &target,
            q0,
            params,
            params.max_iterations,
            false,
        );
        total += it;
        let mut best = (q, np, nr);
        let ok =
            |np: f64, nr: f64| np < params.position_tolerance && nr < params.orientation_tolerance;
        if ok(np, nr) {
            return Ok(IkSolution::of(q, np, nr, total));
        }
        let mut rng = Pcg64Mcg::seed_from_u64(params.seed);
        for _ in 0..params.restarts {
            let mut qr = [0.0; DOF];
            for i in 0..DOF {
                // Sample the inner 80 % of each range, biased towards the ready posture.
                let (lo, hi) = (self.lower[i], self.upper[i]);
                let u: f64 = rng.random_range(0.1..0.9);
                qr[i] = 0.5 * (lo + u * (hi - lo)) + 0.5 * self.ready[i].clamp(lo, hi);
            }
            let (q, np, nr, it) = dls_attempt(
                self,
                base,
                &target,
                qr,
                params,
                params.max_iterations * 2,
                false,
            );
            total += it;
            if ok(np, nr) {
                return Ok(IkSolution::of(q, np, nr, total));
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
    /// [`ArmModel::inverse_kinematics`]' warm start stalls against a limit.
    pub fn inverse_kinematics_near(
        &self,
        base: &Isometry3<f64>,
        target: &Isometry3<f64>,
        seed_joints: &[f64; DOF],
        params: &IkParams,
    ) -> Result<IkSolution, Unreachable> {
        let mut q0 = *seed_joints;
        self.clamp(&mut q0);
        let target = Frame::from_iso(target);
        let (q, np, nr, it) =
            dls_attempt(self, base, &target, q0, params, params.max_iterations, true);
        if np < params.position_tolerance && nr < params.orientation_tolerance {
            Ok(IkSolution::of(q, np, nr, it))
        } else {
            Err(Unreachable {
                best_joints: q,
                position_error: np,
                orientation_error: nr,
            })
        }
    }

    /// [`ArmModel::inverse_kinematics`] warm-started at `from` and again at the ready posture (each with its restarts);
    /// of the solutions found, the one farthest from the joint limits ([`ArmModel::limit_margin`]). For moves
    /// in joint space that must leave the tracker room to follow on: a wrist recovered to its limit
    /// stalls again. The executor's recovery and the streams' check of it both call this.
    pub fn inverse_kinematics_with_room(
        &self,
        base: &Isometry3<f64>,
        target: &Isometry3<f64>,
        from: &[f64; DOF],
        params: &IkParams,
    ) -> Result<IkSolution, Unreachable> {
        let mut best: Option<IkSolution> = None;
        let mut failure = None;
        for seed in [from, &self.ready] {
            match self.inverse_kinematics(base, target, seed, params) {
                Ok(sol) => {
                    if best.as_ref().is_none_or(|b| {
                        self.limit_margin(&sol.joints)
                            > self.limit_margin(&b.joints) + MARGIN_EPSILON
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
            best = self
                .inverse_kinematics(base, target, &self.ready, &wide)
                .ok();
        }
        best.ok_or_else(|| {
            failure.unwrap_or(Unreachable {
                best_joints: self.ready,
                position_error: f64::INFINITY,
                orientation_error: f64::INFINITY,
            })
        })
    }
}

/// One solution has more room to the limits than another only by more than this (a fraction
/// of a joint range): equal solutions keep the warm start's.
const MARGIN_EPSILON: f64 = 1e-9;

/// Random restarts of [`inverse_kinematics_with_room`]'s last try, when the warm start and the
/// ready posture (with their restarts) found nothing.
const ROOMY_EXTRA_RESTARTS: usize = 24;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::panda::{
        forward_frames, forward_kinematics, jacobian, JOINT_LOWER, JOINT_UPPER, READY,
    };

    #[test]
    fn ik_with_room_keeps_away_from_the_limits_the_warm_start_sticks_to() {
        // A wrist at its limit: the warm start keeps it there; the ready seed finds the same
        // pose with room on every joint.
        let arm = ArmModel::panda();
        let base = Isometry3::identity();
        let mut wound = READY;
        wound[6] = JOINT_UPPER[6] - 0.01;
        wound[0] = 0.4;
        let target = forward_kinematics(&base, &wound);
        let p = IkParams::default();
        let warm = arm.inverse_kinematics(&base, &target, &wound, &p).unwrap();
        assert!(arm.limit_margin(&warm.joints) < 0.01);
        let roomy = arm
            .inverse_kinematics_with_room(&base, &target, &wound, &p)
            .unwrap();
        let reached = forward_kinematics(&base, &roomy.joints);
        assert!((reached.translation.vector - target.translation.vector).norm() < 1e-3);
        assert!((reached.rotation.inverse() * target.rotation).angle() < 1e-2);
        assert!(
            arm.limit_margin(&roomy.joints) > 0.05,
            "{:?} has margin {}",
            roomy.joints,
            arm.limit_margin(&roomy.joints)
        );
    }

    #[test]
    fn holding_a_joint_at_its_limit_leaves_the_others_to_reach_the_target() {
        // Targets reachable with one joint at a limit, from warm starts beside them with that
        // joint at the limit too. Where a step drives it further out, the other joints must
        // make up its share.
        let arm = ArmModel::panda();
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
            warm += arm.inverse_kinematics(&base, &target, &seed, &p).is_ok() as usize;
            if let Ok(sol) = arm.inverse_kinematics_near(&base, &target, &seed, &p) {
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
