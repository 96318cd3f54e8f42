//! The classic DMP (Ijspeert, Nakanishi, Hoffmann, Pastor, Schaal 2013), the paper's comparison.
//!
//! ```text
//! τ ż = α_z (β_z (g - y) - z) + f(s),    τ ẏ = z,    τ ṡ = -α_s s,  s(0) = 1
//! f(s) = (Σ_i ψ_i(s) w_i / Σ_i ψ_i(s)) s a,    ψ_i(s) = exp(-h_i (s - c_i)²)
//! ```
//!
//! with the amplitude `a = (g - y_0) / (g - y_0)_demo` per coordinate (Ijspeert's `s (g - y_0)`
//! scaling, normalised by the demo's displacement), or `a = 1` for a coordinate whose demo starts and
//! ends at the same value (less than 1e-3 of the demo's extent apart), where the classic scaling
//! would erase the forcing term.
//!
//! Learning from one demo `y_t` (velocity and acceleration by numpy-style gradients):
//! `f_target = τ² ÿ - α_z (β_z (g - y) - τ ẏ)`, and locally weighted regression per basis function
//! `w_i = Σ_t s_t ψ_i f_target / Σ_t s_t² ψ_i` (a = 1 on the demo). Centers `c_i` are spaced
//! evenly in time along the canonical system, widths `h_i = 1/(c_{i+1} - c_i)²`.
//!
//! Like the LQT-CP [`Skill`](super::Skill), a DMP lives in the object frame; it has no means to
//! encode via-points (the paper's point): [`Dmp`]'s `plan` ignores them. It reacts to a pushed end
//! effector by integrating on from the measured position.

use super::task::gradient;
use super::LqtError;
use nalgebra::{Point3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// Tunables of a classic DMP.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DmpParams {
    /// Number of basis functions of the forcing term.
    pub n_fct: usize,
    /// Spring constant α_z (1/s, in units of τ); β_z = α_z / 4 (critical damping).
    pub alpha_z: f64,
    /// Canonical-system decay α_s (the phase reaches `exp(-α_s)` at the end of the demo).
    pub alpha_s: f64,
    /// Euler sub-steps per time step of the trajectory.
    pub substeps: usize,
}

impl Default for DmpParams {
    fn default() -> Self {
        DmpParams {
            n_fct: 30,
            alpha_z: 25.0,
            alpha_s: 4.0,
            substeps: 10,
        }
    }
}

/// A DMP learned from one demonstrated segment (object frame). Deserialisation checks the
/// lengths and parameters.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(try_from = "DmpData")]
pub struct Dmp {
    params: DmpParams,
    pub(super) dt: f64,
    pub(super) n_steps: usize,
    goal: Vector3<f64>,
    pub(super) demo_rotations: Vec<UnitQuaternion<f64>>,
    weights: Vec<[f64; 3]>,
    demo_displacement: [Option<f64>; 3],
    centers: Vec<f64>,
    widths: Vec<f64>,
}

/// The serialised form of [`Dmp`], validated by `TryFrom`.
#[derive(Deserialize)]
struct DmpData {
    params: DmpParams,
    dt: f64,
    n_steps: usize,
    goal: Vector3<f64>,
    demo_rotations: Vec<UnitQuaternion<f64>>,
    weights: Vec<[f64; 3]>,
    demo_displacement: [Option<f64>; 3],
    centers: Vec<f64>,
    widths: Vec<f64>,
}

impl TryFrom<DmpData> for Dmp {
    type Error = String;

    fn try_from(d: DmpData) -> Result<Self, String> {
        let k = d.params.n_fct;
        if d.n_steps < 3 || !(d.dt.is_finite() && d.dt > 0.0) || d.params.substeps == 0 || k == 0 {
            return Err("dmp: n_steps >= 3, dt > 0, substeps >= 1 and n_fct >= 1 expected".into());
        }
        if d.weights.len() != k || d.centers.len() != k || d.widths.len() != k {
            return Err(format!(
                "dmp: weights, centers and widths must have n_fct = {k} entries"
            ));
        }
        if d.demo_rotations.len() != d.n_steps {
            return Err(format!(
                "dmp: demo_rotations must have n_steps = {} entries",
                d.n_steps
            ));
        }
        Ok(Dmp {
            params: d.params,
            dt: d.dt,
            n_steps: d.n_steps,
            goal: d.goal,
            demo_rotations: d.demo_rotations,
            weights: d.weights,
            demo_displacement: d.demo_displacement,
            centers: d.centers,
            widths: d.widths,
        })
    }
}

/// The integrator of a DMP for one plan: state `[y (3), z (3), s]` in the object frame.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct DmpRunner {
    pub(super) dmp: Dmp,
    pub(super) y0: Vector3<f64>,
}

impl Dmp {
    /// Learn a DMP from demonstrated positions in the object frame.
    pub fn learn(demo: &[Point3<f64>], dt: f64, params: DmpParams) -> Result<Dmp, LqtError> {
        let t_n = demo.len();
        if t_n < 3 {
            return Err(LqtError::input(
                "demo",
                format!("expected at least 3 positions, got {t_n}"),
            ));
        }
        if demo.iter().any(|p| !p.coords.iter().all(|v| v.is_finite())) {
            return Err(LqtError::input("demo", "expected finite coordinates"));
        }
        if !(dt.is_finite() && dt > 0.0) {
            return Err(LqtError::input(
                "dt",
                "expected a finite positive time step",
            ));
        }
        if params.n_fct == 0 || params.substeps == 0 {
            return Err(LqtError::input(
                "params",
                "n_fct and substeps must be at least 1",
            ));
        }
        if !(params.alpha_z > 0.0 && params.alpha_s > 0.0) {
            return Err(LqtError::input(
                "params",
                "alpha_z and alpha_s must be positive",
            ));
        }
        let k_n = params.n_fct;
        let tau = dt * (t_n - 1) as f64;
        let centers: Vec<f64> = (0..k_n)
            .map(|i| {
                let frac = if k_n == 1 {
                    0.5
                } else {
                    i as f64 / (k_n - 1) as f64
                };
                libm::exp(-params.alpha_s * frac)
            })
            .collect();
        let widths: Vec<f64> = (0..k_n)
            .map(|i| {
                let d = if k_n == 1 {
                    0.5
                } else if i + 1 < k_n {
                    centers[i + 1] - centers[i]
                } else {
                    centers[i] - centers[i - 1]
                };
                1.0 / (d * d)
            })
            .collect();
        let goal = demo[t_n - 1].coords;
        let y0 = demo[0].coords;
        let az = params.alpha_z;
        let bz = az / 4.0;
        let extent = demo
            .iter()
            .map(|p| (p - demo[0]).norm())
            .fold(0.0, f64::max);
        let mut demo_displacement = [None; 3];
        for d in 0..3 {
            let g = goal[d] - y0[d];
            if g.abs() > 1e-3 * extent {
                demo_displacement[d] = Some(g);
            }
        }
        let mut weights = vec![[0.0; 3]; k_n];
        for d in 0..3 {
            let y: Vec<f64> = demo.iter().map(|p| p[d]).collect();
            let yd: Vec<f64> = gradient(&y).iter().map(|v| v / dt).collect();
            let ydd: Vec<f64> = gradient(&yd).iter().map(|v| v / dt).collect();
            for (i, w) in weights.iter_mut().enumerate() {
                let (mut num, mut den) = (0.0, 1e-12);
                for t in 0..t_n {
                    let s = libm::exp(-params.alpha_s * t as f64 / (t_n - 1) as f64);
                    let psi = libm::exp(-widths[i] * (s - centers[i]).powi(2));
                    let f = tau * tau * ydd[t] - az * (bz * (goal[d] - y[t]) - tau * yd[t]);
                    let xi = s;
                    num += xi * psi * f;
                    den += xi * xi * psi;
                }
                w[d] = num / den;
            }
        }
        Ok(Dmp {
            params,
            dt,
            n_steps: t_n,
            goal,
            demo_rotations: vec![UnitQuaternion::identity(); t_n],
            weights,
            demo_displacement,
            centers,
            widths,
        })
    }

    /// Tunables.
    pub fn params(&self) -> &DmpParams {
        &self.params
    }

    /// Time step (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Number of steps of the demo (the plans have as many).
    pub fn n_steps(&self) -> usize {
        self.n_steps
    }

    /// Goal g in the object frame (the demo's last position).
    pub fn goal(&self) -> &Vector3<f64> {
        &self.goal
    }

    /// The weights of the forcing term (K per coordinate).
    pub fn weights(&self) -> &[[f64; 3]] {
        &self.weights
    }

    /// The amplitude `a` of coordinate d for a start `y0`.
    fn amplitude(&self, d: usize, y0: f64) -> f64 {
        match self.demo_displacement[d] {
            Some(g) => (self.goal[d] - y0) / g,
            None => 1.0,
        }
    }
}

impl DmpRunner {
    /// `[y0, 0, 0, 0, 1]`.
    pub(crate) fn initial_state(&self) -> Vec<f64> {
        vec![self.y0[0], self.y0[1], self.y0[2], 0.0, 0.0, 0.0, 1.0]
    }

    /// Number of steps of the plan.
    pub fn n_steps(&self) -> usize {
        self.dmp.n_steps
    }

    /// Integrate one time step (Euler, `substeps` sub-steps).
    pub(crate) fn step(&self, state: &mut [f64]) {
        let p = &self.dmp.params;
        let tau = self.dmp.dt * (self.dmp.n_steps - 1) as f64;
        let h = self.dmp.dt / p.substeps as f64;
        let bz = p.alpha_z / 4.0;
        let k_n = self.dmp.centers.len();
        for _ in 0..p.substeps {
            let s = state[6];
            // Normalised basis activations, once per sub-step for the three coordinates.
            let mut f = [0.0; 3];
            let mut den = 1e-12;
            for i in 0..k_n {
                let psi = libm::exp(-self.dmp.widths[i] * (s - self.dmp.centers[i]).powi(2));
                den += psi;
                for (fd, wd) in f.iter_mut().zip(&self.dmp.weights[i]) {
                    *fd += psi * wd;
                }
            }
            for d in 0..3 {
                let (y, z) = (state[d], state[3 + d]);
                let fd = f[d] / den * s * self.dmp.amplitude(d, self.y0[d]);
                let zd = (p.alpha_z * (bz * (self.dmp.goal[d] - y) - z) + fd) / tau;
                state[d] = y + h * z / tau;
                state[3 + d] = z + h * zd;
            }
            state[6] = s - h * p.alpha_s * s / tau;
        }
    }
}
