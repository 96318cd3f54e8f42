//! Generated tasks of more than 12 blocks (`sim::generate`): two towers, their bottoms far apart,
//! every block where the arm works it, a demonstration that reaches the goal in the PDDL model
//! and in the simulator with the arm's links clear of the towers, and the towers' tops in reach.

use std::collections::BTreeMap;

use logic_lfd::plan::validate_names;
use logic_lfd::sim::collide;
use logic_lfd::sim::handleable;
use logic_lfd::sim::{block_range, tower_task, TOWER_SPACING};
use logic_lfd::sim::{goal_facts, Benchmark, BenchmarkSources};
use logic_lfd::sim::{SceneGraph, World};
use nalgebra::Isometry3;

/// The towers of `src`'s goal, each top first, from its `(on x y)` facts.
fn goal_towers(src: &BenchmarkSources) -> Vec<Vec<String>> {
    let domain = logic_lfd::pddl::parse_domain(&src.domain, "domain.pddl").unwrap();
    let problem = logic_lfd::pddl::parse_problem(&src.problem, "problem.pddl", &domain).unwrap();
    let on: BTreeMap<String, String> = goal_facts(&domain, &problem)
        .into_iter()
        .filter(|f| f.predicate == "on")
        .map(|f| (f.args[0].clone(), f.args[1].clone()))
        .collect();
    let below: Vec<&String> = on.values().collect();
    // A top stands on something and has nothing on it.
    let mut towers: Vec<Vec<String>> = on
        .keys()
        .filter(|x| !below.contains(x))
        .map(|top| {
            let mut t = vec![top.clone()];
            while let Some(y) = on.get(t.last().unwrap()) {
                t.push(y.clone());
            }
            t
        })
        .collect();
    towers.sort();
    towers
}

fn names(s: &str) -> Vec<String> {
    s.chars().map(|c| c.to_string()).collect()
}

/// Horizontal position of body `x` in `w`.
fn xy(w: &World, x: &str) -> [f64; 2] {
    let p = w.body_pose(x).unwrap().translation.vector;
    [p.x, p.y]
}

/// Replays `src`'s demonstration in its scene; every 5th step, the deepest overlap of an arm
/// link (the base and the hand excepted) with a block it does not hold, and of the hand with a
/// block standing on another away from the column the hand works (more than 5 cm from the TCP
/// in the plane): `(link, hand)` clearances (m, negative: overlap), and the final world.
fn replay_clearances(src: &BenchmarkSources) -> (f64, f64, World) {
    let demo = logic_lfd::sim::demo::from_json(&src.demo).unwrap();
    let mut w = World::from_json(&src.scene)
        .unwrap()
        .with_motions(Benchmark::B1.motions());
    let (mut link, mut hand) = (f64::INFINITY, f64::INFINITY);
    let mut step = 0usize;
    logic_lfd::sim::demo::replay(&mut w, &demo, |w, _, _| {
        step += 1;
        if step % 5 != 0 {
            return Ok(());
        }
        let held = w.held_by(0);
        let tcp = w.tcp_pose(0).unwrap().translation.vector;
        let caps = w.arm_capsules(0);
        for x in w.block_names() {
            if Some(x) == held {
                continue;
            }
            let c = xy(w, x);
            let stacked = SceneGraph::from_world(w)
                .facts
                .iter()
                .any(|f| f.predicate == "on" && f.args[0] == x);
            let away = libm::hypot(c[0] - tcp.x, c[1] - tcp.y) > 0.05;
            for (iso, cuboid) in w.body_shapes(x) {
                for (i, cap) in caps.iter().enumerate().skip(1) {
                    let is_hand = i == caps.len() - 1;
                    if is_hand && !(stacked && away) {
                        continue;
                    }
                    let Some(ct) =
                        collide::contact(&Isometry3::identity(), cap, &iso, &cuboid, 0.05)
                    else {
                        continue;
                    };
                    let best = if is_hand { &mut hand } else { &mut link };
                    *best = best.min(ct.dist);
                }
            }
        }
        Ok(())
    })
    .unwrap();
    (link, hand, w)
}

#[test]
fn b1_takes_up_to_20_blocks_as_two_towers() {
    assert_eq!(block_range(Benchmark::B1).unwrap(), 3..=20);
    for (n, expected) in [
        (13, vec!["abcdefg", "hijklm"]),
        (20, vec!["abcdefghij", "klmnopqrst"]),
    ] {
        let src = tower_task(Benchmark::B1, n).unwrap_or_else(|e| panic!("B1-{n}: {e}"));
        let world = World::from_json(&src.scene)
            .unwrap()
            .with_motions(Benchmark::B1.motions());
        world.check_invariants().expect("invariants");
        assert_eq!(world.block_names().len(), n);
        for x in world.block_names() {
            handleable(&world, x).unwrap_or_else(|e| panic!("B1-{n} {x}: {e}"));
        }
        let towers = goal_towers(&src);
        let expected: Vec<Vec<String>> = expected.into_iter().map(names).collect();
        assert_eq!(towers, expected, "B1-{n}");
        // The bottoms are as far apart as the generator promises.
        let [p, q] = [
            xy(&world, towers[0].last().unwrap()),
            xy(&world, towers[1].last().unwrap()),
        ];
        let apart = libm::hypot(p[0] - q[0], p[1] - q[1]);
        assert!(
            apart >= TOWER_SPACING - 1e-9,
            "B1-{n}: bottoms {apart} m apart"
        );

        // The demonstration is a valid plan of the problem…
        let domain = logic_lfd::pddl::parse_domain(&src.domain, "domain.pddl").unwrap();
        let problem =
            logic_lfd::pddl::parse_problem(&src.problem, "problem.pddl", &domain).unwrap();
        let demo = logic_lfd::sim::demo::from_json(&src.demo).unwrap();
        let plan: Vec<String> = demo.plan().iter().map(|s| s.to_string()).collect();
        assert_eq!(
            plan.len(),
            2 * (n - 2),
            "B1-{n}: a pick and a stack per block"
        );
        let report = validate_names(&domain, &problem, &plan);
        assert!(report.is_valid(), "B1-{n}: {report}");

        // …and, replayed in the simulator, builds the towers with the arm clear of them.
        let (link, hand, end) = replay_clearances(&src);
        assert!(
            link > 0.0,
            "B1-{n}: an arm link cuts {:.1} mm into a block",
            -link * 1e3
        );
        assert!(
            hand > 0.0,
            "B1-{n}: the hand cuts {:.1} mm into a tower",
            -hand * 1e3
        );
        end.check_invariants().expect("invariants after the replay");
        let sg = SceneGraph::from_world(&end);
        for t in &towers {
            for w in t.windows(2) {
                let f = format!("(on {} {})", w[0], w[1]);
                assert!(
                    sg.contains(&f),
                    "B1-{n}: {f} does not hold after the replay"
                );
            }
            // The arm grasps the top where the tower stands, and comes down onto it.
            handleable(&end, &t[0]).unwrap_or_else(|e| panic!("B1-{n} top {}: {e}", t[0]));
        }
    }
}
