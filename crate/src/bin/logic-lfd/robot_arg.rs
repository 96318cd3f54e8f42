//! `--robot ROBOT.json` of `run`, `soak` and `bench table1`: robot files read into the arm
//! models that take the place of the built-in Panda.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

use logic_lfd::sim::ArmModel;
use logic_lfd::sim::Robot;

/// Help of `--robot`.
pub const HELP: &str = "A robot file (robot.json beside its URDF) whose arm takes the place of \
                        the built-in Panda; given twice, one per arm (B3)";

/// The arm models of the robot files `paths` (none: the scene's own arms); the error names the
/// file and the JSON path, URDF line or mesh that cannot be used.
pub fn load(paths: &[PathBuf]) -> Result<Vec<Arc<ArmModel>>, String> {
    paths
        .iter()
        .map(|p| {
            Robot::load(p)
                .and_then(|r| ArmModel::from_robot(&r))
                .map(Arc::new)
                .map_err(|e| e.to_string())
        })
        .collect()
}

/// [`load`], its error printed on stderr and turned into the bad-input exit code.
pub fn load_or_exit(paths: &[PathBuf]) -> Result<Vec<Arc<ArmModel>>, ExitCode> {
    load(paths).map_err(|e| {
        eprintln!("{e}");
        ExitCode::from(crate::exit::BAD_INPUT)
    })
}
