//! Feedback gains of the `piecewise` basis by a backward Riccati recursion over the windows.
//!
//! With `φ_k(s_j) = 1` iff `⌊j/L⌋ = k`, the control is held at `w_k` over window k (steps
//! `kL .. kL + l_k`), and the batch problem is a dynamic programme over windows: the tail of the
//! optimal solution from the start of window k is optimal for the tail problem from `x̃_{kL}`.
//! Per coordinate, on the augmented state `x̃ = [x; 1]` (n+1) with
//! `Q̃_t = [[Q_t, -Q_t μ_t], [-μ_tᵀ Q_t, μ_tᵀ Q_t μ_t]]`:
//!
//! ```text
//! x̃_{kL+j} = Ã^j x̃_{kL} + Γ_j w_k,       Γ_j = Σ_{i<j} Ã^(j-1-i) B̃
//! V_K = 0,  V_k(x̃) = min_w Σ_{j=1..l_k} x̃_{kL+j}ᵀ (Q̃_{kL+j} + [j = l_k] S_{k+1}) x̃_{kL+j} + r l_k w²
//!        = x̃ᵀ S_k x̃,   w_k = -L_k x̃_{kL},  L_k = S_ww⁻¹ S_wx
//! ```
//!
//! Along any member of the family of optimal trajectories, `x̃_{kL+j} = C_j x̃_{kL}` with
//! `C_j = Ã^j - Γ_j L_k` and `u_{kL+j} = -L_k x̃_{kL}`, so the contract's gains
//! `K̃_t = F_t P_t = F_t Φ_t⁻¹` are exactly `K̃_{kL+j} = L_k C_j⁻¹` (`C_0 = I`: `K̃_{kL} = L_k`).
//! With K = N (Ψ = I) this is the standard backward Riccati recursion of LQT. Unlike the forward
//! product `F_t Φ_t⁻¹`, it stays accurate when strong tracking makes `Φ_t` collapse.

use super::linalg::solve_small_transposed;
use super::LqtError;

/// Gains of one coordinate for the piecewise basis: `(k, c)` with `k` N×n (row-major) and `c` N,
/// `K̃_t = [k_t, c_t]`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn piecewise_gains(
    a1: &[f64],
    b1: &[f64],
    n: usize,
    nc: usize,
    k_n: usize,
    r: f64,
    q: impl Fn(usize, usize) -> f64,
    mu: impl Fn(usize, usize) -> f64,
) -> Result<(Vec<f64>, Vec<f64>), LqtError> {
    let na = n + 1; // augmented state
    let nz = n + 2; // [x̃; w]
    let l = nc.div_ceil(k_n);
    // Ã (na×na).
    let mut at = vec![0.0; na * na];
    for i in 0..n {
        for j in 0..n {
            at[i * na + j] = a1[i * n + j];
        }
    }
    at[n * na + n] = 1.0;
    let mut kx = vec![0.0; nc * n];
    let mut kc = vec![0.0; nc];
    let mut s_next = vec![0.0; na * na];
    let mut qt = vec![0.0; na * na];
    let mut wmat = vec![0.0; nz * nz];
    let mut me = vec![0.0; na * nz];
    for k in (0..k_n).rev() {
        let start = k * l;
        let len = l.min(nc - start);
        // E_j = [Ã^j | Γ_j] (na×nz), kept for j = 0..len-1 to form C_j afterwards.
        let mut es: Vec<Vec<f64>> = Vec::with_capacity(len + 1);
        let mut e = vec![0.0; na * nz];
        for i in 0..na {
            e[i * nz + i] = 1.0;
        }
        wmat.fill(0.0);
        for j in 1..=len {
            es.push(e.clone());
            // E ← Ã E + B̃ e_wᵀ.
            let mut ne = vec![0.0; na * nz];
            for i in 0..na {
                for c in 0..nz {
                    let mut s = 0.0;
                    for p in 0..na {
                        s += at[i * na + p] * e[p * nz + c];
                    }
                    ne[i * nz + c] = s;
                }
            }
            for i in 0..n {
                ne[i * nz + n + 1] += b1[i];
            }
            e = ne;
            let t = start + j;
            // Q̃_t (+ S_{k+1} at the window's end).
            let mut any = false;
            qt.fill(0.0);
            for i in 0..n {
                let qi = q(t, i);
                if qi != 0.0 {
                    any = true;
                    let m = mu(t, i);
                    qt[i * na + i] += qi;
                    qt[i * na + n] -= qi * m;
                    qt[n * na + i] -= qi * m;
                    qt[n * na + n] += qi * m * m;
                }
            }
            if j == len {
                any = true;
                for (a, b) in qt.iter_mut().zip(&s_next) {
                    *a += b;
                }
            }
            if !any {
                continue;
            }
            // W += Eᵀ Q̃ E.
            for i in 0..na {
                for c in 0..nz {
                    let mut s = 0.0;
                    for p in 0..na {
                        s += qt[i * na + p] * e[p * nz + c];
                    }
                    me[i * nz + c] = s;
                }
            }
            for a in 0..nz {
                for b in 0..nz {
                    let mut s = 0.0;
                    for p in 0..na {
                        s += e[p * nz + a] * me[p * nz + b];
                    }
                    wmat[a * nz + b] += s;
                }
            }
        }
        let iw = n + 1;
        wmat[iw * nz + iw] += r * len as f64;
        let sww = wmat[iw * nz + iw];
        if !(sww > 0.0 && sww.is_finite()) {
            return Err(LqtError::Singular(format!(
                "piecewise window {k}: the control weight of the window's Riccati step is not positive"
            )));
        }
        let lk: Vec<f64> = (0..na).map(|c| wmat[iw * nz + c] / sww).collect();
        for a in 0..na {
            for b in 0..na {
                s_next[a * na + b] = wmat[a * nz + b] - wmat[iw * nz + a] * lk[b];
            }
        }
        // Gains inside the window: K̃_{start+j} = L_k C_j⁻¹, C_j = Ã^j - Γ_j L_k.
        for (j, ej) in es.iter().enumerate() {
            let t = start + j;
            let gain = if j == 0 {
                lk.clone()
            } else {
                let mut cj = vec![0.0; na * na];
                for i in 0..na {
                    for c in 0..na {
                        cj[i * na + c] = ej[i * nz + c] - ej[i * nz + iw] * lk[c];
                    }
                }
                let mut g = vec![0.0; na];
                if !solve_small_transposed(&cj, na, &lk, &mut g) {
                    return Err(LqtError::Singular(format!(
                        "closed-loop transition inside piecewise window {k} is singular at step {t}"
                    )));
                }
                g
            };
            kx[t * n..(t + 1) * n].copy_from_slice(&gain[..n]);
            kc[t] = gain[n];
        }
    }
    Ok((kx, kc))
}
