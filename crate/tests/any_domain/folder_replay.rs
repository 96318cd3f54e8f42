//! A task folder's episode log records the folder (path and file hashes) and replays only on the
//! same files: from the folder, or from the files the log carries.

use std::path::Path;

use logic_lfd::experiments::{run_episode_with, EpisodeSpec};
use logic_lfd::lfd::{Level, Method, Mode, Session, SessionError, SessionParams};
use logic_lfd::plan::NoClock;
use logic_lfd::sim::{Benchmark, TaskFolder};

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../domains/b1-paper-naming");

fn folder() -> TaskFolder {
    TaskFolder::read(Path::new(DIR)).unwrap()
}

/// An L3 episode on the folder, as JSON.
fn episode() -> String {
    let spec = EpisodeSpec {
        benchmark: Benchmark::B1,
        level: Some(Level::L3),
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed: 5,
        scene: None,
        robots: vec![],
    };
    let sources = folder().sources().unwrap();
    let report = run_episode_with(&spec, &sources, SessionParams::default(), &NoClock).unwrap();
    assert!(report.success, "{:?}", report.reason);
    let record = report
        .log
        .folder
        .as_ref()
        .expect("the log records its folder");
    assert_eq!(record.dir, folder().dir);
    assert_eq!(record.hashes, folder().hashes());
    assert!(record.files.is_none());
    serde_json::to_string(&report.log).unwrap()
}

/// Replays `json` to its end and returns the replayed log's canonical JSON.
fn replayed(mut s: Session) -> String {
    while s.outcome().is_none() {
        s.step(0.5, &NoClock);
    }
    serde_json::to_string(&s.log().canonical()).unwrap()
}

#[test]
fn a_folder_episode_replays_from_its_folder_and_from_the_files_it_carries() {
    let json = episode();
    let log: logic_lfd::lfd::EpisodeLog = serde_json::from_str(&json).unwrap();
    let want = serde_json::to_string(&log.canonical()).unwrap();

    let from_folder = Session::replay_in_folder(&folder(), &json, &[]).unwrap();
    assert_eq!(replayed(from_folder), want);

    // Without the folder the log alone cannot replay, and says which folder it needs.
    let e = Session::replay(&json).err().expect("refused").to_string();
    assert!(e.contains(&folder().dir), "{e}");

    // With the files in the log (the page's Save), it replays alone.
    let mut carried = log.clone();
    carried.folder.as_mut().unwrap().files = Some(folder().files);
    let carried = serde_json::to_string(&carried).unwrap();
    assert_eq!(replayed(Session::replay(&carried).unwrap()), want);
}

#[test]
fn a_changed_folder_file_is_named_with_both_hashes() {
    let json = episode();
    let mut changed = folder();
    changed
        .files
        .get_mut("problem.pddl")
        .unwrap()
        .push_str("\n; edited\n");
    match Session::replay_in_folder(&changed, &json, &[]) {
        Err(SessionError::Folder(e)) => {
            assert!(e.message.contains("problem.pddl (episode: "), "{e}");
            assert!(!e.message.contains("scene.json"), "{e}");
        }
        other => panic!("expected a folder error, got {:?}", other.err()),
    }
}

#[test]
fn a_benchmark_episode_is_not_replayed_in_a_folder() {
    let spec = EpisodeSpec {
        benchmark: Benchmark::B1,
        level: None,
        method: Method::LogicLfd,
        mode: Mode::Paper,
        seed: 1,
        scene: None,
        robots: vec![],
    };
    let report =
        logic_lfd::experiments::run_episode(&spec, SessionParams::default(), &NoClock).unwrap();
    assert!(report.log.folder.is_none());
    let json = serde_json::to_string(&report.log).unwrap();
    let e = Session::replay_in_folder(&folder(), &json, &[])
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("benchmark b1"), "{e}");
}
