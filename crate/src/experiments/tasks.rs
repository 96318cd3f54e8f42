//! Random initial states for Table I: the template scene varied at one of the levels L1–L4
//! (paper §IV-C: "tasks that share the same task goal but vary in their initial states").
//!
//! A task of level L is the template world after the level-L disturbance of
//! [`crate::lfd::disturb`] (seeded), applied to the *initial* state: L1 moves blocks without
//! changing a fact, L2 starts from another state of the demonstration, L3 from a state it never
//! visits, L4 with an extra block in the way of the demonstration's plan (on a block the tower
//! needs, or, in B2, in the hand). A level the injector cannot produce is an error naming it,
//! never a task of another level (`docs/levels.md`).

use crate::lfd::DemoTrace;
use crate::lfd::TaskBuilder as _;
use crate::lfd::{self, Level};
use crate::lfd::{demo_actions, mix_seed, sources_for, SessionError};
use crate::plan::Task;
use crate::sim::Benchmark;
use crate::sim::{SceneGraph, World};

/// Seeded attempts at a level before the generator gives up with an error.
const ATTEMPTS: u64 = 8;

/// The benchmark's demonstration trace L_0..L_N, derived on its template task: what "seen in
/// the demonstration" means to the injector.
pub fn demo_trace(b: Benchmark) -> Result<DemoTrace, SessionError> {
    demo_trace_for(b, None)
}

/// [`demo_trace`] of the benchmark's generated tower task with `blocks` blocks (`None`: the
/// template task).
pub fn demo_trace_for(b: Benchmark, blocks: Option<usize>) -> Result<DemoTrace, SessionError> {
    Ok(template_task_for(b, blocks)?.1)
}

/// The benchmark's task as the scene graph states its scene (template, or the generated tower
/// with `blocks` blocks), with the trace L_0..L_N of its demonstration on that task.
pub fn template_task_for(
    b: Benchmark,
    blocks: Option<usize>,
) -> Result<(Task, DemoTrace), SessionError> {
    let files = sources_for(b, blocks)?;
    let template = World::from_json(&files.scene)?.with_motions(b.motions());
    let model = crate::lfd::DomainModel::new(
        &files.domain,
        "domain.pddl",
        &files.problem,
        "problem.pddl",
        &b.motions().scene_predicates(),
    )?;
    let objects = SceneGraph::objects(&template);
    let task = model.build(&objects, &SceneGraph::from_world(&template).to_strings())?;
    let trace = DemoTrace::derive(&task, &demo_actions(&files.demo)?)?;
    Ok((task, trace))
}

/// The initial world (as scene JSON) of a Table I task.
pub fn initial_scene(b: Benchmark, level: Level, seed: u64) -> Result<String, SessionError> {
    initial_scene_for(b, None, level, seed)
}

/// [`initial_scene`] of the benchmark's generated tower task with `blocks` blocks (`None`: the
/// template task).
pub fn initial_scene_for(
    b: Benchmark,
    blocks: Option<usize>,
    level: Level,
    seed: u64,
) -> Result<String, SessionError> {
    let files = sources_for(b, blocks)?;
    let mut world = World::from_json(&files.scene)?.with_motions(b.motions());
    let trace = demo_trace_for(b, blocks)?;
    // Up to a few attempts with derived seeds: a level may be impossible from some draws.
    let mut last = String::new();
    for attempt in 0..ATTEMPTS {
        let s = mix_seed(seed, attempt);
        let mut w = world.clone();
        match lfd::inject(&mut w, level, &trace, &[], s) {
            Ok(_) => {
                // L1 tasks get a second motion-level variation for spread.
                if level == Level::L1 {
                    let _ = lfd::inject(&mut w, Level::L1, &trace, &[], mix_seed(s, 1));
                }
                world = w;
                return serde_json::to_string(&world.snapshot())
                    .map_err(|e| SessionError::Json(e.to_string()));
            }
            Err(e) => last = e,
        }
    }
    Err(SessionError::Json(format!(
        "{}: cannot generate a {} task: {last}",
        b.as_str(),
        level.as_str()
    )))
}
