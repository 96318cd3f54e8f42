//! Benchmark worlds for the TAMP and executor tests: template and saved worlds, a world's task and
//! its operators, the skills learned from a benchmark's demonstration, and scenes built from a
//! template.

use logic_lfd::lfd::DomainModel;
use logic_lfd::lfd::SkillKind;
use logic_lfd::lfd::SkillLibrary;
use logic_lfd::lfd::TaskBuilder;
use logic_lfd::plan::Task;
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::ShapeSnapshot;
use logic_lfd::sim::{SceneGraph, World};
use nalgebra::Vector3;

/// The domain model of benchmark `b` and its task in `world` (the benchmark's goal).
pub(crate) fn model_and_task(b: Benchmark, world: &World) -> (DomainModel, Task) {
    model_and_task_for(b, world, &b.sources().unwrap().problem)
}

/// Like [`model_and_task`] with another problem text (its goal).
pub(crate) fn model_and_task_for(
    b: Benchmark,
    world: &World,
    problem: &str,
) -> (DomainModel, Task) {
    let files = b.sources().unwrap();
    let model = DomainModel::new(
        &files.domain,
        "domain.pddl",
        problem,
        "problem.pddl",
        &b.motions().scene_predicates(),
    )
    .unwrap();
    let objs = SceneGraph::objects(world);
    let task = model
        .build(&objs, &SceneGraph::from_world(world).to_strings())
        .unwrap();
    (model, task)
}

/// Benchmark `b`'s template world.
pub(crate) fn template(b: Benchmark) -> World {
    World::from_json(&b.sources().unwrap().scene).unwrap()
}

/// The index of `task`'s operator `name`; panics if there is none.
pub(crate) fn op(task: &Task, name: &str) -> usize {
    task.operators
        .iter()
        .position(|o| o.name == name)
        .unwrap_or_else(|| panic!("no operator {name}"))
}

/// A saved world, `crate/tests/data/worlds/<name>.json`.
pub(crate) fn saved_world(name: &str) -> World {
    let path = format!(
        "{}/tests/data/worlds/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let world = World::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    // A fixture is a benchmark's world: it reads its facts through that benchmark's motions.
    let b = Benchmark::parse(world.name()).expect("a fixture names its benchmark's world");
    world.with_motions(b.motions())
}

/// B1's skills, learned from its demonstration.
pub(crate) fn b1_skills() -> SkillLibrary {
    let b = Benchmark::B1;
    SkillLibrary::learn(
        &b.sources().unwrap().demo,
        SkillKind::Lqt,
        &[],
        &b.motions(),
    )
}

/// B2's skills, learned from its demonstration (the hook's grasp apart from the blocks').
pub(crate) fn b2_skills() -> SkillLibrary {
    let demo = Benchmark::B2.sources().unwrap().demo;
    SkillLibrary::learn(
        &demo,
        SkillKind::Lqt,
        &["hook".to_string()],
        &Benchmark::B2.motions(),
    )
}

/// B1 with block a on the table and c, on d beside it, overhanging a's corner by 4 mm (as when a
/// user drags d next to a and an L1 then nudges c).
pub(crate) fn b1_with_c_overhanging_a() -> World {
    let mut world = template(Benchmark::B1);
    world
        .move_block("a", Vector3::new(0.40, -0.25, 0.03))
        .unwrap();
    world
        .move_block("d", Vector3::new(0.4637, -0.2166, 0.03))
        .unwrap();
    world
        .move_block("c", Vector3::new(0.456, -0.1988, 0.09))
        .unwrap();
    world
        .move_block("b", Vector3::new(0.30, 0.25, 0.03))
        .unwrap();
    let graph = SceneGraph::from_world(&world);
    assert!(graph.contains("(on c d)") && graph.contains("(clear a)"));
    let (a, c) = (world.body_aabb("a").unwrap(), world.body_aabb("c").unwrap());
    assert!(
        c.0.x < a.1.x - 0.003 && c.0.y < a.1.y - 0.003,
        "c does not overhang a"
    );
    world
}

/// The hook's boxes in its frame.
pub(crate) fn hook_parts(world: &World) -> Vec<logic_lfd::sim::PartSnapshot> {
    let snap = world.snapshot();
    let hook = snap.bodies.iter().find(|x| x.name == "hook").unwrap();
    let ShapeSnapshot::Compound { parts } = &hook.shape else {
        panic!("the hook is a compound");
    };
    parts.clone()
}
