//! The retry loop's bans: an action banned at one state stays applicable everywhere else; an
//! action a movable body blocked is banned until that body itself has moved, so a plan moves it
//! first.

use logic_lfd::lfd::FailReason;
use logic_lfd::lfd::{Method, Mode};
use logic_lfd::lfd::{Session, SessionOptions, SkillKind};
use logic_lfd::plan::replay;
use logic_lfd::plan::{search, Algorithm, HeuristicKind, NoClock, SearchConfig};
use logic_lfd::plan::{BannedTask, Operator, Task};
use logic_lfd::sim::Benchmark;
use logic_lfd::tamp::{moves_body, Binder};
use logic_lfd::tamp::{StreamBinder, StreamParams};

use crate::support::bench::{model_and_task, op, saved_world, template};

fn applicable_copies(b: &BannedTask, o: usize, s: &logic_lfd::plan::State) -> usize {
    (0..b.task.operators.len())
        .filter(|&i| b.original(&[i]) == [o] && b.task.operators[i].applicable(s))
        .count()
}

#[test]
fn banning_an_action_at_one_state_keeps_it_applicable_everywhere_else() {
    let world = template(Benchmark::B1);
    let (_, task) = model_and_task(Benchmark::B1, &world);
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
    assert_eq!(logic_lfd::plan::STATE_BANS, 2);
    banned.ban(pick_c, &s2);
    for s in [&s0, &s1, &s2] {
        assert_eq!(applicable_copies(&banned, pick_c, s), 0);
    }
}

#[test]
fn an_action_a_movable_body_blocked_is_banned_until_that_body_has_moved() {
    let b = Benchmark::B2;
    let motions = b.motions();
    let moves = |_: &Task, o: &Operator, x: &str| moves_body(&motions, o, x);
    let world = template(b);
    let (_, task) = model_and_task(b, &world);
    let s0 = task.init.clone();
    let pull_b = op(&task, "(pull panda hook b)");
    let pick_hook = op(&task, "(pick panda hook)");
    let holding = replay(&task, &s0, &[pick_hook]).unwrap();
    // The same arm holding the hook after a went to the shelf: a has moved.
    let a_shelved = replay(
        &task,
        &s0,
        &[
            op(&task, "(pick panda a)"),
            op(&task, "(place-on-shelf panda a)"),
            pick_hook,
        ],
    )
    .unwrap();
    // Holding the hook after putting it down and taking it again: only the hook moved.
    let hook_again = replay(
        &task,
        &s0,
        &[pick_hook, op(&task, "(place panda hook)"), pick_hook],
    )
    .unwrap();
    assert_eq!(hook_again, holding);
    assert!(task.operators[pull_b].applicable(&a_shelved));

    let mut banned = BannedTask::new(&task);
    banned.ban_failed(pull_b, &holding, &[], &["a".to_string()], &moves);
    assert!(!banned.is_empty());
    let at = |b: &BannedTask, ops: &[usize]| in_banned(b, &s0, ops);
    let holding_b = at(&banned, &[pick_hook]);
    let a_shelved_b = at(
        &banned,
        &[
            op(&task, "(pick panda a)"),
            op(&task, "(place-on-shelf panda a)"),
            pick_hook,
        ],
    );
    let hook_again_b = at(
        &banned,
        &[pick_hook, op(&task, "(place panda hook)"), pick_hook],
    );
    assert_eq!(applicable_copies(&banned, pull_b, &holding_b), 0);
    assert_eq!(applicable_copies(&banned, pull_b, &hook_again_b), 0);
    assert!(applicable_copies(&banned, pull_b, &a_shelved_b) >= 1);
    // A plan on the banned task moves a before the pull.
    let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::HMax);
    let r = search(&banned.task, &cfg, &NoClock);
    let ops = banned.original(&r.outcome.plan().expect("a plan").operators);
    let at_pull = ops.iter().position(|&o| o == pull_b).expect("b is pulled");
    assert!(
        ops[..at_pull]
            .iter()
            .any(|&o| task.operators[o].name == "(pick panda a)"),
        "a plan that does not move a first: {:?}",
        ops.iter()
            .map(|&o| task.operators[o].name.as_str())
            .collect::<Vec<_>>()
    );
    let end = replay(&task, &s0, &ops).unwrap();
    assert!(task.goal.holds(&end));
    // Bans until something moves do not count towards banning the action everywhere.
    for _ in 0..=logic_lfd::plan::STATE_BANS {
        banned.ban_failed(pull_b, &holding, &[], &["a".to_string()], &moves);
    }
    assert!(applicable_copies(&banned, pull_b, &a_shelved_b) >= 1);

    // The action's own arguments are not obstructions to move away: a ban at that state only.
    let mut own = BannedTask::new(&task);
    own.ban_failed(
        pull_b,
        &holding,
        &[],
        &["b".to_string(), "hook".to_string()],
        &moves,
    );
    assert_eq!(applicable_copies(&own, pull_b, &own.lift(&holding)), 0);
    let hook_moved = replay(
        &task,
        &s0,
        &[
            op(&task, "(pick panda a)"),
            op(&task, "(place panda a)"),
            pick_hook,
        ],
    )
    .unwrap();
    assert_eq!(hook_moved, holding, "the same facts: still banned");
    assert!(applicable_copies(&own, pull_b, &own.lift(&a_shelved)) >= 1);
}

/// The state of the banned task that the original operators `ops` reach from `s0` (with the
/// `(*moved* b)` facts they set).
fn in_banned(b: &BannedTask, s0: &logic_lfd::plan::State, ops: &[usize]) -> logic_lfd::plan::State {
    ops.iter()
        .fold(b.lift(s0), |s, &o| b.task.operators[o].apply(&s))
}

/// A block under an overhang: c, on d with b on it, reaches over a, so a cannot be lifted until
/// c has moved. Taking b off c changes c's facts but not where c is, and the goal puts c back on
/// d: a ban on c's facts would allow the first and forbid every way to the goal (no plan); a ban
/// until c has moved does neither.
#[test]
fn an_action_banned_until_a_blocker_moves_waits_for_the_blocker_itself_not_its_facts() {
    let world = template(Benchmark::B1);
    let motions = Benchmark::B1.motions();
    let moves = |_: &Task, o: &Operator, x: &str| moves_body(&motions, o, x);
    let (_, task) = model_and_task(Benchmark::B1, &world);
    let names: Vec<String> = [
        "(clear a)",
        "(clear b)",
        "(handempty panda)",
        "(on b c)",
        "(on c d)",
        "(ontable a)",
        "(ontable d)",
    ]
    .map(String::from)
    .to_vec();
    let s = task.state_from_names(&names).unwrap();
    let pick_a = op(&task, "(pick panda a)");
    let mut banned = BannedTask::new(&task);
    banned.ban_failed(pick_a, &s, &[], &["c".to_string()], &moves);
    let unstacked_b = in_banned(
        &banned,
        &s,
        &[
            op(&task, "(unstack panda b c)"),
            op(&task, "(place panda b)"),
        ],
    );
    assert_eq!(
        applicable_copies(&banned, pick_a, &unstacked_b),
        0,
        "c has not moved"
    );
    let restacked_c = in_banned(
        &banned,
        &s,
        &[
            op(&task, "(unstack panda b c)"),
            op(&task, "(place panda b)"),
            op(&task, "(unstack panda c d)"),
            op(&task, "(stack panda c d)"),
        ],
    );
    assert!(applicable_copies(&banned, pick_a, &restacked_c) >= 1);
    let mut t = banned.task.clone();
    t.init = banned.lift(&s);
    let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut);
    let r = search(&t, &cfg, &NoClock);
    let ops = banned.original(&r.outcome.plan().expect("a plan").operators);
    let end = replay(&task, &s, &ops).expect("the plan replays on the original task");
    assert!(task.goal.holds(&end));
    let first_pick_a = ops.iter().position(|&o| o == pick_a).expect("a is picked");
    assert!(
        ops[..first_pick_a]
            .iter()
            .any(|&o| task.operators[o].name.starts_with("(unstack panda c ")),
        "{:?}",
        ops.iter()
            .map(|&o| task.operators[o].name.as_str())
            .collect::<Vec<_>>()
    );
    // Once the prefix has moved c, a second failure of the same pick (c still in the way where
    // the plan put it) bans it at the facts c has there.
    let prefix = &ops[..first_pick_a];
    let there = replay(&task, &s, prefix).unwrap();
    banned.ban_failed(pick_a, &there, prefix, &["c".to_string()], &moves);
    assert_eq!(
        applicable_copies(&banned, pick_a, &in_banned(&banned, &s, prefix)),
        0
    );
}

/// Runs a Logic-LfD session of benchmark `b` from the saved world `name` to its end, checking
/// the world's invariants every tick; its outcome.
fn run_from_saved_world(b: Benchmark, name: &str) -> Option<Result<(), FailReason>> {
    let scene = serde_json::to_string(&saved_world(name).snapshot()).unwrap();
    let options = SessionOptions {
        benchmark: b,
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed: 1,
        skill: SkillKind::Lqt,
        blocks: None,
    };
    let mut s = Session::from_scene(options, &scene, None).unwrap();
    for _ in 0..12_000 {
        if s.outcome().is_some() {
            break;
        }
        s.tick_once(&NoClock);
        assert_eq!(s.world().check_invariants(), Ok(()), "tick {}", s.tick());
    }
    s.outcome().cloned()
}

#[test]
fn a_block_under_an_overhang_is_freed_by_moving_the_block_over_it() {
    // Found by the soak.
    // c, on d with b on it, reaches 1.3 cm over a beside the tower, so a cannot be lifted. The
    // pick is banned until c has moved: c's own moves count (and a's, for a second ban with the
    // tower rebuilt beside it), not changes of c's facts. Taking b off c does not move c, and c
    // put back on d, where the goal wants it, does.
    let world = saved_world("b1-tower-overhanging-a");
    let (_, task) = model_and_task(Benchmark::B1, &world);
    let mut binder = StreamBinder::new(&world, 1, StreamParams::default());
    let pick_a = [op(&task, "(pick panda a)")];
    let failure = binder.bind(&task, &pick_a, 1).unwrap_err();
    assert_eq!(failure.action, 0);
    assert_eq!(failure.blockers, vec!["c".to_string()]);
    assert_eq!(
        run_from_saved_world(Benchmark::B1, "b1-tower-overhanging-a"),
        Some(Ok(()))
    );
}
