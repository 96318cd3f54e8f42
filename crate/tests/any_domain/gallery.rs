//! The task folders of the gallery (`domains/sorting`, `domains/shelf-tower`): written as a user
//! writes a folder, run under every disturbance level in both multi-goal modes, with the
//! demonstration the scripted expert records.

use std::path::Path;

use logic_lfd::experiments::{run_episode_with, EpisodeSpec};
use logic_lfd::lfd::{Level, Method, Mode, SessionParams};
use logic_lfd::plan::NoClock;
use logic_lfd::sim::{Benchmark, TaskFolder};

const GALLERY: [&str; 2] = ["sorting", "shelf-tower"];

fn folder(name: &str) -> TaskFolder {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../domains")
        .join(name);
    TaskFolder::read(&dir).unwrap()
}

#[test]
fn each_gallery_folder_finishes_under_every_level_in_both_modes() {
    for name in GALLERY {
        let sources = folder(name).sources().unwrap();
        for (i, level) in Level::ALL.into_iter().enumerate() {
            for mode in [Mode::Paper, Mode::Prioritised] {
                let spec = EpisodeSpec {
                    // The folder brings its scene; the benchmark field names no files here.
                    benchmark: Benchmark::B1,
                    level: Some(level),
                    method: Method::LogicLfd,
                    mode,
                    seed: 10 + i as u64,
                    scene: None,
                    robots: vec![],
                };
                let r =
                    run_episode_with(&spec, &sources, SessionParams::default(), &NoClock).unwrap();
                assert!(r.success, "{name} {level:?} {mode:?}: {:?}", r.reason);
                assert!(r.injection.is_some() || r.not_injected.is_some());
                assert!(r.log.folder.is_some(), "{name}: the log names its folder");
            }
        }
    }
}

#[test]
fn each_gallery_demo_is_what_the_expert_records() {
    for name in GALLERY {
        let f = folder(name);
        let recorded = f.record_demo(1).unwrap();
        assert_eq!(recorded.trim(), f.files["demo.json"].trim(), "{name}");
    }
}
