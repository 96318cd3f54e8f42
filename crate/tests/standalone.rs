//! A clone of the repository is all a build, a test or a bench needs: no tracked file reads a
//! folder beside the checkout, and the vendored benchmark data are the files their `SHA256SUMS`
//! names, byte for byte.

use std::path::{Path, PathBuf};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The tracked files (`git ls-files`), else every file outside the build and install folders.
fn tracked_files(root: &Path) -> Vec<PathBuf> {
    let git = std::process::Command::new("git")
        .arg("ls-files")
        .arg("-z")
        .current_dir(root)
        .output();
    if let Ok(out) = git {
        if out.status.success() && !out.stdout.is_empty() {
            return out
                .stdout
                .split(|&b| b == 0)
                .filter(|p| !p.is_empty())
                .map(|p| root.join(String::from_utf8_lossy(p).as_ref()))
                .collect();
        }
    }
    let mut files = Vec::new();
    walk(root, &mut files);
    files
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    const SKIP: &[&str] = &[".git", "target", "node_modules", "pkg", "dist", "results"];
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        if p.is_dir() {
            if !SKIP.contains(&name.as_str()) {
                walk(&p, out);
            }
        } else {
            out.push(p);
        }
    }
}

#[test]
fn no_tracked_file_reads_a_folder_beside_the_checkout() {
    let root = repo_root();
    // Spelled in pieces so that this file does not match itself.
    let needles = [
        format!("../{}", "shared"),
        format!("'{}', 'ipc'", "shared"),
        format!("\"{}\", \"ipc\"", "shared"),
        format!("{}/ipc", "shared"),
        format!("{}/lqt-cp", "shared"),
    ];
    let mut found = Vec::new();
    let files = tracked_files(&root);
    assert!(files.len() > 100, "{} files", files.len());
    for path in files {
        if path.file_name().is_some_and(|n| n == "CHANGELOG.md") {
            continue;
        }
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue; // binary files (screenshots, meshes)
        };
        for (n, line) in text.lines().enumerate() {
            if needles.iter().any(|k| line.contains(k.as_str())) {
                let rel = path.strip_prefix(&root).unwrap_or(&path).display();
                found.push(format!("{rel}:{}: {}", n + 1, line.trim()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "reads outside the clone:\n{}",
        found.join("\n")
    );
}

fn sha256(bytes: &[u8]) -> String {
    use sha2::Digest;
    sha2::Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

#[test]
fn vendored_ipc_files_match_their_checksums() {
    let dir = repo_root().join("tests/data/ipc");
    let sums = std::fs::read_to_string(dir.join("SHA256SUMS")).unwrap();
    let mut n = 0;
    for line in sums.lines().filter(|l| !l.trim().is_empty()) {
        let (want, file) = line.split_once("  ").expect("`HASH  PATH` lines");
        let bytes = std::fs::read(dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(sha256(&bytes), want, "{file}");
        n += 1;
    }
    // 5 domains and 207 problems.
    assert_eq!(n, 212);
}

#[test]
fn vendored_lqt_example_matches_its_checksum() {
    let dir = repo_root().join("tests/data/lqt");
    let note = std::fs::read_to_string(dir.join("SOURCE.md")).unwrap();
    let bytes = std::fs::read(dir.join("lqt-cp-example.json")).unwrap();
    assert!(
        note.contains(&sha256(&bytes)),
        "SOURCE.md names another checksum"
    );
}
