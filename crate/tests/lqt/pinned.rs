//! LQT-CP pinned to the contract (`docs/formats.md`) without the crate's own builders: a
//! three-step case solved by hand with every matrix written out, φ of every basis against its
//! formula on `s_j = j/(N-1)`, A/B of orders 1–3 against the closed forms, and the shared
//! example against a dense solve transcribed here from the contract.

use logic_lfd::lqt::{run_case, CaseInput, CaseOutput};
use logic_lfd::lqt::{Basis, LqtConfig};
use nalgebra::{DMatrix, DVector};
use serde_json::{json, Value};

use super::{rel_err, EXAMPLE};

/// Round-off allowed on values that are exact fractions of small integers.
const EXACT: f64 = 1e-12;
/// The contract's normwise tolerance on x, u, cost, F and the rollouts.
const CONTRACT_RTOL: f64 = 1e-6;
/// The contract's loose tolerance on the ill-conditioned weights.
const WEIGHTS_RTOL: f64 = 1e-4;

fn matrix(rows: &[Vec<f64>]) -> DMatrix<f64> {
    DMatrix::from_fn(rows.len(), rows[0].len(), |r, c| rows[r][c])
}

fn literal(rows: &[&[f64]]) -> DMatrix<f64> {
    DMatrix::from_fn(rows.len(), rows[0].len(), |r, c| rows[r][c])
}

fn assert_close(what: &str, got: &DMatrix<f64>, exp: &DMatrix<f64>, tol: f64) {
    assert_eq!(got.shape(), exp.shape(), "{what}: shape");
    let diff = (got - exp).amax();
    assert!(
        diff <= tol,
        "{what}: got {got} expected {exp} (max diff {diff:e})"
    );
}

fn solve_case(case: &Value) -> CaseOutput {
    let input = CaseInput::from_value(case).expect("valid case");
    run_case(&input).expect("case solves")
}

/// D = 1, n = 1, T = 3, dt = 0.5, r = 0.25, piecewise K = N = 2 (Ψ = I), x0 = 0,
/// μ = [0, 1, 2], q = [0, 1, 2]. By hand:
/// A = [1], B = [0.5], Sx = [1 1 1]ᵀ, Su = [[0, 0], [0.5, 0], [0.5, 0.5]],
/// H = SuᵀQSu + rI = [[1, 0.5], [0.5, 0.75]], H⁻¹ = [[1.5, -1], [-1, 2]],
/// SuᵀQμ = [2.5, 2] so w = u = [1.75, 1.5], x = [0, 0.875, 1.625],
/// J = 0.125² + 2·0.375² + 0.25·(1.75² + 1.5²) = 1.625,
/// SuᵀQSx = [1.5, 1] so F = H⁻¹[[1.5, -2.5], [1, -2]] = [[1.25, -1.75], [0.5, -1.5]],
/// K̃_0 = [1.25, -1.75], P_1 = (Ã - B̃K̃_0)⁻¹ = [[0.375, 0.875], [0, 1]]⁻¹ = [[8/3, -7/3], [0, 1]],
/// K̃_1 = F_1 P_1 = [4/3, -8/3] (the one-step Riccati law u_1 = 8/3 - 4/3 x_1).
/// Perturbed by +0.1 after step 0: x_1 = 0.975, u_1 = 8/3 - 1.3, x_2 = 0.975 + u_1/2.
fn hand_case() -> Value {
    json!({
        "dim": 1, "order": 1, "dt": 0.5, "n_steps": 3, "r": 0.25,
        "basis": {"type": "piecewise", "n_fct": 2},
        "x0": [0.0],
        "reference": {"mu": [[0.0], [1.0], [2.0]], "q_diag": [[0.0], [1.0], [2.0]]},
        "targets": [
            {"t": 1, "role": "via", "pos": [1.0], "w_pos": 1.0},
            {"t": 2, "role": "goal", "pos": [2.0], "w_pos": 2.0}
        ],
        "tracking": null,
        "feedback": {"x_init": [0.0], "perturbation": {"after_step": 0, "delta": [0.1]}}
    })
}

#[test]
fn hand_solved_three_step_case() {
    let o = solve_case(&hand_case());
    assert_close("A", &matrix(&o.a), &literal(&[&[1.0]]), EXACT);
    assert_close("B", &matrix(&o.b), &literal(&[&[0.5]]), EXACT);
    assert_close(
        "phi",
        &matrix(&o.phi),
        &literal(&[&[1.0, 0.0], &[0.0, 1.0]]),
        EXACT,
    );
    assert_close("w", &matrix(&o.w), &literal(&[&[1.75], &[1.5]]), EXACT);
    assert_close("u", &matrix(&o.u), &literal(&[&[1.75], &[1.5]]), EXACT);
    let x = literal(&[&[0.0], &[0.875], &[1.625]]);
    assert_close("x", &matrix(&o.x), &x, EXACT);
    assert_close("pos", &matrix(&o.pos), &x, EXACT);
    assert!((o.cost - 1.625).abs() < EXACT, "cost {}", o.cost);
    assert_eq!(o.target_errors.len(), 2);
    assert!((o.target_errors[0].pos_dist - 0.125).abs() < EXACT);
    assert!((o.target_errors[1].pos_dist - 0.375).abs() < EXACT);
    assert_eq!(o.target_errors[1].role.name(), "goal");

    let fb = o.feedback.expect("feedback asked");
    let f = literal(&[&[1.25, -1.75], &[0.5, -1.5]]);
    assert_close("F", &matrix(&fb.f), &f, EXACT);
    assert_eq!(fb.gains.len(), 2);
    assert_close(
        "K0",
        &matrix(&fb.gains[0]),
        &literal(&[&[1.25, -1.75]]),
        EXACT,
    );
    let k1 = literal(&[&[4.0 / 3.0, -8.0 / 3.0]]);
    assert_close("K1", &matrix(&fb.gains[1]), &k1, EXACT);
    assert_close("nominal x", &matrix(&fb.nominal.x), &x, EXACT);
    let pert = fb.perturbed.expect("perturbation given");
    let u1 = 8.0 / 3.0 - 1.3;
    let px = literal(&[&[0.0], &[0.975], &[0.975 + 0.5 * u1]]);
    assert_close("perturbed x", &matrix(&pert.x), &px, EXACT);
    assert_close(
        "perturbed u",
        &matrix(&pert.u),
        &literal(&[&[1.75], &[u1]]),
        EXACT,
    );
    let d = pert.final_goal_pos_dist.expect("goal target given");
    assert!((d - (2.0 - px[(2, 0)])).abs() < EXACT, "{d}");
}

/// The contract's φ, written from its formulas: rows on `s_j = j/(N-1)`, column k.
fn phi_formula(basis: &Value, n: usize) -> DMatrix<f64> {
    let k_n = basis["n_fct"].as_u64().unwrap() as usize;
    let s = |j: usize| j as f64 / (n - 1) as f64;
    let binom = |m: usize, k: usize| -> f64 {
        (0..k).fold(1.0, |c, i| c * (m - i) as f64 / (i + 1) as f64)
    };
    DMatrix::from_fn(n, k_n, |j, k| match basis["type"].as_str().unwrap() {
        "rbf" => {
            let c = basis["centers"][k].as_f64().unwrap();
            let lambda = basis["lambda"].as_f64().unwrap();
            libm::exp(-lambda * (s(j) - c) * (s(j) - c))
        }
        "bernstein" => {
            let m = k_n - 1;
            binom(m, k) * libm::pow(1.0 - s(j), (m - k) as f64) * libm::pow(s(j), k as f64)
        }
        "fourier" => libm::cos(2.0 * std::f64::consts::PI * k as f64 * s(j)),
        "piecewise" => {
            let l = n.div_ceil(k_n);
            if j / l == k {
                1.0
            } else {
                0.0
            }
        }
        other => panic!("unknown basis {other}"),
    })
}

/// A case with zero reference: only `phi` of the output is looked at.
fn phi_case(n_steps: usize, basis: &Value) -> Value {
    json!({
        "dim": 1, "order": 1, "dt": 0.1, "n_steps": n_steps, "r": 1.0, "basis": basis,
        "x0": [0.0],
        "reference": {"mu": vec![[0.0]; n_steps], "q_diag": vec![[1.0]; n_steps]},
        "targets": [], "tracking": null, "feedback": null
    })
}

#[test]
fn phi_of_every_basis_follows_its_formula_on_the_control_grid() {
    let bases = [
        json!({"type": "rbf", "n_fct": 4, "centers": [0.0, 0.3, 0.7, 1.0], "lambda": 20.0}),
        json!({"type": "rbf", "n_fct": 3, "centers": [-0.2, 0.5, 1.4], "lambda": 3.0}),
        json!({"type": "bernstein", "n_fct": 1}),
        json!({"type": "bernstein", "n_fct": 5}),
        json!({"type": "fourier", "n_fct": 4}),
        json!({"type": "piecewise", "n_fct": 3}),
        json!({"type": "piecewise", "n_fct": 4}),
    ];
    for n_steps in [8usize, 11] {
        let n = n_steps - 1;
        for b in &bases {
            let o = solve_case(&phi_case(n_steps, b));
            let exp = phi_formula(b, n);
            assert_close(&format!("phi {b} N={n}"), &matrix(&o.phi), &exp, EXACT);
        }
    }
    // The grid's ends are s = 0 and s = 1 exactly: the last Bernstein function is 1 at the last
    // control and the Fourier columns k ≥ 1 are back to 1 there.
    let o = solve_case(&phi_case(8, &bases[3]));
    assert!((o.phi[6][4] - 1.0).abs() < EXACT && o.phi[6][3].abs() < EXACT);
    let o = solve_case(&phi_case(8, &bases[4]));
    assert!(o.phi[6].iter().all(|v| (v - 1.0).abs() < EXACT));
    assert!((o.phi[1][1] - libm::cos(2.0 * std::f64::consts::PI / 6.0)).abs() < EXACT);
    // Piecewise with N = 10, K = 4: L = ceil(10/4) = 3, the last control alone in window 3.
    let p = Basis::Piecewise { n_fct: 4 }.matrix(10);
    let active: Vec<usize> = (0..10)
        .map(|j| (0..4).find(|&k| p[j * 4 + k] == 1.0).unwrap())
        .collect();
    assert_eq!(active, [0, 0, 0, 1, 1, 1, 2, 2, 2, 3]);
}

#[test]
fn a_and_b_of_orders_one_to_three_are_the_closed_forms() {
    let dt = 0.3;
    let (d2, d3) = (dt * dt / 2.0, dt * dt * dt / 6.0);
    let a1: [&[&[f64]]; 3] = [
        &[&[1.0]],
        &[&[1.0, dt], &[0.0, 1.0]],
        &[&[1.0, dt, d2], &[0.0, 1.0, dt], &[0.0, 0.0, 1.0]],
    ];
    let b1: [&[f64]; 3] = [&[dt], &[d2, dt], &[d3, d2, dt]];
    for order in 1..=3 {
        for dim in [1usize, 2] {
            let cfg = LqtConfig {
                dim,
                order,
                dt,
                n_steps: 5,
                r: 1.0,
                basis: Basis::Bernstein { n_fct: 2 },
            };
            let a1 = literal(a1[order - 1]);
            let b1 = DMatrix::from_column_slice(order, 1, b1[order - 1]);
            let eye = DMatrix::<f64>::identity(dim, dim);
            let (a, b) = (a1.kronecker(&eye), b1.kronecker(&eye));
            let what = format!("order {order} dim {dim}");
            assert_close(&format!("A {what}"), &cfg.a_matrix(), &a, EXACT);
            assert_close(&format!("B {what}"), &cfg.b_matrix(), &b, EXACT);
        }
    }
}

/// The contract's batch solve and feedback, transcribed densely from its equations.
struct DenseSolve {
    w: DMatrix<f64>,
    x: DMatrix<f64>,
    u: DMatrix<f64>,
    cost: f64,
    f: DMatrix<f64>,
}

fn dense_solve(case: &Value) -> DenseSolve {
    let num = |k: &str| case[k].as_f64().unwrap();
    let (dim, order) = (num("dim") as usize, num("order") as usize);
    let (dt, t_n, r) = (num("dt"), num("n_steps") as usize, num("r"));
    let (nx, n) = (dim * order, t_n - 1);
    let rows = |v: &Value| -> DMatrix<f64> {
        let a = v.as_array().unwrap();
        let cols = a[0].as_array().unwrap().len();
        DMatrix::from_fn(a.len(), cols, |i, j| a[i][j].as_f64().unwrap())
    };
    let mu = rows(&case["reference"]["mu"]);
    let qd = rows(&case["reference"]["q_diag"]);
    let x0 = DVector::from_iterator(
        nx,
        case["x0"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap()),
    );
    let fact = |m: usize| (1..=m).fold(1.0, |p, i| p * i as f64);
    let a1 = DMatrix::from_fn(order, order, |i, j| {
        if j >= i {
            libm::pow(dt, (j - i) as f64) / fact(j - i)
        } else {
            0.0
        }
    });
    let b1 = DMatrix::from_fn(order, 1, |i, _| {
        libm::pow(dt, (order - i) as f64) / fact(order - i)
    });
    let eye = DMatrix::<f64>::identity(dim, dim);
    let (a, b) = (a1.kronecker(&eye), b1.kronecker(&eye));
    let phi = phi_formula(&case["basis"], n);
    let k_n = phi.ncols();
    let psi = phi.kronecker(&eye);
    // Sx, Su: x_t = A^t x0 + Σ_{s<t} A^(t-1-s) B u_s
    let mut sx = DMatrix::zeros(t_n * nx, nx);
    let mut su = DMatrix::zeros(t_n * nx, n * dim);
    let mut powers = vec![DMatrix::<f64>::identity(nx, nx)];
    for t in 1..t_n {
        powers.push(&a * &powers[t - 1]);
    }
    for t in 0..t_n {
        sx.view_mut((t * nx, 0), (nx, nx)).copy_from(&powers[t]);
        for s in 0..t {
            su.view_mut((t * nx, s * dim), (nx, dim))
                .copy_from(&(&powers[t - 1 - s] * &b));
        }
    }
    let q = DMatrix::from_diagonal(&DVector::from_iterator(
        t_n * nx,
        qd.transpose().iter().copied(),
    ));
    let mu_v = DVector::from_iterator(t_n * nx, mu.transpose().iter().copied());
    let sup = &su * &psi;
    let h = sup.transpose() * &q * &sup + r * psi.transpose() * &psi;
    let lu = h.clone().lu();
    let rhs = sup.transpose() * &q * (&mu_v - &sx * &x0);
    let w_v = lu.solve(&rhs).expect("H is regular");
    let u_v = &psi * &w_v;
    let x_v = &sx * &x0 + &su * &u_v;
    let e = &x_v - &mu_v;
    let cost = e.dot(&(&q * &e)) + r * u_v.dot(&u_v);
    let mut rhs_f = DMatrix::zeros(k_n * dim, nx + 1);
    rhs_f
        .view_mut((0, 0), (k_n * dim, nx))
        .copy_from(&(sup.transpose() * &q * &sx));
    rhs_f.set_column(nx, &(-(sup.transpose() * &q * &mu_v)));
    let f = &psi * lu.solve(&rhs_f).expect("H is regular");
    DenseSolve {
        w: DMatrix::from_fn(k_n, dim, |k, d| w_v[k * dim + d]),
        x: DMatrix::from_fn(t_n, nx, |t, i| x_v[t * nx + i]),
        u: DMatrix::from_fn(n, dim, |t, d| u_v[t * dim + d]),
        cost,
        f,
    }
}

#[test]
fn shared_example_equals_dense_solve_written_from_the_contract() {
    let case: Value = serde_json::from_str(&std::fs::read_to_string(EXAMPLE).unwrap()).unwrap();
    let exp = dense_solve(&case);
    let o = solve_case(&case);
    assert!(rel_err(&matrix(&o.w), &exp.w) < WEIGHTS_RTOL, "w");
    assert!(rel_err(&matrix(&o.x), &exp.x) < CONTRACT_RTOL, "x");
    assert!(rel_err(&matrix(&o.u), &exp.u) < CONTRACT_RTOL, "u");
    let cost_err = (o.cost - exp.cost).abs() / exp.cost;
    assert!(cost_err < CONTRACT_RTOL, "cost {} vs {}", o.cost, exp.cost);
    let fb = o.feedback.expect("the example asks for feedback");
    assert!(rel_err(&matrix(&fb.f), &exp.f) < CONTRACT_RTOL, "F");
    // The hand case through the same transcription: the transcription itself is right.
    let hand = dense_solve(&hand_case());
    assert!((hand.cost - 1.625).abs() < EXACT);
    assert_close(
        "hand F",
        &hand.f,
        &literal(&[&[1.25, -1.75], &[0.5, -1.5]]),
        EXACT,
    );
}
