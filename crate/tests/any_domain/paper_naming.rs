//! B1 in the paper's own naming (`domains/b1-paper-naming`: untyped objects guarded by `(block ?b)`
//! / `(arm ?a)`, `inhand`, `on-block`, `on-table`, `empty`, block-first actions `pick-up`,
//! `put-on`, …) runs on the robot through its own `motions.json` exactly as B1 does: the same
//! demonstration is recorded, and every disturbance level ends in success with the same actions,
//! replans and simulated time.

use std::sync::Arc;

use logic_lfd::experiments::initial_scene;
use logic_lfd::experiments::table1_task_seed;
use logic_lfd::experiments::{run_episode, run_episode_with, EpisodeSpec};
use logic_lfd::lfd::Level;
use logic_lfd::lfd::SessionParams;
use logic_lfd::lfd::{Method, Mode};
use logic_lfd::pddl::{parse_domain, parse_problem};
use logic_lfd::plan::NoClock;
use logic_lfd::sim::demo::{self, ExpertParams, Script};
use logic_lfd::sim::Motions;
use logic_lfd::sim::World;
use logic_lfd::sim::{goal_facts, Benchmark, BenchmarkSources, TaskFolder};

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../domains/b1-paper-naming");

fn read(file: &str) -> String {
    std::fs::read_to_string(format!("{DIR}/{file}")).unwrap()
}

fn sources() -> BenchmarkSources {
    TaskFolder::read(std::path::Path::new(DIR))
        .and_then(|f| f.sources())
        .unwrap()
}

/// `(pick-up c panda)` → `(pick panda c)`, `(put-on c d panda)` → `(stack panda c d)`.
fn in_b1_names(action: &str) -> String {
    let w: Vec<&str> = action.trim_matches(['(', ')']).split_whitespace().collect();
    let b1 = match w[0] {
        "pick-up" => "pick",
        "put-down" => "place",
        "put-on" => "stack",
        "take-off" => "unstack",
        other => panic!("not a paper-naming action: {other}"),
    };
    let arm = w[w.len() - 1];
    let blocks = w[1..w.len() - 1].join(" ");
    format!("({b1} {arm} {blocks})")
}

#[test]
fn the_paper_named_domain_records_the_same_demonstration_as_b1() {
    let files = sources();
    let domain = parse_domain(&files.domain, "domain.pddl").unwrap();
    let problem = parse_problem(&files.problem, "problem.pddl", &domain).unwrap();
    let motions = Arc::new(Motions::parse(&files.motions, "motions.json", &domain).unwrap());
    let script: Script = serde_json::from_str(&read("expert.json")).unwrap();
    let world = World::from_json(&files.scene)
        .unwrap()
        .with_motions(motions);
    let goal = goal_facts(&domain, &problem);
    let ours = demo::record_script(
        world,
        &script,
        &goal,
        "b1-paper-naming",
        1,
        &ExpertParams::default(),
    )
    .unwrap();
    let b1 = demo::record(Benchmark::B1, 1, &ExpertParams::default()).unwrap();
    assert_eq!(ours.actions.len(), b1.actions.len());
    for (a, b) in ours.actions.iter().zip(&b1.actions) {
        assert_eq!(in_b1_names(&a.action), b.action);
        assert_eq!(a.samples, b.samples, "{}", a.action);
        assert_eq!(a.gripper, b.gripper);
        assert_eq!(a.anchor_pose, b.anchor_pose);
    }
    // The committed demo.json is that recording.
    let committed = demo::from_json(&files.demo).unwrap();
    assert_eq!(committed.actions, ours.actions);
}

#[test]
fn the_paper_named_b1_runs_every_level_to_success_like_b1() {
    let files = sources();
    for (i, (level, mode)) in Level::ALL
        .into_iter()
        .flat_map(|l| [(l, Mode::Paper), (l, Mode::Prioritised)])
        .cycle()
        .take(24)
        .enumerate()
    {
        let seed = table1_task_seed(Benchmark::B1, i, 11);
        let scene = initial_scene(Benchmark::B1, level, seed).unwrap();
        let spec = EpisodeSpec {
            benchmark: Benchmark::B1,
            level: Some(level),
            method: Method::LogicLfd,
            mode,
            seed,
            scene: Some(scene),
            robots: vec![],
        };
        let params = SessionParams::default();
        let ours = run_episode_with(&spec, &files, params, &NoClock).unwrap();
        let b1 = run_episode(&spec, params, &NoClock).unwrap();
        assert!(ours.success, "{level:?}: {:?}", ours.reason);
        assert!(b1.success, "{level:?}: {:?}", b1.reason);
        let actions = |r: &logic_lfd::experiments::EpisodeReport, rename: bool| -> Vec<String> {
            r.log
                .actions
                .iter()
                .map(|a| {
                    if rename {
                        in_b1_names(&a.action)
                    } else {
                        a.action.clone()
                    }
                })
                .collect()
        };
        assert_eq!(actions(&ours, true), actions(&b1, false), "{level:?}");
        assert_eq!(ours.replans, b1.replans, "{level:?}");
        assert_eq!(ours.log.ticks, b1.log.ticks, "{level:?}");
        assert_eq!(ours.execution_s, b1.execution_s, "{level:?}");
    }
}

#[test]
fn run_with_a_domain_directory_succeeds_and_a_bad_declaration_is_refused_with_its_line() {
    let (code, stdout, stderr) = crate::support::cli::run_cli(&[
        "run", "--domain", DIR, "--level", "l3", "--seed", "2", "--json",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(report["success"], true, "{stdout}");
    assert!(stdout.contains("(put-on a b panda)"));
    // The same directory with one action left undeclared.
    let dir = std::env::temp_dir().join(format!("logic-lfd-motions-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for f in ["domain.pddl", "problem.pddl", "demo.json", "scene.json"] {
        std::fs::copy(format!("{DIR}/{f}"), dir.join(f)).unwrap();
    }
    let motions = read("motions.json").replace(
        ",\n    \"put-on\": { \"motion\": \"release\", \"object\": \"?b\", \"arm\": \"?a\", \"onto\": \"?c\" }",
        "",
    );
    std::fs::write(dir.join("motions.json"), motions).unwrap();
    let (code, _, stderr) =
        crate::support::cli::run_cli(&["run", "--domain", dir.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains(
            "motions.json:13:3: actions: no motion declared for the domain's action `put-on`"
        ),
        "{stderr}"
    );
    std::fs::remove_dir_all(dir).ok();
}
