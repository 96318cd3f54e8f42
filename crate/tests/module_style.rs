//! One module style and one public path per item.
//!
//! A module with submodules is a folder with its `mod.rs`. Submodules are private and their
//! items are re-exported by the parent (`logic_lfd::lfd::Session`, never
//! `logic_lfd::lfd::session::Session`); the few public submodules are namespaces whose items
//! the parent does not re-export (`experiments::fig4::plot` beside `experiments::scaling::plot`).
//! A file re-exports only its own children's items, so no item gets a second path; the one
//! exception is `prelude`.

use std::path::{Path, PathBuf};

use crate::support::source::rust_files;

/// Public submodules below the layers: namespaces for items with generic names (`run`, `plot`,
/// `record`) or a family of constants and functions read as one (`panda::DOF`).
const NAMESPACES: [&str; 11] = [
    "sim::collide",
    "sim::demo",
    "sim::geometry",
    "sim::panda",
    "recorder::taught",
    "experiments::fig4",
    "experiments::fig4::plot",
    "experiments::fuzz",
    "experiments::hot_paths",
    "experiments::scaling",
    "experiments::scaling::plot",
];

/// The library's files (the binary is a crate of its own, with no public surface).
fn library_files() -> (PathBuf, Vec<PathBuf>) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut paths = Vec::new();
    rust_files(&src, &mut paths);
    paths.retain(|p| !p.starts_with(src.join("bin")));
    (src, paths)
}

/// `a::b` for `src/a/b/mod.rs`, `src/a/b.rs`; empty for `lib.rs`.
fn module_path(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().into_owned())
        .collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts.join("::")
}

/// The file's top-level statements before its test module, each joined onto one line.
fn top_level_statements(text: &str) -> Vec<String> {
    let code = text.split("#[cfg(test)]\nmod tests").next().unwrap_or("");
    let mut out = Vec::new();
    let mut current = String::new();
    for line in code.lines() {
        if current.is_empty() && !line.starts_with("pub ") {
            continue;
        }
        current.push_str(line.trim());
        current.push(' ');
        let end = line.trim_end();
        // A `use` ends at its `;`; an item's header at its `{` or `;`.
        if end.ends_with(';') || (end.ends_with('{') && !current.starts_with("pub use ")) {
            out.push(std::mem::take(&mut current));
        }
    }
    out
}

#[test]
fn a_module_with_submodules_is_a_folder_with_its_mod_rs() {
    let (src, paths) = library_files();
    let beside: Vec<String> = paths
        .iter()
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n != "mod.rs" && n != "lib.rs")
        })
        .filter(|p| p.with_extension("").is_dir())
        .map(|p| p.strip_prefix(&src).unwrap().display().to_string())
        .collect();
    assert!(
        beside.is_empty(),
        "one module style: move these to NAME/mod.rs: {beside:?}"
    );
}

#[test]
fn every_public_item_has_one_path() {
    let (src, paths) = library_files();
    let mut wrong = Vec::new();
    for file in &paths {
        let module = module_path(&src, file);
        let text = std::fs::read_to_string(file).unwrap();
        let statements = top_level_statements(&text);
        let public_children: Vec<&str> = statements
            .iter()
            .filter_map(|s| s.strip_prefix("pub mod "))
            .filter_map(|s| s.strip_suffix("; "))
            .collect();
        let at = file.strip_prefix(&src).unwrap().display();
        for child in &public_children {
            let path = if module.is_empty() {
                child.to_string()
            } else {
                format!("{module}::{child}")
            };
            // The layers are the crate's top-level modules; below them, only namespaces.
            if !module.is_empty() && !NAMESPACES.contains(&path.as_str()) {
                wrong.push(format!(
                    "{at}: `pub mod {child}`: make it private and re-export its items"
                ));
            }
        }
        for s in statements.iter().filter_map(|s| s.strip_prefix("pub use ")) {
            let root = s.split("::").next().unwrap_or("");
            if root == "super" || root == "crate" {
                wrong.push(format!(
                    "{at}: `pub use {s}` gives an item of another module a second path"
                ));
            } else if public_children.contains(&root) {
                wrong.push(format!(
                    "{at}: `pub use {s}` re-exports from the public module `{root}`"
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn the_path_check_reads_multiline_statements() {
    let text =
        "//! Doc.\npub mod a;\nmod b;\npub use b::{\n    X,\n    Y,\n};\npub use super::Z;\n\
                #[cfg(test)]\nmod tests {\n    pub use crate::W;\n}\n";
    let s = top_level_statements(text);
    assert_eq!(
        s,
        [
            "pub mod a; ",
            "pub use b::{ X, Y, }; ",
            "pub use super::Z; "
        ]
    );
}
