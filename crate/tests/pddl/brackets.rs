//! A missing or stray bracket is reported near the edit that broke the file: every `)` of every
//! domain and problem in `domains/` is deleted (and, separately, doubled) in turn, and the error's
//! line is compared with the line of that edit.

use logic_lfd::pddl::parse_domain;

/// Every `.pddl` file under `domains/`, with its text.
fn domain_files() -> Vec<(String, String)> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../domains");
    let mut out = Vec::new();
    for d in std::fs::read_dir(&root).unwrap() {
        let dir = d.unwrap().path();
        for name in ["domain.pddl", "problem.pddl"] {
            let p = dir.join(name);
            if let Ok(t) = std::fs::read_to_string(&p) {
                out.push((p.display().to_string(), t));
            }
        }
    }
    out.sort();
    assert!(out.len() >= 8, "found {} files", out.len());
    out
}

/// For each `)` of each file, the text with `edit` applied there and the edit's line; then the
/// share of reader errors whose line is within one line of it.
fn share_near(edit: impl Fn(&str, usize) -> String) -> (usize, usize) {
    let (mut near, mut total) = (0, 0);
    for (file, text) in domain_files() {
        for (pos, _) in text.match_indices(')') {
            let line = text[..pos].matches('\n').count() + 1;
            // The line's comment is no bracket.
            let line_start = text[..pos].rfind('\n').map_or(0, |i| i + 1);
            if text[line_start..pos].contains(';') {
                continue;
            }
            let broken = edit(&text, pos);
            // Problems read the domain only after their own brackets, so any domain text serves.
            let e = parse_domain(&broken, &file).expect_err("a broken bracket must be refused");
            total += 1;
            if e.line.abs_diff(line) <= 1 {
                near += 1;
            } else if std::env::var_os("SHOW_FAR").is_some() {
                eprintln!("{file}: edit on line {line}, reported {e}");
            }
        }
    }
    (near, total)
}

#[test]
fn a_deleted_paren_is_reported_within_a_line_of_its_place() {
    let (near, total) = share_near(|t, pos| format!("{}{}", &t[..pos], &t[pos + 1..]));
    eprintln!("deleted `)`: {near} of {total} within ±1 line");
    assert!(total > 300, "{total}");
    // Measured: 848 of 848; the floor leaves room for new files.
    assert!(near * 100 >= total * 95, "{near} of {total}");
}

#[test]
fn a_doubled_paren_is_reported_within_a_line_of_its_place() {
    let (near, total) = share_near(|t, pos| format!("{})){}", &t[..pos], &t[pos + 1..]));
    eprintln!("doubled `)`: {near} of {total} within ±1 line");
    assert!(near * 100 >= total * 95, "{near} of {total}");
}
