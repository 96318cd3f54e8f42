//! Where an unbalanced bracket probably is. The reader only learns that a `(` is unclosed at the
//! end of the file, or that `(define …)` closed too early where the next text appears; both are
//! usually far from the edit that broke the file. This pass re-reads the text with its layout:
//! a line indented at or left of a still-open list's own column (or left of that list's body),
//! or a section keyword such as `(:init` nested where it cannot be, marks where a list should
//! have been closed; a line indented right of `(define`'s body, or an action key outside an
//! action, marks the text after a stray `)`.

// The page's first-load module reads only its compiled-in PDDL, which is balanced: it keeps the
// reader's plain messages and leaves this pass out (its size budget has no room for it).
#![cfg_attr(first_load, allow(dead_code))]

use super::error::{PddlError, SourceMap, Span};

/// The domain sections the reader takes (the reader matches an unknown one against them).
pub(super) const DOMAIN_SECTIONS: [&str; 6] = [
    ":requirements",
    ":types",
    ":constants",
    ":predicates",
    ":functions",
    ":action",
];

/// The problem sections the reader takes.
pub(super) const PROBLEM_SECTIONS: [&str; 6] = [
    ":domain",
    ":requirements",
    ":objects",
    ":init",
    ":goal",
    ":metric",
];

/// Sections the reader knows and refuses (PDDL 2.1+ and PDDL3).
const REFUSED_SECTIONS: [&str; 3] = [":durative-action", ":derived", ":constraints"];

/// The keys of an `(:action …)`.
pub(super) const ACTION_KEYS: [&str; 3] = [":parameters", ":precondition", ":effect"];

/// Whether `head` heads a list that only stands directly inside `(define …)`.
fn is_section(head: &str) -> bool {
    [&DOMAIN_SECTIONS[..], &PROBLEM_SECTIONS, &REFUSED_SECTIONS]
        .iter()
        .any(|list| list.contains(&head))
}

/// A list still open during the scan.
struct Open {
    /// Byte offset of its `(`.
    pos: usize,
    /// Indentation (tabs to multiples of 8) of the line of its `(`.
    col: usize,
    /// Line of its `(`.
    line: usize,
    /// Indentation of the first line that starts inside it, after its own line.
    body: Option<usize>,
    /// Its first atom, lower-cased.
    head: Option<String>,
}

/// What the scan found.
enum Found {
    /// The list opened at `open` probably ends before the token at `next`.
    Unclosed { open: usize, next: usize },
    /// The `)` at `close`, closing the list opened at `open`, is probably one too many.
    Stray { close: usize, open: usize },
}

/// Scans `text` for the first place its layout contradicts its brackets. `stray` looks for the
/// marks of a `)` too many, otherwise for those of a missing `)`.
fn scan(text: &str, stray: bool) -> Option<Found> {
    let bytes = text.as_bytes();
    let mut stack: Vec<Open> = Vec::new();
    let (mut line, mut vcol, mut line_start) = (1usize, 0usize, true);
    let mut last_close: Option<(usize, usize)> = None;
    let mut closed_define = false;
    // Indentation of the current line and that of the last line's first token with its depth.
    let mut indent = 0;
    let mut prev_line: Option<(usize, usize)> = None;
    let mut i = 0;
    while i < bytes.len() {
        let b = bytes[i];
        match b {
            b'\n' => {
                line += 1;
                vcol = 0;
                line_start = true;
                i += 1;
                continue;
            }
            b'\t' => {
                vcol = (vcol / 8 + 1) * 8;
                i += 1;
                continue;
            }
            b';' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            _ if b.is_ascii_whitespace() => {
                vcol += 1;
                i += 1;
                continue;
            }
            _ => {}
        }
        let first = std::mem::replace(&mut line_start, false);
        if first {
            indent = vcol;
        }
        if first && b != b')' {
            // Same indentation as the line above but shallower: a `)` on the way closed too much.
            if let (true, Some((pi, pd)), Some((close, open))) = (stray, prev_line, last_close) {
                if pi == indent && stack.len() < pd {
                    return Some(Found::Stray { close, open });
                }
            }
            prev_line = Some((indent, stack.len()));
            if !stray {
                // The outermost list the line cannot belong to (`(define …)`'s body may sit at
                // its own column).
                let bad = stack.iter().skip(1).find(|o| {
                    o.line < line && o.body.map_or(indent <= o.col, |body| indent < body)
                });
                if let Some(o) = bad {
                    return Some(Found::Unclosed {
                        open: o.pos,
                        next: i,
                    });
                }
            } else if let (1, Some(body), Some((close, open))) =
                (stack.len(), stack.first().and_then(|o| o.body), last_close)
            {
                if indent > body {
                    return Some(Found::Stray { close, open });
                }
            }
            if let Some(top) = stack.last_mut() {
                if top.line < line && top.body.is_none() {
                    top.body = Some(indent);
                }
            }
        }
        if b == b'(' {
            let mut j = i + 1;
            while j < bytes.len() && bytes[j].is_ascii_whitespace() {
                j += 1;
            }
            let end = atom_end(bytes, j);
            let head = text[j..end].to_ascii_lowercase();
            let section = is_section(head.as_str());
            if section && !stray && stack.len() >= 2 {
                return Some(Found::Unclosed {
                    open: stack[1].pos,
                    next: i,
                });
            }
            if section && stray && closed_define && stack.is_empty() {
                return last_close.map(|(close, open)| Found::Stray { close, open });
            }
            stack.push(Open {
                pos: i,
                // A list opened after other text on its line may have its body left of its `(`.
                col: indent,
                line,
                body: None,
                head: None,
            });
            vcol += 1;
            i += 1;
        } else if b == b')' {
            match stack.pop() {
                Some(o) => {
                    last_close = Some((i, o.pos));
                    closed_define |= stack.is_empty();
                }
                None if stray => return Some(Found::Stray { close: i, open: i }),
                None => return None,
            }
            vcol += 1;
            i += 1;
        } else {
            let end = atom_end(bytes, i).max(i + 1);
            let atom = text.get(i..end).unwrap_or("").to_ascii_lowercase();
            if stray && ACTION_KEYS.contains(&atom.as_str()) {
                let in_action = stack.last().and_then(|o| o.head.as_deref()) == Some(":action");
                if !in_action {
                    return last_close.map(|(close, open)| Found::Stray { close, open });
                }
            }
            if let Some(top) = stack.last_mut() {
                if top.head.is_none() {
                    top.head = Some(atom);
                }
            }
            vcol += text.get(i..end).map_or(1, |s| s.chars().count());
            i = end;
            while i < bytes.len() && !text.is_char_boundary(i) {
                i += 1;
            }
        }
    }
    None
}

/// Where a name or keyword starting at `start` ends.
fn atom_end(bytes: &[u8], start: usize) -> usize {
    let mut i = start;
    while i < bytes.len() && !bytes[i].is_ascii_whitespace() && !b"();".contains(&bytes[i]) {
        i += 1;
    }
    i
}

/// The end of the last token (not a comment) before byte `before`.
fn last_token_end(text: &str, before: usize) -> usize {
    let mut end = 0;
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < before.min(bytes.len()) {
        match bytes[i] {
            b';' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
            }
            b if b.is_ascii_whitespace() => i += 1,
            _ => {
                i += 1;
                end = i;
            }
        }
    }
    while end < text.len() && !text.is_char_boundary(end) {
        end += 1;
    }
    end
}

fn at(pos: usize) -> Span {
    Span {
        start: pos,
        end: pos + 1,
    }
}

/// The error for a `(` still open at the end of the file (`innermost`: the reader's innermost
/// unclosed `(`), placed where the list probably should have been closed.
#[cfg(not(first_load))]
pub(crate) fn unclosed(src: &SourceMap, innermost: usize) -> PddlError {
    let text = src.text.as_str();
    let (open, next) = match scan(text, false) {
        Some(Found::Unclosed { open, next }) => (open, Some(next)),
        _ => (innermost, None),
    };
    let (ol, oc) = src.line_col(open);
    let place = last_token_end(text, next.unwrap_or(text.len()));
    let ends = match next {
        Some(n) => format!("before line {}", src.line_col(n).0),
        None => "at the end of the file".to_string(),
    };
    src.error(
        at(place),
        format!("`(` opened at {ol}:{oc} is not closed; the list probably ends {ends}"),
    )
}

/// The error for a `)` too many, found at `found` (text after `(define …)` or a `)` matching
/// nothing), placed at the `)` that probably is the stray one.
#[cfg(not(first_load))]
pub(crate) fn stray(src: &SourceMap, found: usize, fallback: &str) -> PddlError {
    match scan(&src.text, true) {
        Some(Found::Stray { close, open }) if close < found => {
            let (ol, oc) = src.line_col(open);
            let (nl, _) = src.line_col(found);
            src.error(
                at(close),
                format!(
                    "probably a `)` too many: it closes the `(` opened at {ol}:{oc}, \
                     which should still hold the text up to line {nl}"
                ),
            )
        }
        _ => src.error(at(found), fallback),
    }
}

/// The reader's own message, at the innermost unclosed `(`.
#[cfg(first_load)]
pub(crate) fn unclosed(src: &SourceMap, innermost: usize) -> PddlError {
    src.error(at(innermost), "unclosed `(`: the file ends before its `)`")
}

/// The reader's own message, at the `)` found.
#[cfg(first_load)]
pub(crate) fn stray(src: &SourceMap, found: usize, fallback: &str) -> PddlError {
    src.error(at(found), fallback)
}

#[cfg(test)]
mod tests {
    use super::super::lexer::read_one;
    use super::*;

    fn err(t: &str) -> PddlError {
        read_one(&SourceMap::new(t, "p.pddl")).unwrap_err()
    }

    #[test]
    fn a_missing_paren_is_placed_where_the_list_should_end() {
        let t = "; c\n(define (problem p)\n  (:domain d)\n  (:objects a b)\n  (:init (on a b)\n         (clear a)\n  (:goal (on b a))\n)\n";
        let e = err(t);
        assert_eq!((e.line, e.col), (6, 19), "{e}");
        assert_eq!(
            e.message,
            "`(` opened at 5:3 is not closed; the list probably ends before line 7"
        );
    }

    #[test]
    fn a_section_nested_too_deep_closes_the_list_before_it() {
        let e = err("(define (problem p) (:domain d\n (:objects a)\n)");
        assert_eq!(e.line, 1, "{e}");
        assert!(e.message.contains("opened at 1:21"), "{e}");
    }

    #[test]
    fn without_a_clue_the_list_ends_at_the_end_of_the_file() {
        let e = err("(define (problem p)\n(:domain d)\n");
        assert_eq!((e.line, e.col), (2, 12), "{e}");
        assert!(e.message.ends_with("at the end of the file"), "{e}");
    }

    #[test]
    fn a_stray_paren_is_placed_where_it_closes_too_early() {
        let t =
            "(define (problem p)\n  (:domain d))\n  (:objects a)\n  (:init)\n  (:goal (p a))\n)\n";
        let e = err(t);
        assert_eq!((e.line, e.col), (2, 14), "{e}");
        assert!(e.message.contains("`)` too many"), "{e}");
        let t = "(define (domain d)\n  (:action a\n    :parameters (?x))\n    :effect (p ?x))\n)\n";
        let e = err(t);
        assert_eq!(e.line, 3, "{e}");
    }
}
