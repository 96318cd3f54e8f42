//! Hot kinematics maths with the same bits as nalgebra's, faster in WebAssembly.
//!
//! nalgebra is built with `libm-force`, so its `norm()` calls `libm::sqrt`: an SSE2 instruction
//! natively but a bit-by-bit software loop on wasm32 (libm's wasm intrinsic needs nightly).
//! `f64::sqrt` is IEEE-754 correctly rounded on every target (wasm's `f64.sqrt`, x86's `sqrtsd`),
//! hence bit-identical to `libm::sqrt`; the helpers here use it in exactly nalgebra's operation
//! order. The DH twist angles are constants, so their sines and cosines are computed once.

use nalgebra::{Matrix3, Quaternion, SMatrix, SVector, UnitQuaternion, Vector3};
use std::sync::OnceLock;

/// `‖v‖` in nalgebra's order (`0 + (x² + y² + z²)`, then the square root), with the hardware
/// square root.
#[inline]
pub(crate) fn norm3(v: &Vector3<f64>) -> f64 {
    let sq = 0.0 + (v.x * v.x + v.y * v.y + v.z * v.z);
    sq.sqrt()
}

/// `UnitQuaternion::from_rotation_matrix` of a rotation matrix `m`, same branches and operation
/// order, with the hardware square root.
pub(crate) fn quaternion_of(m: &Matrix3<f64>) -> UnitQuaternion<f64> {
    let tr = m[(0, 0)] + m[(1, 1)] + m[(2, 2)];
    let q = if tr > 0.0 {
        let denom = (tr + 1.0).sqrt() * 2.0;
        Quaternion::new(
            0.25 * denom,
            (m[(2, 1)] - m[(1, 2)]) / denom,
            (m[(0, 2)] - m[(2, 0)]) / denom,
            (m[(1, 0)] - m[(0, 1)]) / denom,
        )
    } else if m[(0, 0)] > m[(1, 1)] && m[(0, 0)] > m[(2, 2)] {
        let denom = (1.0 + m[(0, 0)] - m[(1, 1)] - m[(2, 2)]).sqrt() * 2.0;
        Quaternion::new(
            (m[(2, 1)] - m[(1, 2)]) / denom,
            0.25 * denom,
            (m[(0, 1)] + m[(1, 0)]) / denom,
            (m[(0, 2)] + m[(2, 0)]) / denom,
        )
    } else if m[(1, 1)] > m[(2, 2)] {
        let denom = (1.0 + m[(1, 1)] - m[(0, 0)] - m[(2, 2)]).sqrt() * 2.0;
        Quaternion::new(
            (m[(0, 2)] - m[(2, 0)]) / denom,
            (m[(0, 1)] + m[(1, 0)]) / denom,
            0.25 * denom,
            (m[(1, 2)] + m[(2, 1)]) / denom,
        )
    } else {
        let denom = (1.0 + m[(2, 2)] - m[(0, 0)] - m[(1, 1)]).sqrt() * 2.0;
        Quaternion::new(
            (m[(1, 0)] - m[(0, 1)]) / denom,
            (m[(0, 2)] + m[(2, 0)]) / denom,
            (m[(1, 2)] + m[(2, 1)]) / denom,
            0.25 * denom,
        )
    };
    UnitQuaternion::new_unchecked(q)
}

/// `libm::sincos` of each angle, computed on first use (same bits as calling it every time).
pub(crate) fn sincos_table<const N: usize>(
    cell: &'static OnceLock<[(f64, f64); N]>,
    angles: &[f64; N],
) -> &'static [(f64, f64); N] {
    cell.get_or_init(|| angles.map(libm::sincos))
}

/// Cholesky factorisation of a small symmetric positive-definite matrix with the bits of
/// nalgebra's `cholesky()` and `solve` (same operation order), the square roots in hardware.
/// Only the lower triangle is read; `N ≤ 8` (nalgebra's dot products stay sequential there).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cholesky<const N: usize> {
    /// The factor `L` in the lower triangle (the upper one holds the input's leftovers).
    l: SMatrix<f64, N, N>,
}

impl<const N: usize> Cholesky<N> {
    /// Factorises `m`; `None` where nalgebra's gives `None` (a zero, negative or NaN pivot).
    pub(crate) fn new(mut m: SMatrix<f64, N, N>) -> Option<Self> {
        debug_assert!(N <= 8);
        for j in 0..N {
            for k in 0..j {
                // nalgebra: col_j[j..] = (−L_jk)·col_k[j..] + col_j[j..] (an axpy; + commutes).
                let factor = -m[(j, k)];
                for r in j..N {
                    m[(r, j)] += factor * m[(r, k)];
                }
            }
            let diag = m[(j, j)];
            // `try_sqrt` refuses zero, negatives and NaN.
            if diag == 0.0 || diag.is_nan() || diag < 0.0 {
                return None;
            }
            let denom = diag.sqrt();
            m[(j, j)] = denom;
            for r in j + 1..N {
                m[(r, j)] /= denom;
            }
        }
        Some(Cholesky { l: m })
    }

    /// `x` with `L Lᵀ x = b`: forward substitution (axpy form), then back substitution (dot form).
    pub(crate) fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        let l = &self.l;
        let mut x = *b;
        for i in 0..N {
            let coeff = x[i] / l[(i, i)];
            x[i] = coeff;
            for r in i + 1..N {
                x[r] += -coeff * l[(r, i)];
            }
        }
        for i in (0..N).rev() {
            let mut dot = 0.0;
            for r in i + 1..N {
                dot += l[(r, i)] * x[r];
            }
            x[i] = (x[i] - dot) / l[(i, i)];
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64Mcg;

    #[test]
    fn norm3_has_the_bits_of_nalgebras_norm() {
        let mut rng = Pcg64Mcg::seed_from_u64(3);
        for k in 0..100_000 {
            let scale = [1e-12, 1e-3, 1.0, 1e3, 1e150][k % 5];
            let v = Vector3::new(
                rng.random_range(-1.0..1.0) * scale,
                rng.random_range(-1.0..1.0) * scale,
                rng.random_range(-1.0..1.0) * scale,
            );
            assert_eq!(norm3(&v).to_bits(), v.norm().to_bits(), "{v:?}");
        }
        let zero = Vector3::new(-0.0, 0.0, -0.0);
        assert_eq!(norm3(&zero).to_bits(), zero.norm().to_bits());
    }

    #[test]
    fn cholesky_has_the_bits_of_nalgebras() {
        use nalgebra::{Matrix6, Matrix6x1, SMatrix, Vector6};
        let mut rng = Pcg64Mcg::seed_from_u64(5);
        let mut refused = 0;
        for k in 0..20_000 {
            let scale = [1e-6, 1e-2, 1.0, 1e3][k % 4];
            let j = SMatrix::<f64, 6, 7>::from_fn(|_, _| rng.random_range(-1.0..1.0) * scale);
            let mut m: Matrix6<f64> = j * j.transpose();
            // Some damped (positive definite), some rank-deficient or indefinite.
            match k % 5 {
                0 => m[(2, 2)] = -m[(2, 2)],
                1 => m.row_mut(3).fill(0.0),
                _ => m += Matrix6::identity() * [1e-4, 1e-12, 0.0][k % 3],
            }
            let b = Vector6::from_fn(|_, _| rng.random_range(-1.0..1.0));
            let ours = Cholesky::new(m);
            match m.cholesky() {
                None => {
                    assert!(ours.is_none(), "{m}");
                    refused += 1;
                }
                Some(c) => {
                    let ours = ours.expect("nalgebra factorises it");
                    let (x, y): (Matrix6x1<f64>, Vector6<f64>) = (c.solve(&b), ours.solve(&b));
                    for (p, q) in x.iter().zip(y.iter()) {
                        assert_eq!(p.to_bits(), q.to_bits(), "{m}\n{b}");
                    }
                }
            }
        }
        assert!(refused > 1000 && refused < 15_000, "{refused} refused");
        let nan = Matrix6::from_element(f64::NAN);
        assert!(nan.cholesky().is_none() && Cholesky::new(nan).is_none());
    }

    #[test]
    fn quaternion_of_has_the_bits_of_nalgebras() {
        use nalgebra::{Rotation3, Unit};
        let mut rng = Pcg64Mcg::seed_from_u64(7);
        let mut branches = [0; 4];
        for k in 0..40_000 {
            // Random axes and angles, many near π so that every branch (trace ≤ 0) is taken.
            let axis = Unit::new_normalize(Vector3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ));
            let angle = if k % 2 == 0 {
                rng.random_range(-3.2..3.2)
            } else {
                std::f64::consts::PI - rng.random_range(0.0..0.5)
            };
            let m = *Rotation3::from_axis_angle(&axis, angle).matrix();
            let ours = quaternion_of(&m);
            let theirs = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m));
            for (p, q) in ours.coords.iter().zip(theirs.coords.iter()) {
                assert_eq!(p.to_bits(), q.to_bits(), "{m}");
            }
            let tr = m.trace();
            branches[if tr > 0.0 {
                0
            } else if m[(0, 0)] > m[(1, 1)] && m[(0, 0)] > m[(2, 2)] {
                1
            } else if m[(1, 1)] > m[(2, 2)] {
                2
            } else {
                3
            }] += 1;
        }
        assert!(branches.iter().all(|&b| b > 1000), "{branches:?}");
    }

    #[test]
    fn sincos_table_is_libm_sincos() {
        static CELL: OnceLock<[(f64, f64); 3]> = OnceLock::new();
        let angles = [
            0.0,
            std::f64::consts::FRAC_PI_2,
            -std::f64::consts::FRAC_PI_4,
        ];
        for (a, (s, c)) in angles.iter().zip(sincos_table(&CELL, &angles)) {
            let (ls, lc) = libm::sincos(*a);
            assert_eq!((s.to_bits(), c.to_bits()), (ls.to_bits(), lc.to_bits()));
        }
    }
}
