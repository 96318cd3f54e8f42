//! The batch solution of LQT-CP (paper eqs. 1–3; conventions of `docs/formats.md`):
//!
//! ```text
//! J = Σ_{t<T} (x_t-μ_t)ᵀ Q_t (x_t-μ_t) + r Σ_{t<N} |u_t|²,     Q_t = diag(q_t)
//! x = Sx x_0 + Su u,   u = Ψ w,   Ψ = φ ⊗ I_D
//! H = Ψᵀ Suᵀ Q Su Ψ + r ΨᵀΨ,      w = H⁻¹ Ψᵀ Suᵀ Q (μ - Sx x_0)
//! ```
//!
//! [`LqtCp::new`] precomputes what does not depend on μ, one group of coordinates with equal
//! weights at a time (`Y = Su1 φ`, the QR factorisation of `M = [√q ⊙ Su1 φ ; √r φ]`, `W^x`,
//! `F^x` and the gains' state part); [`LqtCp::solve`] is one least-squares solve per coordinate.

use super::super::basis::Basis;
use super::super::dynamics::integrator;
use super::super::linalg::{solve_small_transposed, Qr};
use super::super::LqtError;
use super::config::{check_matrix, check_vector, LqtConfig};
use super::problem::{all_finite, step1, BatchSolution, Group, LqtCp};
use nalgebra::DMatrix;

impl LqtCp {
    /// Validate the configuration and the weights `q_diag` (T×nx, ≥ 0) and precompute everything
    /// that does not depend on μ: `Su1 φ`, the factorisation of each coordinate's least-squares
    /// problem, the state part of F and of the gains.
    pub fn new(config: LqtConfig, q_diag: &DMatrix<f64>) -> Result<LqtCp, LqtError> {
        config.validate()?;
        let (dim, n, t_n) = (config.dim, config.order, config.n_steps);
        let nx = dim * n;
        let nc = t_n - 1;
        let k_n = config.basis.n_fct();
        check_matrix("reference.q_diag", q_diag, t_n, nx, true)?;
        let (a1, b1) = integrator(n, config.dt);
        let phi = config.basis.matrix(nc);
        let mut q = vec![0.0; t_n * nx];
        for t in 0..t_n {
            for c in 0..nx {
                q[t * nx + c] = q_diag[(t, c)];
            }
        }

        let (y, z) = integrate_basis(&a1, &b1, &phi, n, k_n, t_n);
        let r_phi = basis_r_factor(&config, &phi, nc, k_n)?;
        let mut group_of = Vec::with_capacity(dim);
        let mut reps: Vec<usize> = Vec::new();
        let mut groups = Vec::new();
        for d in 0..dim {
            let same = reps.iter().position(|&e| {
                (0..t_n).all(|t| (0..n).all(|i| q[t * nx + i * dim + d] == q[t * nx + i * dim + e]))
            });
            if let Some(g) = same {
                group_of.push(g);
                continue;
            }
            group_of.push(groups.len());
            reps.push(d);
            groups.push(Self::build_group(
                &config, &a1, &b1, &phi, &r_phi, &y, &z, &q, d,
            )?);
        }
        Ok(LqtCp {
            config,
            a1,
            b1,
            phi,
            q,
            group_of,
            groups,
        })
    }

    /// The shared part of the coordinates whose weights equal those of coordinate `d`: the QR
    /// factorisation of their stacked least-squares matrix, `W^x`, `F^x` and the gains' `k_t`.
    #[allow(clippy::too_many_arguments)]
    fn build_group(
        config: &LqtConfig,
        a1: &[f64],
        b1: &[f64],
        phi: &[f64],
        r_phi: &[f64],
        y: &[f64],
        z: &[f64],
        q: &[f64],
        d: usize,
    ) -> Result<Group, LqtError> {
        let (n, t_n) = (config.order, config.n_steps);
        let nc = t_n - 1;
        let k_n = config.basis.n_fct();
        let rows = weighted_rows(config, q, d);
        let m = rows.len() + if config.r > 0.0 { k_n } else { 0 };
        let singular = || {
            LqtError::Singular(format!(
                "H = Ψᵀ Suᵀ Q Su Ψ + r ΨᵀΨ is singular for coordinate {d}: the weights q and r do not determine the {k_n} basis weights"
            ))
        };
        if m < k_n {
            return Err(singular());
        }
        let mat = stacked_matrix(config, &rows, y, r_phi, m);
        if !all_finite(&mat) {
            return Err(LqtError::NonFinite(
                "the weighted matrix √Q Su Ψ overflowed (weights q too large)".into(),
            ));
        }
        let qr = Qr::new(mat, m, k_n).ok_or_else(singular)?;
        let wx = state_weights(&qr, &rows, z, n, k_n, m);
        let fx = state_controls(phi, &wx, n, k_n, nc);
        let kx = state_gains(config, a1, b1, &fx, d)?;
        if !(all_finite(&fx) && all_finite(&kx)) {
            return Err(LqtError::NonFinite(
                "the state part of F or of the gains is not finite".into(),
            ));
        }
        Ok(Group {
            qr,
            rows,
            m,
            wx,
            fx,
            kx,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &LqtConfig {
        &self.config
    }

    /// The weights `q_diag` (T×nx).
    pub fn q_diag(&self) -> DMatrix<f64> {
        let nx = self.config.nx();
        DMatrix::from_row_slice(self.config.n_steps, nx, &self.q)
    }

    /// Least-squares weights of coordinate d for the target `tgt(t, i)` on the weighted rows:
    /// `H_d⁻¹ φᵀ Su1ᵀ Q_d tgt` (K).
    pub(super) fn solve_coord(&self, d: usize, tgt: impl Fn(usize, usize) -> f64) -> Vec<f64> {
        let grp = &self.groups[self.group_of[d]];
        let mut b = vec![0.0; grp.m];
        for (ri, &(t, i, s)) in grp.rows.iter().enumerate() {
            b[ri] = s * tgt(t, i);
        }
        grp.qr.solve_ls(&mut b);
        b.truncate(self.config.basis.n_fct());
        b
    }

    /// The batch solution from `x0` (nx) tracking `mu` (T×nx).
    pub fn solve(&self, mu: &DMatrix<f64>, x0: &[f64]) -> Result<BatchSolution, LqtError> {
        let cfg = &self.config;
        let (dim, n, t_n) = (cfg.dim, cfg.order, cfg.n_steps);
        let nx = dim * n;
        let nc = t_n - 1;
        let k_n = cfg.basis.n_fct();
        check_matrix("reference.mu", mu, t_n, nx, false)?;
        check_vector("x0", x0, nx)?;
        let mut w = DMatrix::zeros(k_n, dim);
        let mut u = DMatrix::zeros(nc, dim);
        let mut x = DMatrix::zeros(t_n, nx);
        let mut free = vec![0.0; t_n * n];
        let mut xd = vec![0.0; n];
        for d in 0..dim {
            // Free motion A1^t x0_d, so that w_d = H_d⁻¹ φᵀ Su1ᵀ Q_d (μ_d - Sx1 x0_d).
            for i in 0..n {
                xd[i] = x0[i * dim + d];
            }
            for t in 0..t_n {
                free[t * n..(t + 1) * n].copy_from_slice(&xd);
                step1(&self.a1, &self.b1, &mut xd, 0.0);
            }
            let wd = self.solve_coord(d, |t, i| mu[(t, i * dim + d)] - free[t * n + i]);
            for a in 0..k_n {
                w[(a, d)] = wd[a];
            }
            for i in 0..n {
                xd[i] = x0[i * dim + d];
                x[(0, i * dim + d)] = xd[i];
            }
            for t in 0..nc {
                let mut ut = 0.0;
                for a in 0..k_n {
                    ut += self.phi[t * k_n + a] * wd[a];
                }
                u[(t, d)] = ut;
                step1(&self.a1, &self.b1, &mut xd, ut);
                for i in 0..n {
                    x[(t + 1, i * dim + d)] = xd[i];
                }
            }
        }
        let cost = self.cost(mu, &x, &u);
        if !(all_finite(w.as_slice()) && all_finite(x.as_slice()) && cost.is_finite()) {
            return Err(LqtError::NonFinite("batch solution".into()));
        }
        Ok(BatchSolution { w, u, x, cost })
    }

    /// `J = Σ_t (x_t-μ_t)ᵀ Q_t (x_t-μ_t) + r Σ_t |u_t|²`.
    pub fn cost(&self, mu: &DMatrix<f64>, x: &DMatrix<f64>, u: &DMatrix<f64>) -> f64 {
        let nx = self.config.nx();
        let mut j = 0.0;
        for t in 0..self.config.n_steps {
            for c in 0..nx {
                let q = self.q[t * nx + c];
                if q != 0.0 {
                    let e = x[(t, c)] - mu[(t, c)];
                    j += q * e * e;
                }
            }
        }
        j + self.config.r * u.iter().map(|v| v * v).sum::<f64>()
    }
}

/// `Y = Su1 φ` (T blocks of n×K) and `Z = Sx1` (T blocks of n×n) by running the integrator:
/// `Y_{t+1} = A1 Y_t + B1 φ_t`, `Z_{t+1} = A1 Z_t` (`Y_0 = 0`, `Z_0 = I`).
fn integrate_basis(
    a1: &[f64],
    b1: &[f64],
    phi: &[f64],
    n: usize,
    k_n: usize,
    t_n: usize,
) -> (Vec<f64>, Vec<f64>) {
    let nc = t_n - 1;
    let blk = n * k_n;
    let mut y = vec![0.0; t_n * blk];
    let mut z = vec![0.0; t_n * n * n];
    for i in 0..n {
        z[i * n + i] = 1.0;
    }
    for t in 0..nc {
        let (prev, next) = y.split_at_mut((t + 1) * blk);
        let yt = &prev[t * blk..];
        let yn = &mut next[..blk];
        for i in 0..n {
            let row = &mut yn[i * k_n..(i + 1) * k_n];
            for (k, v) in row.iter_mut().enumerate() {
                *v = b1[i] * phi[t * k_n + k];
            }
            for j in i..n {
                let a = a1[i * n + j];
                for (k, v) in row.iter_mut().enumerate() {
                    *v += a * yt[j * k_n + k];
                }
            }
        }
        let (zp, zn) = z.split_at_mut((t + 1) * n * n);
        let zt = &zp[t * n * n..];
        for i in 0..n {
            for c in 0..n {
                let mut s = 0.0;
                for j in i..n {
                    s += a1[i * n + j] * zt[j * n + c];
                }
                zn[i * n + c] = s;
            }
        }
    }
    (y, z)
}

/// `R_φ` of `φ = Q_φ R_φ` (K×K, row-major) when r > 0, so that `r φᵀφ = r R_φᵀ R_φ` takes K
/// rows instead of N in every coordinate's stack; empty when r = 0.
fn basis_r_factor(
    config: &LqtConfig,
    phi: &[f64],
    nc: usize,
    k_n: usize,
) -> Result<Vec<f64>, LqtError> {
    Ok(if config.r > 0.0 {
        let mut cm = vec![0.0; nc * k_n];
        for t in 0..nc {
            for c in 0..k_n {
                cm[c * nc + t] = phi[t * k_n + c];
            }
        }
        match Qr::new(cm, nc, k_n) {
            Some(qr) => qr.r_factor().to_vec(),
            None => {
                return Err(LqtError::Singular(format!(
                    "the basis matrix φ ({}) has dependent columns: H is singular",
                    config.basis.name()
                )))
            }
        }
    } else {
        Vec::new()
    })
}

/// The weighted rows `(t, i, √q_{t,i})` of coordinate `d`'s stack, for every q > 0 (t = 0 rows
/// are skipped: x_0 does not depend on w).
fn weighted_rows(config: &LqtConfig, q: &[f64], d: usize) -> Vec<(usize, usize, f64)> {
    let (dim, n, t_n) = (config.dim, config.order, config.n_steps);
    let nx = dim * n;
    let mut rows = Vec::new();
    for t in 1..t_n {
        for i in 0..n {
            let w = q[t * nx + i * dim + d];
            if w > 0.0 {
                rows.push((t, i, w.sqrt()));
            }
        }
    }
    rows
}

/// The stacked least-squares matrix `M = [√q ⊙ Su1 φ ; √r R_φ]`, column-major m×K.
fn stacked_matrix(
    config: &LqtConfig,
    rows: &[(usize, usize, f64)],
    y: &[f64],
    r_phi: &[f64],
    m: usize,
) -> Vec<f64> {
    let k_n = config.basis.n_fct();
    let blk = config.order * k_n;
    let n_q = rows.len();
    let sr = config.r.sqrt();
    let mut mat = vec![0.0; m * k_n];
    for (ri, &(t, i, s)) in rows.iter().enumerate() {
        let yr = &y[t * blk + i * k_n..t * blk + (i + 1) * k_n];
        for (c, yc) in yr.iter().enumerate() {
            mat[c * m + ri] = s * yc;
        }
    }
    if config.r > 0.0 {
        for a in 0..k_n {
            for c in a..k_n {
                mat[c * m + n_q + a] = sr * r_phi[a * k_n + c];
            }
        }
    }
    mat
}

/// `W^x = H⁻¹ φᵀ Su1ᵀ Q Sx1` (K×n), column by column by least squares on the stack.
fn state_weights(
    qr: &Qr,
    rows: &[(usize, usize, f64)],
    z: &[f64],
    n: usize,
    k_n: usize,
    m: usize,
) -> Vec<f64> {
    let mut wx = vec![0.0; k_n * n];
    let mut b = vec![0.0; m];
    for c in 0..n {
        b.fill(0.0);
        for (ri, &(t, i, s)) in rows.iter().enumerate() {
            b[ri] = s * z[t * n * n + i * n + c];
        }
        qr.solve_ls(&mut b);
        for a in 0..k_n {
            wx[a * n + c] = b[a];
        }
    }
    wx
}

/// The state part of F: `F^x = φ W^x` (N×n).
fn state_controls(phi: &[f64], wx: &[f64], n: usize, k_n: usize, nc: usize) -> Vec<f64> {
    let mut fx = vec![0.0; nc * n];
    for t in 0..nc {
        for c in 0..n {
            let mut s = 0.0;
            for a in 0..k_n {
                s += phi[t * k_n + a] * wx[a * n + c];
            }
            fx[t * n + c] = s;
        }
    }
    fx
}

/// State part of the gains: Φ^x_t = ∂x_t/∂x_0 under the open loop u = -F x̃_0
/// (Φ^x_0 = I, Φ^x_{t+1} = A1 Φ^x_t - B1 F^x_t), k_t = F^x_t (Φ^x_t)⁻¹ — equal to the
/// recursion P_t = P_{t-1}(Ã - B̃K̃_{t-1})⁻¹ (P_t = Φ_t⁻¹) without compounding its round-off.
/// Zero for the `piecewise` basis, whose gains come from the Riccati recursion.
fn state_gains(
    config: &LqtConfig,
    a1: &[f64],
    b1: &[f64],
    fx: &[f64],
    d: usize,
) -> Result<Vec<f64>, LqtError> {
    let n = config.order;
    let nc = config.n_steps - 1;
    let mut ph = vec![0.0; n * n];
    for i in 0..n {
        ph[i * n + i] = 1.0;
    }
    let mut kx = vec![0.0; nc * n];
    let mut next = vec![0.0; n * n];
    let phi_form = !matches!(config.basis, Basis::Piecewise { .. });
    for t in 0..if phi_form { nc } else { 0 } {
        // k Φ = F^x_t  <=>  Φᵀ kᵀ = F^x_tᵀ.
        if !solve_small_transposed(&ph, n, &fx[t * n..(t + 1) * n], &mut kx[t * n..(t + 1) * n]) {
            return Err(LqtError::Singular(format!(
                "closed-loop transition Φ_{t} of coordinate {d} is singular: the gain K̃_{t} is undefined"
            )));
        }
        for i in 0..n {
            for c in 0..n {
                let mut s = -b1[i] * fx[t * n + c];
                for j in i..n {
                    s += a1[i * n + j] * ph[j * n + c];
                }
                next[i * n + c] = s;
            }
        }
        std::mem::swap(&mut ph, &mut next);
    }
    Ok(kx)
}
