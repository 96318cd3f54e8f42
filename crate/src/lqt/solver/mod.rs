//! LQT-CP, the fast path (paper §III-B, eqs. 1–4; conventions of `docs/formats.md`).
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
//! Structure exploited (the dense transcription of the formulas is
//! [`super::reference`](mod@super::reference)):
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
//!
//! Files: `config.rs` holds the parameters and the input checks, `batch.rs` the precomputation
//! of [`LqtCp::new`] and the batch solution, `gains.rs` F, the gains K̃_t and the closed-loop
//! rollout of [`FeedbackGains`].

mod batch;
mod config;
mod gains;
mod problem;

pub(crate) use config::{check_matrix, check_perturbation, check_vector};
pub use config::{LqtConfig, Perturbation, MAX_ORDER};
pub use gains::{full_pipeline, FeedbackGains};
pub use problem::{BatchSolution, LqtCp, Rollout};
