//! Small readers shared by the domain, problem and formula parsers: names, variables, typed lists,
//! requirement flags, and the "refused by name" message.

use super::ast::Name;
use super::error::Span;
use super::error::{PddlError, SourceMap};
use super::lexer::SExpr;
use super::suggest::did_you_mean;

/// Requirements this front end implements.
pub(crate) const SUPPORTED_REQUIREMENTS: &[&str] = &[
    ":strips",
    ":typing",
    ":negative-preconditions",
    ":equality",
    ":disjunctive-preconditions",
    ":action-costs",
];

/// Requirements of PDDL 1.2–3.1 that are refused by name.
const KNOWN_UNSUPPORTED_REQUIREMENTS: &[&str] = &[
    ":adl",
    ":existential-preconditions",
    ":universal-preconditions",
    ":quantified-preconditions",
    ":conditional-effects",
    ":fluents",
    ":numeric-fluents",
    ":object-fluents",
    ":durative-actions",
    ":duration-inequalities",
    ":continuous-effects",
    ":derived-predicates",
    ":timed-initial-literals",
    ":preferences",
    ":constraints",
    ":domain-axioms",
    ":expression-evaluation",
    ":open-world",
    ":true-negation",
    ":ucpop",
    ":time",
];

/// `` `construct` is not supported: why`` at the construct.
pub(crate) fn refuse(src: &SourceMap, span: Span, construct: &str, why: &str) -> PddlError {
    src.error(span, format!("`{construct}` is not supported: {why}"))
}

/// Whether `s` is a PDDL name: a letter, then letters, digits, `-` or `_`.
pub(crate) fn is_name(s: &str) -> bool {
    let mut c = s.chars();
    matches!(c.next(), Some(f) if f.is_ascii_alphabetic())
        && c.all(|x| x.is_ascii_alphanumeric() || x == '-' || x == '_')
}

fn describe(e: &SExpr) -> String {
    match e {
        SExpr::Atom(a, _) => format!("`{a}`"),
        SExpr::List(..) => "a list".to_string(),
    }
}

/// The items of a list, or an error naming what was expected.
pub(crate) fn list<'e>(
    src: &SourceMap,
    e: &'e SExpr,
    what: &str,
) -> Result<&'e [SExpr], PddlError> {
    match e {
        SExpr::List(items, _) => Ok(items),
        SExpr::Atom(..) => Err(src.error(
            e.span(),
            format!("expected {what} `( … )`, found {}", describe(e)),
        )),
    }
}

/// A name (not a variable, keyword or number).
pub(crate) fn name(src: &SourceMap, e: &SExpr, what: &str) -> Result<Name, PddlError> {
    match e {
        SExpr::Atom(a, span) if is_name(a) => Ok(Name {
            text: a.clone(),
            span: *span,
        }),
        _ => Err(src.error(e.span(), format!("expected {what}, found {}", describe(e)))),
    }
}

/// A `?variable`.
pub(crate) fn variable(src: &SourceMap, e: &SExpr) -> Result<Name, PddlError> {
    match e {
        SExpr::Atom(a, span) if a.starts_with('?') && is_name(&a[1..]) => Ok(Name {
            text: a.clone(),
            span: *span,
        }),
        _ => Err(src.error(
            e.span(),
            format!("expected a variable `?name`, found {}", describe(e)),
        )),
    }
}

/// A typed list `a b - t c - u d` → `[(a, Some(t)), (b, Some(t)), (c, Some(u)), (d, None)]`.
/// `variables` selects `?x` items or plain names. `(either …)` is refused by name.
pub(crate) fn typed_list(
    src: &SourceMap,
    items: &[SExpr],
    variables: bool,
) -> Result<Vec<(Name, Option<Name>)>, PddlError> {
    let mut out: Vec<(Name, Option<Name>)> = Vec::new();
    let mut pending = 0; // trailing items without a type yet
    let mut i = 0;
    while i < items.len() {
        if items[i].atom() == Some("-") {
            let Some(ty) = items.get(i + 1) else {
                return Err(src.error(items[i].span(), "expected a type after `-`"));
            };
            if let (Some("either"), SExpr::List(parts, _)) = (ty.head(), ty) {
                return Err(refuse(
                    src,
                    parts[0].span(),
                    "either",
                    "union types are not supported; declare a common supertype",
                ));
            }
            if pending == 0 {
                return Err(src.error(items[i].span(), "`-` with no name before it"));
            }
            let ty = name(src, ty, "a type name")?;
            let n = out.len();
            for item in &mut out[n - pending..] {
                item.1 = Some(ty.clone());
            }
            pending = 0;
            i += 2;
        } else {
            let n = if variables {
                variable(src, &items[i])?
            } else {
                name(src, &items[i], "a name")?
            };
            out.push((n, None));
            pending += 1;
            i += 1;
        }
    }
    Ok(out)
}

/// Checks a `(:requirements …)` section: supported flags pass, known PDDL flags we do not
/// implement are refused by name, anything else is unknown.
pub(crate) fn requirements(src: &SourceMap, items: &[SExpr]) -> Result<Vec<Name>, PddlError> {
    let mut out = Vec::new();
    for e in &items[1..] {
        let Some(a) = e.atom() else {
            return Err(src.error(e.span(), "expected a requirement flag such as `:strips`"));
        };
        if SUPPORTED_REQUIREMENTS.contains(&a) {
            out.push(Name {
                text: a.to_string(),
                span: e.span(),
            });
        } else if KNOWN_UNSUPPORTED_REQUIREMENTS.contains(&a) {
            return Err(src.error(
                e.span(),
                format!(
                    "requirement `{a}` is not supported (supported: {})",
                    SUPPORTED_REQUIREMENTS.join(" ")
                ),
            ));
        } else {
            let near = did_you_mean(
                a,
                SUPPORTED_REQUIREMENTS
                    .iter()
                    .chain(KNOWN_UNSUPPORTED_REQUIREMENTS)
                    .copied(),
            );
            return Err(src.error(e.span(), format!("unknown requirement `{a}`{near}")));
        }
    }
    Ok(out)
}

/// A non-negative integer (a cost or a function value).
pub(crate) fn non_negative_integer(src: &SourceMap, e: &SExpr) -> Result<u64, PddlError> {
    let text = e.atom().unwrap_or("");
    // Accept `5` and `5.0` / `5.00`; refuse fractions and negatives.
    let int = text.strip_suffix(".0").or_else(|| {
        text.split_once('.')
            .filter(|(_, f)| !f.is_empty() && f.bytes().all(|b| b == b'0'))
            .map(|(i, _)| i)
    });
    let digits = int.unwrap_or(text);
    if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
        if let Ok(v) = digits.parse::<u64>() {
            return Ok(v);
        }
    }
    Err(src.error(
        e.span(),
        format!("expected a non-negative integer, found {}", describe(e)),
    ))
}

/// Splits `(define (KIND NAME) section …)` into its name and sections, checking the header.
pub(crate) fn define<'e>(
    src: &SourceMap,
    top: &'e SExpr,
    kind: &str,
) -> Result<(Name, &'e [SExpr]), PddlError> {
    let items = list(src, top, "`(define …)`")?;
    match items.first() {
        Some(SExpr::Atom(a, _)) if a == "define" => {}
        Some(e) => {
            return Err(src.error(
                e.span(),
                format!("expected `define`, found {}", describe(e)),
            ))
        }
        None => return Err(src.error(top.span(), "expected `(define …)`, found `()`")),
    }
    let Some(header) = items.get(1) else {
        return Err(src.error(
            top.span(),
            format!("missing `({kind} NAME)` after `define`"),
        ));
    };
    let h = list(src, header, &format!("`({kind} NAME)`"))?;
    match h.first().and_then(|x| x.atom()) {
        Some(k) if k == kind => {}
        Some(other @ ("domain" | "problem")) => {
            return Err(src.error(
                header.span(),
                format!("this is a {other} file, expected `({kind} NAME)`"),
            ))
        }
        _ => return Err(src.error(header.span(), format!("expected `({kind} NAME)`"))),
    }
    if h.len() != 2 {
        return Err(src.error(header.span(), format!("expected `({kind} NAME)`")));
    }
    let n = name(src, &h[1], &format!("the {kind} name"))?;
    Ok((n, &items[2..]))
}
