//! Simulator: kinematics, contact rules, scene graph, snapshots, benchmarks, disturbances. This
//! module holds the scenes several of its test files build.

mod benchmarks;
mod contact;
mod disturb;
mod generate;
mod hook;
mod kinematics;
mod scene_graph;
mod scenes;
mod towers;

use logic_lfd::sim::geometry;
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::{GripperCommand, SceneGraph, World};
use nalgebra::{Isometry3, Vector3};

/// Builds B1 and rearranges blocks through user moves.
fn b1_with(moves: &[(&str, [f64; 3])]) -> World {
    let mut w = Benchmark::B1.scene();
    for (name, p) in moves {
        w.move_block(name, Vector3::new(p[0], p[1], p[2]))
            .unwrap_or_else(|e| panic!("{e}"));
    }
    w
}

/// The facts of `w`'s scene graph, sorted.
fn facts(w: &World) -> Vec<String> {
    let mut f = SceneGraph::from_world(w).to_strings();
    f.sort();
    f
}

/// Benchmark `b`'s template scene with arm 0 holding `body` at its grasp (returned too).
fn holding(b: Benchmark, body: &str) -> (World, Isometry3<f64>) {
    let mut w = b.scene();
    let g = geometry::grasp_pose(&w, 0, body).unwrap();
    let sol = w.reachable(0, &g).unwrap();
    w.set_joints(0, sol.joints).unwrap();
    w.command_arm(0, g, GripperCommand::Close).unwrap();
    w.step();
    assert_eq!(w.held_by(0), Some(body));
    (w, g)
}
