//! The robots compiled into the library: their robot files, URDFs and collision meshes, as
//! `robots/` of the repository holds them, so that any build runs them without the repository.

use std::path::Path;

use super::file::{Robot, RobotError};
use super::files::RobotFiles;

/// The shipped robots by name: `panda` (Franka Emika Panda) and `ur5` (Universal Robots UR5).
pub const SHIPPED_ROBOTS: [&str; 2] = ["panda", "ur5"];

macro_rules! files {
    ($($path:literal),* $(,)?) => {
        [$(($path, include_bytes!(concat!("../../../../", $path)).as_slice())),*]
    };
}

const PANDA: [(&str, &[u8]); 12] = files![
    "robots/panda.json",
    "robots/example-robot-data/robots/panda_description/urdf/panda.urdf",
    "robots/example-robot-data/robots/panda_description/meshes/collision/link0.stl",
    "robots/example-robot-data/robots/panda_description/meshes/collision/link1.stl",
    "robots/example-robot-data/robots/panda_description/meshes/collision/link2.stl",
    "robots/example-robot-data/robots/panda_description/meshes/collision/link3.stl",
    "robots/example-robot-data/robots/panda_description/meshes/collision/link4.stl",
    "robots/example-robot-data/robots/panda_description/meshes/collision/link5.stl",
    "robots/example-robot-data/robots/panda_description/meshes/collision/link6.stl",
    "robots/example-robot-data/robots/panda_description/meshes/collision/link7.stl",
    "robots/example-robot-data/robots/panda_description/meshes/collision/hand.stl",
    "robots/example-robot-data/robots/panda_description/meshes/collision/finger.stl",
];

const UR5: [(&str, &[u8]); 9] = files![
    "robots/ur5.json",
    "robots/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf",
    "robots/example-robot-data/robots/ur_description/meshes/ur5/collision/base.stl",
    "robots/example-robot-data/robots/ur_description/meshes/ur5/collision/shoulder.stl",
    "robots/example-robot-data/robots/ur_description/meshes/ur5/collision/upperarm.stl",
    "robots/example-robot-data/robots/ur_description/meshes/ur5/collision/forearm.stl",
    "robots/example-robot-data/robots/ur_description/meshes/ur5/collision/wrist1.stl",
    "robots/example-robot-data/robots/ur_description/meshes/ur5/collision/wrist2.stl",
    "robots/example-robot-data/robots/ur_description/meshes/ur5/collision/wrist3.stl",
];

/// The shipped robot `name` (one of [`SHIPPED_ROBOTS`]), read from the files compiled in; `None`
/// for another name.
pub fn shipped_robot(name: &str) -> Option<Result<Robot, RobotError>> {
    let files: &[(&str, &[u8])] = match name {
        "panda" => &PANDA,
        "ur5" => &UR5,
        _ => return None,
    };
    let memory = RobotFiles::memory(files.iter().map(|(p, b)| (*p, b.to_vec())));
    Some(Robot::load_from(Path::new(files[0].0), memory))
}
