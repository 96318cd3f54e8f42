//! Hot kinematics maths with the same bits as nalgebra's, faster in WebAssembly.
//!
//! nalgebra is built with `libm-force`, so its `norm()` calls `libm::sqrt`: an SSE2 instruction
//! natively but a bit-by-bit software loop on wasm32 (libm's wasm intrinsic needs nightly).
//! `f64::sqrt` is IEEE-754 correctly rounded on every target (wasm's `f64.sqrt`, x86's `sqrtsd`),
//! hence bit-identical to `libm::sqrt`; the helpers here use it in exactly nalgebra's operation
//! order. The DH twist angles are constants, so their sines and cosines are computed once.

use nalgebra::Vector3;
use std::sync::OnceLock;

/// `‖v‖` in nalgebra's order (`0 + (x² + y² + z²)`, then the square root), with the hardware
/// square root.
#[inline]
pub(crate) fn norm3(v: &Vector3<f64>) -> f64 {
    let sq = 0.0 + (v.x * v.x + v.y * v.y + v.z * v.z);
    sq.sqrt()
}

/// `libm::sincos` of each angle, computed on first use (same bits as calling it every time).
pub(crate) fn sincos_table<const N: usize>(
    cell: &'static OnceLock<[(f64, f64); N]>,
    angles: &[f64; N],
) -> &'static [(f64, f64); N] {
    cell.get_or_init(|| angles.map(libm::sincos))
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
