//! LQT-CP benchmarks: the full DMP-mode pipeline of one skill (T = 100, D = 3, jerk control,
//! K = 10: weights, F, 99 gains, one rollout), the cached re-plan for a new goal, a skill plan for a
//! new object pose, and the classic DMP.
#![allow(missing_docs)]

use criterion::measurement::{Measurement, ValueFormatter};
use criterion::{criterion_group, criterion_main, Criterion, SamplingMode, Throughput};
use logic_lfd::lqt::{build_reference, Target, TargetRole, Tracking};
use logic_lfd::lqt::{full_pipeline, Basis, Dmp, DmpParams, LqtConfig, LqtCp, Skill, SkillParams};
use nalgebra::{DMatrix, Isometry3, Point3, Translation3, UnitQuaternion};
use std::hint::black_box;

fn demo(t_n: usize) -> Vec<Point3<f64>> {
    (0..t_n)
        .map(|t| {
            let s = t as f64 / (t_n - 1) as f64;
            let e = s * s * (3.0 - 2.0 * s);
            Point3::new(
                -0.3 * (1.0 - e),
                0.1 * libm::sin(std::f64::consts::PI * e),
                0.3 - 0.28 * e,
            )
        })
        .collect()
}

fn dmp_mode_problem(basis: Basis, goal: [f64; 3]) -> (LqtConfig, DMatrix<f64>, DMatrix<f64>) {
    let config = LqtConfig {
        dim: 3,
        order: 3,
        dt: 0.01,
        n_steps: 100,
        r: 1e-9,
        basis,
    };
    let d = demo(100);
    let tracking = Tracking {
        demo_pos: DMatrix::from_fn(100, 3, |t, c| d[t][c]),
        weights_per_order: vec![0.0, 0.0, 1e-2],
    };
    let targets = [Target {
        t: 99,
        role: TargetRole::Goal,
        pos: goal.to_vec(),
        w_pos: 1e6,
        vel: Some(vec![0.0; 3]),
        w_vel: Some(1e3),
    }];
    let (mu, q) = build_reference(&config, &targets, Some(&tracking)).unwrap();
    (config, mu, q)
}

/// CPU time of the benchmarking thread (`/proc/thread-self/schedstat`, ns): on a shared machine
/// the wall clock also counts the time other processes hold the cores.
struct ThreadCpu;

fn thread_cpu_ns() -> u64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(0)
}

struct CpuFormatter;

impl ValueFormatter for CpuFormatter {
    fn scale_values(&self, typical: f64, values: &mut [f64]) -> &'static str {
        let (div, unit) = if typical < 1e3 {
            (1.0, "ns (cpu)")
        } else if typical < 1e6 {
            (1e3, "µs (cpu)")
        } else {
            (1e6, "ms (cpu)")
        };
        values.iter_mut().for_each(|v| *v /= div);
        unit
    }

    fn scale_throughputs(&self, _: f64, _: &Throughput, _: &mut [f64]) -> &'static str {
        "ns (cpu)"
    }

    fn scale_for_machines(&self, _: &mut [f64]) -> &'static str {
        "ns"
    }
}

impl Measurement for ThreadCpu {
    type Intermediate = u64;
    type Value = u64;

    fn start(&self) -> u64 {
        thread_cpu_ns()
    }

    fn end(&self, i: u64) -> u64 {
        thread_cpu_ns().saturating_sub(i)
    }

    fn add(&self, a: &u64, b: &u64) -> u64 {
        a + b
    }

    fn zero(&self) -> u64 {
        0
    }

    fn to_f64(&self, v: &u64) -> f64 {
        *v as f64
    }

    fn formatter(&self) -> &dyn ValueFormatter {
        &CpuFormatter
    }
}

/// The target pipeline, on the CPU-time clock. The kernel updates the thread's CPU time at
/// scheduler ticks, so samples are long (flat sampling, 20 samples of ~0.2 s each).
fn cpu_benches(c: &mut Criterion<ThreadCpu>) {
    let mut g = c.benchmark_group("cpu");
    g.sampling_mode(SamplingMode::Flat)
        .sample_size(20)
        .measurement_time(std::time::Duration::from_secs(4));
    let x0 = vec![-0.3, 0.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let (config, mu, q) = dmp_mode_problem(Basis::rbf_uniform(10, 100.0), [0.0, 0.0, 0.02]);
    g.bench_function("lqt full pipeline T100 D3 jerk K10 rbf", |b| {
        b.iter(|| full_pipeline(black_box(&config), black_box(&mu), &q, &x0).unwrap())
    });
    g.bench_function("lqt factor only (LqtCp::new) rbf", |b| {
        b.iter(|| LqtCp::new(black_box(config.clone()), black_box(&q)).unwrap())
    });
    let lqt = LqtCp::new(config.clone(), &q).unwrap();
    let (_, mu2, _) = dmp_mode_problem(config.basis.clone(), [0.1, -0.05, 0.04]);
    g.bench_function("lqt new goal (cached) gains + rollout rbf", |b| {
        b.iter(|| {
            let fb = lqt.feedback(black_box(&mu2)).unwrap();
            fb.rollout(&x0, None).unwrap()
        })
    });
    let d = demo(100);
    let dmp = Dmp::learn(&d, 0.01, DmpParams::default()).unwrap();
    let pose = Isometry3::translation(0.1, 0.0, 0.0);
    g.bench_function("dmp plan T100 K30", |b| {
        b.iter(|| dmp.plan(black_box(&d[0]), black_box(&pose), &[]).unwrap())
    });
    g.finish();
}

fn benches(c: &mut Criterion) {
    let x0 = vec![-0.3, 0.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    for (name, basis) in [
        ("rbf", Basis::rbf_uniform(10, 100.0)),
        ("bernstein", Basis::Bernstein { n_fct: 10 }),
    ] {
        let (config, mu, q) = dmp_mode_problem(basis, [0.0, 0.0, 0.02]);
        c.bench_function(&format!("lqt full pipeline T100 D3 jerk K10 {name}"), |b| {
            b.iter(|| full_pipeline(black_box(&config), black_box(&mu), &q, &x0).unwrap())
        });
        // New goal: only μ changes; the factorisation and the state part of the gains are cached.
        let lqt = LqtCp::new(config.clone(), &q).unwrap();
        let (_, mu2, _) = dmp_mode_problem(config.basis.clone(), [0.1, -0.05, 0.04]);
        c.bench_function(
            &format!("lqt new goal (cached) gains + rollout {name}"),
            |b| {
                b.iter(|| {
                    let g = lqt.feedback(black_box(&mu2)).unwrap();
                    g.rollout(&x0, None).unwrap()
                })
            },
        );
    }
    let d = demo(100);
    let skill = Skill::learn(&d, 0.01, SkillParams::default()).unwrap();
    let pose = Isometry3::from_parts(
        Translation3::new(0.4, -0.2, 0.05),
        UnitQuaternion::from_euler_angles(0.0, 0.0, 0.7),
    );
    let start = Point3::new(0.1, 0.2, 0.4);
    c.bench_function("skill plan new object pose (cached)", |b| {
        b.iter(|| {
            skill
                .plan(black_box(&start), black_box(&pose), &[])
                .unwrap()
        })
    });
    c.bench_function("skill learn T100", |b| {
        b.iter(|| Skill::learn(black_box(&d), 0.01, SkillParams::default()).unwrap())
    });
    let dmp = Dmp::learn(&d, 0.01, DmpParams::default()).unwrap();
    c.bench_function("dmp learn + plan T100 K30", |b| {
        b.iter(|| {
            let dmp = Dmp::learn(black_box(&d), 0.01, DmpParams::default()).unwrap();
            dmp.plan(&start, &pose, &[]).unwrap()
        })
    });
    c.bench_function("dmp plan T100 K30", |b| {
        b.iter(|| dmp.plan(black_box(&start), black_box(&pose), &[]).unwrap())
    });
}

criterion_group! {
    name = lqt;
    config = Criterion::default()
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2));
    targets = benches
}
criterion_group! {
    name = lqt_cpu;
    config = Criterion::default().with_measurement(ThreadCpu);
    targets = cpu_benches
}
criterion_main!(lqt, lqt_cpu);
