//! Inverse kinematics on URDF chains: the shipped Panda (7 joints) and UR5 (6 joints) reach at
//! least 99 % of poses sampled by forward kinematics from their home posture, within their
//! limits and tolerances; a target out of reach, a bad seed and a bad command line get typed
//! errors; a toy chain with prismatic and continuous joints is solved as well.

use std::path::{Path, PathBuf};

use logic_lfd::sim::{parse_urdf, Chain, IkFailure, IkOptions, IkResult, Robot};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use crate::support::cli::run_cli;

fn robots() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots")
}

fn load(name: &str) -> Robot {
    Robot::load(&robots().join(format!("{name}.json"))).unwrap()
}

/// A seeded random joint vector within the chain's limits (turning joints within one turn).
fn sample(chain: &Chain, rng: &mut Pcg64Mcg) -> Vec<f64> {
    chain
        .moving()
        .map(|j| {
            let pi = std::f64::consts::PI;
            let (lo, hi) = (j.lower.max(-pi), j.upper.min(pi));
            rng.random_range(lo..hi)
        })
        .collect()
}

/// `s` is within the chain's limits and its TCP is at `target` within the options' tolerances.
fn check_solution(chain: &Chain, tcp: &Isometry3<f64>, target: &Isometry3<f64>, s: &IkResult) {
    let o = IkOptions::default();
    assert!(chain.outside_limits(&s.joints).is_none(), "{:?}", s.joints);
    let got = chain.tip_frame(&s.joints) * tcp;
    let dp = (got.translation.vector - target.translation.vector).norm();
    let dr = got.rotation.angle_to(&target.rotation);
    assert!(
        dp <= o.position_tolerance + 1e-12,
        "{dp} m at {:?}",
        s.joints
    );
    assert!(
        dr <= o.orientation_tolerance + 1e-9,
        "{dr} rad at {:?}",
        s.joints
    );
    assert!(s.position_error <= o.position_tolerance);
    assert!(s.orientation_error <= o.orientation_tolerance);
}

/// Solves the FK poses of `n` seeded random postures from home; returns how many were solved.
fn solve_sampled(r: &Robot, n: usize, seed: u64) -> usize {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut solved = 0;
    for _ in 0..n {
        let q = sample(&r.chain, &mut rng);
        let target = r.tcp_pose(&q).unwrap();
        match r.ik(&target, &r.home, &IkOptions::default()) {
            Ok(s) => {
                check_solution(&r.chain, &r.tcp, &target, &s);
                solved += 1;
            }
            Err(IkFailure::Unreachable { best_joints, .. }) => {
                assert!(r.chain.outside_limits(&best_joints).is_none());
            }
            Err(e) => panic!("{e}"),
        }
    }
    solved
}

#[test]
fn panda_ik_reaches_99_percent_of_sampled_poses_from_home() {
    let solved = solve_sampled(&load("panda"), 1000, 21);
    assert!(solved >= 990, "{solved} of 1000");
}

#[test]
fn ur5_ik_reaches_99_percent_of_sampled_poses_from_home() {
    let solved = solve_sampled(&load("ur5"), 1000, 22);
    assert!(solved >= 990, "{solved} of 1000");
}

#[test]
fn a_target_two_metres_away_is_unreachable_with_the_best_residual() {
    for name in ["panda", "ur5"] {
        let r = load(name);
        let mut target = r.tcp_pose(&r.home).unwrap();
        target.translation.vector.x += 2.0;
        let o = IkOptions {
            restarts: 5,
            ..IkOptions::default()
        };
        match r.ik(&target, &r.home, &o) {
            Err(IkFailure::Unreachable {
                best_joints,
                position_error,
                attempts,
                ..
            }) => {
                assert_eq!(attempts, 6);
                assert!(r.chain.outside_limits(&best_joints).is_none());
                // The arm cannot stretch further than its reach towards the target.
                assert!(
                    position_error > 0.8 && position_error < 2.0,
                    "{position_error}"
                );
                let best = r.tcp_pose(&best_joints).unwrap();
                let d = (best.translation.vector - target.translation.vector).norm();
                assert!((d - position_error).abs() < 1e-9);
            }
            other => panic!("{name}: {other:?}"),
        }
    }
}

#[test]
fn ik_refuses_a_bad_seed_or_target_with_a_typed_error() {
    let r = load("ur5");
    let target = r.tcp_pose(&r.home).unwrap();
    let o = IkOptions::default();
    assert_eq!(
        r.ik(&target, &[0.0; 7], &o),
        Err(IkFailure::SeedLength { given: 7, dof: 6 })
    );
    let mut nan = r.home.clone();
    nan[2] = f64::NAN;
    assert_eq!(r.ik(&target, &nan, &o), Err(IkFailure::NotFinite));
    let mut far = target;
    far.translation.vector.z = f64::INFINITY;
    assert_eq!(r.ik(&far, &r.home, &o), Err(IkFailure::NotFinite));
    assert!(r
        .jacobian(&[0.0; 5])
        .unwrap_err()
        .contains("5 joint values"));
}

#[test]
fn ik_from_the_same_seed_gives_the_same_joints_and_starts_at_a_clamped_seed() {
    let r = load("panda");
    let mut rng = Pcg64Mcg::seed_from_u64(5);
    let q = sample(&r.chain, &mut rng);
    let target = r.tcp_pose(&q).unwrap();
    let o = IkOptions::default();
    let a = r.ik(&target, &r.home, &o).unwrap();
    let b = r.ik(&target, &r.home, &o).unwrap();
    assert_eq!(a, b);
    // A seed outside the limits is clamped into them, not refused.
    let wild = vec![9.0; 7];
    let s = r.ik(&target, &wild, &o).unwrap();
    check_solution(&r.chain, &r.tcp, &target, &s);
}

#[test]
fn the_jacobian_is_the_tcps_velocity_per_joint_rate() {
    for name in ["panda", "ur5"] {
        let r = load(name);
        let mut rng = Pcg64Mcg::seed_from_u64(3);
        for _ in 0..20 {
            let q = sample(&r.chain, &mut rng);
            let j = r.jacobian(&q).unwrap();
            assert_eq!(j.ncols(), r.chain.dof());
            let t = r.chain.tip_frame(&q) * r.tcp;
            let h = 1e-7;
            for c in 0..q.len() {
                let mut qh = q.clone();
                qh[c] += h;
                let th = r.chain.tip_frame(&qh) * r.tcp;
                let v = (th.translation.vector - t.translation.vector) / h;
                let w = (th.rotation * t.rotation.inverse()).scaled_axis() / h;
                for k in 0..3 {
                    assert!((j[(k, c)] - v[k]).abs() < 1e-5, "{name} v {k} {c}");
                    assert!((j[(k + 3, c)] - w[k]).abs() < 1e-5, "{name} w {k} {c}");
                }
            }
        }
    }
}

/// A Stanford-style arm: base turn, shoulder pitch, a telescoping prismatic link and a wrist of
/// continuous roll, limited pitch and continuous roll.
const TOY_ARM: &str = r#"<robot name="toy">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="l4"/>
  <link name="l5"/><link name="l6"/><link name="flange"/>
  <joint name="turn" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" velocity="1"/></joint>
  <joint name="pitch" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.2"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" velocity="1"/></joint>
  <joint name="reach" type="prismatic"><parent link="l2"/><child link="l3"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="0.1" upper="0.5" velocity="0.2"/></joint>
  <joint name="roll1" type="continuous"><parent link="l3"/><child link="l4"/><origin xyz="0 0 0.05"/><axis xyz="0 0 1"/></joint>
  <joint name="bend" type="revolute"><parent link="l4"/><child link="l5"/><origin xyz="0 0 0.05"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" velocity="1"/></joint>
  <joint name="roll2" type="continuous"><parent link="l5"/><child link="l6"/><origin xyz="0 0 0.05"/><axis xyz="0 0 1"/></joint>
  <joint name="mount" type="fixed"><parent link="l6"/><child link="flange"/><origin xyz="0 0 0.02" rpy="0 0 0.3"/></joint>
</robot>"#;

#[test]
fn a_six_joint_toy_chain_with_prismatic_and_continuous_joints_is_solved() {
    let urdf = parse_urdf(TOY_ARM, "toy.urdf").unwrap();
    let chain = Chain::new(&urdf, "base", "flange").unwrap();
    assert_eq!(chain.dof(), 6);
    let tcp = Isometry3::from_parts(
        Translation3::new(0.0, 0.0, 0.1),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.5),
    );
    let seed = [0.0, 0.0, 0.3, 0.0, 0.0, 0.0];
    let mut rng = Pcg64Mcg::seed_from_u64(9);
    let mut solved = 0;
    for _ in 0..300 {
        let q = sample(&chain, &mut rng);
        let target = chain.tip_frame(&q) * tcp;
        if let Ok(s) = chain.ik(&tcp, &target, &seed, &IkOptions::default()) {
            check_solution(&chain, &tcp, &target, &s);
            // Continuous joints are wound to the turn nearest the seed.
            assert!(s.joints[3].abs() <= std::f64::consts::PI + 1e-9);
            assert!(s.joints[5].abs() <= std::f64::consts::PI + 1e-9);
            solved += 1;
        }
    }
    assert!(solved >= 297, "{solved} of 300");
    let short = Chain::new(&urdf, "base", "base").unwrap();
    assert_eq!(
        short.ik(&tcp, &Isometry3::identity(), &[], &IkOptions::default()),
        Err(IkFailure::UnsupportedChain { dof: 0 })
    );
}

#[test]
fn the_ur5_robot_file_loads_with_the_tool_down_over_the_table_at_home() {
    let r = load("ur5");
    assert_eq!(r.chain.dof(), 6);
    assert!(r.gripper.joints.is_empty());
    assert_eq!(r.gripper.finger_length, Some(0.05));
    let t = r.tcp_pose(&r.home).unwrap();
    let z = t.rotation * Vector3::z();
    assert!(z.z < -0.999, "the tool points down: {z:?}");
    let p = t.translation.vector;
    assert!(p.z > 0.1 && libm::hypot(p.x, p.y) > 0.3, "{p:?}");
    for l in &r.urdf.links {
        for c in &l.collisions {
            if let logic_lfd::sim::Geometry::Mesh { filename, .. } = &c.geometry {
                assert!(r.mesh_path(filename).unwrap().is_file(), "{filename}");
            }
        }
    }
}

#[test]
fn robot_ik_prints_joints_whose_fk_is_the_target_and_exits_1_when_unreachable() {
    let file = robots().join("ur5.json");
    let file = file.to_str().unwrap();
    let (code, out, err) = run_cli(&[
        "robot",
        "ik",
        file,
        "--position",
        "0.4,-0.2,0.3",
        "--rpy",
        "3.1,0.1,0.5",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let q: Vec<f64> = v["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(v["names"][0], "shoulder_pan_joint");
    let r = load("ur5");
    let t = r.tcp_pose(&q).unwrap();
    assert!((t.translation.vector - Vector3::new(0.4, -0.2, 0.3)).norm() < 1e-5);
    let want = UnitQuaternion::from_euler_angles(3.1, 0.1, 0.5);
    assert!(t.rotation.angle_to(&want) < 1e-4);
    assert!(v["position_error"].as_f64().unwrap() < 1e-5);

    // Without --rpy the TCP keeps its orientation at home; the text lists every joint.
    let (code, out, err) = run_cli(&["robot", "ik", file, "--position", "0.45,0.1,0.25"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().count(), 7, "{out}");
    assert!(
        out.contains("wrist_3_joint") && out.contains("error:"),
        "{out}"
    );

    let (code, _, err) = run_cli(&["robot", "ik", file, "--position", "2.5,0,0.3"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("unreachable") && err.contains("(2.5, 0, 0.3)"),
        "{err}"
    );

    for (args, want) in [
        (
            vec!["--position", "0.4,0"],
            "--position: 2 values, expected 3",
        ),
        (
            vec!["--position", "0.4,0,up"],
            "--position: value 3 is `up`",
        ),
        (
            vec!["--position", "0.4,0,0.3", "--rpy", "0,0"],
            "--rpy: 2 values",
        ),
        (
            vec!["--position", "0.4,0,0.3", "--seed-q", "0,0,0"],
            "--seed-q: 3 joint values for 6 joints",
        ),
    ] {
        let mut all = vec!["robot", "ik", file];
        all.extend(args);
        let (code, _, err) = run_cli(&all);
        assert_eq!(code, 2, "{all:?}");
        assert!(err.contains(want), "{err}");
    }
}
