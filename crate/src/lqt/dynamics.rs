//! The point mass as a chain of n integrators in D independent coordinates.
//!
//! `x_{t+1} = A x_t + B u_t` with `A = A1 ⊗ I_D`, `B = B1 ⊗ I_D` and the exact discretisation of
//! an n-th order integrator with the control held over a step of length `dt`:
//!
//! `A1[i][j] = dt^(j-i)/(j-i)!` for j ≥ i (0 below), `B1[i] = dt^(n-i)/(n-i)!`.
//!
//! State layout is derivative-major: `x = [p (D), p' (D), p'' (D), …]`, entry `i*D+d` is the
//! i-th derivative of coordinate d.

use nalgebra::DMatrix;

/// `dt^m / m!`.
pub(crate) fn taylor(dt: f64, m: usize) -> f64 {
    let mut v = 1.0;
    for j in 1..=m {
        v *= dt / j as f64;
    }
    v
}

/// `(A1, B1)`: A1 n×n row-major, B1 length n.
pub(crate) fn integrator(order: usize, dt: f64) -> (Vec<f64>, Vec<f64>) {
    let n = order;
    let mut a1 = vec![0.0; n * n];
    for i in 0..n {
        for j in i..n {
            a1[i * n + j] = taylor(dt, j - i);
        }
    }
    let b1 = (0..n).map(|i| taylor(dt, n - i)).collect();
    (a1, b1)
}

/// `A = A1 ⊗ I_D` (nx×nx) and `B = B1 ⊗ I_D` (nx×D) as dense matrices.
pub(crate) fn dense_ab(dim: usize, order: usize, dt: f64) -> (DMatrix<f64>, DMatrix<f64>) {
    let (a1, b1) = integrator(order, dt);
    let nx = dim * order;
    let mut a = DMatrix::zeros(nx, nx);
    let mut b = DMatrix::zeros(nx, dim);
    for i in 0..order {
        for d in 0..dim {
            for j in 0..order {
                a[(i * dim + d, j * dim + d)] = a1[i * order + j];
            }
            b[(i * dim + d, d)] = b1[i];
        }
    }
    (a, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn second_order_matches_contract() {
        let (a1, b1) = integrator(2, 0.1);
        assert_eq!(a1, vec![1.0, 0.1, 0.0, 1.0]);
        assert!((b1[0] - 0.005).abs() < 1e-15 && (b1[1] - 0.1).abs() < 1e-15);
        let (a, b) = dense_ab(2, 2, 0.1);
        assert_eq!(a[(0, 2)], 0.1);
        assert_eq!(a[(0, 3)], 0.0);
        assert_eq!(b[(3, 1)], 0.1);
    }
}
