//! `--robot ROBOT` of `run`, `soak` and `bench table*`: a shipped robot's name or a robot file,
//! read into the arm models that take the place of the built-in Panda.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

use logic_lfd::sim::ArmModel;
use logic_lfd::sim::{shipped_robot, Robot, RobotError, SHIPPED_ROBOTS};

/// Help of `--robot`.
pub const HELP: &str = "A shipped robot (panda: the Franka Emika Panda from its URDF, ur5) or a \
                        robot file (robot.json beside its URDF) whose arm takes the place of the \
                        built-in Panda; given twice, one per arm (B3)";

/// The arm models of the robots `paths` (none: the scene's own arms): a shipped robot's name
/// (unless a file of that name exists) or a robot file; the error names the file and the JSON
/// path, URDF line or mesh that cannot be used.
pub fn load(paths: &[PathBuf]) -> Result<Vec<Arc<ArmModel>>, String> {
    paths
        .iter()
        .map(|p| ArmModel::load(p).map_err(|e| e.to_string()))
        .collect()
}

/// `p` as a shipped robot's name: one of [`SHIPPED_ROBOTS`], and no file of that name here.
fn shipped_name(p: &Path) -> Option<&'static str> {
    let name = p.to_str()?;
    let shipped = SHIPPED_ROBOTS.into_iter().find(|s| *s == name)?;
    (!p.exists()).then_some(shipped)
}

/// The robot `p`: a shipped robot's name (its compiled-in files) or a robot file.
pub fn robot(p: &Path) -> Result<Robot, RobotError> {
    match shipped_name(p).and_then(shipped_robot) {
        Some(r) => r,
        None => Robot::load(p),
    }
}

/// [`load`], its error printed on stderr and turned into the bad-input exit code.
pub fn load_or_exit(paths: &[PathBuf]) -> Result<Vec<Arc<ArmModel>>, ExitCode> {
    load(paths).map_err(|e| {
        eprintln!("{e}");
        ExitCode::from(crate::exit::BAD_INPUT)
    })
}
