//! The feedback controller of LQT-CP (paper eq. 4; conventions of `docs/formats.md`):
//!
//! ```text
//! F = Ψ H⁻¹ [Ψᵀ Suᵀ Q Sx,  -Ψᵀ Suᵀ Q μ]            (u = -F x̃_0, x̃ = [x; 1])
//! K̃_0 = F_0, P_0 = I,  P_t = P_{t-1} (Ã - B̃ K̃_{t-1})⁻¹,  K̃_t = F_t P_t
//! ```
//!
//! computed as `K̃_t = F_t Φ_t⁻¹` (see [`super`]): the state part `k_t` is precomputed per group
//! of coordinates, the constant column `c_t = F^c_t - k_t φ_t` follows `φ_{t+1} = A1 φ_t - B1
//! F^c_t` for each new reference μ. Also the closed-loop rollout `u_t = -K̃_t x̃_t` with an
//! optional perturbation, and the open-loop controls `u = -F x̃_0`.

use super::super::basis::Basis;
use super::super::riccati::piecewise_gains;
use super::super::LqtError;
use super::config::{
    check_matrix, check_perturbation, check_vector, LqtConfig, Perturbation, MAX_ORDER,
};
use super::problem::{all_finite, step1, LqtCp, Rollout};
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

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

impl LqtCp {
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
