//! Collision-check speed: one full self-collision check plus one distance to a 6 cm block at a
//! reaching posture, with the Panda's URDF hulls (`RobotCollision`: 9 convex hulls and 8 finger
//! boxes) and with the built-in arm's 7 capsules (`sim::geometry::link_capsules`, checked with
//! `sim::collide` as the world checks them). Both include the forward kinematics.
//!
//! `cargo bench --bench robot_collision`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use std::hint::black_box;
use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use logic_lfd::sim::{collide, geometry, Benchmark, Robot, RobotCollision};
use nalgebra::{Isometry3, Point3, Vector3};
use parry3d_f64::query;
use parry3d_f64::shape::{Capsule, Cuboid};

/// A posture reaching forward and down, the hand near the table.
const Q: [f64; 7] = [0.3, 0.25, -0.1, -2.0, 0.1, 2.1, 0.9];
/// The block's pose in the arm base's frame: beside the hand's path.
fn block_pose() -> Isometry3<f64> {
    Isometry3::translation(0.55, 0.2, 0.03)
}

fn hulls(c: &mut Criterion) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots/panda.json");
    let robot = Robot::load(&dir).unwrap();
    let model = RobotCollision::new(&robot).unwrap();
    let block = Cuboid::new(Vector3::repeat(0.03));
    let pose = block_pose();
    c.bench_function("self-collision + block distance (URDF hulls)", |b| {
        b.iter(|| {
            let hits = model.self_collisions(black_box(&Q), 0.04).unwrap();
            let d = model
                .distance_to(&block, &pose, black_box(&Q), 0.04)
                .unwrap();
            black_box((hits, d))
        })
    });
    c.bench_function("self-collision alone (URDF hulls)", |b| {
        b.iter(|| black_box(model.self_collisions(black_box(&Q), 0.04).unwrap()))
    });
    c.bench_function("block distance alone (URDF hulls)", |b| {
        b.iter(|| {
            black_box(
                model
                    .distance_to(&block, &pose, black_box(&Q), 0.04)
                    .unwrap(),
            )
        })
    });
}

fn capsules(c: &mut Criterion) {
    let world = Benchmark::B1.scene();
    let base = world.arm_base(0).unwrap();
    let block = Cuboid::new(Vector3::repeat(0.03));
    let pose = base * block_pose();
    let id = Isometry3::identity();
    c.bench_function("self-collision + block distance (built-in capsules)", |b| {
        b.iter(|| {
            let caps: Vec<Capsule> = geometry::link_capsules(&world, 0, black_box(&Q))
                .iter()
                .map(|(p, q, r)| Capsule::new(Point3::from(*p), Point3::from(*q), *r))
                .collect();
            // Every pair of capsules that are not neighbours along the chain.
            let mut hits = 0;
            for i in 0..caps.len() {
                for j in i + 2..caps.len() {
                    hits += usize::from(collide::intersects(&id, &caps[i], &id, &caps[j]));
                }
            }
            let d = caps
                .iter()
                .map(|k| query::distance(&id, k, &pose, &block).unwrap())
                .fold(f64::INFINITY, f64::min);
            black_box((hits, d))
        })
    });
}

criterion_group!(benches, hulls, capsules);
criterion_main!(benches);
