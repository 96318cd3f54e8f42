//! The layers of the crate point one way: a module imports only from layers below it.
//!
//! ```text
//!   pddl → plan → (sim, lqt) → tamp → lfd → recorder → experiments → (bin, wasm)
//! ```
//!
//! Every `crate::…` path (in `use` lines and inline, multi-line `use crate::{…}` groups and
//! `super::` chains that climb to the crate root included) of every source file is resolved to
//! the top-level module it names and checked against the table below. Comments are skipped:
//! a doc link is not a dependency.

use std::collections::BTreeSet;
use std::path::Path;

use crate::support::source::rust_files;

/// Top-level modules, lowest layer first; modules of equal rank may not import each other.
const LAYERS: &[(&str, u8)] = &[
    ("pddl", 0),
    ("plan", 1),
    ("sim", 2),
    ("lqt", 2),
    ("tamp", 3),
    ("lfd", 4),
    ("recorder", 5),
    ("experiments", 6),
    ("bin", 7),
    ("wasm", 7),
];

fn rank(module: &str) -> Option<u8> {
    LAYERS.iter().find(|(m, _)| *m == module).map(|&(_, r)| r)
}

/// The module path of a source file below `src/` (`lfd/exec/tick.rs` → `[lfd, exec, tick]`,
/// `lfd/mod.rs` → `[lfd]`).
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts
        .last()
        .is_some_and(|l| l == "mod" || l == "lib" || l == "main")
    {
        parts.pop();
    }
    parts
}

/// The top-level modules a piece of source code names through `crate::` or `super::` paths,
/// with the line of each. `module` is the file's module path.
fn imports(source: &str, module: &[String]) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    let mut text = String::new();
    let mut line_of = Vec::new();
    for (n, line) in source.lines().enumerate() {
        let code = match line.find("//") {
            Some(i) => &line[..i],
            None => line,
        };
        text.push_str(code);
        text.push('\n');
        line_of.extend(std::iter::repeat_n(n + 1, code.len() + 1));
    }
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut at = 0;
    while let Some(i) = text[at..].find("crate::") {
        let start = at + i;
        at = start + "crate::".len();
        let before = text[..start].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue; // e.g. `logic_lfd_crate::`
        }
        let rest = &text[at..];
        if let Some(group) = rest.strip_prefix('{') {
            // `use crate::{a::x, b::{y, z}}`: the group's top-level names.
            let mut depth = 0;
            let mut item_start = true;
            for (j, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => item_start = true,
                    c if item_start && !c.is_whitespace() => {
                        item_start = false;
                        found.push((line_of[at + 1 + j], ident(&group[j..])));
                    }
                    _ => {}
                }
            }
        } else {
            found.push((line_of[at], ident(rest)));
        }
    }
    // `super::super::x` from `a::b` names the crate root's `x`.
    let depth = module.len();
    let climb = "super::".repeat(depth);
    if depth > 0 {
        let mut at = 0;
        while let Some(i) = text[at..].find(&climb) {
            let start = at + i;
            at = start + climb.len();
            if text[..start].ends_with("super::") {
                continue;
            }
            found.push((line_of[at], ident(&text[at..])));
        }
    }
    found
}

#[test]
fn no_module_imports_a_module_of_its_own_layer_or_above() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut violations = Vec::new();
    let mut unplaced = BTreeSet::new();
    for file in &files {
        let rel = file.strip_prefix(&src).unwrap();
        let module = module_path(rel);
        let Some(top) = module.first() else {
            continue; // lib.rs declares the modules
        };
        let Some(own) = rank(top) else {
            unplaced.insert(top.clone());
            continue;
        };
        let source = std::fs::read_to_string(file).unwrap();
        for (line, target) in imports(&source, &module) {
            if target == *top || target.is_empty() {
                continue;
            }
            match rank(&target) {
                Some(r) if r < own => {}
                Some(_) => violations.push(format!(
                    "src/{}:{line}: `{top}` imports `{target}`, which is not below it",
                    rel.display()
                )),
                None => {} // a root item (e.g. `crate::VERSION`), not a module
            }
        }
    }
    assert!(
        unplaced.is_empty(),
        "top-level modules missing from LAYERS: {unplaced:?}"
    );
    assert!(
        violations.is_empty(),
        "layer violations:\n{}",
        violations.join("\n")
    );
}

#[test]
fn the_import_scanner_sees_every_form_of_path() {
    let module = vec!["tamp".to_string(), "streams".to_string()];
    let src = "use crate::plan::Task;\n\
               use crate::{\n    sim::World,\n    lfd::{exec, control},\n};\n\
               // use crate::experiments::x; (a comment)\n\
               fn f() { crate::recorder::go(); super::super::wasm::x(); super::action::y(); }\n";
    let got: Vec<(usize, String)> = imports(src, &module);
    let names: Vec<&str> = got.iter().map(|(_, m)| m.as_str()).collect();
    assert_eq!(names, ["plan", "sim", "lfd", "recorder", "wasm"]);
    assert_eq!(
        got.iter().map(|(l, _)| *l).collect::<Vec<_>>(),
        [1, 3, 4, 7, 7]
    );
}
