//! Simulator: kinematics, contact rules, scene graph, snapshots, benchmarks, disturbances.

use logic_lfd::sim::benchmark::Benchmark;
use logic_lfd::sim::demo;
use logic_lfd::sim::disturb;
use logic_lfd::sim::geometry;
use logic_lfd::sim::panda::{self, IkParams};
use logic_lfd::sim::snapshot::WorldSnapshot;
use logic_lfd::sim::{GripperCommand, SceneGraph, World};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// The fluent facts of a PDDL problem's `:init`, read naively (one `(pred args…)` per fact),
/// minus the given static predicates.
fn init_fluents(problem: &str, statics: &[&str]) -> Vec<String> {
    let start = problem.find("(:init").expect("init");
    let rest = &problem[start + 6..];
    let end = rest.find("(:goal").expect("goal");
    let body = &rest[..end];
    let mut out = Vec::new();
    let mut depth = 0;
    let mut cur = String::new();
    for ch in body.chars() {
        match ch {
            '(' => {
                depth += 1;
                cur.clear();
                cur.push('(');
            }
            ')' if depth > 0 => {
                depth -= 1;
                cur.push(')');
                let words: Vec<&str> = cur[1..cur.len() - 1].split_whitespace().collect();
                if !words.is_empty() && !statics.contains(&words[0]) {
                    out.push(format!("({})", words.join(" ")));
                }
                cur.clear();
            }
            _ if depth > 0 => cur.push(ch),
            _ => {}
        }
    }
    out.sort();
    out
}

#[test]
fn template_scenes_are_valid_and_their_facts_equal_the_problem_init() {
    for b in Benchmark::ALL {
        let w = b.scene();
        w.check_invariants()
            .unwrap_or_else(|v| panic!("{b:?}: {v:?}"));
        let mut facts = SceneGraph::from_world(&w).to_strings();
        facts.sort();
        let want = init_fluents(b.problem_pddl(), &["reaches"]);
        assert_eq!(facts, want, "{b:?}");
    }
}

#[test]
fn snapshot_round_trip_is_identity() {
    for b in Benchmark::ALL {
        let w = b.scene();
        let s1 = w.snapshot();
        let json = serde_json::to_string(&s1).unwrap();
        let s2: WorldSnapshot = serde_json::from_str(&json).unwrap();
        let w2 = World::from_snapshot(&s2).unwrap();
        assert_eq!(w2.snapshot(), s1, "{b:?}");
    }
}

#[test]
fn replaying_each_committed_demo_reaches_the_goal_with_invariants_at_every_step() {
    for b in Benchmark::ALL {
        let d = demo::committed(b).unwrap_or_else(|e| panic!("{b:?}: {e}"));
        assert_eq!(d.benchmark, b.dir_name());
        let mut w = b.scene();
        let mut steps = 0usize;
        demo::replay(&mut w, &d, |w, a, k| {
            steps += 1;
            w.check_invariants()
                .map_err(|v| demo::DemoError::Invariant {
                    action: a.action.clone(),
                    step: k,
                    violations: v,
                })
        })
        .unwrap_or_else(|e| panic!("{b:?}: {e}"));
        assert!(steps > 500, "{b:?}: only {steps} steps");
        let sg = SceneGraph::from_world(&w);
        for g in b.goal() {
            assert!(
                sg.facts.contains(&g),
                "{b:?}: goal {g} missing in {:?}",
                sg.to_strings()
            );
        }
        // Every hand is empty at the end and nothing was lost.
        for arm in 0..w.arm_names().len() {
            assert_eq!(w.held_by(arm), None);
        }
    }
}

#[test]
fn demo_samples_are_relative_to_the_anchor_object() {
    // At the grasp key point of a pick, the TCP is at the picked block's centre (anchor origin).
    let d = demo::committed(Benchmark::B1).unwrap();
    let pick = &d.actions[0];
    assert_eq!(pick.name, "pick");
    let k = pick
        .key_points
        .iter()
        .find(|k| k.label == "grasp")
        .unwrap()
        .step;
    let s = pick.samples[k];
    assert!(
        s[0].abs() < 0.004 && s[1].abs() < 0.004 && s[2].abs() < 0.004,
        "{s:?}"
    );
    // The first sample is far from the block (the arm starts at its ready pose).
    assert!(pick.samples[0][2] > 0.2, "{:?}", pick.samples[0]);
}

#[test]
fn ik_round_trip_within_1mm_and_1deg_for_sampled_reachable_poses() {
    let base = Isometry3::identity();
    let params = IkParams::default();
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    let mut solved = 0;
    for _ in 0..60 {
        // Sample a configuration, take its TCP pose: reachable by construction.
        let mut q = [0.0; 7];
        for (k, v) in q.iter_mut().enumerate() {
            let (lo, hi) = (panda::JOINT_LOWER[k], panda::JOINT_UPPER[k]);
            *v = rng.random_range(lo + 0.2 * (hi - lo)..hi - 0.2 * (hi - lo));
        }
        let target = panda::forward_kinematics(&base, &q);
        // Solve from the ready pose, not from q.
        let sol = panda::inverse_kinematics(&base, &target, &panda::READY, &params)
            .unwrap_or_else(|e| panic!("{q:?}: {e}"));
        let got = panda::forward_kinematics(&base, &sol.joints);
        let dp = (got.translation.vector - target.translation.vector).norm();
        let da = (got.rotation * target.rotation.inverse()).angle();
        assert!(dp < 1e-3, "position error {dp}");
        assert!(da < 1f64.to_radians(), "orientation error {da}");
        for k in 0..7 {
            assert!(
                sol.joints[k] >= panda::JOINT_LOWER[k] && sol.joints[k] <= panda::JOINT_UPPER[k]
            );
        }
        solved += 1;
    }
    assert_eq!(solved, 60);
}

#[test]
fn ik_refuses_unreachable_poses_with_a_residual() {
    let base = Isometry3::identity();
    let params = IkParams::default();
    for p in [[1.5, 0.0, 0.3], [0.0, 0.0, 1.6], [0.3, 0.9, -0.2]] {
        let target = Isometry3::from_parts(
            Translation3::new(p[0], p[1], p[2]),
            panda::down_orientation(0.0),
        );
        let err = panda::inverse_kinematics(&base, &target, &panda::READY, &params).unwrap_err();
        assert!(err.position_error > 0.1, "{p:?}: {err}");
        // The best configuration is within limits and really has that residual.
        let got = panda::forward_kinematics(&base, &err.best_joints);
        let dp = (got.translation.vector - target.translation.vector).norm();
        assert!((dp - err.position_error).abs() < 1e-9);
    }
    // World::reachable agrees for B1's arm.
    let w = Benchmark::B1.scene();
    let far = Isometry3::from_parts(
        Translation3::new(1.2, 0.0, 0.03),
        panda::down_orientation(0.0),
    );
    assert!(w.reachable(0, &far).is_err());
    let near = geometry::grasp_pose(&w, 0, "a").unwrap();
    assert!(w.reachable(0, &near).is_ok());
}

/// Builds B1 and rearranges blocks through user moves.
fn b1_with(moves: &[(&str, [f64; 3])]) -> World {
    let mut w = Benchmark::B1.scene();
    for (name, p) in moves {
        w.move_block(name, Vector3::new(p[0], p[1], p[2]))
            .unwrap_or_else(|e| panic!("{e}"));
    }
    w
}

fn facts(w: &World) -> Vec<String> {
    let mut f = SceneGraph::from_world(w).to_strings();
    f.sort();
    f
}

#[test]
fn scene_graph_reports_on_ontable_clear_from_geometry() {
    // c on d, b on c (dropped from above: they settle).
    let w = b1_with(&[("c", [0.55, 0.26, 0.3]), ("b", [0.551, 0.262, 0.4])]);
    w.check_invariants().unwrap();
    let f = facts(&w);
    for want in [
        "(on c d)",
        "(on b c)",
        "(ontable d)",
        "(ontable a)",
        "(clear a)",
        "(clear b)",
        "(handempty panda)",
    ] {
        assert!(f.contains(&want.to_string()), "{want} missing in {f:?}");
    }
    for not in [
        "(clear c)",
        "(clear d)",
        "(ontable c)",
        "(ontable b)",
        "(on c b)",
    ] {
        assert!(!f.contains(&not.to_string()), "{not} wrongly in {f:?}");
    }
    assert_eq!(f.len(), 7, "{f:?}");
}

#[test]
fn scene_graph_reports_holding_and_handempty() {
    let (mut w, g) = holding(Benchmark::B1, "a");
    let f = facts(&w);
    assert!(f.contains(&"(holding panda a)".to_string()), "{f:?}");
    assert!(!f.contains(&"(handempty panda)".to_string()));
    assert!(
        !f.iter()
            .any(|s| s.contains(" a)") && !s.starts_with("(holding")),
        "{f:?}"
    );
    // Lift and release over b: a lands on b.
    let bp = w.body_pose("b").unwrap().translation.vector;
    let up = Isometry3::from_parts(Translation3::new(bp.x, bp.y, 0.2), g.rotation);
    for _ in 0..300 {
        w.command_arm(0, up, GripperCommand::Close).unwrap();
        w.step();
        w.check_invariants().unwrap();
    }
    assert_eq!(w.held_by(0), Some("a"), "still held after moving");
    let ev = {
        w.command_arm(0, up, GripperCommand::Open).unwrap();
        w.step()
    };
    assert!(
        ev.iter().any(|e| e.to_string().contains("onto b")),
        "{ev:?}"
    );
    let f = facts(&w);
    assert!(
        f.contains(&"(on a b)".to_string()) && f.contains(&"(handempty panda)".to_string()),
        "{f:?}"
    );
    w.check_invariants().unwrap();
}

#[test]
fn scene_graph_reports_onshelf_and_inreach_in_b2() {
    let mut w = Benchmark::B2.scene();
    let f = facts(&w);
    assert!(f.contains(&"(inreach panda a)".to_string()));
    assert!(
        !f.contains(&"(inreach panda b)".to_string()),
        "b starts out of reach"
    );
    // Drop a onto the shelf; pull b in by hand: onshelf a, inreach b.
    w.move_block("a", Vector3::new(0.30, -0.50, 0.3)).unwrap();
    w.move_block("b", Vector3::new(0.60, 0.05, 0.1)).unwrap();
    let f = facts(&w);
    for want in [
        "(onshelf a)",
        "(inreach panda a)",
        "(inreach panda b)",
        "(ontable b)",
        "(ontable hook)",
        "(inreach panda hook)",
    ] {
        assert!(f.contains(&want.to_string()), "{want} missing in {f:?}");
    }
    assert!(!f.contains(&"(ontable a)".to_string()));
}

#[test]
fn scene_graph_reports_regions_in_b3() {
    let mut w = Benchmark::B3.scene();
    w.move_block("a", Vector3::new(0.38, 0.0, 0.1)).unwrap();
    w.move_block("b", Vector3::new(0.45, -0.6, 0.1)).unwrap();
    let f = facts(&w);
    for want in [
        "(at a handover)",
        "(at b right-table)",
        "(ontable a)",
        "(handempty left)",
        "(handempty right)",
    ] {
        assert!(f.contains(&want.to_string()), "{want} missing in {f:?}");
    }
    w.move_block("a", Vector3::new(0.45, -0.6, 0.3)).unwrap();
    let f = facts(&w);
    assert!(
        f.contains(&"(on a b)".to_string()) && f.contains(&"(at a right-table)".to_string()),
        "{f:?}"
    );
}

#[test]
fn user_moves_that_interpenetrate_or_float_are_refused_and_change_nothing() {
    let mut w = Benchmark::B1.scene();
    let before = w.snapshot();
    // Into block b.
    let bp = w.body_pose("b").unwrap().translation.vector;
    let e = w
        .move_block("a", bp + Vector3::new(0.02, 0.0, 0.0))
        .unwrap_err();
    assert!(e.reason.contains("interpenetrate b"), "{e}");
    // Off the table: nothing under it.
    let e = w.move_block("a", Vector3::new(2.0, 0.0, 0.2)).unwrap_err();
    assert!(e.reason.contains("fall"), "{e}");
    // Half over the edge of block d: would tip over.
    let dp = w.body_pose("d").unwrap().translation.vector;
    let e = w
        .move_block("a", dp + Vector3::new(0.045, 0.0, 0.2))
        .unwrap_err();
    assert!(e.reason.contains("tip"), "{e}");
    // Into the table top.
    let e = w
        .move_block("a", Vector3::new(0.4, -0.25, 0.0))
        .unwrap_err();
    assert!(e.reason.contains("table"), "{e}");
    // Fixed bodies and unknown names.
    assert!(w.move_block("table", Vector3::new(0.0, 0.0, 0.5)).is_err());
    assert!(w.move_block("zz", Vector3::new(0.0, 0.0, 0.5)).is_err());
    assert_eq!(w.snapshot(), before);
    // An accepted move settles onto the support below.
    let out = w.move_block("a", dp + Vector3::new(0.0, 0.0, 0.3)).unwrap();
    assert_eq!(out.support, "d");
    assert!((out.to[2] - 0.09).abs() < 1e-6, "{out:?}");
    w.check_invariants().unwrap();
}

#[test]
fn moving_a_block_from_under_another_lets_the_upper_one_settle() {
    let mut w = b1_with(&[("c", [0.55, 0.26, 0.3])]);
    assert!(facts(&w).contains(&"(on c d)".to_string()));
    let out = w.move_block("d", Vector3::new(0.40, 0.40, 0.1)).unwrap();
    assert_eq!(out.also_moved.len(), 1, "{out:?}");
    assert!((out.also_moved[0].1[2] - 0.03).abs() < 1e-6);
    let f = facts(&w);
    assert!(
        f.contains(&"(ontable c)".to_string()) && f.contains(&"(ontable d)".to_string()),
        "{f:?}"
    );
    w.check_invariants().unwrap();
}

#[test]
fn bad_scene_json_names_the_body_and_the_field() {
    let good = Benchmark::B1.scene().to_json();
    let e = World::from_json("{ not json").unwrap_err();
    assert!(e.path.starts_with("line 1"), "{e}");
    // Overlapping blocks.
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    let i = s.bodies.iter().position(|b| b.name == "b").unwrap();
    let a = s.bodies.iter().position(|b| b.name == "a").unwrap();
    s.bodies[i].pose.position = s.bodies[a].pose.position;
    let e = World::from_snapshot(&s).unwrap_err();
    assert!(
        e.to_string().contains("\"a\"") && e.to_string().contains("interpenetrate"),
        "{e}"
    );
    // A block in the air.
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.bodies[i].pose.position[2] = 0.3;
    let e = World::from_snapshot(&s).unwrap_err();
    assert!(
        e.path.contains("\"b\"") && e.path.ends_with(".pose") && e.message.contains("in the air"),
        "{e}"
    );
    // Unknown held body; bad quaternion; duplicate name; joint out of limits; unknown predicate.
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.arms[0].holding = Some("zz".into());
    assert!(World::from_snapshot(&s)
        .unwrap_err()
        .to_string()
        .contains("arms[0] \"panda\".holding"));
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.bodies[i].pose.quaternion = [0.0; 4];
    assert!(World::from_snapshot(&s)
        .unwrap_err()
        .path
        .ends_with("\"b\".pose.quaternion"));
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.bodies[i].name = "a".into();
    assert!(World::from_snapshot(&s)
        .unwrap_err()
        .message
        .contains("already used"));
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.arms[0].joints[3] = 0.5;
    assert!(World::from_snapshot(&s)
        .unwrap_err()
        .path
        .ends_with("joints[3]"));
    let mut s: WorldSnapshot = serde_json::from_str(&good).unwrap();
    s.predicates.push("above".into());
    assert!(World::from_snapshot(&s)
        .unwrap_err()
        .message
        .contains("unknown predicate"));
    // And the good one loads.
    World::from_json(&good).unwrap();
}

#[test]
fn committed_scene_json_files_match_the_builders() {
    for b in Benchmark::ALL {
        let path = format!(
            "{}/../domains/{}/scene.json",
            env!("CARGO_MANIFEST_DIR"),
            b.dir_name()
        );
        let text = std::fs::read_to_string(&path).unwrap();
        let w = World::from_json(&text).unwrap_or_else(|e| panic!("{path}: {e}"));
        assert_eq!(
            w.snapshot(),
            b.scene_snapshot(),
            "{path} is stale: run the record_demos example"
        );
    }
}

#[test]
fn the_hook_pushes_a_block_its_blade_sweeps_into() {
    // Hold the hook in place of the demo's contact pose behind b, then pull towards the base.
    let (mut w, _) = holding(Benchmark::B2, "hook");
    let bp = w.body_pose("b").unwrap();
    // Teleport to the contact pose (lifted first so nothing is swept on the way).
    let (tc, tp) = at_stroke_start(&mut w, &bp);
    let before = w.body_pose("b").unwrap().translation.vector;
    let mut pushed = false;
    stroke(&mut w, &tc, &tp, |_, events| pushed |= !events.is_empty());
    assert!(pushed);
    let after = w.body_pose("b").unwrap().translation.vector;
    let r = |v: Vector3<f64>| libm::hypot(v.x, v.y);
    assert!(
        (r(after) - 0.6).abs() < 0.01 && r(before) > 0.9,
        "{before} -> {after}"
    );
    assert!((after.y - before.y).abs() < 0.05 && (after.z - before.z).abs() < 1e-9);
    assert!(facts(&w).contains(&"(inreach panda b)".to_string()));
}

mod pddl_models {
    //! The benchmark PDDL, the demos and the scene graph agree.
    use super::*;
    use logic_lfd::plan::{self, NoClock, SearchConfig, SearchOutcome, State, Task};

    fn task(b: Benchmark) -> Task {
        let dom = logic_lfd::pddl::parse_domain(b.domain_pddl(), "domain.pddl")
            .unwrap_or_else(|e| panic!("{b:?} domain: {e}"));
        let prob = logic_lfd::pddl::parse_problem(b.problem_pddl(), "problem.pddl", &dom)
            .unwrap_or_else(|e| panic!("{b:?} problem: {e}"));
        plan::ground(&dom, &prob).unwrap_or_else(|e| panic!("{b:?} ground: {e}"))
    }

    fn state_of(t: &Task, w: &World) -> State {
        t.state_from_names(&SceneGraph::from_world(w).to_strings())
            .expect("scene-graph facts are facts of the task")
    }

    #[test]
    fn each_benchmark_parses_grounds_and_its_scene_facts_equal_the_init_fluents() {
        for b in Benchmark::ALL {
            let t = task(b);
            let w = b.scene();
            let sg = SceneGraph::from_world(&w).to_strings();
            // Fluents: equal as sets.
            assert_eq!(
                t.state_names(&state_of(&t, &w)),
                t.state_names(&t.init),
                "{b:?}"
            );
            // Statics: the benchmark's extra static facts plus the ones the scene graph reports
            // (B2's `(inreach panda hook)`: nothing changes it) are exactly the task's.
            let mut statics: Vec<String> = b.static_facts().iter().map(|f| f.to_string()).collect();
            statics.extend(sg.iter().filter(|f| t.fact_id(f).is_none()).cloned());
            statics.sort();
            let mut ts = t.static_facts.clone();
            ts.sort();
            assert_eq!(statics, ts, "{b:?} static facts");
            // The goal facts are the problem's goal.
            let mut g = t.empty_state();
            for f in b.goal() {
                g.insert(t.fact_id(&f.to_string()).unwrap());
            }
            assert!(t.goal.holds(&g), "{b:?}");
        }
    }

    #[test]
    fn each_demo_is_a_valid_plan_and_the_simulated_facts_follow_the_pddl_states() {
        for b in Benchmark::ALL {
            let t = task(b);
            let d = demo::committed(b).unwrap();
            // PDDL replay with Operator::apply.
            let mut s = t.init.clone();
            let mut states = vec![s.clone()];
            for a in &d.actions {
                let op = t
                    .operators
                    .iter()
                    .find(|o| o.name == a.action)
                    .unwrap_or_else(|| panic!("{b:?}: no operator {}", a.action));
                assert!(op.applicable(&s), "{b:?}: {} not applicable", a.action);
                s = op.apply(&s);
                states.push(s.clone());
            }
            assert!(t.goal.holds(&s), "{b:?}: demo does not reach the goal");
            // Simulated replay: after each action the scene graph equals the PDDL state.
            let mut w = b.scene();
            assert_eq!(state_of(&t, &w), states[0]);
            let mut k = 0;
            demo::replay(&mut w, &d, |w, a, step| {
                if step + 1 == a.samples.len() {
                    k += 1;
                    let got = state_of(&t, w);
                    assert_eq!(
                        t.state_names(&got),
                        t.state_names(&states[k]),
                        "{b:?}: after {}",
                        a.action
                    );
                }
                Ok(())
            })
            .unwrap();
            assert_eq!(k, d.actions.len());
        }
    }

    #[test]
    fn the_planner_solves_each_template_task_in_the_demo_length() {
        for b in Benchmark::ALL {
            let t = task(b);
            let r = plan::search(&t, &SearchConfig::default(), &NoClock);
            let SearchOutcome::Plan(p) = r.outcome else {
                panic!("{b:?}: {:?}", r.outcome)
            };
            let d = demo::committed(b).unwrap();
            assert_eq!(p.operators.len(), d.actions.len(), "{b:?}");
        }
    }
}

mod disturbances {
    //! Every injector delivers its promise.
    use super::*;
    use logic_lfd::sim::disturb::{self, Level};
    use std::collections::BTreeSet;

    fn fset(w: &World) -> BTreeSet<String> {
        SceneGraph::from_world(w).to_strings().into_iter().collect()
    }

    #[test]
    fn every_level_keeps_its_promise_on_every_benchmark() {
        for b in Benchmark::ALL {
            let states = demo::demo_states(b).unwrap();
            assert_eq!(states.len(), demo::committed(b).unwrap().actions.len() + 1);
            for seed in 0..4 {
                for level in Level::ALL {
                    let mut w = b.scene();
                    let before = fset(&w);
                    let nblocks = w.block_names().len();
                    let d = disturb::inject(&mut w, b, level, &states, seed)
                        .unwrap_or_else(|e| panic!("{b:?} {level:?} seed {seed}: {e}"));
                    w.check_invariants()
                        .unwrap_or_else(|v| panic!("{b:?} {level:?}: {v:?}"));
                    let after = fset(&w);
                    assert_eq!(d.facts_after, after.iter().cloned().collect::<Vec<_>>());
                    assert_eq!(d.facts_before, before.iter().cloned().collect::<Vec<_>>());
                    assert!(!d.description.is_empty());
                    match level {
                        Level::L1 => {
                            assert_eq!(after, before, "{b:?} L1 seed {seed}");
                            assert!(!d.moves.is_empty());
                        }
                        Level::L2 => {
                            assert_ne!(after, before, "{b:?} L2 seed {seed}");
                            assert!(states.contains(&after), "{b:?} L2 seed {seed}: {after:?}");
                        }
                        Level::L3 => {
                            assert!(!states.contains(&after), "{b:?} L3 seed {seed}: {after:?}");
                        }
                        Level::L4 => {
                            assert_eq!(w.block_names().len(), nblocks + 1);
                            assert_eq!(d.added.len(), 1);
                            let e = &d.added[0];
                            assert!(
                                after.iter().any(|f| f.contains(&format!(" {e}"))),
                                "{after:?}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn injection_is_deterministic_in_its_seed() {
        let states = demo::demo_states(Benchmark::B3).unwrap();
        let run = |seed| {
            let mut w = Benchmark::B3.scene();
            disturb::inject(&mut w, Benchmark::B3, Level::L3, &states, seed).unwrap();
            w.snapshot()
        };
        assert_eq!(run(5), run(5));
        assert_ne!(run(5), run(6));
    }
}

mod task_generator {
    //! Table I tasks: the promised level, valid worlds, solvable PDDL problems.
    use super::*;
    use logic_lfd::plan::{self, NoClock, SearchConfig, SearchOutcome};
    use logic_lfd::sim::disturb::Level;
    use logic_lfd::sim::tasks;

    #[test]
    fn generated_tasks_load_and_their_problems_parse_and_are_solvable() {
        for b in Benchmark::ALL {
            let ts = tasks::generate_table1(b, 12, 3).unwrap_or_else(|e| panic!("{b:?}: {e}"));
            assert_eq!(ts.len(), 12);
            let dom = logic_lfd::pddl::parse_domain(b.domain_pddl(), "domain.pddl").unwrap();
            for t in &ts {
                assert_eq!(t.level, Level::ALL[t.index % 4]);
                let w = World::from_snapshot(&t.scene)
                    .unwrap_or_else(|e| panic!("{}: {e}", t.description));
                w.check_invariants().unwrap();
                let blocks = w.block_names().len();
                let want = b.blocks().len() + usize::from(t.level == Level::L4);
                assert_eq!(blocks, want, "{b:?} {:?}", t.level);
                let prob = logic_lfd::pddl::parse_problem(&t.problem_pddl, "task.pddl", &dom)
                    .unwrap_or_else(|e| panic!("{}\n{e}", t.problem_pddl));
                let task = plan::ground(&dom, &prob).unwrap();
                // The problem's init is the scene graph of the world.
                assert_eq!(
                    task.state_names(&task.state_from_names(&t.facts).unwrap()),
                    task.state_names(&task.init)
                );
                let r = plan::search(&task, &SearchConfig::default(), &NoClock);
                assert!(
                    matches!(r.outcome, SearchOutcome::Plan(_)),
                    "{b:?} {}: {:?}",
                    t.description,
                    r.outcome
                );
            }
        }
    }

    #[test]
    fn task_generation_is_deterministic() {
        let a = tasks::generate(Benchmark::B1, Level::L3, 3, 9).unwrap();
        let b = tasks::generate(Benchmark::B1, Level::L3, 3, 9).unwrap();
        assert_eq!(a, b);
        assert_ne!(
            a[0].facts,
            tasks::generate(Benchmark::B1, Level::L3, 1, 10).unwrap()[0].facts
        );
    }
}

#[test]
fn cli_scene_facts_and_check() {
    let exe = env!("CARGO_BIN_EXE_logic-lfd");
    let scene = format!(
        "{}/../domains/b1-tower/scene.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let out = std::process::Command::new(exe)
        .args(["scene", "facts", &scene])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(text.lines().count(), 9, "{text}");
    assert!(text.contains("(ontable a)"));
    // A block in the air: exit 2, the message names the file, the body and the field.
    let mut s: WorldSnapshot =
        serde_json::from_str(&std::fs::read_to_string(&scene).unwrap()).unwrap();
    s.bodies[2].pose.position[2] = 0.5;
    let dir = std::env::temp_dir().join(format!("logic-lfd-sim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.json");
    std::fs::write(&bad, serde_json::to_string(&s).unwrap()).unwrap();
    let out = std::process::Command::new(exe)
        .args(["scene", "check", bad.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("bad.json: bodies[2]")
            && err.contains(".pose: ")
            && err.contains("in the air"),
        "{err}"
    );
    assert!(!err.contains("panicked"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_block_released_over_nothing_is_lost_and_the_invariants_say_so() {
    let mut w = Benchmark::B1.scene();
    // Closing on nothing grasps nothing.
    let home = w.tcp_pose(0).unwrap();
    w.command_arm(0, home, GripperCommand::Close).unwrap();
    let ev = w.step();
    assert!(
        ev.iter()
            .any(|e| e.to_string().contains("closed on nothing")),
        "{ev:?}"
    );
    assert_eq!(w.held_by(0), None);
    // Grasp a, carry it beyond the table's edge (y < -0.6), release.
    w.command_arm(0, home, GripperCommand::Open).unwrap();
    for _ in 0..30 {
        w.step();
    }
    let g = geometry::grasp_pose(&w, 0, "a").unwrap();
    w.set_joints(0, w.reachable(0, &g).unwrap().joints).unwrap();
    w.command_arm(0, g, GripperCommand::Close).unwrap();
    w.step();
    assert_eq!(w.held_by(0), Some("a"));
    let out = Isometry3::from_parts(Translation3::new(0.3, -0.68, 0.15), g.rotation);
    w.set_joints(0, w.reachable(0, &out).unwrap().joints)
        .unwrap();
    w.check_invariants().unwrap();
    w.command_arm(0, out, GripperCommand::Open).unwrap();
    let ev = w.step();
    assert!(
        ev.iter()
            .any(|e| matches!(e, logic_lfd::sim::WorldEvent::Lost { body, .. } if body == "a")),
        "{ev:?}"
    );
    assert!(w.is_lost("a"));
    let v = w.check_invariants().unwrap_err();
    assert!(v
        .iter()
        .any(|x| matches!(x, logic_lfd::sim::Violation::Lost { body } if body == "a")));
    assert!(
        !facts(&w).iter().any(|f| f.contains(" a")),
        "a lost has no facts"
    );
}

#[test]
fn an_arm_commanded_through_the_table_stops_at_its_top() {
    let mut w = Benchmark::B1.scene();
    let g = geometry::grasp_pose(&w, 0, "a").unwrap();
    // 25 cm below the table top, well inside the reach of the links.
    let below = Isometry3::from_parts(Translation3::new(0.45, -0.3, -0.25), g.rotation);
    let top = 0.0;
    let mut stopped = false;
    for _ in 0..400 {
        w.command_arm(0, below, GripperCommand::Open).unwrap();
        w.step();
        w.check_invariants().unwrap();
        let q = w.joints(0).unwrap();
        for (i, (a, b, r)) in geometry::link_capsules(&w, 0, &q)
            .into_iter()
            .enumerate()
            .skip(1)
        {
            let low = a.z.min(b.z) - r;
            assert!(
                low > top - 0.0101,
                "link {i} reaches {low:.4} m, into the table"
            );
        }
        stopped |= w.arm_blocked_by(0) == Some("table");
    }
    assert!(stopped, "the arm never reported the table in its way");
    assert!(w.tcp_pose(0).unwrap().translation.z > -0.05);
}

#[test]
fn the_grasp_turns_a_quarter_when_a_neighbour_stands_in_the_hand_s_way() {
    let w = Benchmark::B1.scene();
    let a = w.body_pose("a").unwrap();
    let g0 = geometry::grasp_pose(&w, 0, "a").unwrap();
    let boxes = geometry::boxes_except(&w, &["a"]);
    let clear = geometry::clear_grasp_at(&w, 0, "a", &a, &boxes, 0.1).unwrap();
    assert_eq!(
        clear, g0,
        "nothing in the way: the grasp closest to the arm's heading"
    );
    // A block 2.5 cm from a along the fingers' closing axis.
    let axis = g0.rotation * Vector3::y();
    let p = a.translation.vector + axis * 0.085;
    let mut w = w;
    w.move_block("b", Vector3::new(p.x, p.y, 0.03)).unwrap();
    let boxes = geometry::boxes_except(&w, &["a"]);
    assert!(geometry::hand_hits(&g0, &boxes), "the hand would hit b");
    let turned = geometry::clear_grasp_at(&w, 0, "a", &a, &boxes, 0.1).unwrap();
    assert!(!geometry::hand_hits(&turned, &boxes));
    let angle = (g0.rotation.inverse() * turned.rotation).angle();
    assert!(
        (angle - std::f64::consts::FRAC_PI_2).abs() < 1e-6,
        "{angle}"
    );
    assert_eq!(turned.translation, g0.translation);
}

#[test]
fn a_turned_pull_stroke_brings_the_block_to_the_reach_radius_along_its_line() {
    let base = Isometry3::identity();
    let block = Isometry3::translation(0.9, 0.2, 0.03);
    let reach = demo::PULL_TARGET_RADIUS;
    let radial = demo::pull_hook_poses(&base, &block, reach);
    let same = demo::pull_hook_poses_turned(&base, &block, reach, 0.0).unwrap();
    assert!((radial.0.translation.vector - same.0.translation.vector).norm() < 1e-12);
    assert!((radial.1.translation.vector - same.1.translation.vector).norm() < 1e-12);
    for turn in [0.35, -0.35, 0.7, -0.7] {
        let (contact, pulled) = demo::pull_hook_poses_turned(&base, &block, reach, turn).unwrap();
        let stroke = pulled.translation.vector - contact.translation.vector;
        let end = block.translation.vector + stroke;
        let r = (end.x * end.x + end.y * end.y).sqrt();
        assert!(
            r <= reach && r > reach - 0.011,
            "turn {turn}: ends at radius {r}"
        );
        // The hook is yawed along the turned line and strokes straight back along it.
        let yaw = libm::atan2(0.2, 0.9) + turn;
        let x = contact.rotation * Vector3::x();
        assert!((libm::atan2(x.y, x.x) - yaw).abs() < 1e-9);
        assert!(stroke.normalize().dot(&x) < -0.999_999);
    }
    // A line that never comes within reach of the base has no stroke.
    assert!(demo::pull_hook_poses_turned(&base, &block, reach, 1.5).is_none());
}

#[test]
fn the_hook_stops_rather_than_push_a_block_into_another() {
    let (mut w, _) = holding(Benchmark::B2, "hook");
    let bp = w.body_pose("b").unwrap();
    // Block a stands 15 cm in front of b, on the line b is pulled along.
    let b = bp.translation.vector;
    let u = Vector3::new(b.x, b.y, 0.0).normalize();
    let in_front = b - u * 0.15;
    w.move_block("a", Vector3::new(in_front.x, in_front.y, 0.03))
        .unwrap_or_else(|e| panic!("{e}"));
    let (tc, tp) = at_stroke_start(&mut w, &bp);
    let mut stopped = false;
    stroke(&mut w, &tc, &tp, |w, _| {
        stopped |= w.arm_blocked_by(0).is_some()
    });
    assert!(stopped, "the stroke was never stopped");
    let a = w.body_pose("a").unwrap().translation.vector;
    let b = w.body_pose("b").unwrap().translation.vector;
    assert!((a - b).norm() > 0.058, "b was driven into a: {a} {b}");
    assert!(!w.snapshot().bodies.iter().any(|x| x.lost));
}

#[test]
fn a_hook_that_turns_during_its_stroke_pushes_the_block_instead_of_stopping() {
    let (mut w, _) = holding(Benchmark::B2, "hook");
    let bp = w.body_pose("b").unwrap();
    let (tc, tp) = at_stroke_start(&mut w, &bp);
    // The hand yaws by −3° over the stroke, as the arm's tracking does near its limits: the
    // blade turns into b as well as dragging it (a translation alone would leave it inside).
    let turned = tc.rotation * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -0.05);
    let mut stopped = None;
    for k in 1..=400 {
        let s = (k as f64 / 300.0).min(1.0);
        let p = tc.translation.vector.lerp(&tp.translation.vector, s);
        let r = tc.rotation.slerp(&turned, s);
        w.command_arm(
            0,
            Isometry3::from_parts(Translation3::from(p), r),
            GripperCommand::Close,
        )
        .unwrap();
        w.step();
        w.check_invariants().unwrap();
        stopped = stopped.or(w.arm_blocked_by(0).map(str::to_string));
    }
    assert_eq!(stopped, None, "the stroke was stopped");
    assert!(facts(&w).contains(&"(inreach panda b)".to_string()));
}

#[test]
fn an_empty_hand_left_around_a_block_rises_first() {
    let (mut w, g) = holding(Benchmark::B1, "a");
    assert_eq!(geometry::rise_first(&w, 0, 0.1), None, "the hand holds a");
    w.command_arm(0, g, GripperCommand::Open).unwrap();
    for _ in 0..40 {
        w.step();
    }
    assert_eq!(w.held_by(0), None);
    let up = geometry::rise_first(&w, 0, 0.1).expect("the open hand is around a");
    let tcp = w.tcp_pose(0).unwrap();
    assert!((up.translation.vector - tcp.translation.vector - Vector3::z() * 0.1).norm() < 1e-12);
    let sol = w.reachable(0, &up).unwrap();
    w.set_joints(0, sol.joints).unwrap();
    assert_eq!(geometry::rise_first(&w, 0, 0.1), None, "10 cm above a");
}

#[test]
fn release_check_says_when_letting_go_would_lose_the_load() {
    assert_eq!(
        Benchmark::B1.scene().release_check(0),
        Ok(()),
        "nothing held"
    );
    let (mut w, g) = holding(Benchmark::B1, "a");
    assert_eq!(w.release_check(0), Ok(()), "a rests where it was grasped");
    // Over the floor, 10 cm beyond the table's far edge.
    let (_, hi) = w.body_aabb("table").unwrap();
    let out = Isometry3::from_parts(Translation3::new(0.4, hi.y + 0.1, 0.15), g.rotation);
    let sol = w.reachable(0, &out).unwrap();
    w.set_joints(0, sol.joints).unwrap();
    let why = w.release_check(0).unwrap_err();
    assert!(!why.is_empty());
    assert_eq!(w.held_by(0), Some("a"), "the check lets go of nothing");
}

/// Benchmark `b`'s template scene with arm 0 holding `body` at its grasp (returned too).
fn holding(b: Benchmark, body: &str) -> (World, Isometry3<f64>) {
    let mut w = b.scene();
    let g = geometry::grasp_pose(&w, 0, body).unwrap();
    let sol = w.reachable(0, &g).unwrap();
    w.set_joints(0, sol.joints).unwrap();
    w.command_arm(0, g, GripperCommand::Close).unwrap();
    w.step();
    assert_eq!(w.held_by(0), Some(body));
    (w, g)
}

/// Drives the TCP from `tc` to `tp` in a straight line over 300 ticks (100 more to settle),
/// checking the invariants after every step; `each` sees the world and the step's events.
fn stroke(
    w: &mut World,
    tc: &Isometry3<f64>,
    tp: &Isometry3<f64>,
    mut each: impl FnMut(&World, &[logic_lfd::sim::WorldEvent]),
) {
    for k in 1..=400 {
        let s = (k as f64 / 300.0).min(1.0);
        let p = tc.translation.vector.lerp(&tp.translation.vector, s);
        w.command_arm(
            0,
            Isometry3::from_parts(Translation3::from(p), tc.rotation),
            GripperCommand::Close,
        )
        .unwrap();
        let events = w.step();
        w.check_invariants().unwrap();
        each(w, &events);
    }
}

/// Puts arm 0 (holding the hook) at the contact pose of the pull stroke of a block at `bp`;
/// returns the TCP poses at contact and pulled.
fn at_stroke_start(w: &mut World, bp: &Isometry3<f64>) -> (Isometry3<f64>, Isometry3<f64>) {
    let base = w.arm_base(0).unwrap();
    let (contact, pulled) = demo::pull_hook_poses(&base, bp, 0.6);
    let tc = geometry::tcp_for_body_pose(w, 0, &contact);
    let tp = geometry::tcp_for_body_pose(w, 0, &pulled);
    let sol = w.reachable(0, &tc).unwrap();
    w.set_joints(0, sol.joints).unwrap();
    w.check_invariants().unwrap();
    (tc, tp)
}

#[test]
fn the_hook_pulls_only_along_strokes_clear_of_the_shelf_and_within_the_arms_reach() {
    let mut w = Benchmark::B2.scene();
    // The template's far block: the radial stroke is clear.
    assert!(disturb::hook_can_pull(&w, 0, "hook", "b"));
    assert_eq!(disturb::handleable(&w, "b"), Ok(()));
    // Right behind the shelf, 0.73 m out: every stroke towards the base drags b into the shelf
    // or lowers the blade onto it.
    w.move_block("b", Vector3::new(0.38, -0.625, 0.03)).unwrap();
    assert!(!disturb::hook_can_pull(&w, 0, "hook", "b"));
    assert!(disturb::handleable(&w, "b").is_err());
    // The same distance out on the open table is fine.
    w.move_block("b", Vector3::new(0.73, 0.0, 0.03)).unwrap();
    assert!(disturb::hook_can_pull(&w, 0, "hook", "b"));
    // 1.15 m out the hook still reaches the block on the table, but the hand cannot come down
    // from the stroke's lifted pose.
    w.move_block("b", Vector3::new(1.14, -0.14, 0.03)).unwrap();
    assert!(!disturb::hook_can_pull(&w, 0, "hook", "b"));
}

#[test]
fn a_hand_stretching_out_at_the_joints_speed_limits_stays_on_its_level_path() {
    // Found by the soak.
    // A hand carried out to 0.8 m at 0.35 m/s saturates the elbow's speed. Clamping each joint to
    // its speed limit alone would let the shoulder pitch on while the elbow lags, and the hand
    // would sink 5 cm below its level path (the hook's blade into a block).
    let mut w = Benchmark::B2.scene();
    let down = panda::down_orientation(0.1);
    let from = Isometry3::from_parts(Translation3::new(0.33, -0.02, 0.132), down);
    let to = Vector3::new(0.755, 0.28, 0.132);
    let sol = w.reachable(0, &from).unwrap();
    w.set_joints(0, sol.joints).unwrap();
    let steps = ((to - from.translation.vector).norm() / 0.0035).ceil() as usize;
    let mut lowest = f64::INFINITY;
    for k in 1..=steps + 150 {
        let s = (k as f64 / steps as f64).min(1.0);
        let p = from.translation.vector.lerp(&to, s);
        w.command_arm(
            0,
            Isometry3::from_parts(Translation3::from(p), down),
            GripperCommand::Open,
        )
        .unwrap();
        w.step();
        w.check_invariants().unwrap();
        lowest = lowest.min(w.tcp_pose(0).unwrap().translation.z);
    }
    assert!(lowest > 0.132 - 0.01, "the hand sank to {lowest:.3} m");
    let end = w.tcp_pose(0).unwrap().translation.vector;
    assert!((end - to).norm() < 0.004, "the hand stopped at {end}");
}

#[test]
fn whether_the_hook_can_pull_does_not_depend_on_how_the_carrying_hand_is_tilted_now() {
    // Found by the soak.
    // Derived from the hand's pose of the moment, the hook's grasp of a hand tilted 7° mid-motion
    // would make a block at the edge of the stroke's reach count as pullable.
    let (mut w, _) = holding(Benchmark::B2, "hook");
    let level = w.joints(0).unwrap();
    let mut tilted = level;
    tilted[5] += 0.12;
    let (mut pullable, mut differ) = (0, vec![]);
    for i in 0..8 {
        for j in 0..8 {
            let p = Vector3::new(0.80 + 0.05 * i as f64, -0.30 + 0.1 * j as f64, 0.03);
            if w.move_block("b", p).is_err() {
                continue;
            }
            w.set_joints(0, level).unwrap();
            let a = disturb::hook_can_pull(&w, 0, "hook", "b");
            w.set_joints(0, tilted).unwrap();
            let b = disturb::hook_can_pull(&w, 0, "hook", "b");
            pullable += a as usize;
            if a != b {
                differ.push(p);
            }
        }
    }
    assert!(pullable > 5 && pullable < 60, "{pullable} of 64 pullable");
    assert!(
        differ.is_empty(),
        "the answer changes with the tilt at {differ:?}"
    );
}

#[test]
fn a_block_carried_into_one_the_other_arm_holds_stops_at_contact() {
    // Found by the soak.
    // The contact stop covers bodies held by the other arm: in B3 the left arm carrying a must
    // not press it into the b the right arm holds.
    let mut w = Benchmark::B3.scene();
    w.move_block("a", Vector3::new(0.38, 0.09, 0.03)).unwrap();
    w.move_block("b", Vector3::new(0.38, -0.06, 0.03)).unwrap();
    for (arm, body) in [(0, "a"), (1, "b")] {
        let g = geometry::grasp_pose(&w, arm, body).unwrap();
        w.set_joints(arm, w.reachable(arm, &g).unwrap().joints)
            .unwrap();
        w.command_arm(arm, g, GripperCommand::Close).unwrap();
        w.step();
        assert_eq!(w.held_by(arm), Some(body));
        let up = Isometry3::from_parts(
            Translation3::new(0.0, 0.0, 0.12),
            UnitQuaternion::identity(),
        ) * g;
        w.set_joints(arm, w.reachable(arm, &up).unwrap().joints)
            .unwrap();
        w.command_arm(arm, up, GripperCommand::Close).unwrap();
    }
    w.check_invariants().unwrap();
    // The left arm carries a straight through where b hangs.
    let from = w.tcp_pose(0).unwrap();
    let mut stopped = false;
    for k in 1..=200 {
        let s = (k as f64 / 150.0).min(1.0);
        let mut to = from;
        to.translation.vector.y = from.translation.vector.y - 0.2 * s;
        w.command_arm(0, to, GripperCommand::Close).unwrap();
        w.step();
        w.check_invariants().unwrap();
        stopped |= w.arm_blocked_by(0) == Some("b");
    }
    assert!(stopped, "the left arm never reported b in its way");
    assert_eq!(w.held_by(1), Some("b"));
}

#[test]
fn a_joint_space_move_names_what_it_sweeps_through_and_the_ready_posture_goes_round_it() {
    // A two-block tower between two low hand poses (the hand's arc in joint space keeps its
    // distance from the base axis, 0.583 m), the other blocks far off.
    let aside = [("c", [0.3, 0.45, 0.03]), ("d", [0.25, -0.45, 0.03])];
    let w = b1_with(&[
        aside[0],
        aside[1],
        ("a", [0.583, 0.0, 0.03]),
        ("b", [0.583, 0.0, 0.09]),
    ]);
    let down = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI);
    let low = |y: f64| Isometry3::from_parts(Translation3::new(0.5, y, 0.1), down);
    let ik = |p: &Isometry3<f64>| w.reachable(0, p).expect("reachable").joints;
    let (from, to) = (ik(&low(-0.3)), ik(&low(0.3)));
    // The hand sweeps low from one side of the tower to the other: through the top block.
    let hit = w.joint_move_hits(0, &from, &to, &[]);
    assert!(matches!(hit.as_deref(), Some("a" | "b")), "{hit:?}");
    assert!(w.joint_move_hits(0, &to, &from, &[]).is_some());
    // By way of the ready posture (high above the table) both legs are clear.
    assert_eq!(w.joint_move_hits(0, &from, &panda::READY, &[]), None);
    assert_eq!(w.joint_move_hits(0, &panda::READY, &to, &[]), None);
    // Without the tower the straight move is clear too.
    let clear = b1_with(&[
        aside[0],
        aside[1],
        ("a", [0.25, 0.3, 0.03]),
        ("b", [0.2, -0.3, 0.03]),
    ]);
    assert_eq!(clear.joint_move_hits(0, &from, &to, &[]), None);
    // What overlaps at the start already (the hand around a block it grasps) is not a hit.
    let around = b1_with(&[aside[0], aside[1], ("a", [0.5, -0.3, 0.03])]);
    let at_a = Isometry3::from_parts(Translation3::new(0.5, -0.3, 0.03), down);
    let grasp = ik(&at_a);
    assert_eq!(around.joint_move_hits(0, &grasp, &panda::READY, &[]), None);
    // Coming down to grasp it the hand meets it, unless it is the body the action touches.
    assert_eq!(
        around
            .joint_move_hits(0, &panda::READY, &grasp, &[])
            .as_deref(),
        Some("a")
    );
    assert_eq!(
        around.joint_move_hits(0, &panda::READY, &grasp, &["a"]),
        None
    );
    // A hand already pressing on the table may not press deeper than the simulator lets links
    // (it would stop there), though the overlap was there at the start.
    let at = |z: f64| {
        ik(&Isometry3::from_parts(
            Translation3::new(0.45, 0.3, z),
            down,
        ))
    };
    let (touching, deeper) = (at(-0.02), at(-0.028));
    assert_eq!(
        w.joint_move_hits(0, &touching, &deeper, &[]).as_deref(),
        Some("table")
    );
    assert_eq!(w.joint_move_hits(0, &deeper, &touching, &[]), None);
}

#[test]
fn a_block_dragged_under_an_overhang_rests_on_the_table_below_it() {
    // c stands on d and overhangs the spot by 4 mm. Dropped there, a rests on the table with
    // its top touching c's underside: what lies above a block's centre cannot hold it up. The
    // settle probe starts 5 mm above the drop, where c is; counting c "in the way" would refuse
    // the drag and lose a block let go there (a pick under the overhang, undone).
    let mut w = b1_with(&[
        ("a", [0.30, 0.25, 0.03]),
        ("d", [0.4637, -0.2166, 0.03]),
        ("c", [0.456, -0.1988, 0.09]),
    ]);
    w.move_block("a", Vector3::new(0.40, -0.25, 0.03))
        .expect("a rests under the overhang");
    let a = w.body_pose("a").unwrap().translation.vector;
    assert!((a.z - 0.03).abs() < 1e-6, "a at {a:?}");
    assert_eq!(w.check_invariants(), Ok(()));
    let f = facts(&w);
    assert!(
        f.contains(&"(ontable a)".to_string()) && f.contains(&"(on c d)".to_string()),
        "{f:?}"
    );
}

#[test]
fn ik_with_room_reaches_above_a_block_at_the_minimum_reach() {
    // Found by the soak.
    // A block 25 cm from the right arm's base (B3), the pre-grasp 10 cm above it. The arm folds
    // its elbow to its limit there, and neither the warm start nor the ready posture with 6
    // restarts each converges, so the streams would refuse a pick the executor makes. More
    // restarts before giving up reach it.
    let base = Isometry3::translation(0.0, -0.45, 0.0);
    let planning = IkParams::default();
    for yaw in [0.0, std::f64::consts::FRAC_PI_2] {
        let target = Isometry3::from_parts(
            Translation3::new(0.2501, -0.4426, 0.13),
            panda::down_orientation(yaw),
        );
        let sol = panda::inverse_kinematics_with_room(&base, &target, &panda::READY, &planning)
            .unwrap_or_else(|e| panic!("yaw {yaw}: {e:?}"));
        let reached = panda::forward_kinematics(&base, &sol.joints);
        assert!((reached.translation.vector - target.translation.vector).norm() < 1e-3);
    }
}
