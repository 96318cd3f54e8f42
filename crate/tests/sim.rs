//! Simulator: kinematics, contact rules, scene graph, snapshots, benchmarks, disturbances.

use logic_lfd::sim::benchmark::Benchmark;
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
