//! Small dense kernels on row-major slices, used by the fast path.
//!
//! * [`Qr`]: Householder QR of the stacked least-squares matrix `[√Q Su Ψ; √r Ψ]` of one
//!   coordinate, so that `H = MᵀM` is never formed (its condition number is the square of M's:
//!   ~1e11 for 10 Bernstein functions against ~3e5 for M);
//! * [`solve_small_transposed`]: LU (partial pivoting) solve of the small n×n systems of the
//!   feedback gains, on the stack.
//!
//! No explicit inverse is ever formed.

/// Largest order of the small systems solved by [`solve_small_transposed`] (n+1 ≤ 7).
pub(crate) const SMALL: usize = 8;

/// Solve `Aᵀ x = b` for a small square row-major `a` (n ≤ [`SMALL`]) by Gaussian elimination with
/// partial pivoting (an LU solve) on the stack. `false` if a pivot is zero or not finite.
pub(crate) fn solve_small_transposed(a: &[f64], n: usize, b: &[f64], x: &mut [f64]) -> bool {
    debug_assert!(n <= SMALL);
    let mut m = [0.0f64; SMALL * SMALL];
    let mut r = [0.0f64; SMALL];
    for i in 0..n {
        for j in 0..n {
            m[i * SMALL + j] = a[j * n + i];
        }
        r[i] = b[i];
    }
    for col in 0..n {
        let mut piv = col;
        let mut best = m[col * SMALL + col].abs();
        for i in col + 1..n {
            let v = m[i * SMALL + col].abs();
            if v > best {
                best = v;
                piv = i;
            }
        }
        if best == 0.0 || !best.is_finite() {
            return false;
        }
        if piv != col {
            for c in 0..n {
                m.swap(col * SMALL + c, piv * SMALL + c);
            }
            r.swap(col, piv);
        }
        let d = m[col * SMALL + col];
        for i in col + 1..n {
            let f = m[i * SMALL + col] / d;
            if f != 0.0 {
                for c in col + 1..n {
                    m[i * SMALL + c] -= f * m[col * SMALL + c];
                }
                r[i] -= f * r[col];
            }
        }
    }
    for i in (0..n).rev() {
        let mut s = r[i];
        for c in i + 1..n {
            s -= m[i * SMALL + c] * x[c];
        }
        x[i] = s / m[i * SMALL + i];
    }
    true
}

/// Householder QR of a tall `m×k` matrix (m ≥ k), for the least-squares solve
/// `min |M w - b|` without forming the normal equations `MᵀM` (whose condition number is the
/// square of M's).
#[derive(Debug, Clone)]
pub(crate) struct Qr {
    m: usize,
    k: usize,
    /// R (k×k, row-major upper triangle).
    r: Vec<f64>,
    /// Householder vectors: column j has length m - j, stored back to back.
    v: Vec<f64>,
    /// Offsets of each vector in `v`.
    off: Vec<usize>,
    /// `2 / (vᵀv)` per reflector (0 for an identity reflector).
    beta: Vec<f64>,
}

impl Qr {
    /// Factor `a` given column-major (`a[c*m + row]`). `None` if M is numerically rank-deficient.
    pub(crate) fn new(mut a: Vec<f64>, m: usize, k: usize) -> Option<Qr> {
        debug_assert!(m >= k && a.len() == m * k);
        let mut v = Vec::with_capacity(k * m);
        let mut off = Vec::with_capacity(k);
        let mut beta = Vec::with_capacity(k);
        let mut r = vec![0.0; k * k];
        for j in 0..k {
            let col = &a[j * m + j..(j + 1) * m];
            let norm = col.iter().map(|x| x * x).sum::<f64>().sqrt();
            if !norm.is_finite() {
                return None;
            }
            let x0 = col[0];
            let alpha = if x0 > 0.0 { -norm } else { norm };
            off.push(v.len());
            let start = v.len();
            v.extend_from_slice(col);
            v[start] -= alpha;
            let vv: f64 = v[start..].iter().map(|x| x * x).sum();
            let b = if vv > 0.0 { 2.0 / vv } else { 0.0 };
            beta.push(b);
            r[j * k + j] = alpha;
            for c in j + 1..k {
                let colc = &mut a[c * m + j..(c + 1) * m];
                let s: f64 = b * v[start..]
                    .iter()
                    .zip(colc.iter())
                    .map(|(p, q)| p * q)
                    .sum::<f64>();
                for (q, p) in colc.iter_mut().zip(&v[start..]) {
                    *q -= s * p;
                }
                r[j * k + c] = colc[0];
            }
        }
        let max = (0..k).map(|j| r[j * k + j].abs()).fold(0.0, f64::max);
        if max == 0.0 || (0..k).any(|j| r[j * k + j].abs() <= 1e-13 * max) {
            return None;
        }
        Some(Qr {
            m,
            k,
            r,
            v,
            off,
            beta,
        })
    }

    /// The triangular factor R (k×k, row-major upper triangle).
    pub(crate) fn r_factor(&self) -> &[f64] {
        &self.r
    }

    /// Overwrite `b` (length m) with `Qᵀ b`, then solve `R w = (Qᵀb)[..k]`; the solution is
    /// left in `b[..k]`.
    pub(crate) fn solve_ls(&self, b: &mut [f64]) {
        let (m, k) = (self.m, self.k);
        for j in 0..k {
            let vj = &self.v[self.off[j]..self.off[j] + (m - j)];
            let bj = &mut b[j..m];
            let s: f64 = self.beta[j] * vj.iter().zip(bj.iter()).map(|(p, q)| p * q).sum::<f64>();
            if s != 0.0 {
                for (q, p) in bj.iter_mut().zip(vj) {
                    *q -= s * p;
                }
            }
        }
        for i in (0..k).rev() {
            let mut s = b[i];
            for p in i + 1..k {
                s -= self.r[i * k + p] * b[p];
            }
            b[i] = s / self.r[i * k + i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_transposed_solve_and_singular() {
        let a = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.5, 4.0];
        let b = [1.0, -2.0, 0.5];
        let mut x = [0.0; 3];
        assert!(solve_small_transposed(&a, 3, &b, &mut x));
        for j in 0..3 {
            let r: f64 = (0..3).map(|i| a[i * 3 + j] * x[i]).sum();
            assert!((r - b[j]).abs() < 1e-12);
        }
        assert!(!solve_small_transposed(
            &[1.0, 2.0, 2.0, 4.0],
            2,
            &[1.0, 1.0],
            &mut x
        ));
    }
}

#[cfg(test)]
mod qr_tests {
    use super::*;

    #[test]
    fn qr_least_squares_matches_normal_equations() {
        // 4×2, column-major.
        let m = 4;
        let a = vec![1.0, 1.0, 1.0, 1.0, 0.0, 1.0, 2.0, 3.0];
        let qr = Qr::new(a, m, 2).unwrap();
        let mut b = vec![1.0, 3.0, 5.0, 7.5];
        qr.solve_ls(&mut b);
        // Fit of y = c0 + c1 t: normal equations [[4,6],[6,14]] c = [16.5, 35.5].
        assert!((b[0] - 0.9).abs() < 1e-12, "{}", b[0]);
        assert!((b[1] - 2.15).abs() < 1e-12, "{}", b[1]);
        assert!(Qr::new(vec![1.0, 2.0, 2.0, 4.0], 2, 2).is_none());
    }
}
