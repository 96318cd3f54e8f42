//! One thing a task folder's check found: the file, where in it, and what is wrong.

use serde::{Deserialize, Serialize};

/// One thing a check of a task folder found wrong or risky.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Finding {
    /// The file (`./mine/scene.json`), as messages name it.
    pub file: String,
    /// Where in it: a JSON path (`bodies[3].name`) or `line:col` (empty: the whole file).
    pub path: String,
    /// What is wrong, and what would be right.
    pub message: String,
}

impl Finding {
    /// A finding in `file` at `path`.
    pub fn new(file: &str, path: impl Into<String>, message: impl Into<String>) -> Finding {
        Finding {
            file: file.to_string(),
            path: path.into(),
            message: message.into(),
        }
    }
}

impl std::fmt::Display for Finding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.path.is_empty() {
            write!(f, "{}: {}", self.file, self.message)
        } else if self.path.starts_with(|c: char| c.is_ascii_digit()) {
            // `line:col`: `file:line:col: message`, as the PDDL errors read.
            write!(f, "{}:{}: {}", self.file, self.path, self.message)
        } else {
            write!(f, "{}: {}: {}", self.file, self.path, self.message)
        }
    }
}

/// 1-based line and column (in characters) of byte offset `pos` of `text`.
pub(super) fn line_col(text: &str, pos: usize) -> (usize, usize) {
    let pos = pos.min(text.len());
    let before = &text[..pos];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

/// `names` as `a b c`, or `none`.
pub(super) fn listed(names: &[String]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        names.join(" ")
    }
}

/// The name of `candidates` closest to `name` by edit distance, if it is close (a misspelling).
pub(super) fn closest<'a>(name: &str, candidates: &'a [String]) -> Option<&'a str> {
    candidates
        .iter()
        .map(|c| (edit_distance(name, c), c))
        .filter(|(d, c)| *d <= 2.max(c.len() / 3))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c.as_str())
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for j in 0..b.len() {
            let cur = row[j + 1];
            // A swap of two letters costs as much as one substitution here: close enough.
            row[j + 1] = (prev + usize::from(ca != b[j]))
                .min(row[j] + 1)
                .min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_misspelt_name_finds_its_closest_declared_name() {
        let names: Vec<String> = ["blue1", "blue2", "red1", "panda"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        assert_eq!(closest("bleu2", &names), Some("blue2"));
        assert_eq!(closest("table", &names), None);
        assert_eq!(line_col("ab\ncd", 4), (2, 2));
    }
}
