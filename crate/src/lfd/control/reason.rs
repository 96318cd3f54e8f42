//! Why the controller re-grounds its task, in the words of what the scene graph shows.

use std::collections::BTreeSet;

use crate::pddl::ObjectDecl;
use crate::plan::Task;

/// Why the scene no longer fits `task` (its objects `known`), as the scene graph shows it: the
/// objects that appeared or went, the facts the task has no atom for, the static facts of a
/// scene predicate that no longer hold.
pub(super) fn reground_reason(
    task: &Task,
    known: &[ObjectDecl],
    objects: &[ObjectDecl],
    facts: &[String],
) -> String {
    let names =
        |v: &[ObjectDecl]| -> BTreeSet<String> { v.iter().map(|o| o.name.clone()).collect() };
    let (was, now) = (names(known), names(objects));
    let plural = |n: usize| if n == 1 { "" } else { "s" };
    let mut parts = Vec::new();
    let added: Vec<&str> = now.difference(&was).map(String::as_str).collect();
    if !added.is_empty() {
        parts.push(format!(
            "new object{} in the scene: {}",
            plural(added.len()),
            added.join(" ")
        ));
    }
    let gone: Vec<&str> = was.difference(&now).map(String::as_str).collect();
    if !gone.is_empty() {
        parts.push(format!(
            "object{} gone from the scene: {}",
            plural(gone.len()),
            gone.join(" ")
        ));
    }
    let statics: BTreeSet<&str> = task.static_facts.iter().map(String::as_str).collect();
    let ungrounded: Vec<&str> = facts
        .iter()
        .filter(|f| task.fact_id(f).is_none() && !statics.contains(f.as_str()))
        .map(String::as_str)
        .collect();
    if !ungrounded.is_empty() {
        parts.push(format!(
            "fact{} the task had no atom for: {}",
            plural(ungrounded.len()),
            ungrounded.join(" ")
        ));
    }
    let preds: BTreeSet<&str> = facts.iter().map(|f| predicate(f)).collect();
    let present: BTreeSet<&str> = facts.iter().map(String::as_str).collect();
    let lost: Vec<&str> = task
        .static_facts
        .iter()
        .filter(|f| preds.contains(predicate(f)) && !present.contains(f.as_str()))
        .map(String::as_str)
        .collect();
    if !lost.is_empty() {
        parts.push(format!(
            "{} no longer hold{}",
            lost.join(" "),
            if lost.len() == 1 { "s" } else { "" }
        ));
    }
    if parts.is_empty() {
        // Same objects and facts, listed in another order: the task is read again as is.
        "the scene's objects were listed anew".into()
    } else {
        parts.join("; ")
    }
}

pub(super) fn predicate(fact: &str) -> &str {
    fact.trim_start_matches('(')
        .split([' ', ')'])
        .next()
        .unwrap_or("")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lfd::testing::blocks_task;

    fn decls(names: &[&str]) -> Vec<ObjectDecl> {
        names
            .iter()
            .map(|n| ObjectDecl {
                name: n.to_string(),
                ty: "block".into(),
            })
            .collect()
    }

    #[test]
    fn a_regrounding_reason_names_only_what_the_scene_shows() {
        let task = blocks_task(&["a", "b"], &["(handempty)", "(ontable a)"], &["(on a b)"]);
        let known = decls(&["a", "b"]);
        let facts = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        // A fact the task has no atom for, with the same objects: no "new objects".
        let why = reground_reason(&task, &known, &known, &facts(&["(handempty)", "(weird a)"]));
        assert_eq!(why, "fact the task had no atom for: (weird a)");
        // A new block and a block gone.
        let why = reground_reason(&task, &known, &decls(&["a", "e"]), &facts(&["(handempty)"]));
        assert_eq!(
            why,
            "new object in the scene: e; object gone from the scene: b"
        );
        // The same objects in another order.
        let why = reground_reason(&task, &known, &decls(&["b", "a"]), &facts(&["(handempty)"]));
        assert_eq!(why, "the scene's objects were listed anew");
    }
}
