//! Where a robot's files are read: the disk, or a folder held in memory (files a browser opened,
//! or the robots compiled into the library).

use std::collections::BTreeMap;
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

/// The files a robot is read from.
///
/// - [`RobotFiles::disk`]: paths are read from the file system.
/// - [`RobotFiles::memory`]: paths name files held in memory; `a/./b/../c` names `a/c`.
#[derive(Clone, Default)]
pub struct RobotFiles {
    memory: Option<Arc<BTreeMap<PathBuf, Vec<u8>>>>,
}

impl RobotFiles {
    /// Files read from the file system.
    pub fn disk() -> RobotFiles {
        RobotFiles { memory: None }
    }

    /// Files held in memory: each path (relative, `/`-separated) with its bytes.
    pub fn memory<P: AsRef<Path>>(files: impl IntoIterator<Item = (P, Vec<u8>)>) -> RobotFiles {
        let map = files
            .into_iter()
            .map(|(p, bytes)| (normal(p.as_ref()), bytes))
            .collect();
        RobotFiles {
            memory: Some(Arc::new(map)),
        }
    }

    /// The bytes of the file at `path`.
    pub fn read(&self, path: &Path) -> Result<Vec<u8>, String> {
        match &self.memory {
            None => std::fs::read(path).map_err(|e| e.to_string()),
            Some(m) => held(m, path).map(<[u8]>::to_vec),
        }
    }

    /// The text of the file at `path`.
    pub fn read_text(&self, path: &Path) -> Result<String, String> {
        String::from_utf8(self.read(path)?).map_err(|e| format!("not UTF-8 text: {e}"))
    }

    /// Whether `path` names a file.
    pub fn is_file(&self, path: &Path) -> bool {
        match &self.memory {
            None => path.is_file(),
            Some(m) => m.contains_key(&normal(path)),
        }
    }

    /// What identifies the file's content for a cache: its canonical path, its length and its
    /// modification time (disk) or a hash of its bytes (memory).
    pub(super) fn stamp(&self, path: &Path) -> Result<(PathBuf, u64, u128), String> {
        match &self.memory {
            None => {
                let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
                let canonical = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
                let modified = meta
                    .modified()
                    .ok()
                    .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
                    .map_or(0, |d| d.as_nanos());
                Ok((canonical, meta.len(), modified))
            }
            Some(m) => {
                // Hashed where it is held: no copy of the file for its cache key.
                let bytes = held(m, path)?;
                Ok((
                    PathBuf::from("memory:").join(normal(path)),
                    bytes.len() as u64,
                    u128::from(fnv1a(bytes)),
                ))
            }
        }
    }
}

impl std::fmt::Debug for RobotFiles {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.memory {
            None => f.write_str("RobotFiles::disk"),
            Some(m) => write!(f, "RobotFiles::memory({} files)", m.len()),
        }
    }
}

impl PartialEq for RobotFiles {
    fn eq(&self, other: &RobotFiles) -> bool {
        match (&self.memory, &other.memory) {
            (None, None) => true,
            (Some(a), Some(b)) => Arc::ptr_eq(a, b) || a == b,
            _ => false,
        }
    }
}

/// The bytes held in memory at `path`.
fn held<'a>(files: &'a BTreeMap<PathBuf, Vec<u8>>, path: &Path) -> Result<&'a [u8], String> {
    files
        .get(&normal(path))
        .map(Vec::as_slice)
        .ok_or_else(|| "no such file among the robot's files".to_string())
}

/// `path` without `.` and with each `..` taking away the folder before it.
fn normal(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::CurDir | Component::RootDir | Component::Prefix(_) => {}
            Component::ParentDir => {
                out.pop();
            }
            Component::Normal(n) => out.push(n),
        }
    }
    out
}

/// The 64-bit FNV-1a hash of `bytes`.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3)
    })
}
