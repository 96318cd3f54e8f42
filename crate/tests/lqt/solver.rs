//! The LQT-CP solver: the fast path equals the dense transcription of the contract, the gains
//! equal the backward Riccati recursion, a heavy via-point is passed within its derived
//! tolerance, feedback rejects a perturbation, and the task builder reproduces the example.

use logic_lfd::lqt::{build_reference, Target, TargetRole, Tracking};
use logic_lfd::lqt::{gains_recursive_dense, rollout_dense, solve_dense};
use logic_lfd::lqt::{Basis, LqtConfig, LqtCp, Perturbation};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, RngSeed};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::{rel_err, EXAMPLE};

/// A random, well-posed problem: config, μ, q, x0, x_init, perturbation.
struct RandomCase {
    config: LqtConfig,
    mu: DMatrix<f64>,
    q: DMatrix<f64>,
    x0: Vec<f64>,
    x_init: Vec<f64>,
    pert: Perturbation,
}

fn random_case(dim: usize, order: usize, n_steps: usize, basis_kind: u8, seed: u64) -> RandomCase {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let nc = n_steps - 1;
    let basis = match basis_kind {
        0 => Basis::rbf_uniform(rng.random_range(1..=nc.min(8)), rng.random_range(5.0..80.0)),
        1 => Basis::Bernstein {
            n_fct: rng.random_range(1..=nc.min(8)),
        },
        2 => Basis::Fourier {
            n_fct: rng.random_range(1..=((nc - 1) / 2).clamp(1, 6)),
        },
        _ => {
            let mut k = rng.random_range(1..=nc);
            while (Basis::Piecewise { n_fct: k }).validate(nc).is_err() {
                k -= 1;
            }
            Basis::Piecewise { n_fct: k }
        }
    };
    let config = LqtConfig {
        dim,
        order,
        dt: rng.random_range(0.01..0.1),
        n_steps,
        r: libm::pow(10f64, rng.random_range(-4.0..-1.0)),
        basis,
    };
    let mut targets = Vec::new();
    for j in 0..rng.random_range(1..=3usize) {
        let t = if j == 0 {
            n_steps - 1
        } else {
            rng.random_range(1..n_steps)
        };
        let with_vel = order >= 2 && rng.random_bool(0.5);
        targets.push(Target {
            t,
            role: if j == 0 {
                TargetRole::Goal
            } else {
                TargetRole::Via
            },
            pos: (0..dim).map(|_| rng.random_range(-1.0..1.0)).collect(),
            w_pos: libm::pow(10f64, rng.random_range(0.0..3.0)),
            vel: with_vel.then(|| (0..dim).map(|_| rng.random_range(-0.5..0.5)).collect()),
            w_vel: with_vel.then(|| rng.random_range(0.1..10.0)),
        });
    }
    let tracking = rng.random_bool(0.5).then(|| {
        let ph: f64 = rng.random_range(0.0..3.0);
        Tracking {
            demo_pos: DMatrix::from_fn(n_steps, dim, |t, d| {
                libm::sin(ph + d as f64 + 3.0 * t as f64 / n_steps as f64)
            }),
            weights_per_order: (0..order)
                .map(|_| {
                    if rng.random_bool(0.3) {
                        0.0
                    } else {
                        rng.random_range(0.01..1.0)
                    }
                })
                .collect(),
        }
    });
    let (mu, q) = build_reference(&config, &targets, tracking.as_ref()).unwrap();
    let nx = config.nx();
    let x0: Vec<f64> = (0..nx).map(|_| rng.random_range(-0.5..0.5)).collect();
    let x_init: Vec<f64> = x0.iter().map(|v| v + rng.random_range(-0.1..0.1)).collect();
    let pert = Perturbation {
        after_step: rng.random_range(0..nc),
        delta: (0..nx).map(|_| rng.random_range(-0.2..0.2)).collect(),
    };
    RandomCase {
        config,
        mu,
        q,
        x0,
        x_init,
        pert,
    }
}

fn seeded(cases: u32, seed: u64) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(seeded(48, 0x1a7c_0de5))]

    /// Fast path equals the dense transcription of the contract (batch, F, gains, rollouts).
    #[test]
    fn fast_path_equals_dense_reference(
        dim in 1usize..=3,
        order in 1usize..=3,
        n_steps in 5usize..=24,
        basis_kind in 0u8..4,
        seed in any::<u64>(),
    ) {
        let c = random_case(dim, order, n_steps, basis_kind, seed);
        let lqt = LqtCp::new(c.config.clone(), &c.q).unwrap();
        let fast = lqt.solve(&c.mu, &c.x0).unwrap();
        let dense = solve_dense(&c.config, &c.mu, &c.q, &c.x0).unwrap();
        prop_assert!(rel_err(&fast.u, &dense.u) < 1e-9, "u {}", rel_err(&fast.u, &dense.u));
        prop_assert!(rel_err(&fast.x, &dense.x) < 1e-9, "x {}", rel_err(&fast.x, &dense.x));
        prop_assert!(rel_err(&fast.w, &dense.w) < 1e-7, "w {}", rel_err(&fast.w, &dense.w));
        prop_assert!((fast.cost - dense.cost).abs() <= 1e-9 * dense.cost.abs().max(1e-300));
        let fb = lqt.feedback(&c.mu).unwrap();
        prop_assert!(rel_err(&fb.f_matrix(), &dense.f) < 1e-9);
        let w2 = fb.weights(&c.x0).unwrap();
        prop_assert!(rel_err(&w2, &dense.w) < 1e-6, "weights {}", rel_err(&w2, &dense.w));
        let gmax = dense.gains.iter().map(|g| g.amax()).fold(0.0, f64::max);
        for (t, g) in dense.gains.iter().enumerate() {
            let e = (fb.gain(t).unwrap() - g).amax() / gmax;
            prop_assert!(e < 1e-7, "gain {} differs by {}", t, e);
        }
        let roll = fb.rollout(&c.x_init, Some(&c.pert)).unwrap();
        let (dx, du) = rollout_dense(&c.config, &dense.gains, &c.x_init, Some(&c.pert)).unwrap();
        prop_assert!(rel_err(&roll.x, &dx) < 1e-9, "rollout x {}", rel_err(&roll.x, &dx));
        prop_assert!(rel_err(&roll.u, &du) < 1e-9, "rollout u {}", rel_err(&roll.u, &du));
    }

    /// With `x_init == x0` the nominal feedback rollout is the batch solution.
    #[test]
    fn nominal_rollout_equals_batch(
        dim in 1usize..=3,
        order in 1usize..=3,
        n_steps in 5usize..=40,
        basis_kind in 0u8..4,
        seed in any::<u64>(),
    ) {
        let c = random_case(dim, order, n_steps, basis_kind, seed);
        let lqt = LqtCp::new(c.config.clone(), &c.q).unwrap();
        let batch = lqt.solve(&c.mu, &c.x0).unwrap();
        let roll = lqt.feedback(&c.mu).unwrap().rollout(&c.x0, None).unwrap();
        prop_assert!(rel_err(&roll.x, &batch.x) < 1e-9, "x {}", rel_err(&roll.x, &batch.x));
        prop_assert!(rel_err(&roll.u, &batch.u) < 1e-9, "u {}", rel_err(&roll.u, &batch.u));
    }
}

/// Standard backward Riccati recursion of LQT on the augmented system (independent of the crate).
fn backward_riccati(cfg: &LqtConfig, mu: &DMatrix<f64>, q: &DMatrix<f64>) -> Vec<DMatrix<f64>> {
    let (dim, nx, nc) = (cfg.dim, cfg.nx(), cfg.n_controls());
    let (a, b) = (cfg.a_matrix(), cfg.b_matrix());
    let mut at = DMatrix::zeros(nx + 1, nx + 1);
    at.view_mut((0, 0), (nx, nx)).copy_from(&a);
    at[(nx, nx)] = 1.0;
    let mut bt = DMatrix::zeros(nx + 1, dim);
    bt.view_mut((0, 0), (nx, dim)).copy_from(&b);
    let q_tilde = |t: usize| {
        let qt = DMatrix::from_diagonal(&DVector::from_iterator(nx, (0..nx).map(|c| q[(t, c)])));
        let m = DVector::from_iterator(nx, (0..nx).map(|c| mu[(t, c)]));
        let qm = &qt * &m;
        let mut s = DMatrix::zeros(nx + 1, nx + 1);
        s.view_mut((0, 0), (nx, nx)).copy_from(&qt);
        s.view_mut((0, nx), (nx, 1)).copy_from(&(-&qm));
        s.view_mut((nx, 0), (1, nx)).copy_from(&(-qm.transpose()));
        s[(nx, nx)] = m.dot(&qm) + 1.0;
        s
    };
    let mut s = q_tilde(nc);
    let mut gains = vec![DMatrix::zeros(dim, nx + 1); nc];
    for t in (0..nc).rev() {
        let r = DMatrix::<f64>::identity(dim, dim) * cfg.r;
        let lhs = &r + bt.transpose() * &s * &bt;
        let k = lhs.lu().solve(&(bt.transpose() * &s * &at)).unwrap();
        s = q_tilde(t) + at.transpose() * &s * (&at - &bt * &k);
        gains[t] = k;
    }
    gains
}

fn example_like(
    basis: Basis,
    order: usize,
    tracking: bool,
) -> (LqtConfig, DMatrix<f64>, DMatrix<f64>) {
    let config = LqtConfig {
        dim: 2,
        order,
        dt: 0.02,
        n_steps: 60,
        r: 1e-6,
        basis,
    };
    let targets = vec![
        Target {
            t: 29,
            role: TargetRole::Via,
            pos: vec![0.3, 0.5],
            w_pos: 1.0,
            vel: None,
            w_vel: None,
        },
        Target {
            t: 59,
            role: TargetRole::Goal,
            pos: vec![1.0, 0.0],
            w_pos: 1.0,
            vel: (order >= 2).then(|| vec![0.0, 0.0]),
            w_vel: (order >= 2).then_some(1.0),
        },
    ];
    let tr = tracking.then(|| Tracking {
        demo_pos: DMatrix::from_fn(60, 2, |t, d| libm::sin((t as f64) * 0.05 + d as f64)),
        weights_per_order: (0..order)
            .map(|i| if i + 1 == order { 1e-3 } else { 0.0 })
            .collect(),
    });
    let (mu, q) = build_reference(&config, &targets, tr.as_ref()).unwrap();
    (config, mu, q)
}

/// With `piecewise` and K = N (Ψ = I) the gains equal the backward Riccati recursion — also
/// with strong velocity tracking, where the forward product of inverses loses all digits.
#[test]
fn piecewise_identity_basis_gains_equal_backward_riccati() {
    for (order, tracking) in [(2, false), (3, false), (2, true), (1, true)] {
        let (mut config, mu, mut q) = example_like(Basis::Piecewise { n_fct: 59 }, order, tracking);
        if tracking {
            // strong tracking of the last derivative: Φ_t collapses by many orders of magnitude
            for t in 0..60 {
                for d in 0..2 {
                    q[(t, (order - 1) * 2 + d)] = 1.0;
                }
            }
            config.r = 1e-3;
        }
        let lqt = LqtCp::new(config.clone(), &q).unwrap();
        let fb = lqt.feedback(&mu).unwrap();
        let ric = backward_riccati(&config, &mu, &q);
        let gmax = ric.iter().map(|g| g.amax()).fold(0.0, f64::max);
        for (t, g) in ric.iter().enumerate() {
            let e = (fb.gain(t).unwrap() - g).amax() / gmax;
            assert!(
                e < 1e-8,
                "order {order} tracking {tracking}: gain {t} off by {e}"
            );
        }
    }
}

/// The contract's recursion `P_t = P_{t-1}(Ã - B̃K̃_{t-1})⁻¹` and the closed form `F_t Φ_t⁻¹` are
/// the same gains where the recursion is numerically meaningful (short horizon, mild weights).
#[test]
fn recursive_gains_equal_closed_form_on_benign_case() {
    let c = random_case(2, 2, 12, 0, 7);
    let dense = solve_dense(&c.config, &c.mu, &c.q, &c.x0).unwrap();
    let rec = gains_recursive_dense(&c.config, &dense.f).unwrap();
    let gmax = dense.gains.iter().map(|g| g.amax()).fold(0.0, f64::max);
    for (a, b) in rec.iter().zip(&dense.gains) {
        assert!((a - b).amax() / gmax < 1e-8);
    }
}

/// A via-point with a large weight W is passed within `sqrt(J(w̄)/W)`, where w̄ is any weight
/// vector passing exactly through every target: `W e² ≤ J(w*) ≤ J(w̄) = r |Ψ w̄|²`.
#[test]
fn heavy_via_point_is_passed_within_derived_tolerance() {
    let (config, _, _) = example_like(Basis::rbf_uniform(8, 50.0), 2, false);
    let w_via = 1e4;
    let targets = vec![
        Target {
            t: 29,
            role: TargetRole::Via,
            pos: vec![0.3, 0.5],
            w_pos: w_via,
            vel: None,
            w_vel: None,
        },
        Target {
            t: 59,
            role: TargetRole::Goal,
            pos: vec![1.0, 0.0],
            w_pos: w_via,
            vel: None,
            w_vel: None,
        },
    ];
    let (mu, q) = build_reference(&config, &targets, None).unwrap();
    let x0 = vec![0.0; 4];
    let sol = LqtCp::new(config.clone(), &q)
        .unwrap()
        .solve(&mu, &x0)
        .unwrap();
    // w̄: minimum-norm weights of one coordinate hitting both positions exactly (x0 = 0).
    let phi = config.phi_matrix();
    let (a1, b1) = (config.a_matrix(), config.b_matrix());
    let row_at = |t: usize| {
        // position of coordinate 0 at step t as a linear function of w[:,0]
        let mut m = DMatrix::<f64>::zeros(4, 8);
        for s in 0..t {
            let mut bu = DMatrix::<f64>::zeros(4, 8);
            for k in 0..8 {
                bu[(0, k)] = b1[(0, 0)] * phi[(s, k)];
                bu[(2, k)] = b1[(2, 0)] * phi[(s, k)];
            }
            m = &a1 * m + bu;
        }
        m.row(0).into_owned()
    };
    let c = DMatrix::from_rows(&[row_at(29), row_at(59)]);
    let mut j_bar = 0.0;
    for d in 0..2 {
        let rhs = DVector::from_vec(vec![targets[0].pos[d], targets[1].pos[d]]);
        let cct = &c * c.transpose();
        let w_bar = c.transpose() * cct.lu().solve(&rhs).unwrap();
        assert!((&c * &w_bar - &rhs).amax() < 1e-9);
        j_bar += config.r * (&phi * &w_bar).norm_squared();
    }
    let tol = (j_bar / w_via).sqrt();
    let e = ((sol.x[(29, 0)] - 0.3).powi(2) + (sol.x[(29, 1)] - 0.5).powi(2)).sqrt();
    assert!(
        e <= tol * (1.0 + 1e-9),
        "via error {e} above the bound {tol}"
    );
    // The bound is not vacuous: without the via-point the trajectory misses it by far more.
    let (mu0, q0) = build_reference(&config, &targets[1..], None).unwrap();
    let free = LqtCp::new(config, &q0).unwrap().solve(&mu0, &x0).unwrap();
    let e0 = ((free.x[(29, 0)] - 0.3).powi(2) + (free.x[(29, 1)] - 0.5).powi(2)).sqrt();
    assert!(e0 > 100.0 * tol, "free error {e0}, bound {tol}");
}

/// After a perturbation the feedback rollout still reaches the goal; the open loop does not.
#[test]
fn feedback_rejects_perturbation_open_loop_does_not() {
    let (config, mu, q) = example_like(Basis::rbf_uniform(8, 50.0), 2, false);
    let x0 = vec![0.0; 4];
    let lqt = LqtCp::new(config.clone(), &q).unwrap();
    let fb = lqt.feedback(&mu).unwrap();
    let pert = Perturbation {
        after_step: 20,
        delta: vec![0.1, -0.1, 0.0, 0.0],
    };
    let closed = fb.rollout(&x0, Some(&pert)).unwrap();
    let goal_dist = |x: &DMatrix<f64>| ((x[(59, 0)] - 1.0).powi(2) + x[(59, 1)].powi(2)).sqrt();
    // open loop: the batch controls replayed with the same perturbation
    let u = fb.open_loop_controls(&x0).unwrap();
    let (a, b) = (config.a_matrix(), config.b_matrix());
    let mut x = DVector::from_vec(x0.clone());
    for t in 0..59 {
        x = &a * &x + &b * u.row(t).transpose();
        if t == 20 {
            x += DVector::from_vec(pert.delta.clone());
        }
    }
    let open_dist = ((x[0] - 1.0).powi(2) + x[1].powi(2)).sqrt();
    let batch_dist = goal_dist(&lqt.solve(&mu, &x0).unwrap().x);
    assert!(open_dist > 0.1, "open loop {open_dist}");
    assert!(
        goal_dist(&closed.x) < 0.01,
        "feedback {}",
        goal_dist(&closed.x)
    );
    assert!(goal_dist(&closed.x) < 2.0 * batch_dist + 1e-3);
}

/// The task builder reproduces the reference of the shared example from its targets.
#[test]
fn builder_reproduces_example_reference() {
    let text = std::fs::read_to_string(EXAMPLE).unwrap();
    let case = logic_lfd::lqt::CaseInput::from_json_str(&text).unwrap();
    let (mu, q) = build_reference(&case.config, &case.targets, case.tracking.as_ref()).unwrap();
    assert_eq!(mu, case.mu);
    assert_eq!(q, case.q_diag);
}
