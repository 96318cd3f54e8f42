//! Running actions with the executor as the loop does: the demonstration's actions with learned
//! skills, or the streams' bindings (placements, transits, hand turns); every tick checks the
//! world's invariants.

use logic_lfd::lfd::SkillLibrary;
use logic_lfd::lfd::{ActionExec, ExecParams, ExecStatus};
use logic_lfd::plan::Task;
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::World;
use logic_lfd::tamp::Binder;
use logic_lfd::tamp::{classify, ActionKind};
use logic_lfd::tamp::{StreamBinder, StreamParams};

use super::bench::{b2_skills, model_and_task, op, template};

/// Executes `ops` of `task` in `world` with the streams' `bindings` (placements and transits),
/// checking the world's invariants every tick; panics unless every action is done.
pub(crate) fn execute_bound(
    world: &mut World,
    task: &Task,
    ops: &[usize],
    bindings: &[logic_lfd::tamp::Binding],
    skills: &SkillLibrary,
) {
    execute_bound_watching(world, task, ops, bindings, skills, |_, _| {});
}

/// [`execute_bound`], calling `watch(action, world)` after every tick.
pub(crate) fn execute_bound_watching(
    world: &mut World,
    task: &Task,
    ops: &[usize],
    bindings: &[logic_lfd::tamp::Binding],
    skills: &SkillLibrary,
    mut watch: impl FnMut(&str, &World),
) {
    let params = ExecParams::default();
    for (&o, binding) in ops.iter().zip(bindings) {
        let operator = &task.operators[o];
        let mut kind = classify(operator, world).unwrap();
        if let ActionKind::Release { placement, .. } = &mut kind {
            placement.clone_from(&binding.placement);
        }
        let mut exec = ActionExec::new(&operator.name, kind, world, skills, &params)
            .with_hand_yaw(binding.hand_yaw);
        if let Some(z) = binding.transit {
            exec = exec.with_transit(z);
        }
        let status =
            tick_to_end_watching(exec, world, skills, &params, |w| watch(&operator.name, w));
        assert_eq!(status, ExecStatus::Done, "{}", operator.name);
    }
}

/// The streams' bindings of the B2 action `name` in `world`; panics unless it binds.
pub(crate) fn b2_bind_one(
    world: &World,
    name: &str,
) -> (Task, [usize; 1], Vec<logic_lfd::tamp::Binding>) {
    let (_, task) = model_and_task(Benchmark::B2, world);
    let ops = [op(&task, name)];
    let mut binder = StreamBinder::new(world, 1, StreamParams::default());
    let r = binder.bind(&task, &ops, ops.len());
    let bindings = r.unwrap_or_else(|e| panic!("{:?}", e.reason));
    (task, ops, bindings)
}

/// Executes one action of `task` in `world` the way the loop does for the demonstration's
/// actions (no stream binding; learned skills), checking the invariants every tick.
pub(crate) fn execute_learned(
    world: &mut World,
    task: &Task,
    name: &str,
    skills: &SkillLibrary,
) -> ExecStatus {
    let params = ExecParams::default();
    let operator = &task.operators[op(task, name)];
    let kind = classify(operator, world).unwrap();
    let exec = ActionExec::new(&operator.name, kind, world, skills, &params);
    tick_to_end(exec, world, skills, &params)
}

/// Ticks `exec` in `world` until it ends (at most 6 000 ticks), checking the world's invariants
/// every tick; its last status.
fn tick_to_end(
    exec: ActionExec,
    world: &mut World,
    skills: &SkillLibrary,
    params: &ExecParams,
) -> ExecStatus {
    tick_to_end_watching(exec, world, skills, params, |_| {})
}

/// [`tick_to_end`], calling `watch(world)` after every tick.
pub(crate) fn tick_to_end_watching(
    mut exec: ActionExec,
    world: &mut World,
    skills: &SkillLibrary,
    params: &ExecParams,
    mut watch: impl FnMut(&World),
) -> ExecStatus {
    let mut status = ExecStatus::Running;
    for _ in 0..6000 {
        status = exec.tick(world, skills, params);
        assert_eq!(world.check_invariants(), Ok(()));
        watch(world);
        if status != ExecStatus::Running {
            break;
        }
    }
    status
}

/// B2's template world with the arm holding the hook (the demonstration's pick, learned skills).
pub(crate) fn b2_holding_hook() -> (World, Task) {
    let b = Benchmark::B2;
    let mut world = template(b);
    let (_, task) = model_and_task(b, &world);
    assert_eq!(
        execute_learned(&mut world, &task, "(pick panda hook)", &b2_skills()),
        ExecStatus::Done
    );
    (world, task)
}
