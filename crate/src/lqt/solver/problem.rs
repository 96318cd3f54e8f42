//! The LQT-CP problem with its μ-independent precomputation, and its solutions.

use super::config::LqtConfig;
use crate::lqt::linalg::Qr;
use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

/// What one group of coordinates with identical weights q shares (nothing here depends on μ).
#[derive(Debug, Clone)]
pub(super) struct Group {
    /// Householder QR of the stacked least-squares matrix `[√q ⊙ Su1 φ ; √r φ]` (m×K).
    pub(super) qr: Qr,
    /// The weighted rows of the stack: `(t, i, √q_{t,i})` for every q > 0 (t ≥ 1), then K rows
    /// `√r R_φ` when r > 0 (`φ = Q_φ R_φ`, so that `r φᵀφ = r R_φᵀ R_φ` with K rows instead of N).
    pub(super) rows: Vec<(usize, usize, f64)>,
    /// Number of rows m of the stack.
    pub(super) m: usize,
    /// `W^x = H⁻¹ φᵀ Su1ᵀ Q Sx1` (K×n).
    pub(super) wx: Vec<f64>,
    /// State part of F: `F^x = φ H_d⁻¹ φᵀ Su1ᵀ Q_d Sx1` (N×n).
    pub(super) fx: Vec<f64>,
    /// State part of the gains `k_t = F^x_t (Φ^x_t)⁻¹` (N×n).
    pub(super) kx: Vec<f64>,
}

/// An LQT-CP problem with everything that does not depend on the reference μ precomputed.
///
/// Build it once per skill (weights q, basis and dynamics fixed); then [`LqtCp::solve`] and
/// [`LqtCp::feedback`] for any μ (new goal, new object pose) only redo the μ-dependent parts.
#[derive(Debug, Clone)]
pub struct LqtCp {
    pub(super) config: LqtConfig,
    pub(super) a1: Vec<f64>,
    pub(super) b1: Vec<f64>,
    /// φ, N×K row-major.
    pub(super) phi: Vec<f64>,
    /// `q` row-major T×nx.
    pub(super) q: Vec<f64>,
    /// Coordinate → index in `groups`.
    pub(super) group_of: Vec<usize>,
    pub(super) groups: Vec<Group>,
}

/// The batch (open-loop) solution from `x_0`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BatchSolution {
    /// Basis weights w (K×D).
    pub w: DMatrix<f64>,
    /// Controls `u_t = Σ_k φ_tk w_k` (N×D).
    pub u: DMatrix<f64>,
    /// States `x_0..x_{T-1}` (T×nx).
    pub x: DMatrix<f64>,
    /// The cost J of this solution.
    pub cost: f64,
}

/// States and controls of a closed-loop rollout.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Rollout {
    /// States `x_0..x_{T-1}` (T×nx).
    pub x: DMatrix<f64>,
    /// Controls `u_0..u_{N-1}` (N×D).
    pub u: DMatrix<f64>,
}

/// Whether every entry is finite.
pub(super) fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// One integrator step of one coordinate: `x ← A1 x + B1 u`.
#[inline]
pub(super) fn step1(a1: &[f64], b1: &[f64], x: &mut [f64], u: f64) {
    let n = x.len();
    for i in 0..n {
        let mut s = b1[i] * u;
        for j in i..n {
            s += a1[i * n + j] * x[j];
        }
        x[i] = s;
    }
}
