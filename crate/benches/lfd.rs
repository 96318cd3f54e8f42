//! Logic-LfD timings (criterion): planning from B1 states (LogicIn, multi-goal prefix + suffix,
//! TAMP from scratch on the same state) and one replanning tick of the closed loop.
//!
//! `cargo bench --bench lfd`. Targets (not asserted anywhere): Logic-LfD planning ≤ 1 ms on B1,
//! ≥ 3× faster than our TAMP on the same states; a replanning tick ≤ 16 ms (60 Hz).
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use logic_lfd::lfd::DomainModel;
use logic_lfd::lfd::{demo_actions, Session, SessionOptions, SkillKind};
use logic_lfd::lfd::{plan_logic_lfd, DemoTrace, Method, Mode, MultiGoalSpec, TaskBuilder};
use logic_lfd::plan::{Algorithm, HeuristicKind, NoClock, SearchConfig};
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::{SceneGraph, World};
use logic_lfd::tamp::plan_from_scratch;
use logic_lfd::tamp::{StreamBinder, StreamParams};
use std::hint::black_box;

fn planning(c: &mut Criterion) {
    let files = Benchmark::B1.sources().unwrap();
    let motions = Benchmark::B1.motions();
    let world = World::from_json(&files.scene)
        .unwrap()
        .with_motions(motions.clone());
    let model = DomainModel::new(
        &files.domain,
        "domain.pddl",
        &files.problem,
        "problem.pddl",
        &motions.scene_predicates(),
    )
    .unwrap();
    let objs = SceneGraph::objects(&world);
    let template = model
        .build(&objs, &SceneGraph::from_world(&world).to_strings())
        .unwrap();
    let trace = DemoTrace::derive(&template, &demo_actions(&files.demo).unwrap()).unwrap();
    let cfg = SearchConfig::new(Algorithm::Astar, HeuristicKind::HMax);
    // An unseen state: d on a.
    let facts: Vec<String> = [
        "(on d a)",
        "(ontable a)",
        "(ontable b)",
        "(ontable c)",
        "(clear d)",
        "(clear b)",
        "(clear c)",
        "(handempty panda)",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let task = model.build(&objs, &facts).unwrap();
    let spec = MultiGoalSpec::new(&task, &trace);
    let mut g = c.benchmark_group("b1-planning");
    g.bench_function("logic-lfd multi-goal (paper)", |b| {
        b.iter(|| plan_logic_lfd(&task, &spec, &task.init, Mode::Paper, &cfg, &NoClock).unwrap())
    });
    g.bench_function("logic-lfd multi-goal (prioritised)", |b| {
        b.iter(|| {
            plan_logic_lfd(&task, &spec, &task.init, Mode::Prioritised, &cfg, &NoClock).unwrap()
        })
    });
    g.bench_function("logic-lfd LogicIn (template state)", |b| {
        let spec0 = MultiGoalSpec::new(&template, &trace);
        b.iter(|| {
            plan_logic_lfd(
                &template,
                &spec0,
                &template.init,
                Mode::Paper,
                &cfg,
                &NoClock,
            )
            .unwrap()
        })
    });
    g.bench_function("tamp from scratch (same state)", |b| {
        b.iter(|| {
            let mut binder = StreamBinder::new(&world, 1, StreamParams::default());
            plan_from_scratch(&task, &task.init, &mut binder, &cfg, 8, &NoClock).unwrap()
        })
    });
    g.finish();
}

fn replanning_tick(c: &mut Criterion) {
    let opts = SessionOptions {
        benchmark: Benchmark::B1,
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed: 1,
        skill: SkillKind::Lqt,
        blocks: None,
    };
    let mut base = Session::new(opts).unwrap();
    base.step(3.0, &NoClock);
    // Move a onto d mid-action: the next tick interrupts and the one after replans.
    let d = base.world().body_pose("d").unwrap().translation.vector;
    base.perturb("a", [d.x, d.y, d.z + 0.1]).unwrap();
    c.bench_function(
        "b1 replanning tick (re-observe + replan + bind + first skill step)",
        |b| {
            b.iter_batched(
                || Session::replay(&base.episode_json()).unwrap(),
                |mut s| {
                    s.tick_once(&NoClock);
                    s.tick_once(&NoClock);
                    black_box(s.controller().replans().len())
                },
                criterion::BatchSize::LargeInput,
            )
        },
    );
}

criterion_group!(
    name = benches;
    config = Criterion::default();
    targets = planning, replanning_tick
);
criterion_main!(benches);
