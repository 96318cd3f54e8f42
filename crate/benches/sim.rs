//! Simulator speed: one B3 world step (both arms tracking a moving target through IK) plus the
//! scene graph; one B1 world step on the built-in Panda (capsules), the URDF Panda and the UR5
//! (their collision hulls); one IK solve for a top grasp over the table from the ready pose.
//!
//! `cargo bench --bench sim`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use logic_lfd::experiments::hot_paths;
use logic_lfd::sim::tower_task;
use logic_lfd::sim::{ArmModel, IkParams};
use logic_lfd::sim::{Benchmark, Robot};
use logic_lfd::sim::{GripperCommand, SceneGraph};
use nalgebra::Isometry3;
use std::hint::black_box;
use std::sync::Arc;

fn step_and_scene_graph(c: &mut Criterion) {
    let mut w = Benchmark::B3.scene();
    let homes: Vec<Isometry3<f64>> = (0..2).map(|a| w.tcp_pose(a).unwrap()).collect();
    let mut k = 0u64;
    c.bench_function("b3 step + scene graph", |bch| {
        bch.iter(|| {
            // A slow circle (r = 5 cm, 4 s period) keeps both arms moving, so IK runs every step.
            k += 1;
            let t = k as f64 * 0.01;
            for (a, h) in homes.iter().enumerate() {
                let mut p = *h;
                p.translation.vector.x += 0.05 * libm::cos(t * 1.57) - 0.05;
                p.translation.vector.y += 0.05 * libm::sin(t * 1.57);
                w.command_arm(a, p, GripperCommand::Open).unwrap();
            }
            let ev = w.step();
            let sg = SceneGraph::from_world(&w);
            black_box((ev, sg))
        })
    });
}

/// One B1 step with the arm tracking a slow circle low over the table (its links near the
/// table top, so the collision checks run), on each arm model.
fn step_per_robot(c: &mut Criterion) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots");
    let urdf = |name: &str| {
        let robot = Robot::load(&dir.join(format!("{name}.json"))).unwrap();
        Arc::new(ArmModel::from_robot(&robot).unwrap())
    };
    let mut g = c.benchmark_group("b1 step");
    for (label, model) in [
        ("built-in panda (capsules)", ArmModel::panda()),
        ("urdf panda (hulls)", urdf("panda")),
        ("urdf ur5 (hulls)", urdf("ur5")),
    ] {
        let mut w = Benchmark::B1.scene();
        w.set_robot(0, model).unwrap();
        let mut home = w.tcp_pose(0).unwrap();
        home.translation.vector.z = 0.15;
        let mut k = 0u64;
        g.bench_function(label, |bch| {
            bch.iter(|| {
                k += 1;
                let t = k as f64 * 0.01;
                let mut p = home;
                p.translation.vector.x += 0.05 * libm::cos(t * 1.57) - 0.05;
                p.translation.vector.y += 0.05 * libm::sin(t * 1.57);
                w.command_arm(0, p, GripperCommand::Open).unwrap();
                black_box(w.step())
            })
        });
    }
    g.finish();
}

fn ik_solve(c: &mut Criterion) {
    let base = Isometry3::identity();
    let params = IkParams::default();
    let targets = hot_paths::ik_targets();
    let arm = ArmModel::panda();
    let mut i = 0;
    c.bench_function("ik solve (top grasp from ready)", |bch| {
        bch.iter(|| {
            i = (i + 1) % targets.len();
            black_box(arm.inverse_kinematics(&base, &targets[i], &arm.ready(), &params))
        })
    });
}

/// Scene generation + the recorded demonstration of the tallest generated tower (B1, 12 blocks).
fn tower_generation(c: &mut Criterion) {
    let mut g = c.benchmark_group("generate");
    g.sample_size(10);
    g.bench_function("b1 tower of 12 blocks (scene + demonstration)", |bch| {
        bch.iter(|| black_box(tower_task(Benchmark::B1, 12).unwrap()))
    });
    g.finish();
}

criterion_group!(
    benches,
    step_and_scene_graph,
    step_per_robot,
    ik_solve,
    tower_generation
);
criterion_main!(benches);
