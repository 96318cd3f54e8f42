//! A robot from its URDF: the shipped Panda's chain, limits and TCP agree with the built-in arm's
//! published DH model, and every broken robot file or URDF is refused at its JSON path or line.

use std::path::{Path, PathBuf};

use logic_lfd::sim::panda::{self, DOF};
use logic_lfd::sim::{parse_urdf, JointKind, Robot};
use nalgebra::Isometry3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

fn robots() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots")
}

fn panda() -> Robot {
    Robot::load(&robots().join("panda.json")).unwrap()
}

#[test]
fn the_panda_urdf_gives_the_dh_models_tcp_at_every_sampled_posture() {
    let r = panda();
    assert_eq!(r.chain.dof(), DOF);
    let mut rng = Pcg64Mcg::seed_from_u64(7);
    for _ in 0..200 {
        let q: [f64; DOF] =
            std::array::from_fn(|i| rng.random_range(panda::JOINT_LOWER[i]..panda::JOINT_UPPER[i]));
        let urdf = r.tcp_pose(&q).unwrap();
        let dh = panda::forward_kinematics(&Isometry3::identity(), &q);
        let dp = (urdf.translation.vector - dh.translation.vector).norm();
        let dr = urdf.rotation.angle_to(&dh.rotation);
        assert!(dp < 1e-9 && dr < 1e-9, "{q:?}: {dp} m, {dr} rad");
    }
}

#[test]
fn the_panda_urdf_has_the_published_joint_limits() {
    let r = panda();
    let moving: Vec<_> = r.chain.moving().collect();
    for (i, j) in moving.iter().enumerate() {
        assert_eq!(j.kind, JointKind::Revolute);
        assert_eq!(
            (j.lower, j.upper),
            (panda::JOINT_LOWER[i], panda::JOINT_UPPER[i]),
            "{}",
            j.name
        );
        assert_eq!(j.velocity, panda::JOINT_VELOCITY[i], "{}", j.name);
    }
    assert!(r
        .tcp_pose(&[0.0; DOF])
        .unwrap_err()
        .contains("panda_joint4"));
    assert!(r
        .tcp_pose(&[0.0; 6])
        .unwrap_err()
        .contains("6 joint values for 7"));
}

/// A copy of the shipped robot folder in a temporary directory, with `edit` applied to
/// `panda.json`'s text and `urdf_edit` to the URDF's.
fn broken(
    name: &str,
    edit: impl Fn(&str) -> String,
    urdf_edit: impl Fn(&str) -> String,
) -> Result<Robot, String> {
    let dir = std::env::temp_dir().join(format!("logic-lfd-robot-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    copy(&robots(), &dir);
    let json = dir.join("panda.json");
    std::fs::write(&json, edit(&std::fs::read_to_string(&json).unwrap())).unwrap();
    let urdf = dir.join("example-robot-data/robots/panda_description/urdf/panda.urdf");
    std::fs::write(&urdf, urdf_edit(&std::fs::read_to_string(&urdf).unwrap())).unwrap();
    let r = Robot::load(&json).map_err(|e| e.to_string());
    let _ = std::fs::remove_dir_all(&dir);
    r
}

fn copy(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        let target = to.join(p.file_name().unwrap());
        if p.is_dir() {
            copy(&p, &target);
        } else {
            std::fs::copy(&p, &target).unwrap();
        }
    }
}

fn same(s: &str) -> String {
    s.to_string()
}

#[test]
fn a_broken_robot_file_is_refused_at_its_json_path() {
    let e = broken(
        "home-len",
        |s| s.replace("\"home\": [0, ", "\"home\": ["),
        same,
    )
    .unwrap_err();
    assert!(e.contains("panda.json: home: 6 values for 7 joints"), "{e}");
    let e = broken(
        "home-type",
        |s| s.replace("\"home\": [0, ", "\"home\": [\"zero\", "),
        same,
    )
    .unwrap_err();
    assert!(e.contains("home[0]"), "{e}");
    let e = broken("tip", |s| s.replace("panda_link8", "panda_link9"), same).unwrap_err();
    assert!(
        e.contains("tip_link: the URDF has no link `panda_link9`"),
        "{e}"
    );
    let e = broken("short", |s| s.replace("panda_link8", "panda_link3"), same).unwrap_err();
    assert!(
        e.contains("has 3 moving joints; an arm needs 6 or 7"),
        "{e}"
    );
    let e = broken(
        "finger",
        |s| s.replace("panda_finger_joint2", "panda_finger_joint3"),
        same,
    )
    .unwrap_err();
    assert!(
        e.contains("gripper.joints[1]: the URDF has no joint `panda_finger_joint3`"),
        "{e}"
    );
    let e = broken(
        "package",
        |s| s.replace("\"example-robot-data\": ", "\"erd\": "),
        same,
    )
    .unwrap_err();
    assert!(
        e.contains("panda.urdf:13:1") && e.contains("no folder for package `example-robot-data`"),
        "{e}"
    );
    let e = broken("unknown", |s| s.replace("\"name\"", "\"nmae\""), same).unwrap_err();
    assert!(e.contains("unknown field `nmae`"), "{e}");
}

#[test]
fn a_broken_urdf_is_refused_at_its_line() {
    let e = broken("floating", same, |s| {
        s.replacen("type=\"revolute\"", "type=\"floating\"", 1)
    })
    .unwrap_err();
    assert!(
        e.contains("panda.urdf:41:") && e.contains("type `floating` is not supported"),
        "{e}"
    );
    let e = broken("mesh", same, |s| {
        s.replace("collision/link3.stl", "collision/link33.stl")
    })
    .unwrap_err();
    assert!(
        e.contains("panda.urdf:82:1") && e.contains("link33.stl"),
        "{e}"
    );
    let e = broken("xml", same, |s| s.replacen("</link>", "</lnk>", 1)).unwrap_err();
    assert!(e.contains("panda.urdf:23:"), "{e}");
    let e = broken("limit", same, |s| {
        s.replacen(
            "lower=\"-2.8973\" upper=\"2.8973\"",
            "lower=\"2.9\" upper=\"2.8973\"",
            1,
        )
    })
    .unwrap_err();
    assert!(
        e.contains("panda.urdf:46:") && e.contains("lower limit 2.9 above upper 2.8973"),
        "{e}"
    );
}

#[test]
fn a_urdf_with_every_supported_shape_and_joint_kind_parses() {
    let text = r#"<robot name="toy">
  <link name="base"><collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision></link>
  <link name="a"><collision><origin xyz="0 0 0.1"/><geometry><cylinder radius="0.05" length="0.2"/></geometry></collision></link>
  <link name="b"><collision><geometry><sphere radius="0.04"/></geometry></collision></link>
  <link name="c"/>
  <joint name="j1" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 2"/></joint>
  <joint name="j2" type="prismatic"><parent link="a"/><child link="b"/><origin xyz="0 0 0.2"/><axis xyz="1 0 0"/><limit lower="0" upper="0.3" velocity="0.5"/></joint>
  <joint name="j3" type="fixed"><parent link="b"/><child link="c"/><origin xyz="0 0 0.1" rpy="0 0 1.5707963267948966"/></joint>
</robot>"#;
    let u = parse_urdf(text, "toy.urdf").unwrap();
    let chain = logic_lfd::sim::Chain::new(&u, "base", "c").unwrap();
    assert_eq!(chain.dof(), 2);
    // j1 turns by π/2 about z (its axis normalised), j2 slides 0.3 along x of the turned frame.
    let t = chain.tip_frame(&[std::f64::consts::FRAC_PI_2, 0.3]);
    let p = t.translation.vector;
    assert!(
        (p - nalgebra::Vector3::new(0.0, 0.3, 0.3)).norm() < 1e-12,
        "{p:?}"
    );
    assert!(
        chain.outside_limits(&[100.0, 0.3]).is_none(),
        "continuous joints have no limits"
    );
    assert!(chain
        .outside_limits(&[0.0, 0.4])
        .unwrap()
        .contains("j2 = 0.4"));
    let e = logic_lfd::sim::Chain::new(&u, "c", "base").unwrap_err();
    assert!(e.contains("not below"), "{e}");
}

#[test]
fn robot_fk_prints_the_tcp_pose_as_json_and_refuses_a_short_joint_vector() {
    let bin = env!("CARGO_BIN_EXE_logic-lfd");
    let file = robots().join("panda.json");
    let q = panda::READY.map(|v| v.to_string()).join(",");
    let out = std::process::Command::new(bin)
        .args(["robot", "fk", file.to_str().unwrap(), "--q", &q, "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let want = panda::forward_kinematics(&Isometry3::identity(), &panda::READY);
    for (i, p) in v["position"].as_array().unwrap().iter().enumerate() {
        assert!((p.as_f64().unwrap() - want.translation.vector[i]).abs() < 1e-12);
    }
    let m = want.rotation.to_rotation_matrix();
    for r in 0..3 {
        for c in 0..3 {
            assert!((v["rotation"][r][c].as_f64().unwrap() - m[(r, c)]).abs() < 1e-12);
        }
    }
    let out = std::process::Command::new(bin)
        .args(["robot", "fk", file.to_str().unwrap(), "--q", "0,0,0"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("3 joint values for 7 joints"));
    let out = std::process::Command::new(bin)
        .args(["robot", "check", file.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["dof"], 7);
    assert_eq!(v["joints"][3]["upper"], -0.0698);
}
