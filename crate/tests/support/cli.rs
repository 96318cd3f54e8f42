//! Running the `logic-lfd` binary.

use std::path::Path;
use std::process::Command;

/// Runs `logic-lfd` with `args`: its exit code, stdout and stderr.
pub(crate) fn run_cli(args: &[&str]) -> (i32, String, String) {
    run_cli_in(Path::new("."), args)
}

/// Runs `logic-lfd args…` in the directory `cwd`: its exit code, stdout and stderr.
pub(crate) fn run_cli_in(cwd: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_logic-lfd"))
        .current_dir(cwd)
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}
