//! TAMP streams and the retry loop: per-state bans, certified motions (swept path of the arm and
//! the carried body), the pull stream's prediction against the executor, and TAMP from scratch.

use logic_lfd::lfd::control::{BannedTask, Binder};
use logic_lfd::lfd::exec::{classify, ActionExec, ExecParams, ExecStatus};
use logic_lfd::lfd::logic::replay;
use logic_lfd::lfd::model::DomainModel;
use logic_lfd::lfd::session::{BenchmarkId, SkillKind};
use logic_lfd::lfd::skill::SkillLibrary;
use logic_lfd::lfd::TaskBuilder;
use logic_lfd::plan::{search, Algorithm, HeuristicKind, NoClock, SearchConfig, Task};
use logic_lfd::sim::demo::PULL_TARGET_RADIUS;
use logic_lfd::sim::{SceneGraph, World};
use logic_lfd::tamp::plan_from_scratch;
use logic_lfd::tamp::streams::{StreamBinder, StreamParams};
use nalgebra::Vector3;

fn model_and_task(b: BenchmarkId, world: &World) -> (DomainModel, Task) {
    let files = b.sources().unwrap();
    let model = DomainModel::new(
        &files.domain,
        "domain.pddl",
        &files.problem,
        "problem.pddl",
        &world.snapshot().predicates,
    )
    .unwrap();
    let objs: Vec<(String, String)> = SceneGraph::objects(world)
        .into_iter()
        .map(|o| (o.name, o.kind))
        .collect();
    let task = model
        .build(&objs, &SceneGraph::from_world(world).to_strings())
        .unwrap();
    (model, task)
}

fn template(b: BenchmarkId) -> World {
    World::from_json(&b.sources().unwrap().scene).unwrap()
}

fn op(task: &Task, name: &str) -> usize {
    task.operators
        .iter()
        .position(|o| o.name == name)
        .unwrap_or_else(|| panic!("no operator {name}"))
}

fn applicable_copies(b: &BannedTask, o: usize, s: &logic_lfd::plan::State) -> usize {
    (0..b.task.operators.len())
        .filter(|&i| b.original(&[i]) == [o] && b.task.operators[i].applicable(s))
        .count()
}

#[test]
fn banning_an_action_at_one_state_keeps_it_applicable_everywhere_else() {
    let world = template(BenchmarkId::B1);
    let (_, task) = model_and_task(BenchmarkId::B1, &world);
    let s0 = task.init.clone();
    let pick_c = op(&task, "(pick panda c)");
    assert!(task.operators[pick_c].applicable(&s0));
    // Another state where (pick panda c) applies: a stacked on b.
    let s1 = replay(
        &task,
        &s0,
        &[op(&task, "(pick panda a)"), op(&task, "(stack panda a b)")],
    )
    .unwrap();
    assert!(task.operators[pick_c].applicable(&s1));
    let mut banned = BannedTask::new(&task);
    banned.ban(pick_c, &s0);
    assert_eq!(applicable_copies(&banned, pick_c, &s0), 0);
    assert!(applicable_copies(&banned, pick_c, &s1) >= 1);
    // Other actions are untouched.
    let pick_a = op(&task, "(pick panda a)");
    assert_eq!(applicable_copies(&banned, pick_a, &s0), 1);
    // A plan on the banned task maps back to a valid plan of the task that avoids (pick c) at s0.
    let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::HMax);
    let r = search(&banned.task, &cfg, &NoClock);
    let ops = banned.original(&r.outcome.plan().expect("a plan").operators);
    assert_ne!(ops[0], pick_c);
    let end = replay(&task, &s0, &ops).unwrap();
    assert!(task.goal.holds(&end));
    // A second ban (another state) keeps it out of both states, and only there.
    let s2 = replay(
        &task,
        &s0,
        &[op(&task, "(pick panda b)"), op(&task, "(stack panda b a)")],
    )
    .unwrap();
    assert!(task.operators[pick_c].applicable(&s2));
    banned.ban(pick_c, &s1);
    assert_eq!(applicable_copies(&banned, pick_c, &s1), 0);
    assert_eq!(applicable_copies(&banned, pick_c, &s0), 0);
    assert!(applicable_copies(&banned, pick_c, &s2) >= 1);
    let r = search(&banned.task, &cfg, &NoClock);
    let ops = banned.original(&r.outcome.plan().expect("a plan").operators);
    let end = replay(&task, &s0, &ops).unwrap();
    assert!(task.goal.holds(&end));
    // One ban more than STATE_BANS bans it everywhere.
    assert_eq!(logic_lfd::lfd::control::STATE_BANS, 2);
    banned.ban(pick_c, &s2);
    for s in [&s0, &s1, &s2] {
        assert_eq!(applicable_copies(&banned, pick_c, s), 0);
    }
}

#[test]
fn tamp_from_scratch_binds_every_benchmark_with_certified_motions() {
    for b in BenchmarkId::ALL {
        let world = template(b);
        let (_, task) = model_and_task(b, &world);
        let mut binder = StreamBinder::new(&world, 1, StreamParams::default());
        let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::HMax);
        let ops = plan_from_scratch(&task, &task.init, &mut binder, &cfg, 4, &NoClock)
            .unwrap_or_else(|e| panic!("{b:?}: {e}"));
        let end = replay(&task, &task.init, &ops).unwrap();
        assert!(task.goal.holds(&end), "{b:?}");
        assert_eq!(binder.bindings.len(), ops.len());
        // Every motion was sampled along its path (1.5 cm steps: dozens per action).
        assert!(
            binder.stats.path_samples >= 10 * ops.len(),
            "{b:?}: {:?}",
            binder.stats
        );
    }
}

#[test]
fn a_carried_block_is_not_swept_through_a_tower() {
    // a is picked at (0.40, −0.25) and put down at (0.30, 0.25): the straight transfer passes
    // (0.35, 0.00). With a three-block tower there the demonstration-like placement is refused.
    let hint = (0.30, 0.25, 0.0);
    let bind = |world: &World| {
        let (_, task) = model_and_task(BenchmarkId::B1, world);
        let ops = [op(&task, "(pick panda a)"), op(&task, "(place panda a)")];
        let hints = [("(place panda a)".to_string(), hint)]
            .into_iter()
            .collect();
        let mut binder = StreamBinder::new(world, 3, StreamParams::default()).with_hints(&hints);
        let r = binder.bind(&task, &ops, ops.len());
        (r, binder.predicted_pose("a"), binder.stats)
    };
    let free = template(BenchmarkId::B1);
    let (r, pose, _) = bind(&free);
    assert_eq!(r, Ok(()));
    let p = pose.unwrap().translation.vector;
    assert!(
        (p.x - hint.0).abs() < 1e-9 && (p.y - hint.1).abs() < 1e-9,
        "{p:?}"
    );

    let mut tower = template(BenchmarkId::B1);
    tower
        .move_block("d", Vector3::new(0.35, 0.0, 0.03))
        .unwrap();
    tower
        .move_block("c", Vector3::new(0.35, 0.0, 0.10))
        .unwrap();
    tower
        .move_block("b", Vector3::new(0.35, 0.0, 0.17))
        .unwrap();
    assert!(SceneGraph::from_world(&tower).contains("(on b c)"));
    let (r, pose, stats) = bind(&tower);
    assert!(stats.rejected_collision >= 1, "{stats:?}");
    if r.is_ok() {
        let p = pose.unwrap().translation.vector;
        assert!(
            (p.x - hint.0).abs() > 1e-6 || (p.y - hint.1).abs() > 1e-6,
            "the swept placement was accepted"
        );
    }
}

#[test]
fn the_pull_stream_predicts_where_the_executor_leaves_the_block() {
    let b = BenchmarkId::B2;
    let mut world = template(b);
    let (_, task) = model_and_task(b, &world);
    let ops = [
        op(&task, "(pick panda hook)"),
        op(&task, "(pull panda hook b)"),
    ];
    let predicted = {
        let mut binder = StreamBinder::new(&world, 1, StreamParams::default());
        binder.bind(&task, &ops, ops.len()).expect("pull certified");
        binder.predicted_pose("b").unwrap().translation.vector
    };
    // One definition of the stroke: the block ends PULL_TARGET_RADIUS from the base axis.
    let base = world.arm_base(0).unwrap().translation.vector;
    let r = ((predicted.x - base.x).powi(2) + (predicted.y - base.y).powi(2)).sqrt();
    assert!(
        (r - PULL_TARGET_RADIUS).abs() < 0.01,
        "predicted radius {r}"
    );
    // The executor does what the stream predicted.
    let files = b.sources().unwrap();
    let skills = SkillLibrary::learn(&files.demo, SkillKind::Lqt, &["hook".to_string()]);
    let params = ExecParams::default();
    for &o in &ops {
        let operator = &task.operators[o];
        let kind = classify(&task, operator, &world).unwrap();
        let mut exec = ActionExec::new(&operator.name, kind, &world, &skills, &params);
        let mut status = ExecStatus::Running;
        for _ in 0..6000 {
            status = exec.tick(&mut world, &skills, &params);
            if status != ExecStatus::Running {
                break;
            }
        }
        assert_eq!(status, ExecStatus::Done, "{}", operator.name);
    }
    let actual = world.body_pose("b").unwrap().translation.vector;
    assert!(
        (actual - predicted).norm() < 0.01,
        "executor left b at {actual:?}, the stream predicted {predicted:?}"
    );
    assert!(SceneGraph::from_world(&world).contains("(inreach panda b)"));
}
