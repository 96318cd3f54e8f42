//! The fixed parameters of an LQT-CP problem (dynamics `A = A1 ⊗ I_D`, `B = B1 ⊗ I_D` of an
//! n-th order integrator, horizon T, control weight `R = r I`, basis φ) and the checks of every
//! input matrix and vector, whose errors name the offending key.

use super::super::basis::Basis;
use super::super::dynamics::dense_ab;
use super::super::LqtError;
use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

/// A perturbation added to the state part of `x̃_{after_step+1}`, just after the update.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Perturbation {
    /// Control step t after whose update the perturbation hits (0..N-1).
    pub after_step: usize,
    /// Added state (nx, derivative-major).
    pub delta: Vec<f64>,
}

/// Highest integrator order accepted (6: up to the 5th derivative in the state).
pub const MAX_ORDER: usize = 6;

/// The problem's fixed parameters: dynamics, horizon, control weight and basis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LqtConfig {
    /// D, number of position coordinates (also the control dimension).
    pub dim: usize,
    /// n, integrator order: 1 velocity, 2 acceleration, 3 jerk commands (1..=6).
    pub order: usize,
    /// Time step (s), > 0.
    pub dt: f64,
    /// T, number of states `x_0..x_{T-1}` (≥ 3); there are N = T-1 controls.
    pub n_steps: usize,
    /// Control weight r (R = r I), ≥ 0.
    pub r: f64,
    /// Basis functions of the control primitives.
    pub basis: Basis,
}

impl LqtConfig {
    /// State size `nx = D n`.
    pub fn nx(&self) -> usize {
        self.dim * self.order
    }

    /// N = T - 1, the number of controls.
    pub fn n_controls(&self) -> usize {
        self.n_steps.saturating_sub(1)
    }

    /// Check every parameter; the error names the offending key.
    pub fn validate(&self) -> Result<(), LqtError> {
        if self.dim == 0 {
            return Err(LqtError::input("dim", "expected at least 1, got 0"));
        }
        if self.order == 0 || self.order > MAX_ORDER {
            return Err(LqtError::input(
                "order",
                format!(
                    "expected an integrator order in 1..={MAX_ORDER}, got {}",
                    self.order
                ),
            ));
        }
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(LqtError::input(
                "dt",
                format!("expected a finite positive time step, got {}", self.dt),
            ));
        }
        if self.n_steps < 3 {
            return Err(LqtError::input(
                "n_steps",
                format!("expected at least 3 states, got {}", self.n_steps),
            ));
        }
        if !(self.r.is_finite() && self.r >= 0.0) {
            return Err(LqtError::input(
                "r",
                format!(
                    "expected a finite non-negative control weight, got {}",
                    self.r
                ),
            ));
        }
        self.basis.validate(self.n_controls())
    }

    /// `A = A1 ⊗ I_D` (nx×nx).
    pub fn a_matrix(&self) -> DMatrix<f64> {
        dense_ab(self.dim, self.order, self.dt).0
    }

    /// `B = B1 ⊗ I_D` (nx×D).
    pub fn b_matrix(&self) -> DMatrix<f64> {
        dense_ab(self.dim, self.order, self.dt).1
    }

    /// The basis matrix φ (N×K).
    pub fn phi_matrix(&self) -> DMatrix<f64> {
        let n = self.n_controls();
        let k = self.basis.n_fct();
        DMatrix::from_row_slice(n, k, &self.basis.matrix(n))
    }
}

/// Check that `m` is `rows×cols`, finite, and (if `nonneg`) without negative entries.
pub(crate) fn check_matrix(
    key: &str,
    m: &DMatrix<f64>,
    rows: usize,
    cols: usize,
    nonneg: bool,
) -> Result<(), LqtError> {
    if m.nrows() != rows || m.ncols() != cols {
        return Err(LqtError::input(
            key,
            format!(
                "expected {rows} rows of {cols} numbers, got {}×{}",
                m.nrows(),
                m.ncols()
            ),
        ));
    }
    for r in 0..rows {
        for c in 0..cols {
            let v = m[(r, c)];
            if !v.is_finite() {
                return Err(LqtError::input(
                    format!("{key}[{r}][{c}]"),
                    format!("expected a finite number, got {v}"),
                ));
            }
            if nonneg && v < 0.0 {
                return Err(LqtError::input(
                    format!("{key}[{r}][{c}]"),
                    format!("expected a non-negative weight, got {v}"),
                ));
            }
        }
    }
    Ok(())
}

/// Check that a state vector has `nx` finite entries.
pub(crate) fn check_vector(key: &str, v: &[f64], len: usize) -> Result<(), LqtError> {
    if v.len() != len {
        return Err(LqtError::input(
            key,
            format!("expected {len} numbers, got {}", v.len()),
        ));
    }
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        return Err(LqtError::input(
            format!("{key}[{i}]"),
            format!("expected a finite number, got {}", v[i]),
        ));
    }
    Ok(())
}

/// Check a perturbation's step and shape.
pub(crate) fn check_perturbation(p: &Perturbation, nx: usize, nc: usize) -> Result<(), LqtError> {
    if p.after_step >= nc {
        return Err(LqtError::input(
            "feedback.perturbation.after_step",
            format!(
                "expected a control step in 0..{} (N - 1 = {}), got {}",
                nc,
                nc - 1,
                p.after_step
            ),
        ));
    }
    check_vector("feedback.perturbation.delta", &p.delta, nx)
}
