//! The PDDL model of a benchmark, and the grounded task of the *current* world.
//!
//! The loop re-grounds whenever the scene holds an object the task does not know (L4: a new
//! block). The problem of the current world is assembled from the scene
//! ([`pddl::ProblemBuilder`]): its objects (from the world), its `:init` = S_C plus the template
//! problem's facts of predicates the scene graph does not report (static ones), and the
//! template's `:goal` (and `:metric`) unchanged.

use std::collections::BTreeSet;

use crate::pddl::{self, Domain, ObjectDecl, Problem, ProblemBuilder};
use crate::plan::{self, Task};

use super::control::TaskBuilder;
use super::LfdError;

/// A benchmark's PDDL domain plus what is reused from its template problem.
#[derive(Clone, Debug)]
pub struct DomainModel {
    domain: Domain,
    template: Problem,
    static_init: Vec<String>,
    template_objects: Vec<ObjectDecl>,
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
        let preds: BTreeSet<&str> = scene_predicates.iter().map(String::as_str).collect();
        let static_init = problem
            .init
            .iter()
            .filter(|a| !preds.contains(domain.predicates[a.predicate].name.text.as_str()))
            .map(|a| domain.atom_text(a, &[]))
            .collect();
        let template_objects = problem
            .objects
            .iter()
            .map(|o| ObjectDecl {
                name: o.name.text.clone(),
                ty: domain.types[o.ty].name.text.clone(),
            })
            .collect();
        Ok(DomainModel {
            domain,
            template: problem,
            static_init,
            template_objects,
        })
    }

    /// The parsed domain.
    pub fn domain(&self) -> &Domain {
        &self.domain
    }

    /// The problem of a world with these objects (those of a type the domain declares) and facts.
    pub fn problem(&self, objects: &[ObjectDecl], facts: &[String]) -> Result<Problem, LfdError> {
        let decls = objects
            .iter()
            .filter(|o| self.domain.type_index(&o.ty).is_some())
            .cloned();
        ProblemBuilder::from_template(&self.domain, &self.template)
            .objects(decls)
            .init(facts.iter().chain(&self.static_init).cloned())
            .build()
            .map_err(|e| LfdError::Model(e.to_string()))
    }

    /// The template problem's objects.
    pub fn template_objects(&self) -> &[ObjectDecl] {
        &self.template_objects
    }
}

impl TaskBuilder for DomainModel {
    fn build(&self, objects: &[ObjectDecl], facts: &[String]) -> Result<Task, LfdError> {
        let problem = self.problem(objects, facts)?;
        plan::ground(&self.domain, &problem).map_err(|e| LfdError::Model(e.to_string()))
    }
}
