//! The PDDL model of a benchmark, and the grounded task of the *current* world.
//!
//! The loop re-grounds whenever the scene holds an object the task does not know (L4: a new
//! block). The problem of the current world is written from the scene: its objects (from the
//! world), its `:init` = S_C plus the template problem's facts of predicates the scene graph does
//! not report (static ones), and the template's `:goal` (and `:metric`) unchanged.

use std::collections::BTreeSet;

use crate::pddl::{self, Domain};
use crate::plan::{self, Task};

use super::control::TaskBuilder;
use super::LfdError;

/// A benchmark's PDDL domain plus what is reused from its template problem.
#[derive(Clone, Debug)]
pub struct DomainModel {
    domain: Domain,
    domain_name: String,
    goal_text: String,
    metric_text: Option<String>,
    static_init: Vec<String>,
    template_objects: Vec<(String, String)>,
    file: String,
}

/// The balanced `( … )` starting at byte `start`.
fn balanced(text: &str, start: usize) -> Option<&str> {
    let mut depth = 0usize;
    for (i, ch) in text[start..].char_indices() {
        match ch {
            '(' => depth += 1,
            ')' => {
                depth = depth.checked_sub(1)?;
                if depth == 0 {
                    return Some(&text[start..start + i + 1]);
                }
            }
            _ => {}
        }
    }
    None
}

fn section<'t>(lower: &'t str, key: &str) -> Option<&'t str> {
    let at = lower.find(&format!("({key}"))?;
    balanced(lower, at)
}

/// Top-level `( … )` groups inside a section body.
fn groups(body: &str) -> Vec<String> {
    let mut out = vec![];
    let inner = &body[1..body.len() - 1];
    let mut i = 0;
    while let Some(off) = inner[i..].find('(') {
        let at = i + off;
        match balanced(inner, at) {
            Some(g) => {
                out.push(g.split_whitespace().collect::<Vec<_>>().join(" "));
                i = at + g.len();
            }
            None => break,
        }
    }
    out
}

fn strip_comments(text: &str) -> String {
    text.lines()
        .map(|l| l.split(';').next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

impl DomainModel {
    /// Parses the domain and the template problem. `scene_predicates` are the fluents the scene
    /// graph reports; the template's other init facts are kept in every re-grounded problem.
    pub fn new(
        domain_text: &str,
        domain_file: &str,
        problem_text: &str,
        problem_file: &str,
        scene_predicates: &[String],
    ) -> Result<Self, LfdError> {
        let domain = pddl::parse_domain(domain_text, domain_file)
            .map_err(|e| LfdError::Model(e.to_string()))?;
        let problem = pddl::parse_problem(problem_text, problem_file, &domain)
            .map_err(|e| LfdError::Model(e.to_string()))?;
        let lower = strip_comments(problem_text).to_lowercase();
        let goal_text = section(&lower, ":goal")
            .ok_or_else(|| LfdError::Model(format!("{problem_file}: no (:goal …)")))?
            .to_string();
        let metric_text = section(&lower, ":metric").map(str::to_string);
        let init = section(&lower, ":init").map(groups).unwrap_or_default();
        let preds: BTreeSet<&str> = scene_predicates.iter().map(String::as_str).collect();
        let static_init = init
            .into_iter()
            .filter(|f| !preds.contains(plan::fact_args(f).0))
            .filter(|f| !f.starts_with("(="))
            .collect();
        let template_objects = problem
            .objects
            .iter()
            .map(|o| (o.name.text.clone(), domain.types[o.ty].name.text.clone()))
            .collect();
        Ok(DomainModel {
            domain_name: domain.name.text.clone(),
            domain,
            goal_text,
            metric_text,
            static_init,
            template_objects,
            file: problem_file.to_string(),
        })
    }

    /// The parsed domain.
    pub fn domain(&self) -> &Domain {
        &self.domain
    }

    /// The parsed problem of a world with these objects and facts.
    pub fn problem(
        &self,
        objects: &[(String, String)],
        facts: &[String],
    ) -> Result<pddl::Problem, LfdError> {
        pddl::parse_problem(&self.problem_text(objects, facts), &self.file, &self.domain)
            .map_err(|e| LfdError::Model(e.to_string()))
    }

    /// The template problem's objects (name, type).
    pub fn template_objects(&self) -> &[(String, String)] {
        &self.template_objects
    }

    /// The PDDL problem text of a world with these objects and facts.
    pub fn problem_text(&self, objects: &[(String, String)], facts: &[String]) -> String {
        let constants: BTreeSet<&str> = self
            .domain
            .constants
            .iter()
            .map(|c| c.name.text.as_str())
            .collect();
        let mut objs = String::new();
        for (name, ty) in objects {
            if !constants.contains(name.as_str()) && self.domain.type_index(ty).is_some() {
                objs.push_str(&format!(" {name} - {ty}"));
            }
        }
        let mut init: Vec<&str> = facts.iter().map(String::as_str).collect();
        init.extend(self.static_init.iter().map(String::as_str));
        format!(
            "(define (problem current) (:domain {})\n (:objects{})\n (:init {})\n {}\n {})\n",
            self.domain_name,
            objs,
            init.join(" "),
            self.goal_text,
            self.metric_text.as_deref().unwrap_or("")
        )
    }
}

impl TaskBuilder for DomainModel {
    fn build(&self, objects: &[(String, String)], facts: &[String]) -> Result<Task, LfdError> {
        let text = self.problem_text(objects, facts);
        let problem = pddl::parse_problem(&text, &self.file, &self.domain)
            .map_err(|e| LfdError::Model(e.to_string()))?;
        plan::ground(&self.domain, &problem).map_err(|e| LfdError::Model(e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sections_are_extracted_with_balanced_parentheses() {
        let t = "(define (problem p) (:init (on a b) (clear a)) (:goal (and (on a b))))";
        assert_eq!(section(t, ":goal"), Some("(:goal (and (on a b)))"));
        assert_eq!(
            groups(section(t, ":init").unwrap()),
            vec!["(on a b)".to_string(), "(clear a)".to_string()]
        );
        assert_eq!(balanced("(a (b)", 0), None);
    }
}
