//! Episodes on robots read from their URDFs: the arm model agrees with the URDF chain, the UR5
//! (6 joints) and the URDF Panda run B1 and B2 closed loop with the world's invariants checked
//! after every tick, logs replay exactly on the same robots, and every wrong use is refused.

// Joint i of q against limit i of the model.
#![allow(clippy::needless_range_loop)]

use std::path::{Path, PathBuf};
use std::sync::Arc;

use logic_lfd::experiments::{run_episode, EpisodeSpec};
use logic_lfd::lfd::{Level, Method, Mode, Session, SessionOptions, SessionParams, SkillKind};
use logic_lfd::plan::NoClock;
use logic_lfd::sim::panda::DOF;
use logic_lfd::sim::{ArmModel, IkParams};
use logic_lfd::sim::{Benchmark, Robot, World};
use nalgebra::Isometry3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Logic-LfD in paper mode with LQT skills on benchmark `b`'s template task.
fn options(b: Benchmark, seed: u64) -> SessionOptions {
    SessionOptions {
        benchmark: b,
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed,
        skill: SkillKind::Lqt,
        blocks: None,
    }
}

fn robot_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../robots")
        .join(format!("{name}.json"))
}

fn model(name: &str) -> Arc<ArmModel> {
    let robot = Robot::load(&robot_file(name)).unwrap();
    Arc::new(ArmModel::from_robot(&robot).unwrap())
}

#[test]
fn a_urdf_arm_model_moves_its_tcp_as_the_urdf_chain_does() {
    for name in ["panda", "ur5"] {
        let robot = Robot::load(&robot_file(name)).unwrap();
        let m = ArmModel::from_robot(&robot).unwrap();
        assert_eq!(m.dof(), robot.chain.dof(), "{name}");
        let base = Isometry3::translation(0.1, -0.2, 0.05);
        let mut rng = Pcg64Mcg::seed_from_u64(3);
        for _ in 0..100 {
            let mut q = [0.0; DOF];
            for i in 0..m.dof() {
                q[i] = rng.random_range(m.lower()[i]..m.upper()[i]);
            }
            let want = base * robot.tcp_pose(&q[..m.dof()]).unwrap();
            let got = m.forward_kinematics(&base, &q);
            let dp = (want.translation.vector - got.translation.vector).norm();
            assert!(dp < 1e-9, "{name} {q:?}: {dp} m");
            assert!(want.rotation.angle_to(&got.rotation) < 1e-9, "{name} {q:?}");
        }
    }
}

#[test]
fn the_urdf_panda_moves_as_the_built_in_one() {
    let (urdf, dh) = (model("panda"), ArmModel::panda());
    let base = Isometry3::identity();
    let q = dh.ready();
    let (a, b) = (
        urdf.forward_kinematics(&base, &q),
        dh.forward_kinematics(&base, &q),
    );
    assert!((a.translation.vector - b.translation.vector).norm() < 1e-9);
    assert_eq!(urdf.lower(), dh.lower());
    assert_eq!(urdf.upper(), dh.upper());
}

#[test]
fn the_ur5_solves_its_own_forward_kinematics_back_within_its_limits() {
    let m = model("ur5");
    let base = Isometry3::identity();
    let params = IkParams::default();
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    let (mut solved, cases) = (0, 200);
    for _ in 0..cases {
        let mut q = m.ready();
        for i in 0..m.dof() {
            q[i] += rng.random_range(-0.6..0.6);
        }
        let target = m.forward_kinematics(&base, &q);
        if let Ok(s) = m.inverse_kinematics(&base, &target, &m.ready(), &params) {
            let reached = m.forward_kinematics(&base, &s.joints);
            assert!((reached.translation.vector - target.translation.vector).norm() < 1e-3);
            assert_eq!(s.joints[DOF - 1], 0.0, "the unused joint stays 0");
            for i in 0..m.dof() {
                assert!((m.lower()[i]..=m.upper()[i]).contains(&s.joints[i]));
            }
            solved += 1;
        }
    }
    assert!(solved * 100 >= cases * 99, "{solved} of {cases}");
}

/// Runs a session to its end with the world's invariants checked after every tick; its log.
fn run_checked(mut s: Session) -> (bool, String) {
    let clock = NoClock;
    for _ in 0..30_000 {
        if s.outcome().is_some() {
            break;
        }
        s.step(0.01, &clock);
        if let Err(v) = s.world().check_invariants() {
            panic!("tick {}: {v:?}", s.tick());
        }
    }
    (s.outcome().is_some_and(|o| o.is_ok()), s.episode_json())
}

#[test]
fn the_ur5_and_the_urdf_panda_finish_b1_and_b2_with_a_disturbance_and_replay_exactly() {
    for robot in ["ur5", "panda"] {
        let m = model(robot);
        for (b, level) in [
            (Benchmark::B1, "l3"),
            (Benchmark::B2, "l2"),
            (Benchmark::B1, "l1"),
        ] {
            let mut s = Session::new(options(b, 5)).unwrap();
            s.set_robots(std::slice::from_ref(&m)).unwrap();
            assert_eq!(s.world().snapshot().arms[0].robot.as_deref(), Some(robot));
            assert_eq!(s.world().joints(0).unwrap(), m.ready());
            // Two seconds in, then the disturbance.
            let clock = NoClock;
            for _ in 0..200 {
                s.step(0.01, &clock);
            }
            s.inject(level).unwrap();
            let (ok, json) = run_checked(s);
            assert!(ok, "{robot} {} {level}", b.as_str());
            let replayed = Session::replay_with_robots(&json, std::slice::from_ref(&m)).unwrap();
            assert_eq!(replayed.episode_json(), json, "{robot} {}", b.as_str());
            // A shipped robot needs no robot file: the log's scene names it.
            let shipped = Session::replay(&json).unwrap();
            assert_eq!(shipped.episode_json(), json, "{robot} {}", b.as_str());
        }
    }
}

#[test]
fn the_ur5_runs_table_one_episodes_of_b1_and_b2() {
    let m = model("ur5");
    for b in [Benchmark::B1, Benchmark::B2] {
        for (i, level) in Level::ALL.iter().enumerate() {
            let spec = EpisodeSpec {
                benchmark: b,
                level: Some(*level),
                method: Method::LogicLfd,
                mode: Mode::Paper,
                seed: 20 + i as u64,
                scene: None,
                robots: vec![Arc::clone(&m)],
            };
            let r = run_episode(&spec, SessionParams::default(), &NoClock).unwrap();
            assert!(
                r.success,
                "{} {}: {:?}",
                b.as_str(),
                level.as_str(),
                r.reason
            );
        }
    }
}

#[test]
fn robots_are_refused_where_they_cannot_take_an_arms_place() {
    let m = model("ur5");
    let mut s = Session::new(options(Benchmark::B3, 1)).unwrap();
    let three = vec![Arc::clone(&m); 3];
    let e = s.set_robots(&three).unwrap_err().to_string();
    assert!(e.contains("3 robots for 2 arms"), "{e}");
    s.step(0.01, &NoClock);
    let e = s.set_robots(&three[..1]).unwrap_err().to_string();
    assert!(e.contains("before the episode's first step"), "{e}");
    // B3 on one robot per arm: the left the UR5, the right the built-in Panda.
    let mut s = Session::new(options(Benchmark::B3, 1)).unwrap();
    s.set_robots(&[Arc::clone(&m), ArmModel::panda()]).unwrap();
    let arms = s.world().snapshot().arms;
    assert_eq!(arms[0].robot.as_deref(), Some("ur5"));
    assert_eq!(arms[0].joints.len(), 6);
    assert_eq!(arms[1].robot, None);
    assert_eq!(arms[1].joints.len(), 7);
}

#[test]
fn a_saved_scene_names_its_robot_and_loads_only_with_it() {
    let mut w = Benchmark::B1.scene();
    w.set_robot(0, model("ur5")).unwrap();
    // A shipped robot loads by its name alone.
    let json = w.to_json();
    assert_eq!(World::from_json(&json).unwrap().to_json(), json);
    let robot = Robot::load(&short_arm()).unwrap();
    w.set_robot(0, Arc::new(ArmModel::from_robot(&robot).unwrap()))
        .unwrap();
    let json = w.to_json();
    let e = World::from_json(&json).unwrap_err().to_string();
    assert!(
        e.contains("arms[0] \"panda\".robot") && e.contains("robot `short` is not loaded"),
        "{e}"
    );
    // The snapshot carries the model: the world comes back as it was.
    let again = World::from_snapshot(&w.snapshot()).unwrap();
    assert_eq!(again.to_json(), json);
    // Six joint angles for a seven-joint arm are refused by name.
    let mut snap = Benchmark::B1.scene().snapshot();
    snap.arms[0].joints.pop();
    let e = World::from_snapshot(&snap).unwrap_err().to_string();
    assert!(e.contains("needs 7 joint angles for `panda`, got 6"), "{e}");
}

/// A 6-joint arm 35 cm long (boxes for links), in a fresh folder: it reaches none of B1's blocks.
fn short_arm() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("logic-lfd-short-arm-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in short_arm_files() {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir.join("robot.json")
}

/// The short arm's files: `robot.json` and `short.urdf`.
pub fn short_arm_files() -> [(&'static str, String); 2] {
    let joint = |n: usize, parent: &str, child: &str, z: f64, axis: &str| {
        format!(
            r#"<joint name="j{n}" type="revolute"><parent link="{parent}"/><child link="{child}"/><origin xyz="0 0 {z}"/><axis xyz="{axis}"/><limit lower="-3" upper="3" velocity="2"/></joint>"#
        )
    };
    let link = |name: &str| {
        format!(
            r#"<link name="{name}"><collision><origin xyz="0 0 0.03"/><geometry><box size="0.04 0.04 0.06"/></geometry></collision></link>"#
        )
    };
    let names = ["base", "l1", "l2", "l3", "l4", "l5", "l6"];
    let mut urdf = String::from(r#"<robot name="short">"#);
    for n in names {
        urdf.push_str(&link(n));
    }
    let axes = ["0 0 1", "0 1 0", "0 1 0", "0 1 0", "0 0 1", "0 1 0"];
    for k in 0..6 {
        let z = if k == 0 { 0.05 } else { 0.06 };
        urdf.push_str(&joint(k + 1, names[k], names[k + 1], z, axes[k]));
    }
    urdf.push_str("</robot>");
    let robot = r#"{ "name": "short", "urdf": "short.urdf", "base_link": "base", "tip_link": "l6",
             "tcp": { "xyz": [0, 0, 0.05] }, "home": [0, 0.5, 0.5, 0.5, 0, 0],
             "gripper": { "max_opening": 0.08, "finger_length": 0.04 } }"#;
    [("robot.json", robot.to_string()), ("short.urdf", urdf)]
}

#[test]
fn a_block_the_robot_cannot_reach_is_named_before_the_episode() {
    let robot = Robot::load(&short_arm()).unwrap();
    let short = Arc::new(ArmModel::from_robot(&robot).unwrap());
    let mut s = Session::new(options(Benchmark::B1, 1)).unwrap();
    let before = s.world().to_json();
    let e = s.set_robots(&[short]).unwrap_err().to_string();
    assert!(
        e.starts_with("block ")
            && e.contains("m from the base of arm panda, out of the robots' reach"),
        "{e}"
    );
    assert_eq!(s.world().to_json(), before, "nothing is half-applied");
}
