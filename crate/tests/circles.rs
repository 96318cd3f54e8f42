//! No import circles between the files of one module.
//!
//! A shared name lives in the lowest file that uses it, so the files of a module form a
//! directed acyclic graph: `a.rs` may import from `b.rs` or `b.rs` from `a.rs`, never both
//! (directly or through other files). Every `use` line and inline `crate::`/`super::`/`self::`
//! path is resolved to the file that *defines* the item (following `pub use` re-exports), so
//! importing `crate::lfd::Session` where `lfd/mod.rs` re-exports it from `lfd/session/mod.rs`
//! points at the latter. Test modules inside a file (`mod tests { … }`) are skipped.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use crate::support::source::rust_files;

/// One source file: its module path, the items it defines and the paths it names.
struct File {
    rel: String,
    module: Vec<String>,
    defines: BTreeSet<String>,
    /// `pub use` names: exported name → absolute path of the original.
    reexports: BTreeMap<String, Vec<String>>,
    /// `pub use path::*`: absolute module paths.
    globs: Vec<Vec<String>>,
    /// Absolute paths this file names (its imports, re-exports included).
    paths: Vec<Vec<String>>,
}

/// The module path of a file below `src/`, and the root its `crate::` paths start from (the
/// binary's `main.rs` is a crate root of its own).
fn module_of(rel: &Path) -> (Vec<String>, Vec<String>) {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts.last().is_some_and(|l| l == "mod" || l == "main") {
        parts.pop();
    }
    let root = if parts.first().is_some_and(|p| p == "bin") {
        parts[..2.min(parts.len())].to_vec()
    } else {
        Vec::new()
    };
    (parts, root)
}

/// Source without comments and without inline `mod name { … }` blocks.
fn code_of(source: &str) -> String {
    let mut text = String::new();
    for line in source.lines() {
        text.push_str(line.find("//").map_or(line, |i| &line[..i]));
        text.push('\n');
    }
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(i) = find_inline_mod(rest) {
        out.push_str(&rest[..i]);
        let open = i + rest[i..].find('{').unwrap();
        let mut depth = 0;
        let mut end = rest.len();
        for (j, c) in rest[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + j + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// Where `mod name {` starts in `text`, if anywhere.
fn find_inline_mod(text: &str) -> Option<usize> {
    let mut at = 0;
    while let Some(i) = text[at..].find("mod ") {
        let start = at + i;
        at = start + 4;
        if text[..start]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_')
        {
            continue;
        }
        let after = text[at..].trim_start();
        let name_len = ident_len(after);
        if name_len > 0 && after[name_len..].trim_start().starts_with('{') {
            return Some(start);
        }
    }
    None
}

fn ident_len(s: &str) -> usize {
    s.char_indices()
        .find(|(_, c)| !(c.is_alphanumeric() || *c == '_'))
        .map_or(s.len(), |(i, _)| i)
}

/// The leaves of a use tree (`a::{b, c::{d as e, *}}`) as (path, exported name).
fn use_leaves(tree: &str, prefix: &[String], out: &mut Vec<(Vec<String>, String)>) {
    let tree = tree.trim();
    if let Some(i) = tree.find('{').filter(|&i| !tree[..i].contains(',')) {
        let mut base = prefix.to_vec();
        base.extend(segments(&tree[..i]));
        let inner = &tree[i + 1..tree.rfind('}').unwrap_or(tree.len())];
        let mut depth = 0;
        let mut start = 0;
        for (j, c) in inner.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    use_leaves(&inner[start..j], &base, out);
                    start = j + 1;
                }
                _ => {}
            }
        }
        use_leaves(&inner[start..], &base, out);
        return;
    }
    if tree.is_empty() {
        return;
    }
    let (path, alias) = match tree.split_once(" as ") {
        Some((p, a)) => (p, Some(a.trim().to_string())),
        None => (tree, None),
    };
    let mut full = prefix.to_vec();
    for s in segments(path) {
        if s != "self" || full.is_empty() {
            full.push(s);
        }
    }
    let name = alias.unwrap_or_else(|| full.last().cloned().unwrap_or_default());
    out.push((full, name));
}

fn segments(path: &str) -> Vec<String> {
    path.split("::")
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .collect()
}

/// An absolute path from one written in `module` (crate root `root`), or `None` for an
/// external crate.
fn absolute(
    path: &[String],
    module: &[String],
    root: &[String],
    modules: &BTreeSet<Vec<String>>,
) -> Option<Vec<String>> {
    let first = path.first()?;
    let (mut base, rest) = match first.as_str() {
        "crate" => (root.to_vec(), &path[1..]),
        "self" => (module.to_vec(), &path[1..]),
        "super" => {
            let mut base = module.to_vec();
            let mut rest = path;
            while rest.first().is_some_and(|s| s == "super") {
                base.pop();
                rest = &rest[1..];
            }
            (base, rest)
        }
        _ => {
            let mut child = module.to_vec();
            child.push(first.clone());
            if !modules.contains(&child) {
                return None; // an external crate or a local name
            }
            (module.to_vec(), path)
        }
    };
    base.extend(rest.iter().cloned());
    Some(base)
}

const ITEM_KEYWORDS: &[&str] = &[
    "struct",
    "enum",
    "fn",
    "trait",
    "type",
    "const",
    "static",
    "union",
    "macro_rules!",
];

fn parse(rel: &str, source: &str, modules: &BTreeSet<Vec<String>>) -> File {
    let (module, root) = module_of(Path::new(rel));
    let code = code_of(source);
    let mut file = File {
        rel: rel.to_string(),
        module: module.clone(),
        defines: BTreeSet::new(),
        reexports: BTreeMap::new(),
        globs: Vec::new(),
        paths: Vec::new(),
    };
    let words: Vec<&str> = code.split_whitespace().collect();
    for w in words.windows(2) {
        if ITEM_KEYWORDS.contains(&w[0]) {
            let n = ident_len(w[1]);
            if n > 0 {
                file.defines.insert(w[1][..n].to_string());
            }
        }
    }
    // `use` statements, re-exports among them; their text is then blanked for the inline scan.
    let mut rest_code = code.clone();
    let mut at = 0;
    while let Some(i) = code[at..].find("use ") {
        let start = at + i;
        at = start + 4;
        let before = code[..start].trim_end();
        let boundary = before.is_empty()
            || before.ends_with(';')
            || before.ends_with('}')
            || before.ends_with('{')
            || before.ends_with(')')
            || before.ends_with(']')
            || before.ends_with("pub");
        if !boundary
            || code[..start]
                .chars()
                .next_back()
                .is_some_and(|c| c.is_alphanumeric() || c == '_')
        {
            continue;
        }
        let Some(end) = code[at..].find(';') else {
            break;
        };
        let public = before.ends_with("pub") || before.ends_with(')') && before.contains("pub(");
        let mut leaves = Vec::new();
        use_leaves(&code[at..at + end], &[], &mut leaves);
        for (path, name) in leaves {
            let Some(abs) = absolute(&path, &module, &root, modules) else {
                continue;
            };
            if public {
                if name == "*" {
                    file.globs.push(abs[..abs.len() - 1].to_vec());
                } else {
                    file.reexports.insert(name, abs.clone());
                }
            }
            file.paths.push(abs);
        }
        rest_code.replace_range(start..at + end, &" ".repeat(at + end - start));
    }
    // Inline paths: `crate::a::B`, `super::C`, `self::d::E`.
    for head in ["crate::", "super::", "self::"] {
        let mut at = 0;
        while let Some(i) = rest_code[at..].find(head) {
            let start = at + i;
            at = start + head.len();
            let prev = rest_code[..start].chars().next_back();
            if prev.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let mut end = start;
            let bytes = rest_code.as_bytes();
            while end < bytes.len()
                && (bytes[end].is_ascii_alphanumeric() || bytes[end] == b'_' || bytes[end] == b':')
            {
                end += 1;
            }
            let path = segments(&rest_code[start..end]);
            if let Some(abs) = absolute(&path, &module, &root, modules) {
                file.paths.push(abs);
            }
        }
    }
    // Inline paths through a child module: `child::item` (a `mod.rs` calling its children).
    let bytes = rest_code.as_bytes();
    let mut at = 0;
    while let Some(i) = rest_code[at..].find("::") {
        let colons = at + i;
        at = colons + 2;
        let mut start = colons;
        while start > 0 && (bytes[start - 1].is_ascii_alphanumeric() || bytes[start - 1] == b'_') {
            start -= 1;
        }
        if start == colons || (start > 0 && bytes[start - 1] == b':') {
            continue;
        }
        let mut child = module.clone();
        child.push(rest_code[start..colons].to_string());
        if modules.contains(&child) {
            let n = ident_len(&rest_code[at..]);
            if n > 0 {
                child.push(rest_code[at..at + n].to_string());
            }
            file.paths.push(child);
        }
    }
    file
}

/// The file that defines the item an absolute path names.
fn resolve(
    path: &[String],
    files: &[File],
    by_module: &BTreeMap<Vec<String>, usize>,
    depth: usize,
) -> Option<usize> {
    let mut n = path.len();
    while n > 0 && !by_module.contains_key(&path[..n]) {
        n -= 1;
    }
    let &f = by_module.get(&path[..n])?;
    let Some(item) = path.get(n) else {
        return Some(f);
    };
    if depth > 8 || files[f].defines.contains(item) {
        return Some(f);
    }
    if let Some(orig) = files[f].reexports.get(item) {
        return resolve(orig, files, by_module, depth + 1).or(Some(f));
    }
    for glob in &files[f].globs {
        let mut p = glob.clone();
        p.push(item.clone());
        if let Some(g) = resolve(&p, files, by_module, depth + 1) {
            if g != f && (files[g].defines.contains(item) || files[g].reexports.contains_key(item))
            {
                return Some(g);
            }
        }
    }
    Some(f)
}

/// Strongly connected components of more than one file (Tarjan).
fn circles(edges: &[BTreeSet<usize>]) -> Vec<Vec<usize>> {
    struct Tarjan<'a> {
        edges: &'a [BTreeSet<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    impl Tarjan<'_> {
        fn visit(&mut self, v: usize) {
            self.index[v] = Some(self.next);
            self.low[v] = self.next;
            self.next += 1;
            self.stack.push(v);
            self.on_stack[v] = true;
            for &w in self.edges[v].iter() {
                match self.index[w] {
                    None => {
                        self.visit(w);
                        self.low[v] = self.low[v].min(self.low[w]);
                    }
                    Some(i) if self.on_stack[w] => self.low[v] = self.low[v].min(i),
                    Some(_) => {}
                }
            }
            if Some(self.low[v]) == self.index[v] {
                let mut scc = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack[w] = false;
                    scc.push(w);
                    if w == v {
                        break;
                    }
                }
                if scc.len() > 1 {
                    scc.sort();
                    self.out.push(scc);
                }
            }
        }
    }
    let n = edges.len();
    let mut t = Tarjan {
        edges,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if t.index[v].is_none() {
            t.visit(v);
        }
    }
    t.out
}

/// Every file of `src/`, parsed, and the import edges between files of one top-level module.
fn graph() -> (Vec<File>, Vec<BTreeSet<usize>>) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut paths = Vec::new();
    rust_files(&src, &mut paths);
    paths.sort();
    let rels: Vec<String> = paths
        .iter()
        .map(|p| p.strip_prefix(&src).unwrap().display().to_string())
        .collect();
    let modules: BTreeSet<Vec<String>> = rels.iter().map(|r| module_of(Path::new(r)).0).collect();
    let files: Vec<File> = rels
        .iter()
        .zip(&paths)
        .map(|(rel, p)| parse(rel, &std::fs::read_to_string(p).unwrap(), &modules))
        .collect();
    let by_module: BTreeMap<Vec<String>, usize> = files
        .iter()
        .enumerate()
        .map(|(i, f)| (f.module.clone(), i))
        .collect();
    let edges = files
        .iter()
        .enumerate()
        .map(|(i, f)| {
            f.paths
                .iter()
                .filter_map(|p| resolve(p, &files, &by_module, 0))
                .filter(|&t| t != i && files[t].module.first() == f.module.first())
                .collect()
        })
        .collect();
    (files, edges)
}

#[test]
fn no_two_files_of_a_module_import_each_other() {
    let (files, edges) = graph();
    let files = &files;
    let found: Vec<String> = circles(&edges)
        .iter()
        .map(|scc| {
            let names: Vec<&str> = scc.iter().map(|&i| files[i].rel.as_str()).collect();
            let links: Vec<String> = scc
                .iter()
                .flat_map(|&a| {
                    edges[a]
                        .iter()
                        .filter(|b| scc.contains(b))
                        .map(move |&b| format!("{} → {}", files[a].rel, files[b].rel))
                })
                .collect();
            format!("{}\n    {}", names.join(", "), links.join("\n    "))
        })
        .collect();
    assert!(
        found.is_empty(),
        "import circles between files (move the shared name down to the lowest file):\n{}",
        found.join("\n")
    );
}

#[test]
fn the_circle_finder_resolves_reexports_and_finds_a_circle() {
    let modules: BTreeSet<Vec<String>> = [
        vec![],
        vec!["m".to_string()],
        vec!["m".to_string(), "a".to_string()],
        vec!["m".to_string(), "b".to_string()],
    ]
    .into_iter()
    .collect();
    let files = vec![
        parse(
            "m/mod.rs",
            "mod a;\nmod b;\npub use a::{Alpha, helper as h};\npub struct Root;\n",
            &modules,
        ),
        parse(
            "m/a.rs",
            "pub struct Alpha;\npub fn helper() {}\n#[cfg(test)]\nmod tests {\n    use super::super::Root;\n}\n",
            &modules,
        ),
        parse(
            "m/b.rs",
            "use crate::m::{Alpha, h};\nfn f() { super::Root; }\n",
            &modules,
        ),
    ];
    let by_module: BTreeMap<Vec<String>, usize> = files
        .iter()
        .enumerate()
        .map(|(i, f)| (f.module.clone(), i))
        .collect();
    let targets = |i: usize| -> BTreeSet<usize> {
        files[i]
            .paths
            .iter()
            .filter_map(|p| resolve(p, &files, &by_module, 0))
            .filter(|&t| t != i)
            .collect()
    };
    // b's `Alpha` and `h` resolve through mod.rs's re-exports to a.rs; `super::Root` to mod.rs.
    assert_eq!(targets(2), BTreeSet::from([0, 1]));
    // a.rs's test module is skipped, so mod.rs → a.rs is one way.
    assert_eq!(targets(1), BTreeSet::new());
    assert_eq!(targets(0), BTreeSet::from([1]));
    let edges: Vec<BTreeSet<usize>> = (0..3).map(targets).collect();
    assert!(circles(&edges).is_empty());
    // mod.rs importing from b.rs closes a circle mod.rs ⇄ b.rs.
    let mut with_circle = edges.clone();
    with_circle[0].insert(2);
    assert_eq!(circles(&with_circle), vec![vec![0, 2]]);
}
#[test]
#[ignore = "prints the import edges of one module: MODULE=lfd cargo test ... -- --ignored"]
fn print_edges() {
    let (files, edges) = graph();
    let module = std::env::var("MODULE").unwrap_or_default();
    for (i, f) in files.iter().enumerate() {
        if f.rel.starts_with(&module) {
            let t: Vec<&str> = edges[i].iter().map(|&j| files[j].rel.as_str()).collect();
            eprintln!("{} -> {:?}", f.rel, t);
        }
    }
}
