//! The N-block tower tasks (`sim::generate`): generated scenes load and keep the world's
//! invariants, their demonstrations reach the goal in the PDDL model, sessions on them succeed,
//! and the disturbance levels L1–L4 work on them.

use logic_lfd::lfd::{Method, Mode};
use logic_lfd::lfd::{Session, SessionOptions, SessionParams, SkillKind};
use logic_lfd::plan::{validate_names, NoClock};
use logic_lfd::sim::World;
use logic_lfd::sim::{block_names, tower_task};
use logic_lfd::sim::{Benchmark, BenchmarkSources};

/// Checks that `src`'s scene loads with its invariants and that its demonstration is a valid
/// plan of its problem.
fn check_task(b: Benchmark, n: usize, src: &BenchmarkSources) {
    let world = World::from_json(&src.scene).expect("scene loads");
    world.check_invariants().expect("invariants");
    let blocks = world
        .snapshot()
        .bodies
        .iter()
        .filter(|x| x.kind == logic_lfd::sim::BodyKind::Block)
        .count();
    assert_eq!(blocks, n, "{b:?}-{n}");
    let domain = logic_lfd::pddl::parse_domain(&src.domain, "domain.pddl").unwrap();
    let problem = logic_lfd::pddl::parse_problem(&src.problem, "problem.pddl", &domain).unwrap();
    let demo = logic_lfd::sim::demo::from_json(&src.demo).expect("demo parses");
    let plan: Vec<String> = demo.plan().iter().map(|s| s.to_string()).collect();
    let report = validate_names(&domain, &problem, &plan);
    assert!(report.is_valid(), "{b:?}-{n}: {report}");
}

#[test]
fn b1_tower_tasks_from_3_to_12_blocks_are_valid() {
    for n in 3..=12 {
        let src = tower_task(Benchmark::B1, n).unwrap_or_else(|e| panic!("B1-{n}: {e}"));
        check_task(Benchmark::B1, n, &src);
    }
}

#[test]
fn b3_tower_tasks_from_2_to_10_blocks_are_valid() {
    for n in 2..=10 {
        let src = tower_task(Benchmark::B3, n).unwrap_or_else(|e| panic!("B3-{n}: {e}"));
        check_task(Benchmark::B3, n, &src);
    }
}

#[test]
fn block_counts_outside_the_range_and_b2_are_refused() {
    for (b, n) in [
        (Benchmark::B1, 2),
        (Benchmark::B1, 21),
        (Benchmark::B3, 1),
        (Benchmark::B3, 11),
    ] {
        let e = tower_task(b, n).unwrap_err().to_string();
        assert!(e.contains("allowed"), "{e}");
    }
    let e = tower_task(Benchmark::B2, 4).unwrap_err().to_string();
    assert!(e.contains("B2 has no N-block variant"), "{e}");
}

#[test]
fn generation_is_deterministic() {
    let a = tower_task(Benchmark::B1, 4).unwrap();
    let b = tower_task(Benchmark::B1, 4).unwrap();
    assert_eq!(a, b);
    assert_eq!(block_names(3), ["a", "b", "c"]);
}

/// Runs an undisturbed Logic-LfD episode on `src` to its end; whether it succeeded.
fn undisturbed(b: Benchmark, src: &BenchmarkSources) -> bool {
    let opts = SessionOptions {
        benchmark: b,
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed: 1,
        skill: SkillKind::Lqt,
        blocks: None,
    };
    let mut s = Session::with_sources(opts, src, None, None, SessionParams::default()).unwrap();
    for _ in 0..100_000 {
        if s.outcome().is_some() {
            break;
        }
        s.tick_once(&NoClock);
        if let Err(v) = s.world().check_invariants() {
            panic!("{b:?} tick {}: {v:?}", s.tick());
        }
    }
    matches!(s.outcome(), Some(Ok(())))
}

#[test]
fn undisturbed_episodes_on_tall_towers_succeed() {
    for (b, n) in [
        (Benchmark::B1, 4),
        (Benchmark::B1, 8),
        (Benchmark::B1, 12),
        (Benchmark::B3, 4),
        (Benchmark::B3, 8),
    ] {
        let src = tower_task(b, n).unwrap();
        assert!(undisturbed(b, &src), "{b:?}-{n}");
    }
}

#[test]
fn every_disturbance_level_ends_in_success_on_8_and_12_blocks() {
    use logic_lfd::experiments::{run_episode_with_blocks, EpisodeSpec};
    use logic_lfd::lfd::Level;
    for n in [8, 12] {
        for (i, level) in Level::ALL.into_iter().enumerate() {
            let spec = EpisodeSpec {
                benchmark: Benchmark::B1,
                level: Some(level),
                method: Method::LogicLfd,
                mode: Mode::Paper,
                seed: 1 + i as u64,
                scene: None,
                robots: vec![],
            };
            let r = run_episode_with_blocks(&spec, Some(n), SessionParams::default(), &NoClock)
                .unwrap();
            assert!(r.injection.is_some(), "B1-{n} {level:?}: not injected");
            assert!(r.success, "B1-{n} {level:?}: {:?}", r.reason);
        }
    }
}

#[test]
fn every_disturbance_level_generates_tasks_on_5_blocks() {
    use logic_lfd::experiments::initial_scene_for;
    use logic_lfd::lfd::Level;
    for level in [Level::L1, Level::L2, Level::L3, Level::L4] {
        let scene = initial_scene_for(Benchmark::B1, Some(5), level, 3)
            .unwrap_or_else(|e| panic!("{level:?}: {e}"));
        let world = World::from_json(&scene).unwrap();
        world.check_invariants().unwrap();
    }
}

#[test]
fn a_session_with_blocks_uses_the_generated_task() {
    let opts = SessionOptions {
        benchmark: Benchmark::B1,
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed: 1,
        skill: SkillKind::Lqt,
        blocks: Some(5),
    };
    let s = Session::new(opts).unwrap();
    // Two actions per block put on the tower.
    assert_eq!(s.controller().trace().len(), 8);
    let e = logic_lfd::lfd::sources_for(Benchmark::B1, Some(40))
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(e.contains("allowed: 3 to 20"), "{e}");
}

#[test]
fn the_scaling_study_s_default_counts_are_b1_tasks() {
    use logic_lfd::experiments::scaling::DEFAULT_BLOCKS;
    use logic_lfd::sim::{block_range, block_ranges_text};
    let r = block_range(Benchmark::B1).unwrap();
    assert!(
        DEFAULT_BLOCKS.iter().all(|n| r.contains(n)),
        "{DEFAULT_BLOCKS:?}"
    );
    assert_eq!(
        DEFAULT_BLOCKS.last(),
        Some(r.end()),
        "the study reaches the most blocks"
    );
    assert_eq!(block_ranges_text(), "B1: 3 to 20, B3: 2 to 10");
}
