//! The dense reference path: a literal transcription of the LQT-CP case conventions
//! (`docs/formats.md`), kept to check the fast path ([`super::LqtCp`]) in tests. Slow (it forms
//! `Sx`, `Su`, `Ψ` and `Q` as dense matrices) but obviously the formulas:
//!
//! ```text
//! x = Sx x_0 + Su u, block (t,s) of Su = A^(t-1-s) B for s < t, Ψ = φ ⊗ I_D
//! H = Ψᵀ Suᵀ Q Su Ψ + r ΨᵀΨ = MᵀM,   M = [√Q Su Ψ; √r Ψ]   (H⁻¹ Mᵀ b by dense QR of M)
//! w = H⁻¹ Ψᵀ Suᵀ Q (μ - Sx x_0),   F = Ψ H⁻¹ [Ψᵀ Suᵀ Q Sx, -Ψᵀ Suᵀ Q μ]
//! Φ_t = S̃x_t - S̃u_t F (rows of step t),  K̃_t = F_t Φ_t⁻¹ (LU solve)
//! ```
//!
//! [`gains_recursive_dense`] is the contract's recursion itself
//! (`K̃_0 = F_0, P_0 = I, P_t = P_{t-1} (Ã - B̃ K̃_{t-1})⁻¹, K̃_t = F_t P_t`), used in tests to show
//! that both forms agree where the recursion is numerically meaningful (it compounds round-off
//! when `Φ_t` collapses).

use super::solver::{check_matrix, check_perturbation, check_vector, LqtConfig, Perturbation};
use super::LqtError;
use nalgebra::DMatrix;

/// Everything the dense path computes.
#[derive(Debug, Clone)]
pub struct DenseSolution {
    /// Basis weights (K×D).
    pub w: DMatrix<f64>,
    /// Batch controls (N×D).
    pub u: DMatrix<f64>,
    /// Batch states (T×nx).
    pub x: DMatrix<f64>,
    /// Cost J of the batch solution.
    pub cost: f64,
    /// F ((N·D)×(nx+1)).
    pub f: DMatrix<f64>,
    /// The gains K̃_t (N of them, D×(nx+1)).
    pub gains: Vec<DMatrix<f64>>,
}

/// Solve the problem densely from `x0`, reference `mu` (T×nx) and weights `q_diag` (T×nx).
pub fn solve_dense(
    config: &LqtConfig,
    mu: &DMatrix<f64>,
    q_diag: &DMatrix<f64>,
    x0: &[f64],
) -> Result<DenseSolution, LqtError> {
    config.validate()?;
    let (dim, t_n) = (config.dim, config.n_steps);
    let nx = config.nx();
    let nc = config.n_controls();
    let k_n = config.basis.n_fct();
    check_matrix("reference.mu", mu, t_n, nx, false)?;
    check_matrix("reference.q_diag", q_diag, t_n, nx, true)?;
    check_vector("x0", x0, nx)?;
    let a = config.a_matrix();
    let b = config.b_matrix();
    let phi = config.phi_matrix();

    // Sx (T nx × nx): block t = A^t.  Su (T nx × N D): block (t,s) = A^(t-1-s) B, s < t.
    let mut sx = DMatrix::zeros(t_n * nx, nx);
    let mut pow = DMatrix::identity(nx, nx);
    let mut pows: Vec<DMatrix<f64>> = Vec::with_capacity(t_n);
    for t in 0..t_n {
        sx.view_mut((t * nx, 0), (nx, nx)).copy_from(&pow);
        pows.push(pow.clone());
        pow = &a * pow;
    }
    let mut su = DMatrix::zeros(t_n * nx, nc * dim);
    for t in 1..t_n {
        for s in 0..t {
            let blk = &pows[t - 1 - s] * &b;
            su.view_mut((t * nx, s * dim), (nx, dim)).copy_from(&blk);
        }
    }
    // Ψ = φ ⊗ I_D.
    let psi = phi.kronecker(&DMatrix::<f64>::identity(dim, dim));
    let qv: Vec<f64> = (0..t_n * nx).map(|r| q_diag[(r / nx, r % nx)]).collect();
    let muv = DMatrix::from_fn(t_n * nx, 1, |r, _| mu[(r / nx, r % nx)]);
    let q = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(qv));
    let sup = &su * &psi;
    // M = [√Q Su Ψ; √r Ψ], so that H = MᵀM and H⁻¹ Ψᵀ Suᵀ Q b = argmin |M w - [√Q b; 0]|.
    let sq = DMatrix::from_diagonal(&q.diagonal().map(f64::sqrt));
    let (m_top, m_bot) = (t_n * nx, nc * dim);
    let mut m = DMatrix::zeros(m_top + m_bot, k_n * dim);
    m.view_mut((0, 0), (m_top, k_n * dim))
        .copy_from(&(&sq * &sup));
    m.view_mut((m_top, 0), (m_bot, k_n * dim))
        .copy_from(&(config.r.sqrt() * &psi));
    let qr = m.qr();
    let (qq, rr) = (qr.q(), qr.r());
    if (0..k_n * dim).any(|i| rr[(i, i)].abs() <= 1e-13 * rr.diagonal().amax()) {
        return Err(LqtError::Singular("H is singular".into()));
    }
    let ls = |b_top: &DMatrix<f64>| -> DMatrix<f64> {
        let mut b = DMatrix::zeros(m_top + m_bot, b_top.ncols());
        b.view_mut((0, 0), (m_top, b_top.ncols()))
            .copy_from(&(&sq * b_top));
        let qtb = qq.transpose() * b;
        rr.solve_upper_triangular(&qtb)
            .unwrap_or_else(|| DMatrix::from_element(k_n * dim, b_top.ncols(), f64::NAN))
    };
    let x0v = DMatrix::from_column_slice(nx, 1, x0);
    let wv = ls(&(&muv - &sx * &x0v));
    let w = DMatrix::from_fn(k_n, dim, |k, d| wv[(k * dim + d, 0)]);
    let uv = &psi * &wv;
    let u = DMatrix::from_fn(nc, dim, |t, d| uv[(t * dim + d, 0)]);
    let xv = &sx * &x0v + &su * &uv;
    let x = DMatrix::from_fn(t_n, nx, |t, c| xv[(t * nx + c, 0)]);
    let e = &xv - &muv;
    let cost = (e.transpose() * &q * &e)[(0, 0)] + config.r * uv.norm_squared();
    let mut rhs_f = DMatrix::zeros(t_n * nx, nx + 1);
    rhs_f.view_mut((0, 0), (t_n * nx, nx)).copy_from(&sx);
    rhs_f.set_column(nx, &(-&muv).column(0));
    let f = &psi * ls(&rhs_f);

    // Φ_t = S̃x_t - S̃u_t F, K̃_t = F_t Φ_t⁻¹.
    let mut gains = Vec::with_capacity(nc);
    for t in 0..nc {
        let mut phi_t = DMatrix::<f64>::identity(nx + 1, nx + 1);
        phi_t.view_mut((0, 0), (nx, nx)).copy_from(&pows[t]);
        let su_t = su.view((t * nx, 0), (nx, nc * dim));
        let corr = su_t * &f;
        let mut top = phi_t.view_mut((0, 0), (nx, nx + 1));
        top -= &corr;
        let ft = f.rows(t * dim, dim).into_owned();
        // K Φ = F_t  <=>  Φᵀ Kᵀ = F_tᵀ.
        let kt = phi_t
            .transpose()
            .lu()
            .solve(&ft.transpose())
            .ok_or_else(|| LqtError::Singular(format!("Φ_{t} is singular")))?;
        gains.push(kt.transpose());
    }
    Ok(DenseSolution {
        w,
        u,
        x,
        cost,
        f,
        gains,
    })
}

/// The contract's recursion `K̃_0 = F_0, P_0 = I, P_t = P_{t-1} (Ã - B̃ K̃_{t-1})⁻¹, K̃_t = F_t P_t`
/// on dense matrices (each inverse an LU solve).
pub fn gains_recursive_dense(
    config: &LqtConfig,
    f: &DMatrix<f64>,
) -> Result<Vec<DMatrix<f64>>, LqtError> {
    let (dim, nx, nc) = (config.dim, config.nx(), config.n_controls());
    let (a, b) = (config.a_matrix(), config.b_matrix());
    let mut at = DMatrix::zeros(nx + 1, nx + 1);
    at.view_mut((0, 0), (nx, nx)).copy_from(&a);
    at[(nx, nx)] = 1.0;
    let mut bt = DMatrix::zeros(nx + 1, dim);
    bt.view_mut((0, 0), (nx, dim)).copy_from(&b);
    let mut p = DMatrix::<f64>::identity(nx + 1, nx + 1);
    let mut gains: Vec<DMatrix<f64>> = Vec::with_capacity(nc);
    for t in 0..nc {
        if t > 0 {
            let m = &at - &bt * &gains[t - 1];
            // P_t = P_{t-1} M⁻¹  <=>  Mᵀ P_tᵀ = P_{t-1}ᵀ.
            let pt = m
                .transpose()
                .lu()
                .solve(&p.transpose())
                .ok_or_else(|| LqtError::Singular(format!("Ã - B̃ K̃_{} is singular", t - 1)))?;
            p = pt.transpose();
        }
        gains.push(f.rows(t * dim, dim) * &p);
    }
    Ok(gains)
}

/// Literal closed-loop rollout on the augmented system with dense gains.
pub fn rollout_dense(
    config: &LqtConfig,
    gains: &[DMatrix<f64>],
    x_init: &[f64],
    perturbation: Option<&Perturbation>,
) -> Result<(DMatrix<f64>, DMatrix<f64>), LqtError> {
    let (dim, nx, nc) = (config.dim, config.nx(), config.n_controls());
    check_vector("feedback.x_init", x_init, nx)?;
    if let Some(p) = perturbation {
        check_perturbation(p, nx, nc)?;
    }
    let a = config.a_matrix();
    let b = config.b_matrix();
    let mut xt = nalgebra::DVector::zeros(nx + 1);
    xt.rows_mut(0, nx).copy_from_slice(x_init);
    xt[nx] = 1.0;
    let mut x = DMatrix::zeros(nc + 1, nx);
    let mut u = DMatrix::zeros(nc, dim);
    x.row_mut(0).copy_from(&xt.rows(0, nx).transpose());
    for t in 0..nc {
        let ut = -(&gains[t] * &xt);
        let xs = &a * xt.rows(0, nx) + &b * &ut;
        xt.rows_mut(0, nx).copy_from(&xs);
        if let Some(p) = perturbation {
            if p.after_step == t {
                for c in 0..nx {
                    xt[c] += p.delta[c];
                }
            }
        }
        u.row_mut(t).copy_from(&ut.transpose());
        x.row_mut(t + 1).copy_from(&xt.rows(0, nx).transpose());
    }
    Ok((x, u))
}
