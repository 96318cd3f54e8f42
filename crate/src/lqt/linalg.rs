//! Small dense kernels on row-major slices, used by the fast path.
//!
//! * [`Qr`]: Householder QR of the stacked least-squares matrix `[√Q Su Ψ; √r Ψ]` of one
//!   coordinate, so that `H = MᵀM` is never formed (its condition number is the square of M's:
//!   ~1e11 for 10 Bernstein functions against ~3e5 for M);
//! * [`Lu`]: LU with partial pivoting for the small n×n systems of the feedback gains.
//!
//! No explicit inverse is ever formed.

/// LU factorisation with partial pivoting of a square row-major matrix.
#[derive(Debug, Clone)]
pub(crate) struct Lu {
    n: usize,
    lu: Vec<f64>,
    perm: Vec<usize>,
}

impl Lu {
    /// Factor `a` (n×n, row-major). `None` if a pivot is exactly zero or not finite.
    pub(crate) fn new(mut a: Vec<f64>, n: usize) -> Option<Lu> {
        let mut perm: Vec<usize> = (0..n).collect();
        for j in 0..n {
            let mut piv = j;
            let mut best = a[j * n + j].abs();
            for i in j + 1..n {
                let v = a[i * n + j].abs();
                if v > best {
                    best = v;
                    piv = i;
                }
            }
            if best == 0.0 || !best.is_finite() {
                return None;
            }
            if piv != j {
                for c in 0..n {
                    a.swap(j * n + c, piv * n + c);
                }
                perm.swap(j, piv);
            }
            let d = a[j * n + j];
            for i in j + 1..n {
                let f = a[i * n + j] / d;
                a[i * n + j] = f;
                if f != 0.0 {
                    for c in j + 1..n {
                        a[i * n + c] -= f * a[j * n + c];
                    }
                }
            }
        }
        Some(Lu { n, lu: a, perm })
    }

    /// Solve `A x = b`, returning x.
    #[cfg_attr(not(test), allow(dead_code))]
    pub(crate) fn solve(&self, b: &[f64]) -> Vec<f64> {
        let n = self.n;
        let mut x: Vec<f64> = self.perm.iter().map(|&p| b[p]).collect();
        for i in 0..n {
            let mut s = x[i];
            for p in 0..i {
                s -= self.lu[i * n + p] * x[p];
            }
            x[i] = s;
        }
        for i in (0..n).rev() {
            let mut s = x[i];
            for p in i + 1..n {
                s -= self.lu[i * n + p] * x[p];
            }
            x[i] = s / self.lu[i * n + i];
        }
        x
    }

    /// Solve `Aᵀ x = b`, returning x.
    pub(crate) fn solve_transpose(&self, b: &[f64]) -> Vec<f64> {
        // A = Pᵀ L U  =>  Aᵀ = Uᵀ Lᵀ P ; solve Uᵀ y = b, Lᵀ z = y, x = Pᵀ z.
        let n = self.n;
        let mut y = b.to_vec();
        for i in 0..n {
            let mut s = y[i];
            for p in 0..i {
                s -= self.lu[p * n + i] * y[p];
            }
            y[i] = s / self.lu[i * n + i];
        }
        for i in (0..n).rev() {
            let mut s = y[i];
            for p in i + 1..n {
                s -= self.lu[p * n + i] * y[p];
            }
            y[i] = s;
        }
        let mut x = vec![0.0; n];
        for (i, &p) in self.perm.iter().enumerate() {
            x[p] = y[i];
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn matvec(a: &[f64], n: usize, x: &[f64]) -> Vec<f64> {
        (0..n)
            .map(|i| (0..n).map(|j| a[i * n + j] * x[j]).sum())
            .collect()
    }

    #[test]
    fn lu_solves_and_transposed_solves() {
        let a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.5, 4.0];
        let lu = Lu::new(a.clone(), 3).unwrap();
        let b = [1.0, -2.0, 0.5];
        let x = lu.solve(&b);
        let r = matvec(&a, 3, &x);
        for i in 0..3 {
            assert!((r[i] - b[i]).abs() < 1e-12);
        }
        let at: Vec<f64> = (0..9).map(|k| a[(k % 3) * 3 + k / 3]).collect();
        let y = lu.solve_transpose(&b);
        let r = matvec(&at, 3, &y);
        for i in 0..3 {
            assert!((r[i] - b[i]).abs() < 1e-12);
        }
    }

    #[test]
    fn lu_refuses_singular() {
        assert!(Lu::new(vec![1.0, 2.0, 2.0, 4.0], 2).is_none());
    }
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
