//! Logic-LfD end to end: closed-loop episodes for every benchmark × level × method at two seeds
//! (every world invariant after every tick for every method, only the hook's shallow contact with
//! the shelf tolerated; every plan adopted in a tick valid in the PDDL model; the expected outcome
//! and failure reason per method), replay identity, prioritised vs paper mode, and the multi-goal
//! specification on the real B1 PDDL.

use logic_lfd::experiments::EpisodeSpec;
use logic_lfd::lfd::FailReason;
use logic_lfd::lfd::Level;
use logic_lfd::lfd::{
    logic_in, plan_logic_lfd, DemoTrace, Method, Mode, MultiGoalSpec, PlanSource, TaskBuilder,
};
use logic_lfd::lfd::{mix_seed, Session, SessionOptions, SessionParams, SkillKind, StatusKind};
use logic_lfd::plan::{validate_names, Algorithm, HeuristicKind, NoClock, SearchConfig};
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::{SceneGraph, Violation};

use crate::support::invariants::{broken, tolerated, HOOK_SHELF_DEPTH};

/// How an episode ended, as the tests see it: its outcome, or the first tick at which the world
/// broke an invariant (beyond the hook's tolerated contact with the shelf), which ends it as a
/// failure whatever the session would have reported later.
#[derive(Debug)]
enum End {
    Success,
    Failed(FailReason),
    Broke {
        tick: u64,
        violations: Vec<Violation>,
    },
    Unfinished,
}

/// What one episode did, as the tests see it.
struct Run {
    end: End,
    injected: bool,
    actions: usize,
}

impl std::fmt::Display for End {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            End::Success => write!(f, "success"),
            End::Failed(r) => write!(f, "failed: {r}"),
            End::Broke { tick, violations } => {
                let v: Vec<String> = violations.iter().map(|v| v.to_string()).collect();
                write!(f, "broke the world at tick {tick}: {}", v.join("; "))
            }
            End::Unfinished => write!(f, "no outcome"),
        }
    }
}

impl Run {
    fn success(&self) -> bool {
        matches!(self.end, End::Success)
    }

    fn reason(&self) -> Option<&FailReason> {
        match &self.end {
            End::Failed(r) => Some(r),
            _ => None,
        }
    }
}

fn objects(s: &Session) -> Vec<logic_lfd::pddl::ObjectDecl> {
    SceneGraph::objects(s.world())
}

/// Runs an episode like `logic-lfd run` does, checking the world's invariants after every tick
/// and every plan adopted in a tick (Logic-LfD, TAMP, RLDS; linear's only at the start) in the
/// PDDL model from the facts it was planned from.
fn episode(b: Benchmark, level: Level, method: Method, mode: Mode, seed: u64) -> Run {
    let opts = SessionOptions {
        benchmark: b,
        method,
        mode,
        seed,
        skill: SkillKind::Lqt,
        blocks: None,
    };
    let mut s = Session::new(opts).expect("session");
    let n = s.controller().trace().len().max(3);
    let mut next_try = 1 + (mix_seed(seed, 77) % (n as u64 - 2)) as usize;
    let mut injected = false;
    let mut checked = 0;
    for _ in 0..40_000 {
        if s.outcome().is_some() {
            break;
        }
        if !injected && !s.is_executing() && s.actions_done() >= next_try {
            match s.inject(level.as_str()) {
                Ok(_) => injected = true,
                Err(_) => next_try = s.actions_done() + 1,
            }
        }
        let facts = SceneGraph::from_world(s.world()).to_strings();
        let objs = objects(&s);
        s.tick_once(&NoClock);
        let violations = broken(s.world());
        if !violations.is_empty() {
            return Run {
                end: End::Broke {
                    tick: s.tick(),
                    violations,
                },
                injected,
                actions: s.actions_done(),
            };
        }
        let replans = s.controller().replans();
        for (i, r) in replans.iter().enumerate().skip(checked) {
            if method != Method::Linear || i == 0 {
                let problem = s.model().problem(&objs, &facts).expect("problem");
                let report = validate_names(s.model().domain(), &problem, &r.plan);
                assert!(
                    report.is_valid(),
                    "{b:?} {level:?} {method:?} seed {seed}: plan {i} {:?} invalid from {facts:?}: {:?}",
                    r.plan,
                    report.outcome
                );
            }
        }
        checked = replans.len();
    }
    let end = match s.outcome() {
        Some(Ok(())) => End::Success,
        Some(Err(r)) => End::Failed(r.clone()),
        None => End::Unfinished,
    };
    Run {
        end,
        injected,
        actions: s.actions_done(),
    }
}

fn matrix(b: Benchmark) {
    for seed in [1, 3] {
        for level in Level::ALL {
            for method in Method::ALL {
                let r = episode(b, level, method, Mode::Paper, seed);
                let tag = format!(
                    "{b:?} {level:?} {method:?} seed {seed}: {} after {} actions",
                    r.end, r.actions
                );
                // Every level can be injected. On B2 the linear baseline may succeed at L2–L4
                // (its skills re-target the pull to the moved block, and its first grasp opens
                // the hand the L4 block was put into) and RLDS at L4 (docs/levels.md).
                assert!(r.injected, "{tag}: no disturbance injected");
                assert!(!matches!(r.end, End::Unfinished), "{tag}: no outcome");
                let blind_failure = matches!(
                    r.end,
                    End::Broke { .. }
                        | End::Failed(
                            FailReason::GoalNotReached { .. } | FailReason::ActionFailed { .. }
                        )
                );
                match (method, level) {
                    (Method::LogicLfd | Method::Tamp, _) => assert!(r.success(), "{tag}"),
                    (_, Level::L1) => assert!(r.success(), "{tag}"),
                    (Method::Rlds, Level::L2) => assert!(r.success(), "{tag}"),
                    (Method::Rlds, Level::L3) => assert!(
                        matches!(r.reason(), Some(FailReason::NoDemoStateMatches { .. })),
                        "{tag}"
                    ),
                    (Method::Rlds, Level::L4) if b != Benchmark::B2 => assert!(
                        matches!(r.reason(), Some(FailReason::NoDemoStateMatches { .. })),
                        "{tag}"
                    ),
                    (Method::Rlds, Level::L4) => assert!(
                        r.success()
                            || matches!(r.reason(), Some(FailReason::NoDemoStateMatches { .. })),
                        "{tag}"
                    ),
                    // B1's L3 takes b's support away: the blind baseline releases it in the air.
                    (Method::Linear, Level::L3) if b == Benchmark::B1 => assert!(
                        matches!(&r.end, End::Broke { violations, .. }
                            if matches!(violations[..], [Violation::Unsupported { .. }])),
                        "{tag}"
                    ),
                    (Method::Linear, _) if b != Benchmark::B2 => assert!(blind_failure, "{tag}"),
                    (Method::Linear, _) => assert!(r.success() || blind_failure, "{tag}"),
                }
            }
        }
    }
}

/// Only the hook in the shelf, and only to the stated depth, is tolerated.
#[test]
fn only_a_shallow_hook_in_the_shelf_is_tolerated() {
    let w = Benchmark::B2.scene();
    let cut = |a: &str, b: &str, depth: f64| Violation::Interpenetration {
        a: a.into(),
        b: b.into(),
        depth,
    };
    assert!(tolerated(&w, &cut("hook", "shelf", 0.8 * HOOK_SHELF_DEPTH)));
    assert!(tolerated(&w, &cut("shelf", "hook", HOOK_SHELF_DEPTH)));
    assert!(!tolerated(
        &w,
        &cut("hook", "shelf", 1.5 * HOOK_SHELF_DEPTH)
    ));
    assert!(!tolerated(&w, &cut("hook", "a", 0.001)));
    assert!(!tolerated(&w, &cut("a", "shelf", 0.001)));
    assert!(!tolerated(&w, &cut("hook", "table", 0.001)));
}

#[test]
fn b1_every_level_and_method_ends_as_expected() {
    matrix(Benchmark::B1);
}

#[test]
fn b2_every_level_and_method_ends_as_expected() {
    matrix(Benchmark::B2);
}

#[test]
fn b3_every_level_and_method_ends_as_expected() {
    matrix(Benchmark::B3);
}

#[test]
fn the_same_seed_gives_the_identical_episode_and_the_json_replays_exactly() {
    let spec = EpisodeSpec {
        benchmark: Benchmark::B1,
        level: Some(Level::L3),
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed: 5,
        scene: None,
        robots: vec![],
    };
    let a = logic_lfd::experiments::run_episode(&spec, SessionParams::default(), &NoClock).unwrap();
    let b = logic_lfd::experiments::run_episode(&spec, SessionParams::default(), &NoClock).unwrap();
    assert_eq!(
        serde_json::to_string(&a.log).unwrap(),
        serde_json::to_string(&b.log).unwrap()
    );
    assert!(a.success && a.injection.is_some() && a.replans >= 2);
    let json = serde_json::to_string(&a.log).unwrap();
    let replayed = Session::replay(&json).unwrap().log();
    assert_eq!(replayed.canonical(), a.log.canonical());
    // A different seed is a different episode.
    let c = logic_lfd::experiments::run_episode(
        &EpisodeSpec { seed: 6, ..spec },
        SessionParams::default(),
        &NoClock,
    )
    .unwrap();
    assert_ne!(c.log.canonical(), a.log.canonical());
}

#[test]
fn a_user_drag_is_logged_and_replayed() {
    let opts = SessionOptions {
        benchmark: Benchmark::B1,
        method: Method::LogicLfd,
        mode: Mode::Prioritised,
        seed: 2,
        skill: SkillKind::Lqt,
        blocks: None,
    };
    let mut s = Session::new(opts).unwrap();
    let f = s.step(3.0, &NoClock);
    assert_eq!(f.tick, 300);
    assert!(matches!(
        f.status.kind,
        StatusKind::Executing | StatusKind::Replanning
    ));
    // Move block a onto d while the arm works on c: a task-level change.
    let pos = s.world().body_pose("d").unwrap().translation.vector;
    let out = s.perturb("a", [pos.x, pos.y, pos.z + 0.1]);
    assert!(out.is_ok(), "{out:?}");
    assert!(s.perturb("nosuchblock", [0.0, 0.0, 0.5]).is_err());
    for _ in 0..100 {
        s.step(0.5, &NoClock);
        if s.outcome().is_some() {
            break;
        }
    }
    assert_eq!(s.outcome(), Some(&Ok(())));
    let log = s.log();
    assert!(log.replans.len() >= 2, "{:?}", log.replans);
    let replayed = Session::replay(&s.episode_json()).unwrap().log();
    assert_eq!(replayed.canonical(), log.canonical());
}

#[test]
fn a_drag_after_done_reopens_the_episode_which_finishes_again_and_replays() {
    let mut s = Session::new(b1_paper(1)).unwrap();
    let start = s.world().body_pose("a").unwrap().translation.vector;
    s.run_to_end(40_000, &NoClock);
    assert_eq!(s.outcome(), Some(&Ok(())));
    let replans = s.controller().replans().len();
    // Take the top block off the finished tower back to where it started.
    let out = s.perturb("a", [start.x, start.y, start.z + 0.01]);
    assert!(out.is_ok(), "{out:?}");
    assert_eq!(
        s.outcome(),
        None,
        "the drag opens the finished episode again"
    );
    assert_eq!(s.frame().status.kind, StatusKind::Planning);
    s.run_to_end(40_000, &NoClock);
    assert_eq!(s.outcome(), Some(&Ok(())));
    assert!(s.controller().replans().len() > replans);
    let log = s.log();
    let replayed = Session::replay(&s.episode_json()).unwrap().log();
    assert_eq!(replayed.canonical(), log.canonical());
}

fn b1_paper(seed: u64) -> SessionOptions {
    SessionOptions {
        benchmark: Benchmark::B1,
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed,
        skill: SkillKind::Lqt,
        blocks: None,
    }
}

#[test]
fn can_inject_answers_as_inject_would_and_changes_nothing() {
    let mut s = Session::new(b1_paper(1)).unwrap();
    s.step(1.0, &NoClock);
    for level in ["l1", "l2", "l3", "l4"] {
        let before = s.episode_json();
        let can = s.can_inject(level);
        assert_eq!(
            s.episode_json(),
            before,
            "{level}: can_inject changed the session"
        );
        let mut twin = Session::new(b1_paper(1)).unwrap();
        twin.step(1.0, &NoClock);
        assert_eq!(can.is_ok(), twin.inject(level).is_ok(), "{level}");
    }
    assert!(s.can_inject("l9").is_err());
}

#[test]
fn a_drop_no_arm_can_grasp_is_refused_and_changes_nothing() {
    let mut s = Session::new(b1_paper(1)).unwrap();
    let before = s.episode_json();
    // The table corner farthest from the arm's base.
    let snap = serde_json::to_value(s.world().snapshot()).unwrap();
    let base = &snap["arms"][0]["base"]["position"];
    let (bx, by) = (base[0].as_f64().unwrap(), base[1].as_f64().unwrap());
    let table = snap["bodies"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["kind"] == "table")
        .unwrap();
    let p = &table["pose"]["position"];
    let h = &table["shape"]["half_extents"];
    let f = |v: &serde_json::Value, i: usize| v[i].as_f64().unwrap();
    let corner = [-1.0, 1.0]
        .iter()
        .flat_map(|sx| [-1.0, 1.0].map(|sy| (*sx, sy)))
        .map(|(sx, sy)| {
            (
                f(p, 0) + sx * (f(h, 0) - 0.03),
                f(p, 1) + sy * (f(h, 1) - 0.03),
            )
        })
        .max_by(|a, b| {
            let d = |q: &(f64, f64)| libm::hypot(q.0 - bx, q.1 - by);
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    let top = f(p, 2) + f(h, 2);
    let out = s.perturb("a", [corner.0, corner.1, top + 0.03]);
    let why = out.expect_err("a drop out of every arm's reach").reason;
    assert!(why.contains("no arm could grasp it there"), "{why}");
    assert_eq!(s.episode_json(), before);
    let a = s.world().body_pose("a").unwrap().translation.vector;
    let near = s.perturb("a", [a.x + 0.05, a.y, a.z + 0.01]);
    assert!(near.is_ok(), "{near:?}");
    assert_ne!(s.episode_json(), before);
}

#[test]
fn prioritised_mode_never_executes_more_actions_than_paper_mode() {
    for b in Benchmark::ALL {
        for seed in [1, 2, 3] {
            for level in [Level::L2, Level::L3, Level::L4] {
                let p = episode(b, level, Method::LogicLfd, Mode::Paper, seed);
                let q = episode(b, level, Method::LogicLfd, Mode::Prioritised, seed);
                // Known failure (README, "Reproducing the paper's tables"): B2 seed 2 L3, both
                // modes plan the same repair and the demonstrated hook placement is stopped by
                // block b. Any other failure, or a failure of one mode only, fails the test.
                if b == Benchmark::B2 && seed == 2 && level == Level::L3 && !p.success() {
                    assert_eq!(p.reason(), q.reason(), "{b:?} seed {seed} {level:?}");
                    continue;
                }
                assert!(
                    p.success() && q.success(),
                    "{b:?} seed {seed} {level:?}: {} / {}",
                    p.end,
                    q.end
                );
                assert!(
                    q.actions <= p.actions,
                    "{b:?} seed {seed} {level:?}: prioritised {} > paper {}",
                    q.actions,
                    p.actions
                );
            }
        }
    }
}

#[test]
fn multi_goal_plan_plus_suffix_reaches_the_goal_in_the_pddl_model() {
    let b = Benchmark::B1;
    let files = b.sources().unwrap();
    let world = logic_lfd::sim::World::from_json(&files.scene)
        .unwrap()
        .with_motions(b.motions());
    let model = logic_lfd::lfd::DomainModel::new(
        &files.domain,
        "domain.pddl",
        &files.problem,
        "problem.pddl",
        &b.motions().scene_predicates(),
    )
    .unwrap();
    let objs = SceneGraph::objects(&world);
    let facts = SceneGraph::from_world(&world).to_strings();
    let template = model.build(&objs, &facts).unwrap();
    let demo = logic_lfd::lfd::demo_actions(&files.demo).unwrap();
    let trace = DemoTrace::derive(&template, &demo).unwrap();
    // Hand-made states: unseen (needs a prefix), seen (LogicIn), and the goal.
    let cases: [(&[&str], Option<PlanSource>); 3] = [
        (
            &[
                "(on d a)",
                "(ontable a)",
                "(ontable b)",
                "(ontable c)",
                "(clear d)",
                "(clear b)",
                "(clear c)",
                "(handempty panda)",
            ],
            Some(PlanSource::MultiGoal),
        ),
        (
            &[
                "(on c d)",
                "(ontable a)",
                "(ontable b)",
                "(ontable d)",
                "(clear c)",
                "(clear a)",
                "(clear b)",
                "(handempty panda)",
            ],
            Some(PlanSource::LogicIn),
        ),
        (
            &[
                "(on a b)",
                "(on b c)",
                "(on c d)",
                "(ontable d)",
                "(clear a)",
                "(handempty panda)",
            ],
            Some(PlanSource::GoalHolds),
        ),
    ];
    let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::HMax);
    for (facts, source) in cases {
        let facts: Vec<String> = facts.iter().map(|s| s.to_string()).collect();
        let task = model.build(&objs, &facts).unwrap();
        let spec = MultiGoalSpec::new(&task, &trace);
        for mode in [Mode::Paper, Mode::Prioritised] {
            let p = plan_logic_lfd(&task, &spec, &task.init, mode, &cfg, &NoClock).unwrap();
            assert_eq!(Some(p.source), source);
            let names: Vec<String> = p
                .ops
                .iter()
                .map(|&o| task.operators[o].name.clone())
                .collect();
            let problem = model.problem(&objs, &facts).unwrap();
            let report = validate_names(model.domain(), &problem, &names);
            assert!(report.is_valid(), "{names:?}: {:?}", report.outcome);
            if source == Some(PlanSource::LogicIn) {
                assert_eq!(logic_in(&spec, &task.init), Some(2));
                assert_eq!(names.len(), 4);
            }
        }
    }
}

#[test]
fn a_tower_bottom_a_new_prefix_puts_down_goes_back_to_its_demonstrated_spot() {
    let mut s = Session::new(b1_paper(1)).unwrap();
    let home = s.world().body_pose("d").unwrap().translation.vector;
    let a = s.world().body_pose("a").unwrap().translation.vector;
    // d, the tower's bottom, dragged onto a before the arm moves.
    let out = s.perturb("d", [a.x, a.y, a.z + 0.07]);
    assert!(out.is_ok(), "{out:?}");
    s.run_to_end(40_000, &NoClock);
    assert_eq!(s.outcome(), Some(&Ok(())));
    let log = s.log();
    let first = &log.replans[0].plan;
    assert_eq!(
        first[..2],
        ["(unstack panda d a)", "(place panda d)"],
        "{first:?}"
    );
    // The demonstration has no release of d: it goes back where the demonstration had it.
    let d = s.world().body_pose("d").unwrap().translation.vector;
    assert!(
        (d.xy() - home.xy()).norm() < 0.01,
        "d at {d}, shown at {home}"
    );
}
