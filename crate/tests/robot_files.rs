//! Robots read from files in memory: the shipped robots equal the repository's robot files, and a
//! robot folder given by its files (as a browser or a script holds them) loads, or is refused
//! with the file at fault.

use std::path::Path;

use logic_lfd::sim::panda::DOF;
use logic_lfd::sim::{shipped_robot, ArmModel, Robot, SHIPPED_ROBOTS};
use nalgebra::Isometry3;

use crate::robot_episodes::short_arm_files;

#[test]
fn the_shipped_robots_are_the_repository_robot_files() {
    for name in SHIPPED_ROBOTS {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../robots/{name}.json"));
        let disk = Robot::load(&file).unwrap();
        let shipped = shipped_robot(name).unwrap().unwrap();
        assert_eq!(shipped.urdf, disk.urdf, "{name}");
        assert_eq!(
            (shipped.tcp, &shipped.home),
            (disk.tcp, &disk.home),
            "{name}"
        );
        let (a, b) = (
            ArmModel::from_robot(&disk).unwrap(),
            ArmModel::shipped(name).unwrap(),
        );
        assert_eq!(
            (a.lower(), a.upper(), a.ready()),
            (b.lower(), b.upper(), b.ready())
        );
        let mut q = a.ready();
        for (i, qi) in q.iter_mut().enumerate().take(a.dof()) {
            *qi += 0.1 * (i as f64 + 1.0);
        }
        a.clamp(&mut q);
        let base = Isometry3::identity();
        assert_eq!(
            a.forward_kinematics(&base, &q),
            b.forward_kinematics(&base, &q),
            "{name}"
        );
    }
    assert!(ArmModel::shipped("ur10").is_none());
    assert_eq!(ArmModel::shipped("ur5").unwrap().dof(), 6);
    assert_eq!(ArmModel::shipped("panda").unwrap().dof(), DOF);
}

fn folder(prefix: &str) -> Vec<(String, Vec<u8>)> {
    short_arm_files()
        .into_iter()
        .map(|(p, t)| (format!("{prefix}{p}"), t.into_bytes()))
        .collect()
}

#[test]
fn a_robot_folder_in_memory_loads_from_its_robot_json() {
    let flat = Robot::from_folder(folder("")).unwrap();
    assert_eq!(flat.name, "short");
    assert_eq!(flat.chain.dof(), 6);
    // As a browser names a chosen folder's files: under the folder's name.
    let nested = Robot::from_folder(folder("my-arm/")).unwrap();
    assert_eq!(nested.urdf, flat.urdf);
    // Without a robot.json, the one .json file naming a urdf.
    let renamed: Vec<_> = folder("")
        .into_iter()
        .map(|(p, b)| (p.replace("robot.json", "short.json"), b))
        .collect();
    assert_eq!(Robot::from_folder(renamed).unwrap().name, "short");
    let shipped = ArmModel::from_robot(&flat).unwrap();
    assert_eq!(shipped.name(), "short");
}

#[test]
fn a_robot_folder_in_memory_is_refused_with_the_file_at_fault() {
    let e = Robot::from_folder(vec![("a.txt".into(), b"x".to_vec())])
        .unwrap_err()
        .to_string();
    assert!(e.contains("no robot.json") && e.contains("1 files"), "{e}");
    let mut two = folder("a/");
    two.extend(folder("b/"));
    let e = Robot::from_folder(two).unwrap_err().to_string();
    assert!(e.contains("2 robot files side by side"), "{e}");
    let no_urdf: Vec<_> = folder("")
        .into_iter()
        .filter(|(p, _)| p.ends_with(".json"))
        .collect();
    let e = Robot::from_folder(no_urdf).unwrap_err().to_string();
    assert!(
        e.starts_with("robot.json: urdf") && e.contains("short.urdf"),
        "{e}"
    );
    // A collision mesh the URDF names and the folder lacks is named with its URDF line.
    let mut meshy = folder("");
    let urdf = String::from_utf8(meshy[1].1.clone()).unwrap().replacen(
        r#"<box size="0.04 0.04 0.06"/>"#,
        r#"<mesh filename="meshes/base.stl"/>"#,
        1,
    );
    meshy[1].1 = urdf.into_bytes();
    let e = Robot::from_folder(meshy).unwrap_err().to_string();
    assert!(
        e.starts_with("short.urdf:") && e.contains("meshes/base.stl"),
        "{e}"
    );
}

#[test]
fn a_robot_file_narrows_joint_limits_and_names_a_wrong_one() {
    let with = |limits: &str| -> Vec<(String, Vec<u8>)> {
        folder("")
            .into_iter()
            .map(|(p, b)| {
                if p == "robot.json" {
                    let t = String::from_utf8(b).unwrap();
                    let t = t.replacen("\"home\"", &format!("\"limits\": {limits}, \"home\""), 1);
                    (p, t.into_bytes())
                } else {
                    (p, b)
                }
            })
            .collect()
    };
    let r = Robot::from_folder(with(r#"{ "j2": [-1, 1.5] }"#)).unwrap();
    let j2 = r.chain.moving().nth(1).unwrap();
    assert_eq!((j2.lower, j2.upper), (-1.0, 1.5));
    let m = ArmModel::from_robot(&r).unwrap();
    assert_eq!((m.lower()[1], m.upper()[1]), (-1.0, 1.5));
    for (limits, want) in [
        (
            r#"{ "j9": [0, 1] }"#,
            "robot.json: limits.j9: `j9` is not a moving joint",
        ),
        (
            r#"{ "j2": [1, 1] }"#,
            "robot.json: limits.j2: [1, 1]: expected [lower, upper]",
        ),
        (
            r#"{ "j2": [-4, 1] }"#,
            "robot.json: limits.j2: [-4, 1] is not within the URDF's limits [-3, 3]",
        ),
        (r#"{ "j2": [0.6, 1] }"#, "robot.json: home"),
    ] {
        let e = Robot::from_folder(with(limits)).unwrap_err().to_string();
        assert!(e.starts_with(want), "{limits}: {e}");
    }
    // The shipped UR5 keeps its upper arm above the shoulder: the lift joint within [-π, 0].
    let ur5 = ArmModel::shipped("ur5").unwrap();
    assert_eq!(
        (ur5.lower()[1], ur5.upper()[1]),
        (-std::f64::consts::PI, 0.0)
    );
}
