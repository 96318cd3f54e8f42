//! Inverse kinematics speed on URDF robots: one solve from the home posture for a TCP pose of a
//! seeded random posture within the limits, for the Panda (7 joints) and the UR5 (6 joints).
//! Before timing, the whole set is solved once and the success rate printed.
//!
//! `cargo bench --bench robot_ik`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use criterion::{criterion_group, criterion_main, Criterion};
use logic_lfd::sim::{IkOptions, Robot};
use nalgebra::Isometry3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Target poses per robot.
const TARGETS: usize = 1000;

/// The TCP poses of `TARGETS` seeded random postures within the limits (turning joints within
/// one turn).
fn targets(r: &Robot) -> Vec<Isometry3<f64>> {
    let mut rng = Pcg64Mcg::seed_from_u64(2024);
    let pi = std::f64::consts::PI;
    (0..TARGETS)
        .map(|_| {
            let q: Vec<f64> = r
                .chain
                .moving()
                .map(|j| rng.random_range(j.lower.max(-pi)..j.upper.min(pi)))
                .collect();
            r.tcp_pose(&q).unwrap()
        })
        .collect()
}

fn ik_solve(c: &mut Criterion) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots");
    let options = IkOptions::default();
    for name in ["panda", "ur5"] {
        let r = Robot::load(&dir.join(format!("{name}.json"))).unwrap();
        let poses = targets(&r);
        // Criterion times the mean over the cycled poses; the median and the tail of the
        // per-pose times (each the fastest of three solves) come from here.
        let mut solved = 0;
        let mut ms: Vec<f64> = poses
            .iter()
            .map(|t| {
                let mut fastest = f64::INFINITY;
                for _ in 0..3 {
                    let start = Instant::now();
                    let ok = black_box(r.ik(t, &r.home, &options)).is_ok();
                    fastest = fastest.min(start.elapsed().as_secs_f64() * 1e3);
                    solved += usize::from(ok);
                }
                fastest
            })
            .collect();
        ms.sort_by(f64::total_cmp);
        println!(
            "{name}: {} of {TARGETS} poses solved ({:.1} %); per pose median {:.4} ms, \
             90th percentile {:.4} ms, slowest {:.3} ms",
            solved / 3,
            100.0 * (solved / 3) as f64 / TARGETS as f64,
            ms[TARGETS / 2],
            ms[TARGETS * 9 / 10],
            ms[TARGETS - 1]
        );
        let mut i = 0;
        c.bench_function(&format!("ik solve {name} (sampled pose from home)"), |b| {
            b.iter(|| {
                i = (i + 1) % poses.len();
                black_box(r.ik(&poses[i], &r.home, &options))
            })
        });
    }
}

criterion_group!(benches, ik_solve);
criterion_main!(benches);
