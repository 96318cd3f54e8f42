//! The checks that tie a folder's scene to its problem: every scene object is a problem object
//! (a misspelt body is named at its JSON path, with the objects the problem declares), every
//! physical problem object is in the scene, and the scene shows what `:init` states.

use std::collections::BTreeSet;
use std::sync::Arc;

use super::finding::{closest, line_col, listed, Finding};
use crate::pddl::{Domain, Problem};
use crate::sim::{
    normalise, parse_json, BenchmarkSources, BodyKind, Motions, ObjectKind, SceneGraph, World,
    WorldSnapshot,
};

/// A folder's files, parsed.
pub(super) struct Loaded {
    pub(super) domain: Domain,
    pub(super) problem: Problem,
    pub(super) motions: Arc<Motions>,
    pub(super) snapshot: WorldSnapshot,
    pub(super) world: World,
}

/// Parses the folder's domain, problem, motions and scene; the first that fails is the finding.
pub(super) fn load(s: &BenchmarkSources) -> Result<Loaded, Finding> {
    let pddl = |e: crate::pddl::PddlError| {
        Finding::new(&e.file, format!("{}:{}", e.line, e.col), e.message)
    };
    let domain = crate::pddl::parse_domain(&s.domain, &s.file("domain.pddl")).map_err(pddl)?;
    let problem =
        crate::pddl::parse_problem(&s.problem, &s.file("problem.pddl"), &domain).map_err(pddl)?;
    let motions = Motions::parse(&s.motions, &s.file("motions.json"), &domain).map_err(|e| {
        Finding::new(
            &e.file,
            format!("{}:{}", e.line, e.column),
            format!("{}: {}", e.path, e.message),
        )
    })?;
    let scene_file = s.file("scene.json");
    let snapshot: WorldSnapshot = parse_json(&s.scene).map_err(|e| {
        let (path, message) = e.into_parts();
        Finding::new(&scene_file, path, message)
    })?;
    let motions = Arc::new(motions);
    let world = World::from_snapshot(&snapshot)
        .map_err(|e| Finding::new(&scene_file, e.path, e.message))?
        .with_motions(Arc::clone(&motions));
    Ok(Loaded {
        domain,
        problem,
        motions,
        snapshot,
        world,
    })
}

/// A scene object: its name, kind and JSON path (`bodies[3].name`).
struct SceneObject {
    name: String,
    kind: ObjectKind,
    path: String,
}

fn scene_objects(snap: &WorldSnapshot) -> Vec<SceneObject> {
    let mut out = Vec::new();
    for (i, a) in snap.arms.iter().enumerate() {
        out.push(SceneObject {
            name: a.name.to_ascii_lowercase(),
            kind: ObjectKind::Arm,
            path: format!("arms[{i}].name"),
        });
    }
    for (i, b) in snap.bodies.iter().enumerate() {
        let kind = match b.kind {
            BodyKind::Block => ObjectKind::Block,
            BodyKind::Hook => ObjectKind::Hook,
            BodyKind::Table | BodyKind::Shelf => continue,
        };
        if !b.lost {
            out.push(SceneObject {
                name: b.name.to_ascii_lowercase(),
                kind,
                path: format!("bodies[{i}].name"),
            });
        }
    }
    for (i, r) in snap.regions.iter().enumerate() {
        out.push(SceneObject {
            name: r.name.to_ascii_lowercase(),
            kind: ObjectKind::Region,
            path: format!("regions[{i}].name"),
        });
    }
    out
}

fn kind_word(kind: ObjectKind) -> &'static str {
    match kind {
        ObjectKind::Arm => "arm",
        ObjectKind::Block => "block",
        ObjectKind::Hook => "hook",
        ObjectKind::Region => "region",
    }
}

/// Scene objects the problem does not declare, and physical problem objects (of a kind
/// motions.json declares) the scene lacks.
pub(super) fn check_names(l: &Loaded, s: &BenchmarkSources) -> Vec<Finding> {
    let scene_file = s.file("scene.json");
    let problem_file = s.file("problem.pddl");
    let declared: Vec<String> = l
        .problem
        .objects
        .iter()
        .chain(&l.domain.constants)
        .map(|o| o.name.text.clone())
        .collect();
    let scene = scene_objects(&l.snapshot);
    let mut out = Vec::new();
    for o in &scene {
        if declared.contains(&o.name) {
            continue;
        }
        let hint = closest(&o.name, &declared)
            .map(|c| format!("; did you mean `{c}`?"))
            .unwrap_or_default();
        out.push(Finding::new(
            &scene_file,
            o.path.clone(),
            format!(
                "the {} `{}` is not an object of the problem: {problem_file} declares {}{hint}",
                kind_word(o.kind),
                o.name,
                listed(&declared)
            ),
        ));
    }
    let typed = |pred: &str, name: &str| {
        l.problem.init.iter().any(|a| {
            l.domain.predicates[a.predicate].name.text == pred
                && a.args.len() == 1
                && a.args[0].text() == name
        })
    };
    for o in &l.problem.objects {
        let name = &o.name.text;
        let kind = l.motions.objects.iter().find(|(_, spec)| {
            let by_type = spec.ty.as_deref().is_some_and(|t| {
                l.domain
                    .type_index(t)
                    .is_some_and(|ti| ti != 0 && l.domain.is_subtype(o.ty, ti))
            });
            by_type || spec.predicate.as_deref().is_some_and(|p| typed(p, name))
        });
        let Some((kind, _)) = kind else { continue };
        if scene.iter().any(|so| so.name == *name && so.kind == *kind) {
            continue;
        }
        let same_kind: Vec<String> = scene
            .iter()
            .filter(|so| so.kind == *kind)
            .map(|so| so.name.clone())
            .collect();
        let (line, col) = line_col(&s.problem, o.name.span.start);
        out.push(Finding::new(
            &problem_file,
            format!("{line}:{col}"),
            format!(
                "`{name}` is a {} (as motions.json declares {}s), but {scene_file} has no {} of that name (its {}s: {})",
                kind_word(*kind),
                kind_word(*kind),
                kind_word(*kind),
                kind_word(*kind),
                listed(&same_kind)
            ),
        ));
    }
    out
}

/// The facts of scene predicates that `:init` states and the scene does not show, and those
/// the scene shows and `:init` does not state.
pub(super) fn check_init(l: &Loaded, s: &BenchmarkSources) -> Vec<Finding> {
    let preds: BTreeSet<String> = l.motions.scene_predicates().into_iter().collect();
    let init: BTreeSet<String> = l
        .problem
        .init
        .iter()
        .filter(|a| preds.contains(&l.domain.predicates[a.predicate].name.text))
        .map(|a| normalise(&l.domain.atom_text(a, &[])))
        .collect();
    let seen: BTreeSet<String> = SceneGraph::from_world(&l.world)
        .to_strings()
        .iter()
        .map(|f| normalise(f))
        .collect();
    let only_init: Vec<String> = init.difference(&seen).cloned().collect();
    let only_seen: Vec<String> = seen.difference(&init).cloned().collect();
    if only_init.is_empty() && only_seen.is_empty() {
        return vec![];
    }
    let at = l
        .problem
        .init
        .first()
        .map(|a| {
            let (line, col) = line_col(&s.problem, a.span.start);
            format!("{line}:{col}")
        })
        .unwrap_or_default();
    let scene_file = s.file("scene.json");
    vec![Finding::new(
        &s.file("problem.pddl"),
        at,
        format!(
            ":init and {scene_file} disagree (the scene graph reads the scene through motions.json): \
             in :init but not seen in the scene: {}; seen in the scene but not in :init: {}",
            listed(&only_init),
            listed(&only_seen)
        ),
    )]
}
