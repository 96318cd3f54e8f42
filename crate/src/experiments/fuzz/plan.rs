//! Plan files under fuzzing: character and line edits, and the oracle of `parse_plan` and
//! `validate` (errors located, a failing step exists, step counts agree).

use rand::Rng;
use rand_pcg::Pcg64Mcg;

use super::common::{ensure, header, idx, Verdict};
use super::pddl::pddl_error_in_bounds;
use crate::pddl::{parse_domain, parse_problem, Domain, Problem};
use crate::plan::{parse_plan, validate, Outcome};

/// An edit of a plan file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PlanEdit {
    /// Delete the i-th character.
    Delete(usize),
    /// Insert a fragment before the i-th character.
    Insert(usize, &'static str),
    /// Swap two lines.
    SwapLines(usize, usize),
    /// Duplicate a line.
    DupLine(usize),
    /// Cut the text after `i` characters.
    Truncate(usize),
}

impl PlanEdit {
    /// A random edit.
    pub fn random(rng: &mut Pcg64Mcg) -> PlanEdit {
        const F: [&str; 17] = [
            "(",
            ")",
            " ",
            "\n",
            ";",
            "x",
            "(stack a b)",
            "(pick panda zz)",
            "()",
            "((",
            "-",
            "?x",
            "é",
            "\t",
            "(unstack a a)",
            "panda",
            "; cost = 3 (general cost)",
        ];
        let (i, j) = (idx(rng), idx(rng));
        match rng.random_range(0..5) {
            0 => PlanEdit::Delete(i),
            1 => PlanEdit::Insert(i, F[rng.random_range(0..F.len())]),
            2 => PlanEdit::SwapLines(i, j),
            3 => PlanEdit::DupLine(i),
            _ => PlanEdit::Truncate(i),
        }
    }
}

/// Applies plan edits to `text`.
pub fn mutate_plan(text: &str, edits: &[PlanEdit]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for e in edits {
        let n = chars.len();
        match e {
            PlanEdit::Delete(i) if n > 0 => {
                chars.remove(i % n);
            }
            PlanEdit::Insert(i, f) => {
                let at = i % (n + 1);
                chars.splice(at..at, f.chars());
            }
            PlanEdit::Truncate(i) => chars.truncate(i % (n + 1)),
            PlanEdit::SwapLines(i, j) | PlanEdit::DupLine(i @ j) if n > 0 => {
                let s: String = chars.iter().collect();
                let mut lines: Vec<String> = s.split('\n').map(str::to_string).collect();
                let m = lines.len();
                if matches!(e, PlanEdit::DupLine(_)) {
                    let l = lines[i % m].clone();
                    lines.insert(i % m, l);
                } else {
                    lines.swap(i % m, j % m);
                }
                chars = lines.join("\n").chars().collect();
            }
            _ => {}
        }
    }
    chars.into_iter().collect()
}

pub(super) fn check_plan(input: &str) -> Result<Verdict, String> {
    let (b, _) = header(input);
    let files = b.sources().map_err(|e| e.to_string())?;
    let d = parse_domain(&files.domain, "domain.pddl").map_err(|e| e.to_string())?;
    let p = parse_problem(&files.problem, "problem.pddl", &d).map_err(|e| e.to_string())?;
    check_plan_against(&d, &p, input)
}

/// The `plan` oracle for a plan text `input` (file name `m.plan`) against any domain and problem.
pub fn check_plan_against(d: &Domain, p: &Problem, input: &str) -> Result<Verdict, String> {
    let steps = match parse_plan(input, "m.plan") {
        Err(e) => {
            ensure(
                pddl_error_in_bounds(input, &e) && e.file == "m.plan",
                || format!("plan parse error outside the text: {e}"),
            )?;
            return Ok(Verdict::Refused);
        }
        Ok(s) => s,
    };
    let report = validate(d, p, &steps);
    match &report.outcome {
        Outcome::Valid => {
            ensure(report.steps_applied == steps.len(), || {
                format!(
                    "valid but {} of {} steps applied",
                    report.steps_applied,
                    steps.len()
                )
            })?;
            Ok(Verdict::Accepted)
        }
        Outcome::Malformed(e) => {
            ensure(pddl_error_in_bounds(input, e) && e.file == "m.plan", || {
                format!("malformed step outside the text: {e}")
            })?;
            Ok(Verdict::Refused)
        }
        Outcome::PreconditionFalse {
            step,
            location,
            false_literals,
            ..
        } => {
            ensure(*step >= 1 && *step <= steps.len(), || {
                format!("failing step {step} of {}", steps.len())
            })?;
            ensure(report.steps_applied == step - 1, || {
                format!("step {step} failed after {} applied", report.steps_applied)
            })?;
            ensure(location.starts_with("m.plan:"), || {
                format!("unlocated step: {location}")
            })?;
            ensure(!false_literals.is_empty(), || {
                "a precondition failure names no literal".into()
            })?;
            Ok(Verdict::Refused)
        }
        Outcome::GoalNotReached { false_literals } => {
            ensure(report.steps_applied == steps.len(), || {
                "goal check before the last step".into()
            })?;
            ensure(!false_literals.is_empty(), || {
                "an unreached goal names no literal".into()
            })?;
            Ok(Verdict::Refused)
        }
    }
}
