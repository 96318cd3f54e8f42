//! Lexer and s-expression reader: PDDL text → tokens with byte spans → a tree of lists and atoms.
//!
//! PDDL is case-insensitive: every atom is lower-cased here, once. `;` starts a comment that runs
//! to the end of the line, anywhere. Nesting is bounded ([`MAX_DEPTH`]) so that no input can
//! exhaust the stack of the recursive-descent interpreters that read the tree.

use super::brackets;
use super::error::Span;
use super::error::{PddlError, SourceMap};

/// Deepest list nesting accepted (real domains stay below 20).
pub(crate) const MAX_DEPTH: usize = 200;

/// A node of the s-expression tree.
#[derive(Clone, Debug)]
pub(crate) enum SExpr {
    /// A name, variable, keyword or number, lower-cased.
    Atom(String, Span),
    /// A parenthesised list; the span covers both parentheses.
    List(Vec<SExpr>, Span),
}

impl SExpr {
    pub(crate) fn span(&self) -> Span {
        match self {
            SExpr::Atom(_, s) | SExpr::List(_, s) => *s,
        }
    }

    pub(crate) fn atom(&self) -> Option<&str> {
        match self {
            SExpr::Atom(a, _) => Some(a),
            SExpr::List(..) => None,
        }
    }

    /// The head atom of a list, if the list starts with an atom.
    pub(crate) fn head(&self) -> Option<&str> {
        match self {
            SExpr::List(items, _) => items.first().and_then(|i| i.atom()),
            SExpr::Atom(..) => None,
        }
    }
}

/// Reads exactly one top-level list (the `(define …)`), with nothing but comments after it.
pub(crate) fn read_one(src: &SourceMap) -> Result<SExpr, PddlError> {
    let text = src.text.as_str();
    let bytes = text.as_bytes();
    let mut stack: Vec<(usize, Vec<SExpr>)> = Vec::new();
    let mut done: Option<SExpr> = None;
    let mut i = 0;
    while i < bytes.len() {
        let b = bytes[i];
        if b.is_ascii_whitespace() {
            i += 1;
        } else if b == b';' {
            while i < bytes.len() && bytes[i] != b'\n' {
                i += 1;
            }
        } else if done.is_some() {
            return Err(brackets::stray(
                src,
                i,
                if b == b')' {
                    "unmatched `)` after the end of `(define …)`"
                } else {
                    "unexpected text after the end of `(define …)`"
                },
            ));
        } else if b == b'(' {
            if stack.len() >= MAX_DEPTH {
                return Err(src.error(
                    Span {
                        start: i,
                        end: i + 1,
                    },
                    format!("lists nested deeper than {MAX_DEPTH} levels"),
                ));
            }
            stack.push((i, Vec::new()));
            i += 1;
        } else if b == b')' {
            let Some((start, items)) = stack.pop() else {
                return Err(brackets::stray(src, i, "unmatched `)`"));
            };
            let list = SExpr::List(items, Span { start, end: i + 1 });
            match stack.last_mut() {
                Some((_, parent)) => parent.push(list),
                None => done = Some(list),
            }
            i += 1;
        } else {
            let start = i;
            i = atom_end(bytes, start);
            // `i` stops at an ASCII byte or the end, so it is a char boundary.
            let atom = SExpr::Atom(text[start..i].to_lowercase(), Span { start, end: i });
            match stack.last_mut() {
                Some((_, parent)) => parent.push(atom),
                None => {
                    return Err(src.error(
                        atom.span(),
                        format!("expected `(` but found `{}`", &text[start..i]),
                    ))
                }
            }
        }
    }
    if let Some((start, _)) = stack.last() {
        return Err(brackets::unclosed(src, *start));
    }
    done.ok_or_else(|| {
        src.error(
            Span {
                start: text.len(),
                end: text.len(),
            },
            "empty file: expected `(define …)`",
        )
    })
}

/// Where the name or number starting at `start` ends: at whitespace, `(`, `)`, `;`, or a `?`
/// that starts a variable (`(aircraft?a)` is `aircraft ?a`, as Fast Downward, VAL and pyperplan
/// read it).
fn atom_end(bytes: &[u8], start: usize) -> usize {
    let mut i = start;
    while i < bytes.len() {
        let c = bytes[i];
        if c.is_ascii_whitespace()
            || c == b'('
            || c == b')'
            || c == b';'
            || (c == b'?' && i > start)
        {
            break;
        }
        i += 1;
    }
    i
}

/// Reads a sequence of top-level lists (a plan file: one `(action arg …)` per line).
pub(crate) fn read_many(src: &SourceMap) -> Result<Vec<SExpr>, PddlError> {
    let text = src.text.as_str();
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let b = bytes[i];
        if b.is_ascii_whitespace() {
            i += 1;
        } else if b == b';' {
            while i < bytes.len() && bytes[i] != b'\n' {
                i += 1;
            }
        } else if b == b'(' {
            let start = i;
            let mut items = Vec::new();
            i += 1;
            loop {
                while i < bytes.len() && bytes[i].is_ascii_whitespace() && bytes[i] != b'\n' {
                    i += 1;
                }
                if i >= bytes.len() || bytes[i] == b';' || bytes[i] == b'\n' {
                    return Err(src.error(
                        Span {
                            start,
                            end: start + 1,
                        },
                        "unclosed `(`: the step must end with `)` on its line",
                    ));
                }
                let c = bytes[i];
                if c == b')' {
                    i += 1;
                    break;
                }
                if c == b'(' {
                    return Err(src.error(
                        Span {
                            start: i,
                            end: i + 1,
                        },
                        "unexpected `(` inside a plan step",
                    ));
                }
                let s = i;
                i = atom_end(bytes, s);
                items.push(SExpr::Atom(
                    text[s..i].to_lowercase(),
                    Span { start: s, end: i },
                ));
            }
            out.push(SExpr::List(items, Span { start, end: i }));
        } else {
            return Err(src.error(
                Span {
                    start: i,
                    end: i + 1,
                },
                "expected `(` to start a plan step",
            ));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(t: &str) -> Result<SExpr, PddlError> {
        read_one(&SourceMap::new(t, "t"))
    }

    #[test]
    fn reads_nested_lists_lowercased_without_comments() {
        let e = read("; c\n(Define (A ?B) ;x)\n :K)").unwrap();
        let SExpr::List(items, span) = e else {
            panic!()
        };
        assert_eq!(span, Span { start: 4, end: 27 });
        assert_eq!(items[0].atom(), Some("define"));
        assert_eq!(items[1].head(), Some("a"));
        assert_eq!(items[2].atom(), Some(":k"));
    }

    #[test]
    fn a_question_mark_inside_a_name_starts_a_variable() {
        let e = read("(p?x ?y?z q?)").unwrap();
        let SExpr::List(items, _) = e else { panic!() };
        let atoms: Vec<_> = items.iter().map(|i| i.atom().unwrap()).collect();
        assert_eq!(atoms, ["p", "?x", "?y", "?z", "q", "?"]);
        assert_eq!(items[1].span(), Span { start: 2, end: 4 });
    }

    #[test]
    fn unbalanced_parentheses_are_located() {
        let e = read("(a\n (b)").unwrap_err();
        assert_eq!((e.line, e.col), (2, 5));
        let e = read("(a))").unwrap_err();
        assert_eq!((e.line, e.col), (1, 4));
        let e = read("(a) (b)").unwrap_err();
        assert_eq!((e.line, e.col), (1, 5));
        let e = read("  ").unwrap_err();
        assert!(e.message.contains("empty"));
        let deep = "(".repeat(1000);
        assert!(read(&deep).unwrap_err().message.contains("nested"));
    }
}
