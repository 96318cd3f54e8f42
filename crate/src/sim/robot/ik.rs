//! Inverse kinematics for any chain of up to seven moving joints (revolute, continuous,
//! prismatic) with a TCP on its tip: find joints within the URDF's limits that put the TCP at a
//! target pose.
//!
//! Each attempt is a Levenberg–Marquardt iteration on the geometric Jacobian, with the damping
//! tied to the error as Sugihara (2011) proposes, so it neither blows up at singularities nor
//! crawls near the solution:
//!
//! ```text
//! e  = (p* − p, w · log(R* Rᵀ)),   E = ½ |e|²
//! Δq = (JᵀJ + (E + b) I)⁻¹ Jᵀ e,   q ← clamp(q + Δq, lower, upper)
//! ```
//!
//! with `w` the orientation weight (m/rad) and `b` a small bias. A joint at a limit that the
//! step would drive further out is held there and the step solved again without it. A redundant
//! (7-joint) chain also moves in the Jacobian's null space towards the middle of its joint
//! ranges while far from the target, which keeps it away from the limits. An attempt that stops
//! improving gives way to a restart from a seeded random posture within the limits. The
//! solution's continuous and wide-range joints are wound to the turn nearest the seed.

use nalgebra::{Cholesky, Isometry3, Matrix6xX, SMatrix, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::chain::Chain;
use super::file::Robot;
use super::model::{rotation_error, Frames, Joints, Model, MAX_DOF};

/// Tunables of the IK solver.
#[derive(Clone, Debug, PartialEq)]
pub struct IkOptions {
    /// Iterations per attempt (the seed's and each restart's).
    pub max_iterations: usize,
    /// Random restarts after the attempt from the seed fails.
    pub restarts: usize,
    /// Solved when the TCP is this close to the target position (m).
    pub position_tolerance: f64,
    /// Solved when the TCP's orientation is within this angle of the target's (rad).
    pub orientation_tolerance: f64,
    /// Gain of the redundant chain's null-space pull towards mid-range (per iteration).
    pub null_space_gain: f64,
    /// Seed of the restart postures.
    pub seed: u64,
}

impl Default for IkOptions {
    fn default() -> Self {
        IkOptions {
            max_iterations: 100,
            restarts: 40,
            position_tolerance: 1e-5,
            orientation_tolerance: 1e-4,
            null_space_gain: 0.05,
            seed: 1,
        }
    }
}

/// A solved IK problem.
#[derive(Clone, Debug, PartialEq)]
pub struct IkResult {
    /// The joint vector, within the limits, in chain order.
    pub joints: Vec<f64>,
    /// Distance of its TCP from the target position (m).
    pub position_error: f64,
    /// Angle between its TCP's orientation and the target's (rad).
    pub orientation_error: f64,
    /// Iterations over all attempts.
    pub iterations: usize,
    /// Attempts made (1: the seed's attempt solved it).
    pub attempts: usize,
}

/// Why IK found no joints.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum IkFailure {
    /// The seed has the wrong length.
    #[error("{given} seed values for {dof} joints")]
    SeedLength {
        /// Values given.
        given: usize,
        /// Moving joints of the chain.
        dof: usize,
    },
    /// The target or the seed holds a NaN or an infinity.
    #[error("the target pose or the seed is not finite")]
    NotFinite,
    /// The chain has no moving joint or more than seven.
    #[error("inverse kinematics needs 1 to 7 moving joints; the chain has {dof}")]
    UnsupportedChain {
        /// Moving joints of the chain.
        dof: usize,
    },
    /// No attempt reached the target within the tolerances.
    #[error(
        "unreachable: the closest posture found leaves the TCP {position_error:.4} m and \
         {orientation_error:.4} rad from the target ({attempts} attempts)"
    )]
    Unreachable {
        /// The closest posture found, within the limits.
        best_joints: Vec<f64>,
        /// Its position error (m).
        position_error: f64,
        /// Its orientation error (rad).
        orientation_error: f64,
        /// Iterations over all attempts.
        iterations: usize,
        /// Attempts made.
        attempts: usize,
    },
}

/// Metres of position error one radian of orientation error weighs as.
const ORIENTATION_WEIGHT: f64 = 0.3;

/// Bias `b` of the damping: keeps the step finite where the Jacobian loses rank at `E = 0`.
const DAMPING_BIAS: f64 = 1e-6;

/// Largest change of any joint in one iteration (rad or m): keeps far-off steps inside the
/// region where the linearisation means something.
const MAX_STEP: f64 = 0.5;

/// An attempt stalls when the error has not dropped by this fraction ...
const STALL_GAIN: f64 = 1e-3;

/// ... within this many iterations.
const STALL_WINDOW: usize = 8;

/// The redundant chain pulls towards mid-range only while the weighted error `E` exceeds this:
/// near the target the pull would leak into the task through the damping.
const PULL_UNTIL: f64 = 1e-6;

/// What one attempt ended with.
#[derive(Clone, Copy, Debug)]
struct Attempt {
    q: Joints,
    position_error: f64,
    orientation_error: f64,
    cost: f64,
    iterations: usize,
    solved: bool,
}

impl Chain {
    /// Joints within the limits whose TCP (`tcp` on the tip link) reaches `target` (in the base
    /// link's frame), starting from `seed`; see [`IkOptions`] for the tolerances and restarts.
    pub fn ik(
        &self,
        tcp: &Isometry3<f64>,
        target: &Isometry3<f64>,
        seed: &[f64],
        options: &IkOptions,
    ) -> Result<IkResult, IkFailure> {
        let model = Model::new(self, tcp).map_err(|dof| IkFailure::UnsupportedChain { dof })?;
        if seed.len() != model.n {
            return Err(IkFailure::SeedLength {
                given: seed.len(),
                dof: model.n,
            });
        }
        let finite = target.translation.vector.iter().all(|v| v.is_finite())
            && target.rotation.coords.iter().all(|v| v.is_finite())
            && seed.iter().all(|v| v.is_finite());
        if !finite {
            return Err(IkFailure::NotFinite);
        }
        let mut start = [0.0; MAX_DOF];
        for i in 0..model.n {
            start[i] = seed[i].clamp(model.lower[i], model.upper[i]);
        }
        let mut rng = Pcg64Mcg::seed_from_u64(options.seed);
        let mut best: Option<Attempt> = None;
        let mut iterations = 0;
        for k in 0..=options.restarts {
            if k > 0 {
                start = random_posture(&model, &mut rng);
            }
            let a = attempt(&model, target, start, options);
            iterations += a.iterations;
            if a.solved {
                return Ok(IkResult {
                    joints: wound_near(&model, &a.q, seed),
                    position_error: a.position_error,
                    orientation_error: a.orientation_error,
                    iterations,
                    attempts: k + 1,
                });
            }
            if best.is_none_or(|b| a.cost < b.cost) {
                best = Some(a);
            }
        }
        let b = best.unwrap_or(Attempt {
            q: start,
            position_error: f64::INFINITY,
            orientation_error: f64::INFINITY,
            cost: f64::INFINITY,
            iterations: 0,
            solved: false,
        });
        Err(IkFailure::Unreachable {
            best_joints: b.q[..model.n].to_vec(),
            position_error: b.position_error,
            orientation_error: b.orientation_error,
            iterations,
            attempts: options.restarts + 1,
        })
    }

    /// The geometric Jacobian of the TCP (`tcp` on the tip link) at `q`: six rows (the TCP's
    /// linear then angular velocity in the base link's frame), one column per moving joint.
    pub fn jacobian(&self, tcp: &Isometry3<f64>, q: &[f64]) -> Result<Matrix6xX<f64>, String> {
        let model = Model::new(self, tcp).map_err(|dof| {
            format!("the Jacobian needs 1 to {MAX_DOF} moving joints; the chain has {dof}")
        })?;
        if q.len() != model.n {
            return Err(format!("{} joint values for {} joints", q.len(), model.n));
        }
        let mut padded = [0.0; MAX_DOF];
        padded[..model.n].copy_from_slice(q);
        let j = model.jacobian(&model.frames(&padded));
        Ok(Matrix6xX::from_fn(model.n, |r, c| j[(r, c)]))
    }
}

impl Robot {
    /// Joints within the URDF's limits whose TCP reaches `target` (in the base link's frame),
    /// starting from `seed`: [`Chain::ik`] with the robot's TCP.
    pub fn ik(
        &self,
        target: &Isometry3<f64>,
        seed: &[f64],
        options: &IkOptions,
    ) -> Result<IkResult, IkFailure> {
        self.chain.ik(&self.tcp, target, seed, options)
    }

    /// The TCP's geometric Jacobian at `q` ([`Chain::jacobian`] with the robot's TCP).
    pub fn jacobian(&self, q: &[f64]) -> Result<Matrix6xX<f64>, String> {
        self.chain.jacobian(&self.tcp, q)
    }
}

/// One Levenberg–Marquardt descent from `q` until solved, stalled or out of iterations; returns
/// the best posture it passed.
fn attempt(m: &Model, target: &Isometry3<f64>, mut q: Joints, o: &IkOptions) -> Attempt {
    let mut mid = [0.0; MAX_DOF];
    let mut pulls = [false; MAX_DOF];
    for i in 0..m.n {
        // Only finite ranges have a middle to pull towards.
        if (m.upper[i] - m.lower[i]).is_finite() {
            mid[i] = 0.5 * (m.lower[i] + m.upper[i]);
            pulls[i] = m.n > 6;
        }
    }
    let mut best = Attempt {
        q,
        position_error: f64::INFINITY,
        orientation_error: f64::INFINITY,
        cost: f64::INFINITY,
        iterations: 0,
        solved: false,
    };
    let mut reference = f64::INFINITY;
    let mut since = 0;
    for it in 0..=o.max_iterations {
        let f = m.frames(&q);
        let ep = target.translation.vector - f.tcp.translation.vector;
        let er = rotation_error(&target.rotation, &f.tcp.rotation);
        let (np, nr) = (ep.norm(), er.norm());
        let cost = 0.5 * (np * np + ORIENTATION_WEIGHT * ORIENTATION_WEIGHT * nr * nr);
        if cost < best.cost {
            best = Attempt {
                q,
                position_error: np,
                orientation_error: nr,
                cost,
                iterations: it,
                solved: false,
            };
        }
        if np <= o.position_tolerance && nr <= o.orientation_tolerance {
            // This posture, not the best-scoring one passed: that may miss a tolerance.
            return Attempt {
                q,
                position_error: np,
                orientation_error: nr,
                cost,
                iterations: it,
                solved: true,
            };
        }
        if cost < reference * (1.0 - STALL_GAIN) {
            reference = cost;
            since = 0;
        } else {
            since += 1;
            if since >= STALL_WINDOW {
                best.iterations = it;
                return best;
            }
        }
        if it == o.max_iterations {
            break;
        }
        let dq = step(m, &f, &ep, &er, cost, &q, &mid, &pulls, o.null_space_gain);
        for i in 0..m.n {
            q[i] = (q[i] + dq[i]).clamp(m.lower[i], m.upper[i]);
        }
    }
    best.iterations = o.max_iterations;
    best
}

/// The damped least-squares step at frames `f` with errors `ep`, `er` and weighted cost `cost`,
/// plus the redundant chain's null-space pull towards `mid` on the joints that `pulls`.
#[allow(clippy::too_many_arguments)]
fn step(
    m: &Model,
    f: &Frames,
    ep: &Vector3<f64>,
    er: &Vector3<f64>,
    cost: f64,
    q: &Joints,
    mid: &Joints,
    pulls: &[bool; MAX_DOF],
    gain: f64,
) -> SMatrix<f64, MAX_DOF, 1> {
    let mut weighted = m.jacobian(f);
    for r in 3..6 {
        for c in 0..m.n {
            weighted[(r, c)] *= ORIENTATION_WEIGHT;
        }
    }
    let e = Vector6::new(
        ep.x,
        ep.y,
        ep.z,
        ORIENTATION_WEIGHT * er.x,
        ORIENTATION_WEIGHT * er.y,
        ORIENTATION_WEIGHT * er.z,
    );
    // A joint at a limit that the step drives further out is held (its column dropped) and the
    // step solved again, so the other joints do its share instead of the clamp eating it.
    let mut held = [false; MAX_DOF];
    loop {
        let mut j = weighted;
        for c in (0..m.n).filter(|&c| held[c]) {
            j.column_mut(c).fill(0.0);
        }
        let jt = j.transpose();
        let mut h: SMatrix<f64, MAX_DOF, MAX_DOF> = jt * j;
        // Columns past the chain (and held ones) are zero: their damping alone keeps their
        // step at 0.
        for i in 0..MAX_DOF {
            h[(i, i)] += cost + DAMPING_BIAS;
        }
        let Some(chol) = Cholesky::new(h) else {
            return SMatrix::zeros();
        };
        let mut dq = chol.solve(&(jt * e));
        if cost > PULL_UNTIL && pulls.iter().any(|&p| p) {
            let mut z = SMatrix::<f64, MAX_DOF, 1>::zeros();
            for i in (0..m.n).filter(|&i| pulls[i] && !held[i]) {
                z[i] = gain * (mid[i] - q[i]);
            }
            // (I − J⁺J) z with the damped pseudo-inverse J⁺ = (JᵀJ + λI)⁻¹ Jᵀ.
            dq += z - chol.solve(&(jt * (j * z)));
        }
        let mut newly_held = false;
        for i in 0..m.n {
            let out = (q[i] >= m.upper[i] && dq[i] > 0.0) || (q[i] <= m.lower[i] && dq[i] < 0.0);
            if out && !held[i] {
                held[i] = true;
                newly_held = true;
            }
        }
        if !newly_held {
            return capped(dq);
        }
    }
}

/// `dq` scaled down so that no joint moves more than [`MAX_STEP`].
fn capped(mut dq: SMatrix<f64, MAX_DOF, 1>) -> SMatrix<f64, MAX_DOF, 1> {
    let largest = dq.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    if largest > MAX_STEP {
        dq *= MAX_STEP / largest;
    }
    dq
}

/// A seeded random posture within the limits; turning joints sample one turn at most
/// (`[-π, π]` within their limits), as every orientation lies in it.
fn random_posture(m: &Model, rng: &mut Pcg64Mcg) -> Joints {
    let mut q = [0.0; MAX_DOF];
    for i in 0..m.n {
        let (mut lo, mut hi) = (m.lower[i], m.upper[i]);
        if !m.prismatic[i] {
            lo = lo.max(-std::f64::consts::PI);
            hi = hi.min(std::f64::consts::PI);
        }
        q[i] = if hi > lo {
            rng.random_range(lo..hi)
        } else {
            lo
        };
    }
    q
}

/// `q` with each turning joint moved by whole turns (within its limits) to the value nearest
/// the seed's: the same TCP pose, the least motion from the seed.
fn wound_near(m: &Model, q: &Joints, seed: &[f64]) -> Vec<f64> {
    let turn = 2.0 * std::f64::consts::PI;
    (0..m.n)
        .map(|i| {
            if m.prismatic[i] {
                return q[i];
            }
            let k = ((seed[i] - q[i]) / turn).round();
            [k - 1.0, k, k + 1.0]
                .into_iter()
                .map(|k| q[i] + k * turn)
                .filter(|v| *v >= m.lower[i] && *v <= m.upper[i])
                .min_by(|a, b| (a - seed[i]).abs().total_cmp(&(b - seed[i]).abs()))
                .unwrap_or(q[i])
        })
        .collect()
}
