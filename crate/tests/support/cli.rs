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

/// Stderr of `logic-lfd args…` run in `cwd`, which must refuse its input: exit code 2 and
/// nothing on stdout.
pub(crate) fn refused_in(cwd: &Path, args: &[&str]) -> String {
    let (code, out, err) = run_cli_in(cwd, args);
    assert_eq!(code, 2, "logic-lfd {args:?} was not refused: {out}{err}");
    assert!(
        out.is_empty(),
        "logic-lfd {args:?} refused with output: {out}"
    );
    err
}
