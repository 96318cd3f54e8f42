//! Nothing in `crate/src` names a shipped benchmark's predicate or action: what an action does
//! physically and which predicate states what comes from each domain's `motions.json`, so a
//! domain with other names (the paper's own B1 naming, a user's) runs the same.
//!
//! Every string literal of the library's non-test code is checked: no literal that *is* one of
//! the benchmarks' predicate or action names, and none that starts a fact or an action of one
//! (`"(holding "`, `"(stack "`). Comments, `#[cfg(test)]` modules and the fuzzer's corpus of
//! malformed inputs (`experiments/fuzz/`) are not code that reads a domain.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::support::source::rust_files;

/// The predicates and actions of `domains/b1-tower`, `b2-workspace-reach` and `b3-dual-arm`
/// (read from their domain files, so a renamed one is still checked).
fn benchmark_names() -> BTreeSet<String> {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../domains");
    let mut names = BTreeSet::new();
    for dir in ["b1-tower", "b2-workspace-reach", "b3-dual-arm"] {
        let text = std::fs::read_to_string(format!("{root}/{dir}/domain.pddl")).unwrap();
        let d = logic_lfd::pddl::parse_domain(&text, "domain.pddl").unwrap();
        names.extend(d.predicates.iter().map(|p| p.name.text.clone()));
        names.extend(d.actions.iter().map(|a| a.name.text.clone()));
    }
    names
}

/// Names that are also words of the library's own vocabulary (a relation key `clear`, a motion
/// `pull`, PDDL's time specifier `at`): as a whole literal they mean that, so only `"(clear "`,
/// `"(pull "` and `"(at "` are forbidden.
const OWN_WORDS: [&str; 3] = ["clear", "pull", "at"];

/// Files of modules compiled only for tests (`#[cfg(test)] mod name;`).
fn test_only_files(files: &[PathBuf]) -> BTreeSet<PathBuf> {
    let mut out = BTreeSet::new();
    for f in files {
        let text = std::fs::read_to_string(f).unwrap();
        let dir = if f.ends_with("mod.rs") || f.ends_with("lib.rs") {
            f.parent().unwrap().to_path_buf()
        } else {
            f.with_extension("")
        };
        let lines: Vec<&str> = text.lines().map(str::trim).collect();
        for w in lines.windows(2) {
            let decl = w[1]
                .trim_start_matches("pub(crate) ")
                .trim_start_matches("pub ")
                .strip_prefix("mod ")
                .and_then(|r| r.strip_suffix(';'));
            if let (true, Some(name)) = (w[0] == "#[cfg(test)]", decl) {
                out.insert(dir.join(format!("{name}.rs")));
                out.insert(dir.join(name).join("mod.rs"));
            }
        }
    }
    out
}

/// The string literals of a source file's code, with their lines: comments and everything from
/// a `#[cfg(test)]` on are skipped.
fn literals(source: &str) -> Vec<(usize, String)> {
    let code = match source.find("#[cfg(test)]") {
        Some(i) => &source[..i],
        None => source,
    };
    let mut out = Vec::new();
    let bytes: Vec<char> = code.chars().collect();
    let (mut i, mut line) = (0, 1);
    while i < bytes.len() {
        let c = bytes[i];
        if c == '\n' {
            line += 1;
        } else if c == '/' && bytes.get(i + 1) == Some(&'/') {
            while i < bytes.len() && bytes[i] != '\n' {
                i += 1;
            }
            continue;
        } else if c == '\'' && bytes.get(i + 2) == Some(&'\'') {
            i += 3;
            continue;
        } else if c == '"' {
            let start = line;
            let mut s = String::new();
            i += 1;
            while i < bytes.len() && bytes[i] != '"' {
                if bytes[i] == '\\' {
                    i += 1;
                }
                if bytes.get(i) == Some(&'\n') {
                    line += 1;
                }
                if let Some(&ch) = bytes.get(i) {
                    s.push(ch);
                }
                i += 1;
            }
            out.push((start, s));
        }
        i += 1;
    }
    out
}

#[test]
fn no_benchmark_predicate_or_action_is_named_in_the_library() {
    let names = benchmark_names();
    assert!(names.contains("holding") && names.contains("place-on-shelf"));
    let src = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/src"));
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let test_only = test_only_files(&files);
    assert!(test_only.iter().any(|f| f.ends_with("lfd/testing.rs")));
    let mut found = Vec::new();
    for f in files.into_iter().filter(|f| !test_only.contains(f)) {
        let rel = f
            .strip_prefix(src)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if rel.starts_with("experiments/fuzz/") {
            continue;
        }
        let text = std::fs::read_to_string(&f).unwrap();
        for (line, lit) in literals(&text) {
            let t = lit.trim();
            let whole = names.contains(t) && !OWN_WORDS.contains(&t);
            let opens = names.iter().any(|n| {
                t.strip_prefix('(')
                    .and_then(|r| r.strip_prefix(n.as_str()))
                    .is_some_and(|r| r.starts_with([' ', ')', '{']))
            });
            if whole || opens {
                found.push(format!("src/{rel}:{line}: \"{lit}\""));
            }
        }
    }
    assert!(
        found.is_empty(),
        "benchmark names in the library (declare them in domains/*/motions.json):\n{}",
        found.join("\n")
    );
}

#[test]
fn the_literal_scanner_sees_strings_and_skips_comments_and_tests() {
    let src = "let a = \"(holding x)\"; // \"(stack a b)\"\nlet c = '\"';\nlet b = \"ok\";\n#[cfg(test)]\nmod t { const X: &str = \"pick\"; }";
    let lits: Vec<String> = literals(src).into_iter().map(|(_, s)| s).collect();
    assert_eq!(lits, vec!["(holding x)".to_string(), "ok".to_string()]);
}
