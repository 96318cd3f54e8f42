//! PDDL domain and problem files under fuzzing: structural edits of the text's lists and names,
//! and the oracle that every refusal is located inside the text of the file it names.

use rand::Rng;
use rand_pcg::Pcg64Mcg;

use super::common::{ensure, header, idx, Verdict};
use crate::pddl::{parse_domain, parse_problem, PddlError};
use crate::plan::ground;

/// A structural edit of a PDDL text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PddlEdit {
    /// Delete the i-th balanced list.
    DeleteList(usize),
    /// Put a copy of list j right after list i.
    CopyList(usize, usize),
    /// Swap the texts of lists i and j (when they do not overlap).
    SwapLists(usize, usize),
    /// Replace name i by name j of the same text.
    Rename(usize, usize),
    /// Wrap list i in `n` more parentheses.
    Nest(usize, u16),
    /// Delete the i-th character.
    DeleteChar(usize),
    /// Insert a fragment before the i-th character.
    Insert(usize, &'static str),
}

impl PddlEdit {
    /// A random edit (structural edits weighted over character edits).
    pub fn random(rng: &mut Pcg64Mcg) -> PddlEdit {
        let (i, j) = (idx(rng), idx(rng));
        match rng.random_range(0..10) {
            0 => PddlEdit::DeleteList(i),
            1 => PddlEdit::CopyList(i, j),
            2 => PddlEdit::SwapLists(i, j),
            3..=5 => PddlEdit::Rename(i, j),
            6 => PddlEdit::Nest(i, rng.random_range(1..300)),
            7 => PddlEdit::DeleteChar(i),
            _ => {
                const F: [&str; 14] = [
                    "(", ")", " ", "\n", ";", "?x", "-", "é", "\t", "(not ", "(or)", ":typing",
                    "(and)", "- object",
                ];
                PddlEdit::Insert(i, F[rng.random_range(0..F.len())])
            }
        }
    }
}

/// Byte ranges of every balanced `( … )` of the text.
fn lists(text: &str) -> Vec<(usize, usize)> {
    let mut open = Vec::new();
    let mut out = Vec::new();
    for (i, c) in text.char_indices() {
        match c {
            '(' => open.push(i),
            ')' => {
                if let Some(s) = open.pop() {
                    out.push((s, i + 1));
                }
            }
            _ => {}
        }
    }
    out
}

/// Byte ranges of every name (a run of non-space, non-paren characters).
fn names(text: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in text
        .char_indices()
        .chain(std::iter::once((text.len(), ' ')))
    {
        let sep = c == '(' || c == ')' || c.is_whitespace();
        match (start, sep) {
            (None, false) => start = Some(i),
            (Some(s), true) => {
                out.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// Byte offset of the `i`-th character boundary (modulo the count + 1).
fn char_boundary(t: &str, i: usize) -> usize {
    let n = t.chars().count();
    t.char_indices()
        .map(|(b, _)| b)
        .chain(std::iter::once(t.len()))
        .nth(i % (n + 1))
        .unwrap_or(t.len())
}

/// Applies PDDL edits to `text`.
pub fn mutate_pddl(text: &str, edits: &[PddlEdit]) -> String {
    let mut t = text.to_string();
    for e in edits {
        let ls = lists(&t);
        let ns = names(&t);
        match *e {
            PddlEdit::DeleteChar(i) => {
                if !t.is_empty() {
                    let at = char_boundary(&t, i % t.chars().count());
                    t.remove(at);
                }
                continue;
            }
            PddlEdit::Insert(i, f) => {
                let at = char_boundary(&t, i);
                t.insert_str(at, f);
                continue;
            }
            _ => {}
        }
        if ls.is_empty() || ns.is_empty() {
            continue;
        }
        let l = |i: usize| ls[i % ls.len()];
        let n = |i: usize| ns[i % ns.len()];
        match *e {
            PddlEdit::DeleteList(i) => {
                let (s, e) = l(i);
                t.replace_range(s..e, "");
            }
            PddlEdit::CopyList(i, j) => {
                let (_, e) = l(i);
                let (s2, e2) = l(j);
                let copy = format!(" {}", &t[s2..e2]);
                t.insert_str(e, &copy);
            }
            PddlEdit::SwapLists(i, j) => {
                let (a, b) = (l(i), l(j));
                let (first, second) = if a.0 < b.0 { (a, b) } else { (b, a) };
                if first.1 <= second.0 {
                    let x = t[first.0..first.1].to_string();
                    let y = t[second.0..second.1].to_string();
                    t.replace_range(second.0..second.1, &x);
                    t.replace_range(first.0..first.1, &y);
                }
            }
            PddlEdit::Rename(i, j) => {
                let (s, e) = n(i);
                let (s2, e2) = n(j);
                let name = t[s2..e2].to_string();
                t.replace_range(s..e, &name);
            }
            PddlEdit::Nest(i, k) => {
                let (s, e) = l(i);
                t.insert_str(e, &")".repeat(k as usize));
                t.insert_str(s, &"(".repeat(k as usize));
            }
            PddlEdit::DeleteChar(_) | PddlEdit::Insert(..) => {}
        }
    }
    t
}

/// Whether a PDDL error lies inside `text` (1-based line and column, in characters).
pub fn pddl_error_in_bounds(text: &str, e: &PddlError) -> bool {
    let lines: Vec<&str> = text.split('\n').collect();
    e.line >= 1
        && e.line <= lines.len()
        && e.col >= 1
        && e.col <= lines[e.line - 1].chars().count() + 1
}

pub(super) fn check_pddl(input: &str) -> Result<Verdict, String> {
    let (b, words) = header(input);
    let files = b.sources().map_err(|e| e.to_string())?;
    let is_problem = words.get(1).is_some_and(|w| w == "problem");
    let (dom_text, prob_text) = if is_problem {
        (files.domain.as_str(), input)
    } else {
        (input, files.problem.as_str())
    };
    let located = |text: &str, file: &str, e: &PddlError| {
        ensure(pddl_error_in_bounds(text, e) && e.file == file, || {
            format!("error outside the text: {e}")
        })?;
        ensure(e.to_string().starts_with(&format!("{file}:")), || {
            format!("error does not start with its file: {e}")
        })
    };
    let d = match parse_domain(dom_text, "domain.pddl") {
        Ok(d) => d,
        Err(e) => {
            located(dom_text, "domain.pddl", &e)?;
            return Ok(Verdict::Refused);
        }
    };
    let p = match parse_problem(prob_text, "problem.pddl", &d) {
        Ok(p) => p,
        Err(e) => {
            located(prob_text, "problem.pddl", &e)?;
            return Ok(Verdict::Refused);
        }
    };
    match ground(&d, &p) {
        Ok(_) => Ok(Verdict::Accepted),
        Err(e) => {
            ensure(!e.to_string().is_empty(), || "empty grounding error".into())?;
            Ok(Verdict::Refused)
        }
    }
}
