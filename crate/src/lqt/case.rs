//! The JSON contract of `logic-lfd lqt CASE.json` (`docs/formats.md`): parse a case with
//! errors that name the key and the expected shape, solve it with the fast path, and build the
//! output object (`A`, `B`, `phi`, `w`, `u`, `x`, `pos`, `cost`, `target_errors`, `feedback`).
//!
//! `reference.mu` and `reference.q_diag` are authoritative; `targets` are used for the reported
//! errors (and, like `tracking`, are validated). Unknown keys are ignored.

use super::basis::Basis;
use super::solver::{LqtConfig, LqtCp, Perturbation};
use super::task::{validate_targets, validate_tracking, Target, TargetRole, Tracking};
use super::LqtError;
use nalgebra::DMatrix;
use serde::Serialize;
use serde_json::Value;

/// The `feedback` object of a case.
#[derive(Debug, Clone, PartialEq)]
pub struct FeedbackSpec {
    /// Initial state of the rollouts (nx).
    pub x_init: Vec<f64>,
    /// Optional perturbation of the second rollout.
    pub perturbation: Option<Perturbation>,
}

/// A parsed and validated case.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseInput {
    /// Dynamics, horizon, control weight and basis.
    pub config: LqtConfig,
    /// Initial state of the batch solve (nx).
    pub x0: Vec<f64>,
    /// Reference μ (T×nx).
    pub mu: DMatrix<f64>,
    /// Diagonal of Q_t (T×nx).
    pub q_diag: DMatrix<f64>,
    /// How μ and q were built (reported in `target_errors`).
    pub targets: Vec<Target>,
    /// The tracked demonstration, if any (validated, informative).
    pub tracking: Option<Tracking>,
    /// Feedback rollouts to compute, if any.
    pub feedback: Option<FeedbackSpec>,
}

/// Distances of the batch trajectory to one input target.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct LqtTargetError {
    /// The target's step.
    pub t: usize,
    /// Via-point or goal.
    pub role: TargetRole,
    /// Euclidean distance between the position at `t` and the target position.
    pub pos_dist: f64,
    /// Euclidean distance between the velocity at `t` and the target velocity (when given).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vel_dist: Option<f64>,
}

/// One feedback rollout in the output.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct LqtRollout {
    /// States (T×nx).
    pub x: Vec<Vec<f64>>,
    /// Controls (N×D).
    pub u: Vec<Vec<f64>>,
    /// Positions (T×D).
    pub pos: Vec<Vec<f64>>,
    /// Distance to the last goal target's position at its step (null without a goal target).
    pub final_goal_pos_dist: Option<f64>,
}

/// The `feedback` object of the output.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct LqtFeedback {
    /// F ((N·D)×(nx+1)).
    #[serde(rename = "F")]
    pub f: Vec<Vec<f64>>,
    /// The gains K̃_t (N×D×(nx+1)).
    pub gains: Vec<Vec<Vec<f64>>>,
    /// Rollout from `x_init` without perturbation.
    pub nominal: LqtRollout,
    /// Rollout from `x_init` with the perturbation (when given).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub perturbed: Option<LqtRollout>,
}

/// The output object of `logic-lfd lqt`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(
    feature = "wasm-core",
    derive(tsify::Tsify),
    tsify(missing_as_null, rename = "LqtOutput")
)]
pub struct CaseOutput {
    /// A (nx×nx).
    #[serde(rename = "A")]
    pub a: Vec<Vec<f64>>,
    /// B (nx×D).
    #[serde(rename = "B")]
    pub b: Vec<Vec<f64>>,
    /// φ (N×K).
    pub phi: Vec<Vec<f64>>,
    /// Batch weights (K×D).
    pub w: Vec<Vec<f64>>,
    /// Batch controls (N×D).
    pub u: Vec<Vec<f64>>,
    /// Batch states (T×nx).
    pub x: Vec<Vec<f64>>,
    /// Batch positions (T×D).
    pub pos: Vec<Vec<f64>>,
    /// Cost J of the batch solution.
    pub cost: f64,
    /// One entry per input target, in order.
    pub target_errors: Vec<LqtTargetError>,
    /// Present when the input has a `feedback` object.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub feedback: Option<LqtFeedback>,
}

/// A JSON value with its dotted path, for error messages.
struct Node<'a> {
    v: &'a Value,
    path: String,
}

fn type_name(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "a list",
        Value::Object(_) => "an object",
    }
}

impl<'a> Node<'a> {
    fn err(&self, msg: impl Into<String>) -> LqtError {
        LqtError::input(self.path.clone(), msg)
    }

    fn child_path(&self, k: &str) -> String {
        if self.path.is_empty() {
            k.to_string()
        } else {
            format!("{}.{k}", self.path)
        }
    }

    fn obj(&self) -> Result<&'a serde_json::Map<String, Value>, LqtError> {
        self.v
            .as_object()
            .ok_or_else(|| self.err(format!("expected an object, got {}", type_name(self.v))))
    }

    fn key(&self, k: &str) -> Result<Node<'a>, LqtError> {
        let path = self.child_path(k);
        match self.obj()?.get(k) {
            Some(v) => Ok(Node { v, path }),
            None => Err(LqtError::input(path, "missing key")),
        }
    }

    /// A key that may be absent or null.
    fn opt_key(&self, k: &str) -> Result<Option<Node<'a>>, LqtError> {
        let path = self.child_path(k);
        Ok(match self.obj()?.get(k) {
            None | Some(Value::Null) => None,
            Some(v) => Some(Node { v, path }),
        })
    }

    fn index(&self, i: usize, v: &'a Value) -> Node<'a> {
        Node {
            v,
            path: format!("{}[{i}]", self.path),
        }
    }

    fn f64(&self) -> Result<f64, LqtError> {
        match self.v.as_f64() {
            Some(x) if x.is_finite() => Ok(x),
            Some(x) => Err(self.err(format!("expected a finite number, got {x}"))),
            None => Err(self.err(format!("expected a number, got {}", type_name(self.v)))),
        }
    }

    fn usize(&self) -> Result<usize, LqtError> {
        if let Some(u) = self.v.as_u64() {
            return usize::try_from(u).map_err(|_| self.err("integer too large"));
        }
        match self.v.as_f64() {
            Some(x) if x.is_finite() && x >= 0.0 && x.fract() == 0.0 && x < 1e15 => Ok(x as usize),
            Some(x) => Err(self.err(format!("expected a non-negative integer, got {x}"))),
            None => Err(self.err(format!(
                "expected a non-negative integer, got {}",
                type_name(self.v)
            ))),
        }
    }

    fn str(&self) -> Result<&'a str, LqtError> {
        self.v
            .as_str()
            .ok_or_else(|| self.err(format!("expected a string, got {}", type_name(self.v))))
    }

    fn list(&self) -> Result<&'a Vec<Value>, LqtError> {
        self.v
            .as_array()
            .ok_or_else(|| self.err(format!("expected a list, got {}", type_name(self.v))))
    }

    fn vec_f64(&self, len: usize) -> Result<Vec<f64>, LqtError> {
        let l = self.list()?;
        if l.len() != len {
            return Err(self.err(format!("expected {len} numbers, got {}", l.len())));
        }
        l.iter()
            .enumerate()
            .map(|(i, v)| self.index(i, v).f64())
            .collect()
    }

    fn matrix(&self, rows: usize, cols: usize) -> Result<DMatrix<f64>, LqtError> {
        let shape = format!("expected {rows} rows of {cols} numbers");
        let l = self.list()?;
        if l.len() != rows {
            return Err(self.err(format!("{shape}, got {} rows", l.len())));
        }
        let mut m = DMatrix::zeros(rows, cols);
        for (r, rv) in l.iter().enumerate() {
            let row = self.index(r, rv);
            let rl = row
                .list()
                .map_err(|_| self.err(format!("{shape}, row {r} is {}", type_name(rv))))?;
            if rl.len() != cols {
                return Err(self.err(format!("{shape}, row {r} has {} numbers", rl.len())));
            }
            for (c, v) in rl.iter().enumerate() {
                m[(r, c)] = row.index(c, v).f64()?;
            }
        }
        Ok(m)
    }
}

fn parse_basis(node: &Node) -> Result<Basis, LqtError> {
    let ty = node.key("type")?;
    let n_fct = node.key("n_fct")?.usize()?;
    Ok(match ty.str()? {
        "rbf" => {
            let c = node.key("centers")?;
            let centers = c.vec_f64(n_fct)?;
            let lambda = node.key("lambda")?.f64()?;
            Basis::Rbf {
                n_fct,
                centers,
                lambda,
            }
        }
        "bernstein" => Basis::Bernstein { n_fct },
        "fourier" => Basis::Fourier { n_fct },
        "piecewise" => Basis::Piecewise { n_fct },
        other => {
            return Err(ty.err(format!(
                "unknown basis \"{other}\": expected rbf, bernstein, fourier or piecewise"
            )))
        }
    })
}

impl CaseInput {
    /// Parse a case from JSON text. Syntax errors carry line and column.
    pub fn from_json_str(text: &str) -> Result<CaseInput, LqtError> {
        let v: Value = serde_json::from_str(text).map_err(|e| LqtError::Json {
            line: e.line(),
            column: e.column(),
            message: e.to_string(),
        })?;
        CaseInput::from_value(&v)
    }

    /// Parse and validate a case from a JSON value.
    pub fn from_value(v: &Value) -> Result<CaseInput, LqtError> {
        let root = Node {
            v,
            path: String::new(),
        };
        root.obj()?;
        let config = LqtConfig {
            dim: root.key("dim")?.usize()?,
            order: root.key("order")?.usize()?,
            dt: root.key("dt")?.f64()?,
            n_steps: root.key("n_steps")?.usize()?,
            r: root.key("r")?.f64()?,
            basis: parse_basis(&root.key("basis")?)?,
        };
        config.validate()?;
        let (t_n, nx) = (config.n_steps, config.nx());
        let x0 = root.key("x0")?.vec_f64(nx)?;
        let reference = root.key("reference")?;
        let mu = reference.key("mu")?.matrix(t_n, nx)?;
        let q_diag = reference.key("q_diag")?.matrix(t_n, nx)?;
        super::solver::check_matrix("reference.q_diag", &q_diag, t_n, nx, true)?;

        let mut targets = Vec::new();
        if let Some(tl) = root.opt_key("targets")? {
            for (j, tv) in tl.list()?.iter().enumerate() {
                let tn = tl.index(j, tv);
                let role = tn.key("role")?;
                let role = match role.str()? {
                    "via" => TargetRole::Via,
                    "goal" => TargetRole::Goal,
                    other => {
                        return Err(role.err(format!(
                            "unknown role \"{other}\": expected \"via\" or \"goal\""
                        )))
                    }
                };
                let vel = tn
                    .opt_key("vel")?
                    .map(|n| n.vec_f64(config.dim))
                    .transpose()?;
                let w_vel = match tn.opt_key("w_vel")? {
                    Some(n) => Some(n.f64()?),
                    None if vel.is_some() => {
                        return Err(LqtError::input(
                            format!("{}.w_vel", tn.path),
                            "missing key (required with vel)",
                        ))
                    }
                    None => None,
                };
                targets.push(Target {
                    t: tn.key("t")?.usize()?,
                    role,
                    pos: tn.key("pos")?.vec_f64(config.dim)?,
                    w_pos: tn.key("w_pos")?.f64()?,
                    vel,
                    w_vel,
                });
            }
        }
        validate_targets(&config, &targets)?;

        let tracking = match root.opt_key("tracking")? {
            Some(tn) => {
                let demo_pos = tn.key("demo_pos")?.matrix(t_n, config.dim)?;
                let wn = tn.key("weights_per_order")?;
                let weights_per_order = wn.vec_f64(config.order)?;
                let tr = Tracking {
                    demo_pos,
                    weights_per_order,
                };
                validate_tracking(&config, &tr)?;
                Some(tr)
            }
            None => None,
        };

        let feedback = match root.opt_key("feedback")? {
            Some(fb) => {
                let x_init = fb.key("x_init")?.vec_f64(nx)?;
                let perturbation = match fb.opt_key("perturbation")? {
                    Some(p) => {
                        let pert = Perturbation {
                            after_step: p.key("after_step")?.usize()?,
                            delta: p.key("delta")?.vec_f64(nx)?,
                        };
                        super::solver::check_perturbation(&pert, nx, t_n - 1)?;
                        Some(pert)
                    }
                    None => None,
                };
                Some(FeedbackSpec {
                    x_init,
                    perturbation,
                })
            }
            None => None,
        };
        Ok(CaseInput {
            config,
            x0,
            mu,
            q_diag,
            targets,
            tracking,
            feedback,
        })
    }
}

/// A matrix as a list of rows.
pub(crate) fn rows(m: &DMatrix<f64>) -> Vec<Vec<f64>> {
    (0..m.nrows())
        .map(|r| (0..m.ncols()).map(|c| m[(r, c)]).collect())
        .collect()
}

/// Euclidean distance between row `t` of `x` at columns `off..off+dim` and `p`.
fn dist(x: &DMatrix<f64>, t: usize, off: usize, p: &[f64]) -> f64 {
    p.iter()
        .enumerate()
        .map(|(d, pd)| (x[(t, off + d)] - pd).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Solve a case: batch solution, target errors and, if asked, F, the gains and the rollouts.
pub fn run_case(input: &CaseInput) -> Result<CaseOutput, LqtError> {
    let cfg = &input.config;
    let dim = cfg.dim;
    let lqt = LqtCp::new(cfg.clone(), &input.q_diag)?;
    let sol = lqt.solve(&input.mu, &input.x0)?;
    let pos_of = |x: &DMatrix<f64>| rows(&x.columns(0, dim).into_owned());
    let target_errors = input
        .targets
        .iter()
        .map(|tg| LqtTargetError {
            t: tg.t,
            role: tg.role,
            pos_dist: dist(&sol.x, tg.t, 0, &tg.pos),
            vel_dist: tg.vel.as_ref().map(|v| dist(&sol.x, tg.t, dim, v)),
        })
        .collect();
    let last_goal = input
        .targets
        .iter()
        .rev()
        .find(|tg| tg.role == TargetRole::Goal);
    let feedback = match &input.feedback {
        None => None,
        Some(fb) => {
            let gains = lqt.feedback(&input.mu)?;
            let out = |x: DMatrix<f64>, u: DMatrix<f64>| LqtRollout {
                pos: pos_of(&x),
                final_goal_pos_dist: last_goal.map(|g| dist(&x, g.t, 0, &g.pos)),
                x: rows(&x),
                u: rows(&u),
            };
            let nominal = gains.rollout(&fb.x_init, None)?;
            let perturbed = match &fb.perturbation {
                Some(p) => {
                    let r = gains.rollout(&fb.x_init, Some(p))?;
                    Some(out(r.x, r.u))
                }
                None => None,
            };
            Some(LqtFeedback {
                f: rows(&gains.f_matrix()),
                gains: (0..gains.n_controls())
                    .filter_map(|t| gains.gain(t))
                    .map(|k| rows(&k))
                    .collect(),
                nominal: out(nominal.x, nominal.u),
                perturbed,
            })
        }
    };
    Ok(CaseOutput {
        a: rows(&cfg.a_matrix()),
        b: rows(&cfg.b_matrix()),
        phi: rows(&cfg.phi_matrix()),
        w: rows(&sol.w),
        u: rows(&sol.u),
        pos: pos_of(&sol.x),
        x: rows(&sol.x),
        cost: sol.cost,
        target_errors,
        feedback,
    })
}
