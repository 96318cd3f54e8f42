//! LQT-CP, the fast path (paper §III-B, eqs. 1–4; conventions of `shared/lqt-cp-io.md`).
//!
//! Cost and batch solution from `x_0`:
//!
//! ```text
//! J = Σ_{t<T} (x_t-μ_t)ᵀ Q_t (x_t-μ_t) + r Σ_{t<N} |u_t|²,     Q_t = diag(q_t)
//! x = Sx x_0 + Su u,   u = Ψ w,   Ψ = φ ⊗ I_D
//! H = Ψᵀ Suᵀ Q Su Ψ + r ΨᵀΨ,      w = H⁻¹ Ψᵀ Suᵀ Q (μ - Sx x_0)
//! F = Ψ H⁻¹ [Ψᵀ Suᵀ Q Sx,  -Ψᵀ Suᵀ Q μ]            (u = -F x̃_0, x̃ = [x; 1])
//! K̃_0 = F_0, P_0 = I,  P_t = P_{t-1} (Ã - B̃ K̃_{t-1})⁻¹,  K̃_t = F_t P_t
//! ```
//!
//! Structure exploited (the dense transcription of the formulas is [`super::reference`](mod@super::reference)):
//!
//! * `A = A1 ⊗ I_D`, `B = B1 ⊗ I_D`, Q diagonal: the D coordinates are independent. Each one is
//!   a 1-D problem with K unknowns and a K×K matrix `H_d`; coordinates whose weights `q` are equal
//!   share `H_d`, its factorisation and the state part of the gains.
//! * `Su` is block-Toeplitz: `Y = Su1 φ` (T blocks of n×K) is obtained by running the integrator
//!   on the columns of φ, `Y_{t+1} = A1 Y_t + B1 φ_t`, in O(T n² K) instead of a product with the
//!   (T n)×N matrix `Su1`. `Sx1` is the stack of powers `A1^t`.
//! * Q is diagonal and mostly zero: `H_d = Σ_{(t,i): q>0} q Y_t[i]ᵀ Y_t[i] + r φᵀφ` only visits
//!   rows with a nonzero weight.
//! * `H_d = MᵀM` with the stacked least-squares matrix `M = [√q ⊙ Su1 φ ; √r φ]`: instead of a
//!   Cholesky factorisation of `H_d` (whose condition number, ~1e11 for 10 Bernstein functions,
//!   costs 5 digits), M is factored by Householder QR (condition ~3e5), and every solve
//!   `H_d⁻¹ Mᵀ b` is a least-squares solve `R⁻¹ Qᵀ b`. No inverse is formed. Everything that depends
//!   on q, φ and the dynamics but not on μ — the factorisation, `H⁻¹ Ψᵀ Suᵀ Q Sx`, the state part of
//!   F and of the gains — is computed once in [`LqtCp::new`]; a new reference μ (a new goal, a new
//!   object pose) only costs one least-squares solve per coordinate, F's last column and an O(N n²)
//!   recursion for the gains' last column.
//!
//! Gains. With `Φ_t = ∂x̃_t/∂x̃_0` along the open loop `u = -F x̃_0` (`Φ_0 = I`,
//! `Φ_{t+1} = Ã Φ_t - B̃ F_t`), the recursion of the contract gives `P_t = Φ_t⁻¹`, hence
//! `K̃_t = F_t Φ_t⁻¹`: computed by an (n×n) LU solve per step and coordinate (`Φ_t` is
//! `[[Φ^x_t, φ_t], [0, 1]]`, so `k_t = F^x_t (Φ^x_t)⁻¹` and `c_t = F^c_t - k_t φ_t`). This is the
//! same matrix as the product of inverses, without compounding the round-off of each inverse.
//! For the `piecewise` basis the gains come from a backward Riccati recursion over the windows
//! (exact equivalent, see [`super::riccati`]), which stays accurate when `Φ_t` collapses (strong
//! tracking makes `x_t` almost independent of `x_0`, and `F_t Φ_t⁻¹` a ratio of round-off).

use super::basis::Basis;
use super::dynamics::{dense_ab, integrator};
use super::linalg::{solve_small_transposed, Qr};
use super::riccati::piecewise_gains;
use super::LqtError;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

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

/// What one group of coordinates with identical weights q shares (nothing here depends on μ).
#[derive(Debug, Clone)]
struct Group {
    /// Householder QR of the stacked least-squares matrix `[√q ⊙ Su1 φ ; √r φ]` (m×K).
    qr: Qr,
    /// The weighted rows of the stack: `(t, i, √q_{t,i})` for every q > 0 (t ≥ 1), then K rows
    /// `√r R_φ` when r > 0 (`φ = Q_φ R_φ`, so that `r φᵀφ = r R_φᵀ R_φ` with K rows instead of N).
    rows: Vec<(usize, usize, f64)>,
    /// Number of rows m of the stack.
    m: usize,
    /// `W^x = H⁻¹ φᵀ Su1ᵀ Q Sx1` (K×n).
    wx: Vec<f64>,
    /// State part of F: `F^x = φ H_d⁻¹ φᵀ Su1ᵀ Q_d Sx1` (N×n).
    fx: Vec<f64>,
    /// State part of the gains `k_t = F^x_t (Φ^x_t)⁻¹` (N×n).
    kx: Vec<f64>,
}

/// An LQT-CP problem with everything that does not depend on the reference μ precomputed.
///
/// Build it once per skill (weights q, basis and dynamics fixed); then [`LqtCp::solve`] and
/// [`LqtCp::feedback`] for any μ (new goal, new object pose) only redo the μ-dependent parts.
#[derive(Debug, Clone)]
pub struct LqtCp {
    config: LqtConfig,
    a1: Vec<f64>,
    b1: Vec<f64>,
    /// φ, N×K row-major.
    phi: Vec<f64>,
    /// `q` row-major T×nx.
    q: Vec<f64>,
    /// Coordinate → index in `groups`.
    group_of: Vec<usize>,
    groups: Vec<Group>,
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

/// A perturbation added to the state part of `x̃_{after_step+1}`, just after the update.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Perturbation {
    /// Control step t after whose update the perturbation hits (0..N-1).
    pub after_step: usize,
    /// Added state (nx, derivative-major).
    pub delta: Vec<f64>,
}

/// States and controls of a closed-loop rollout.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Rollout {
    /// States `x_0..x_{T-1}` (T×nx).
    pub x: DMatrix<f64>,
    /// Controls `u_0..u_{N-1}` (N×D).
    pub u: DMatrix<f64>,
}

/// The feedback controller `u_t = -K̃_t x̃_t` of an LQT-CP problem for one reference μ.
///
/// Stored compactly: for each coordinate d, `K̃_t` has nonzeros only on that coordinate's n
/// derivatives and on the constant column. [`FeedbackGains::gain`] expands to D×(nx+1).
/// Deserialisation checks every length, so a malformed JSON is an error, never a later panic.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "FeedbackGainsData")]
pub struct FeedbackGains {
    dim: usize,
    order: usize,
    n_controls: usize,
    a1: Vec<f64>,
    b1: Vec<f64>,
    /// `F^x` per coordinate: D×N×n.
    fx: Vec<f64>,
    /// `F^c` per coordinate: D×N.
    fc: Vec<f64>,
    /// `k_t` per coordinate: D×N×n.
    kx: Vec<f64>,
    /// `c_t` per coordinate: D×N.
    kc: Vec<f64>,
    /// Number of basis functions K.
    k_n: usize,
    /// `W^x` per coordinate: D×K×n (`w_d = -(W^x_d x0_d + W^c_d)`).
    wx: Vec<f64>,
    /// `W^c = -H⁻¹ Ψᵀ Suᵀ Q μ` per coordinate: D×K.
    wc: Vec<f64>,
}

/// The serialised form of [`FeedbackGains`], validated by `TryFrom`.
#[derive(Deserialize)]
struct FeedbackGainsData {
    dim: usize,
    order: usize,
    n_controls: usize,
    a1: Vec<f64>,
    b1: Vec<f64>,
    fx: Vec<f64>,
    fc: Vec<f64>,
    kx: Vec<f64>,
    kc: Vec<f64>,
    k_n: usize,
    wx: Vec<f64>,
    wc: Vec<f64>,
}

impl TryFrom<FeedbackGainsData> for FeedbackGains {
    type Error = String;

    fn try_from(g: FeedbackGainsData) -> Result<Self, String> {
        let (d, n, nc, k) = (g.dim, g.order, g.n_controls, g.k_n);
        if d == 0 || n == 0 || n > MAX_ORDER || nc == 0 || k == 0 {
            return Err("feedback gains: dim, order, n_controls and k_n must be positive".into());
        }
        let lens = [
            ("a1", g.a1.len(), n * n),
            ("b1", g.b1.len(), n),
            ("fx", g.fx.len(), d * nc * n),
            ("fc", g.fc.len(), d * nc),
            ("kx", g.kx.len(), d * nc * n),
            ("kc", g.kc.len(), d * nc),
            ("wx", g.wx.len(), d * k * n),
            ("wc", g.wc.len(), d * k),
        ];
        for (name, got, want) in lens {
            if got != want {
                return Err(format!(
                    "feedback gains: {name} has {got} numbers, expected {want}"
                ));
            }
        }
        Ok(FeedbackGains {
            dim: d,
            order: n,
            n_controls: nc,
            a1: g.a1,
            b1: g.b1,
            fx: g.fx,
            fc: g.fc,
            kx: g.kx,
            kc: g.kc,
            k_n: k,
            wx: g.wx,
            wc: g.wc,
        })
    }
}

fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

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

        // Y_{t+1} = A1 Y_t + B1 φ_t  (Y = Su1 φ), Z_{t+1} = A1 Z_t (Z = Sx1).
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

        // r φᵀφ = r R_φᵀ R_φ: K rows instead of N in every coordinate's stack.
        let r_phi = if config.r > 0.0 {
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
        };
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
        let (dim, n, t_n) = (config.dim, config.order, config.n_steps);
        let nx = dim * n;
        let nc = t_n - 1;
        let k_n = config.basis.n_fct();
        let blk = n * k_n;
        // The stacked least-squares matrix M = [√q ⊙ Su1 φ ; √r φ], column-major m×K.
        // (t = 0 rows are skipped: x_0 does not depend on w.)
        let mut rows = Vec::new();
        for t in 1..t_n {
            for i in 0..n {
                let w = q[t * nx + i * dim + d];
                if w > 0.0 {
                    rows.push((t, i, w.sqrt()));
                }
            }
        }
        let n_q = rows.len();
        let sr = config.r.sqrt();
        let m = n_q + if config.r > 0.0 { k_n } else { 0 };
        let singular = || {
            LqtError::Singular(format!(
                "H = Ψᵀ Suᵀ Q Su Ψ + r ΨᵀΨ is singular for coordinate {d}: the weights q and r do not determine the {k_n} basis weights"
            ))
        };
        if m < k_n {
            return Err(singular());
        }
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
        if !all_finite(&mat) {
            return Err(LqtError::NonFinite(
                "the weighted matrix √Q Su Ψ overflowed (weights q too large)".into(),
            ));
        }
        let qr = Qr::new(mat, m, k_n).ok_or_else(singular)?;
        // W^x = H⁻¹ φᵀ Su1ᵀ Q Sx1 (K×n) column by column, F^x = φ W^x (N×n).
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
        // State part of the gains: Φ^x_t = ∂x_t/∂x_0 under the open loop u = -F x̃_0
        // (Φ^x_0 = I, Φ^x_{t+1} = A1 Φ^x_t - B1 F^x_t), k_t = F^x_t (Φ^x_t)⁻¹ — equal to the
        // recursion P_t = P_{t-1}(Ã - B̃K̃_{t-1})⁻¹ (P_t = Φ_t⁻¹) without compounding its
        // round-off.
        let mut ph = vec![0.0; n * n];
        for i in 0..n {
            ph[i * n + i] = 1.0;
        }
        let mut kx = vec![0.0; nc * n];
        let mut next = vec![0.0; n * n];
        let phi_form = !matches!(config.basis, Basis::Piecewise { .. });
        for t in 0..if phi_form { nc } else { 0 } {
            // k Φ = F^x_t  <=>  Φᵀ kᵀ = F^x_tᵀ.
            if !solve_small_transposed(&ph, n, &fx[t * n..(t + 1) * n], &mut kx[t * n..(t + 1) * n])
            {
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
    fn solve_coord(&self, d: usize, tgt: impl Fn(usize, usize) -> f64) -> Vec<f64> {
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

    /// The feedback controller (F and the gains K̃_t) for the reference `mu` (T×nx).
    pub fn feedback(&self, mu: &DMatrix<f64>) -> Result<FeedbackGains, LqtError> {
        let cfg = &self.config;
        let (dim, n, t_n) = (cfg.dim, cfg.order, cfg.n_steps);
        let nx = dim * n;
        let nc = t_n - 1;
        let k_n = cfg.basis.n_fct();
        check_matrix("reference.mu", mu, t_n, nx, false)?;
        let mut fx = vec![0.0; dim * nc * n];
        let mut fc = vec![0.0; dim * nc];
        let mut kx = vec![0.0; dim * nc * n];
        let mut kc = vec![0.0; dim * nc];
        let mut wx_all = vec![0.0; dim * k_n * n];
        let mut wc_all = vec![0.0; dim * k_n];
        let mut ph = vec![0.0; n];
        for d in 0..dim {
            let grp = &self.groups[self.group_of[d]];
            fx[d * nc * n..(d + 1) * nc * n].copy_from_slice(&grp.fx);
            kx[d * nc * n..(d + 1) * nc * n].copy_from_slice(&grp.kx);
            // W^c = -H⁻¹ φᵀ Su1ᵀ Q μ_d, F^c = φ W^c; the constant column of Φ_t follows
            // φ_{t+1} = A1 φ_t - B1 F^c_t, and c_t = F^c_t - k_t φ_t.
            let wc = self.solve_coord(d, |t, i| mu[(t, i * dim + d)]);
            wx_all[d * k_n * n..(d + 1) * k_n * n].copy_from_slice(&grp.wx);
            for a in 0..k_n {
                wc_all[d * k_n + a] = -wc[a];
            }
            ph.fill(0.0);
            for t in 0..nc {
                let mut f = 0.0;
                for a in 0..k_n {
                    f -= self.phi[t * k_n + a] * wc[a];
                }
                fc[d * nc + t] = f;
                let mut c = f;
                for i in 0..n {
                    c -= grp.kx[t * n + i] * ph[i];
                }
                kc[d * nc + t] = c;
                step1(&self.a1, &self.b1, &mut ph, -f);
            }
            if matches!(cfg.basis, Basis::Piecewise { .. }) {
                let (k, c) = piecewise_gains(
                    &self.a1,
                    &self.b1,
                    n,
                    nc,
                    k_n,
                    cfg.r,
                    |t, i| self.q[t * nx + i * dim + d],
                    |t, i| mu[(t, i * dim + d)],
                )?;
                kx[d * nc * n..(d + 1) * nc * n].copy_from_slice(&k);
                kc[d * nc..(d + 1) * nc].copy_from_slice(&c);
            }
        }
        if !(all_finite(&fc) && all_finite(&kc)) {
            return Err(LqtError::NonFinite("feedback gains".into()));
        }
        Ok(FeedbackGains {
            dim,
            order: n,
            n_controls: nc,
            a1: self.a1.clone(),
            b1: self.b1.clone(),
            fx,
            fc,
            kx,
            kc,
            k_n,
            wx: wx_all,
            wc: wc_all,
        })
    }
}

/// The whole pipeline of one skill from scratch, as one call (benchmarked natively and from wasm):
/// factorisation, F and the N gains, the batch weights w from `x0` (K×D) and one closed-loop
/// rollout from `x0` (which is the batch trajectory).
pub fn full_pipeline(
    config: &LqtConfig,
    mu: &DMatrix<f64>,
    q_diag: &DMatrix<f64>,
    x0: &[f64],
) -> Result<(DMatrix<f64>, FeedbackGains, Rollout), LqtError> {
    let lqt = LqtCp::new(config.clone(), q_diag)?;
    let gains = lqt.feedback(mu)?;
    let w = gains.weights(x0)?;
    let roll = gains.rollout(x0, None)?;
    Ok((w, gains, roll))
}

/// One integrator step of one coordinate: `x ← A1 x + B1 u`.
#[inline]
pub(crate) fn step1(a1: &[f64], b1: &[f64], x: &mut [f64], u: f64) {
    let n = x.len();
    for i in 0..n {
        let mut s = b1[i] * u;
        for j in i..n {
            s += a1[i * n + j] * x[j];
        }
        x[i] = s;
    }
}

impl FeedbackGains {
    /// D.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Integrator order n.
    pub fn order(&self) -> usize {
        self.order
    }

    /// N, the number of gains (one per control step).
    pub fn n_controls(&self) -> usize {
        self.n_controls
    }

    /// Basis weights of the open loop from `x0`: `w_d = -(W^x_d x0_d + W^c_d)` (K×D), i.e. the
    /// batch solution's weights without another solve.
    pub fn weights(&self, x0: &[f64]) -> Result<DMatrix<f64>, LqtError> {
        let (dim, n, k_n) = (self.dim, self.order, self.k_n);
        check_vector("x0", x0, dim * n)?;
        Ok(DMatrix::from_fn(k_n, dim, |a, d| {
            let mut s = self.wc[d * k_n + a];
            for i in 0..n {
                s += self.wx[(d * k_n + a) * n + i] * x0[i * dim + d];
            }
            -s
        }))
    }

    /// `F` ((N·D)×(nx+1)): row `t*D+d` maps `x̃_0` to `-u_t[d]` in open loop.
    pub fn f_matrix(&self) -> DMatrix<f64> {
        let (dim, n, nc) = (self.dim, self.order, self.n_controls);
        let nx = dim * n;
        let mut f = DMatrix::zeros(nc * dim, nx + 1);
        for d in 0..dim {
            for t in 0..nc {
                for i in 0..n {
                    f[(t * dim + d, i * dim + d)] = self.fx[(d * nc + t) * n + i];
                }
                f[(t * dim + d, nx)] = self.fc[d * nc + t];
            }
        }
        f
    }

    /// `K̃_t` (D×(nx+1)); the last column multiplies the constant 1. `None` if `t ≥ N`.
    pub fn gain(&self, t: usize) -> Option<DMatrix<f64>> {
        if t >= self.n_controls {
            return None;
        }
        let (dim, n, nc) = (self.dim, self.order, self.n_controls);
        let nx = dim * n;
        let mut k = DMatrix::zeros(dim, nx + 1);
        for d in 0..dim {
            for i in 0..n {
                k[(d, i * dim + d)] = self.kx[(d * nc + t) * n + i];
            }
            k[(d, nx)] = self.kc[d * nc + t];
        }
        Some(k)
    }

    /// The feedback command `u_t = -K̃_t [x; 1]` for a measured state `x` (nx).
    pub fn control(&self, t: usize, x: &[f64]) -> Result<DVector<f64>, LqtError> {
        let (dim, n, nc) = (self.dim, self.order, self.n_controls);
        if t >= nc {
            return Err(LqtError::input(
                "t",
                format!("expected a control step below N = {nc}, got {t}"),
            ));
        }
        check_vector("x", x, dim * n)?;
        Ok(DVector::from_iterator(
            dim,
            (0..dim).map(|d| self.control_coord(t, d, |i| x[i * dim + d])),
        ))
    }

    #[inline]
    fn control_coord(&self, t: usize, d: usize, x: impl Fn(usize) -> f64) -> f64 {
        let (n, nc) = (self.order, self.n_controls);
        let k = &self.kx[(d * nc + t) * n..(d * nc + t + 1) * n];
        let mut s = self.kc[d * nc + t];
        for (i, ki) in k.iter().enumerate() {
            s += ki * x(i);
        }
        -s
    }

    /// One step of the dynamics `x ← A x + B u` (x: nx, u: D).
    pub fn step_state(&self, x: &mut [f64], u: &[f64]) {
        let (dim, n) = (self.dim, self.order);
        let mut xd = vec![0.0; n];
        for d in 0..dim.min(u.len()) {
            for i in 0..n {
                xd[i] = x[i * dim + d];
            }
            step1(&self.a1, &self.b1, &mut xd, u[d]);
            for i in 0..n {
                x[i * dim + d] = xd[i];
            }
        }
    }

    /// Closed-loop rollout from `x̃_0 = [x_init; 1]` with `u_t = -K̃_t x̃_t`, adding the optional
    /// perturbation to `x_{after_step+1}` just after the update.
    pub fn rollout(
        &self,
        x_init: &[f64],
        perturbation: Option<&Perturbation>,
    ) -> Result<Rollout, LqtError> {
        let (dim, n, nc) = (self.dim, self.order, self.n_controls);
        let nx = dim * n;
        check_vector("feedback.x_init", x_init, nx)?;
        if let Some(p) = perturbation {
            check_perturbation(p, nx, nc)?;
        }
        let mut x = DMatrix::zeros(nc + 1, nx);
        let mut u = DMatrix::zeros(nc, dim);
        let mut xd = vec![0.0; n];
        for d in 0..dim {
            for i in 0..n {
                xd[i] = x_init[i * dim + d];
                x[(0, i * dim + d)] = xd[i];
            }
            for t in 0..nc {
                let ut = self.control_coord(t, d, |i| xd[i]);
                u[(t, d)] = ut;
                step1(&self.a1, &self.b1, &mut xd, ut);
                if let Some(p) = perturbation {
                    if p.after_step == t {
                        for i in 0..n {
                            xd[i] += p.delta[i * dim + d];
                        }
                    }
                }
                for i in 0..n {
                    x[(t + 1, i * dim + d)] = xd[i];
                }
            }
        }
        if !(all_finite(x.as_slice()) && all_finite(u.as_slice())) {
            return Err(LqtError::NonFinite("rollout".into()));
        }
        Ok(Rollout { x, u })
    }

    /// Open-loop controls `u = -F x̃_0` from `x̃_0 = [x_init; 1]` (N×D).
    pub fn open_loop_controls(&self, x_init: &[f64]) -> Result<DMatrix<f64>, LqtError> {
        let (dim, n, nc) = (self.dim, self.order, self.n_controls);
        check_vector("x_init", x_init, dim * n)?;
        let mut u = DMatrix::zeros(nc, dim);
        for d in 0..dim {
            for t in 0..nc {
                let mut s = self.fc[d * nc + t];
                for i in 0..n {
                    s += self.fx[(d * nc + t) * n + i] * x_init[i * dim + d];
                }
                u[(t, d)] = -s;
            }
        }
        Ok(u)
    }
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
