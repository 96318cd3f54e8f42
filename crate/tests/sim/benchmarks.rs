//! The benchmarks agree with themselves: template scenes are valid and their facts are the
//! problem's init, the committed demos replay to the goal, the committed scene files match the
//! builders, and the PDDL models follow the simulated demos.

use logic_lfd::sim::demo;
use logic_lfd::sim::Benchmark;
use logic_lfd::sim::{SceneGraph, World};

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
