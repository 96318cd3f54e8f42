//! A task folder given on the command line (`--domain DIR`, `demo record DIR`).

use std::path::{Path, PathBuf};

use logic_lfd::sim::TaskFolder;

/// Reads the task folder `dir`. A bare name is read as `./NAME`, so no message names it as if it
/// were one of the shipped `domains/`.
pub fn read(dir: &Path) -> Result<TaskFolder, String> {
    let mut parts = dir.components();
    let bare = matches!(
        (parts.next(), parts.next()),
        (Some(std::path::Component::Normal(_)), None)
    );
    let dir: PathBuf = if bare {
        Path::new(".").join(dir)
    } else {
        dir.to_path_buf()
    };
    TaskFolder::read(&dir).map_err(|e| e.to_string())
}
