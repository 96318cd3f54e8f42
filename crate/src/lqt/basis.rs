//! Basis functions of the control primitives (paper §III-B): `u_t = Σ_k φ_k(s_t) w_k`.
//!
//! The basis matrix `φ` is N×K, evaluated on the control steps at `s_j = j/(N-1)`,
//! `j = 0..N-1` (N = T-1 controls):
//!
//! * `rbf`: `φ_k(s) = exp(-λ (s - c_k)²)`, centers `c_k` and λ given;
//! * `bernstein`: `φ_k(s) = C(K-1,k) (1-s)^(K-1-k) s^k`;
//! * `fourier`: `φ_k(s) = cos(2π k s)`, k = 0..K-1;
//! * `piecewise`: `φ_k(s_j) = 1` if `⌊j/L⌋ = k` else 0, with `L = ⌈N/K⌉`.
//!
//! The stacked controls are `u = Ψ vec(w)` with `Ψ = φ ⊗ I_D` (w stored K×D).

use super::LqtError;
use serde::{Deserialize, Serialize};

/// A family of K basis functions on the normalised time `s ∈ [0, 1]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum Basis {
    /// Radial basis functions `exp(-λ (s - c_k)²)`.
    Rbf {
        /// K, the number of functions.
        n_fct: usize,
        /// The K centers `c_k` (normalised time, usually `linspace(0, 1, K)`).
        centers: Vec<f64>,
        /// Width parameter λ (1/normalised-time²), > 0.
        lambda: f64,
    },
    /// Bernstein polynomials of degree K-1.
    Bernstein {
        /// K, the number of functions.
        n_fct: usize,
    },
    /// Cosines `cos(2π k s)`, k = 0..K-1.
    Fourier {
        /// K, the number of functions.
        n_fct: usize,
    },
    /// Piecewise-constant windows of `L = ⌈N/K⌉` control steps (K = N gives Ψ = I).
    Piecewise {
        /// K, the number of functions.
        n_fct: usize,
    },
}

impl Basis {
    /// RBFs with centers `linspace(0, 1, K)` and width λ.
    pub fn rbf_uniform(n_fct: usize, lambda: f64) -> Basis {
        let centers = if n_fct == 1 {
            vec![0.5]
        } else {
            (0..n_fct).map(|k| k as f64 / (n_fct - 1) as f64).collect()
        };
        Basis::Rbf {
            n_fct,
            centers,
            lambda,
        }
    }

    /// K, the number of basis functions.
    pub fn n_fct(&self) -> usize {
        match self {
            Basis::Rbf { n_fct, .. }
            | Basis::Bernstein { n_fct }
            | Basis::Fourier { n_fct }
            | Basis::Piecewise { n_fct } => *n_fct,
        }
    }

    /// The name used in JSON (`rbf`, `bernstein`, `fourier`, `piecewise`).
    pub fn name(&self) -> &'static str {
        match self {
            Basis::Rbf { .. } => "rbf",
            Basis::Bernstein { .. } => "bernstein",
            Basis::Fourier { .. } => "fourier",
            Basis::Piecewise { .. } => "piecewise",
        }
    }

    /// Check the basis against `n_controls` = N control steps (K ≤ N, N ≥ 2, finite parameters,
    /// no piecewise window left empty).
    pub fn validate(&self, n_controls: usize) -> Result<(), LqtError> {
        let k = self.n_fct();
        if k == 0 {
            return Err(LqtError::input("basis.n_fct", "expected at least 1, got 0"));
        }
        if k > n_controls {
            return Err(LqtError::input(
                "basis.n_fct",
                format!(
                    "K = {k} is larger than the number of controls N = n_steps - 1 = {n_controls}"
                ),
            ));
        }
        match self {
            Basis::Rbf {
                centers, lambda, ..
            } => {
                if centers.len() != k {
                    return Err(LqtError::input(
                        "basis.centers",
                        format!("expected {k} numbers (n_fct), got {}", centers.len()),
                    ));
                }
                if let Some(i) = centers.iter().position(|c| !c.is_finite()) {
                    return Err(LqtError::input(
                        format!("basis.centers[{i}]"),
                        "expected a finite number",
                    ));
                }
                if !(lambda.is_finite() && *lambda > 0.0) {
                    return Err(LqtError::input(
                        "basis.lambda",
                        format!("expected a finite positive number, got {lambda}"),
                    ));
                }
            }
            Basis::Piecewise { .. } => {
                let l = n_controls.div_ceil(k);
                if (k - 1) * l >= n_controls {
                    return Err(LqtError::input(
                        "basis.n_fct",
                        format!(
                            "piecewise with K = {k} over N = {n_controls} controls leaves function {} empty (L = ceil(N/K) = {l})",
                            k - 1
                        ),
                    ));
                }
            }
            Basis::Bernstein { .. } | Basis::Fourier { .. } => {}
        }
        Ok(())
    }

    /// `φ(s)` for one normalised time `s`, written into `out` (length K).
    pub fn eval_into(&self, s: f64, out: &mut [f64]) {
        let k_n = self.n_fct();
        match self {
            Basis::Rbf {
                centers, lambda, ..
            } => {
                for (o, c) in out.iter_mut().zip(centers) {
                    *o = libm::exp(-lambda * (s - c) * (s - c));
                }
            }
            Basis::Bernstein { .. } => {
                let deg = k_n - 1;
                for (k, o) in out.iter_mut().enumerate() {
                    *o = binomial(deg, k) * (1.0 - s).powi((deg - k) as i32) * s.powi(k as i32);
                }
            }
            Basis::Fourier { .. } => {
                for (k, o) in out.iter_mut().enumerate() {
                    *o = libm::cos(2.0 * std::f64::consts::PI * k as f64 * s);
                }
            }
            Basis::Piecewise { .. } => {
                // Only meaningful on the grid; see `matrix`. Off the grid: nearest window.
                let active = ((s * k_n as f64).floor() as usize).min(k_n - 1);
                for (k, o) in out.iter_mut().enumerate() {
                    *o = if k == active { 1.0 } else { 0.0 };
                }
            }
        }
    }

    /// The N×K matrix `φ` on `s_j = j/(N-1)`, row-major. Call [`Basis::validate`] first.
    pub fn matrix(&self, n_controls: usize) -> Vec<f64> {
        let k_n = self.n_fct();
        let mut phi = vec![0.0; n_controls * k_n];
        match self {
            Basis::Piecewise { .. } => {
                let l = n_controls.div_ceil(k_n);
                for j in 0..n_controls {
                    let k = j / l;
                    if k < k_n {
                        phi[j * k_n + k] = 1.0;
                    }
                }
            }
            _ => {
                let denom = (n_controls.max(2) - 1) as f64;
                for j in 0..n_controls {
                    let s = j as f64 / denom;
                    self.eval_into(s, &mut phi[j * k_n..(j + 1) * k_n]);
                }
            }
        }
        phi
    }
}

/// `C(n, k)` as a float (exact for the small n used here).
fn binomial(n: usize, k: usize) -> f64 {
    let k = k.min(n - k);
    let mut c = 1.0;
    for i in 0..k {
        c = c * (n - i) as f64 / (i + 1) as f64;
    }
    c.round()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bernstein_rows_sum_to_one() {
        let b = Basis::Bernstein { n_fct: 6 };
        let phi = b.matrix(20);
        for j in 0..20 {
            let s: f64 = phi[j * 6..(j + 1) * 6].iter().sum();
            assert!((s - 1.0).abs() < 1e-12);
        }
        assert_eq!(binomial(9, 4), 126.0);
    }

    #[test]
    fn piecewise_windows_and_empty_window_refused() {
        let b = Basis::Piecewise { n_fct: 4 };
        b.validate(10).unwrap();
        let phi = b.matrix(10);
        // L = 3: rows 0..3 -> 0, 3..6 -> 1, 6..9 -> 2, 9 -> 3
        assert_eq!(phi[9 * 4 + 3], 1.0);
        assert_eq!(phi[5 * 4 + 1], 1.0);
        assert!(Basis::Piecewise { n_fct: 6 }.validate(10).is_err());
        assert!(Basis::Piecewise { n_fct: 10 }.validate(10).is_ok());
    }

    #[test]
    fn fourier_first_is_constant_and_k_larger_than_n_refused() {
        let b = Basis::Fourier { n_fct: 3 };
        let phi = b.matrix(5);
        assert!((0..5).all(|j| phi[j * 3] == 1.0));
        assert!(Basis::Fourier { n_fct: 6 }.validate(5).is_err());
    }
}
