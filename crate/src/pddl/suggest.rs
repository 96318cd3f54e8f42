//! "Did you mean …?" for an unknown name: the closest known name by edit distance (adjacent
//! letters swapped count as one edit), when it is close enough to be a likely typo.

#![cfg_attr(first_load, allow(dead_code))]

/// Edits (insert, delete, substitute, swap two adjacent characters) from `a` to `b`.
fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let w = b.len() + 1;
    let mut d = vec![0usize; (a.len() + 1) * w];
    for i in 0..=a.len() {
        for j in 0..=b.len() {
            d[i * w + j] = if i == 0 || j == 0 {
                i + j
            } else {
                let cost = usize::from(a[i - 1] != b[j - 1]);
                let mut v = (d[(i - 1) * w + j] + 1)
                    .min(d[i * w + j - 1] + 1)
                    .min(d[(i - 1) * w + j - 1] + cost);
                if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                    v = v.min(d[(i - 2) * w + j - 2] + 1);
                }
                v
            };
        }
    }
    d[a.len() * w + b.len()]
}

/// The known name closest to `name`, if within a third of its length (at least one edit) and
/// not a rewrite of every character (`x` is no typo of `o`).
pub(crate) fn closest<'a>(name: &str, known: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let len = name.chars().count();
    let limit = (len / 3).max(1).min(len.saturating_sub(1));
    known
        .into_iter()
        .filter(|k| *k != name)
        .map(|k| (distance(name, k), k))
        .filter(|&(d, _)| d <= limit)
        .min()
        .map(|(_, k)| k)
}

/// `; did you mean `x`?` for the closest known name, or nothing.
#[cfg(not(first_load))]
pub(crate) fn did_you_mean<'a>(name: &str, known: impl IntoIterator<Item = &'a str>) -> String {
    closest(name, known).map_or_else(String::new, |k| format!("; did you mean `{k}`?"))
}

/// Nothing: the page's first-load module reads only its compiled-in PDDL, and its size budget
/// has no room for the search.
#[cfg(first_load)]
pub(crate) fn did_you_mean<'a>(_name: &str, _known: impl IntoIterator<Item = &'a str>) -> String {
    String::new()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_typo_gets_the_nearest_name_and_a_stranger_none() {
        let known = ["on-table", "on", "clear", "holding"];
        assert_eq!(closest("on-tabel", known), Some("on-table"));
        assert_eq!(closest("clera", known), Some("clear"));
        assert_eq!(closest("hodling", known), Some("holding"));
        assert_eq!(closest("gripper", known), None);
        assert_eq!(did_you_mean("cler", known), "; did you mean `clear`?");
        assert_eq!(did_you_mean("xyz", known), "");
        assert_eq!(closest("x", ["o", "a"]), None);
        assert_eq!(closest("ab", ["ac"]), Some("ac"));
        assert_eq!(distance("kitten", "sitting"), 3);
    }
}
