//! The task builder: the reference μ (T×nx) and the weights `q_diag` (T×nx) of an LQT-CP problem
//! from a tracked demonstration, via-points and goals (paper §III-B: "we incorporate via-point
//! specifications by simply indicating the via-points in the reference trajectory μ and assigning
//! the same importance to via-point and goal reaching in the weight matrix Q").
//!
//! Start from μ = 0, q = 0. With tracking: μ's position columns are the demo positions, the
//! velocity columns `gradient(pos)/dt`, the acceleration columns `gradient(vel)/dt` (and each
//! higher derivative in the state the gradient of the previous one over dt), where `gradient` is
//! numpy's with unit spacing (central differences inside, one-sided at both ends); q of derivative
//! order i is `weights_per_order[i]` at every step. Then each target overwrites μ and q at its step
//! for the orders it gives (position, and velocity when present).
//!
//! DMP mode (LQT-CP as an optimal-control DMP) is tracking with weights only on the acceleration
//! (e.g. `[0, 0, w]`) plus a goal target at the last step.

use super::solver::LqtConfig;
use super::LqtError;
use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

/// Whether a target is an intermediate via-point or the goal (same maths; the role says which
/// target the feedback rollouts are measured against).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify))]
pub enum TargetRole {
    /// An intermediate point to pass through.
    Via,
    /// The point to reach (the last goal is the rollouts' `final_goal_pos_dist` reference).
    Goal,
}

impl TargetRole {
    /// `"via"` or `"goal"`.
    pub fn name(self) -> &'static str {
        match self {
            TargetRole::Via => "via",
            TargetRole::Goal => "goal",
        }
    }
}

/// A position (and optionally velocity) to reach at step `t` with the given precisions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Target {
    /// State index (0..T-1).
    pub t: usize,
    /// Via-point or goal.
    pub role: TargetRole,
    /// Position (D).
    pub pos: Vec<f64>,
    /// Precision on the position (1/length²), ≥ 0.
    pub w_pos: f64,
    /// Optional velocity (D); needs order ≥ 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vel: Option<Vec<f64>>,
    /// Precision on the velocity (1/(length/s)²), ≥ 0; 0 when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub w_vel: Option<f64>,
}

/// A demonstration to track along the whole horizon.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Tracking {
    /// Demonstrated positions (T×D).
    pub demo_pos: DMatrix<f64>,
    /// One precision per derivative order in the state (n of them), ≥ 0.
    pub weights_per_order: Vec<f64>,
}

/// numpy's `gradient` with unit spacing: central differences inside, one-sided at the ends.
pub fn gradient(v: &[f64]) -> Vec<f64> {
    let n = v.len();
    match n {
        0 => Vec::new(),
        1 => vec![0.0],
        _ => (0..n)
            .map(|i| {
                if i == 0 {
                    v[1] - v[0]
                } else if i == n - 1 {
                    v[n - 1] - v[n - 2]
                } else {
                    (v[i + 1] - v[i - 1]) / 2.0
                }
            })
            .collect(),
    }
}

fn check_finite_vec(key: &str, v: &[f64], len: usize) -> Result<(), LqtError> {
    super::solver::check_vector(key, v, len)
}

fn check_weight(key: &str, w: f64) -> Result<(), LqtError> {
    if !(w.is_finite() && w >= 0.0) {
        return Err(LqtError::input(
            key,
            format!("expected a finite non-negative weight, got {w}"),
        ));
    }
    Ok(())
}

/// Validate targets against the configuration (step in range, shapes, weights, velocity only
/// with order ≥ 2).
pub fn validate_targets(config: &LqtConfig, targets: &[Target]) -> Result<(), LqtError> {
    for (j, tg) in targets.iter().enumerate() {
        let key = format!("targets[{j}]");
        if tg.t >= config.n_steps {
            return Err(LqtError::input(
                format!("{key}.t"),
                format!("expected a step in 0..{}, got {}", config.n_steps, tg.t),
            ));
        }
        check_finite_vec(&format!("{key}.pos"), &tg.pos, config.dim)?;
        check_weight(&format!("{key}.w_pos"), tg.w_pos)?;
        if let Some(w) = tg.w_vel {
            check_weight(&format!("{key}.w_vel"), w)?;
        }
        if let Some(v) = &tg.vel {
            if config.order < 2 {
                return Err(LqtError::input(
                    format!("{key}.vel"),
                    "an order-1 state has no velocity to constrain",
                ));
            }
            check_finite_vec(&format!("{key}.vel"), v, config.dim)?;
        }
    }
    Ok(())
}

/// Validate a tracking specification (demo T×D, n weights ≥ 0).
pub fn validate_tracking(config: &LqtConfig, tracking: &Tracking) -> Result<(), LqtError> {
    super::solver::check_matrix(
        "tracking.demo_pos",
        &tracking.demo_pos,
        config.n_steps,
        config.dim,
        false,
    )?;
    if tracking.weights_per_order.len() != config.order {
        return Err(LqtError::input(
            "tracking.weights_per_order",
            format!(
                "expected {} numbers (one per derivative order of the state), got {}",
                config.order,
                tracking.weights_per_order.len()
            ),
        ));
    }
    for (i, &w) in tracking.weights_per_order.iter().enumerate() {
        check_weight(&format!("tracking.weights_per_order[{i}]"), w)?;
    }
    Ok(())
}

/// Build `(μ, q_diag)` (both T×nx) from targets and an optional tracked demonstration.
pub fn build_reference(
    config: &LqtConfig,
    targets: &[Target],
    tracking: Option<&Tracking>,
) -> Result<(DMatrix<f64>, DMatrix<f64>), LqtError> {
    config.validate()?;
    validate_targets(config, targets)?;
    let (dim, n, t_n) = (config.dim, config.order, config.n_steps);
    let nx = dim * n;
    let mut mu = DMatrix::zeros(t_n, nx);
    let mut q = DMatrix::zeros(t_n, nx);
    if let Some(tr) = tracking {
        validate_tracking(config, tr)?;
        for d in 0..dim {
            let mut deriv: Vec<f64> = (0..t_n).map(|t| tr.demo_pos[(t, d)]).collect();
            for i in 0..n {
                if i > 0 {
                    deriv = gradient(&deriv)
                        .into_iter()
                        .map(|v| v / config.dt)
                        .collect();
                }
                for t in 0..t_n {
                    mu[(t, i * dim + d)] = deriv[t];
                    q[(t, i * dim + d)] = tr.weights_per_order[i];
                }
            }
        }
    }
    for tg in targets {
        for d in 0..dim {
            mu[(tg.t, d)] = tg.pos[d];
            q[(tg.t, d)] = tg.w_pos;
            if let Some(v) = &tg.vel {
                mu[(tg.t, dim + d)] = v[d];
                q[(tg.t, dim + d)] = tg.w_vel.unwrap_or(0.0);
            }
        }
    }
    Ok((mu, q))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gradient_matches_numpy() {
        assert_eq!(gradient(&[1.0, 2.0, 4.0, 7.0]), vec![1.0, 1.5, 2.5, 3.0]);
    }
}
